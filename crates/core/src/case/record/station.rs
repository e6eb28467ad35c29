//! A station's three-component record as the agencies publish it: every channel with its
//! orientation, the station, the event and the agency, as the readers of COSMOS V0/V1/V2,
//! the CSMIP (CGS) fixed-format volumes (Avol1 V1 `.RAW`/`.V1`, V2), USGS SMC and GeoNet
//! V1A/V2A give it (`station_file` tells the layouts apart); and the channels made ready
//! for a run: a stated baseline correction for an uncorrected record
//! (with the drift it removes), unequal channels trimmed to a common window with a note.

use super::filter::HighPass;
use super::{Baseline, Record, integrate};

/// Which way a channel's sensor points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Orientation {
    /// Horizontal, at this azimuth: degrees clockwise from north (0 north, 90 east).
    Azimuth(f64),
    /// Vertical, positive upward.
    Up,
    /// Vertical, positive downward.
    Down,
}

impl Orientation {
    /// Short text: "90°", "up", "down".
    pub fn describe(&self) -> String {
        match self {
            Self::Azimuth(a) => format!("{a}°"),
            Self::Up => "up".into(),
            Self::Down => "down".into(),
        }
    }

    /// Read an orientation as the headers write it: "90 Deg", "360 DEG", "Up", "DOWN",
    /// "N28W" (GeoNet-style quadrant bearings), a bare azimuth "270".
    pub fn parse(text: &str) -> Option<Self> {
        let t = text.trim().to_ascii_uppercase();
        let word = t.split_whitespace().next()?;
        match word {
            "UP" | "VERT" | "V" | "Z" => return Some(Self::Up),
            "DOWN" => return Some(Self::Down),
            _ => {}
        }
        let unit = t.split_whitespace().nth(1).unwrap_or("DEG");
        if let Ok(a) = word.trim_end_matches("DEG").parse::<f64>()
            && (0.0..=360.0).contains(&a)
            && unit.starts_with("DEG")
        {
            return Some(Self::Azimuth(a));
        }
        quadrant_bearing(word).map(Self::Azimuth)
    }
}

/// "N28W" → 332, "S10E" → 170, "N90E" → 90: a quadrant bearing as an azimuth.
fn quadrant_bearing(word: &str) -> Option<f64> {
    let from = word.chars().next()?;
    let to = word.chars().last()?;
    let angle: f64 = word.get(1..word.len() - 1)?.parse().ok()?;
    if !(0.0..=90.0).contains(&angle) {
        return None;
    }
    let az = match (from, to) {
        ('N', 'E') => angle,
        ('N', 'W') => 360.0 - angle,
        ('S', 'E') => 180.0 - angle,
        ('S', 'W') => 180.0 + angle,
        _ => return None,
    };
    Some(az.rem_euclid(360.0))
}

/// A line with nothing but blanks or the DOS end-of-file filler (Ctrl-Z) some agencies'
/// files end with: the end of the channels.
pub(super) fn is_blank(line: &str) -> bool {
    line.trim_matches(|c: char| c.is_whitespace() || c == '\u{1a}')
        .is_empty()
}

/// Whether the values are as recorded or already corrected by the agency.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    /// Raw or uncorrected (COSMOS V0/V1, CSMIP Avol1 V1, SMC code 1): needs a baseline
    /// correction before it is integrated.
    Uncorrected,
    /// Corrected by the agency (V2, SMC code 2): used as published.
    Corrected,
}

/// One channel of a station.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// Its orientation from the header.
    pub orientation: Orientation,
    /// Its samples, m/s².
    pub record: Record,
    /// The 1-based line of the file where its header starts.
    pub line: usize,
}

/// A station's record: its channels and where it comes from.
#[derive(Debug, Clone, PartialEq)]
pub struct StationRecord {
    /// The file layout read ("CSMIP Avol1 V1", "COSMOS V2", "USGS SMC").
    pub format: &'static str,
    /// The station, as its header names it.
    pub station: String,
    /// The event, as its header names it.
    pub event: String,
    /// The agency that processed or distributed it.
    pub agency: String,
    /// Uncorrected or corrected.
    pub level: Level,
    /// The channels in file order.
    pub channels: Vec<Channel>,
}

/// The channels of a station made ready for a run, and what was done to them.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedStation {
    /// The channels, trimmed to one length, corrected when uncorrected.
    pub channels: Vec<Channel>,
    /// Ground velocity and displacement at the end, before and after the correction.
    pub drift: Vec<Drift>,
    /// What was done (trimming, the correction), one sentence each.
    pub notes: Vec<String>,
}

/// The end of a channel's integrated ground motion, before and after its correction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drift {
    /// Final ground velocity, m/s, as read and as used.
    pub velocity: [f64; 2],
    /// Final ground displacement, m, as read and as used.
    pub displacement: [f64; 2],
}

/// What is done to an uncorrected record after its pre-event mean is removed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Processing {
    /// A baseline fitted over the run's window ([`Baseline`]).
    Baseline(Baseline),
    /// The acausal Butterworth high-pass over the whole record, before the window is cut.
    HighPass(HighPass),
}

impl From<Baseline> for Processing {
    fn from(b: Baseline) -> Self {
        Self::Baseline(b)
    }
}

impl From<HighPass> for Processing {
    fn from(h: HighPass) -> Self {
        Self::HighPass(h)
    }
}

/// Seconds at the start of an uncorrected record whose mean is taken as its pre-event
/// offset (the CSMIP and COSMOS volumes keep several seconds of pre-event memory).
pub const PRE_EVENT_S: f64 = 1.0;

/// Prepare a station's channels: all trimmed to the shortest (a note names the lengths);
/// an uncorrected record has its pre-event mean (the first [`PRE_EVENT_S`]) removed and
/// then `processing` applied (a [`Baseline`] or a [`HighPass`]); a corrected one is used
/// as published. Every channel's velocity and displacement drift (their values at the
/// end) before and after is kept.
pub fn prepare(station: &StationRecord, processing: impl Into<Processing>) -> PreparedStation {
    prepare_window(station, processing, 0.0, f64::INFINITY)
}

/// [`prepare`] for the window of `length` seconds from `start` (a run uses only those):
/// the pre-event mean is still taken from the file's first [`PRE_EVENT_S`], a baseline
/// is fitted over the window, a high-pass filters the whole record before the window is
/// cut, and the drift is the window's.
pub fn prepare_window(
    station: &StationRecord,
    processing: impl Into<Processing>,
    start: f64,
    length: f64,
) -> PreparedStation {
    let processing = processing.into();
    let mut notes = Vec::new();
    let lengths: Vec<usize> = station
        .channels
        .iter()
        .map(|c| c.record.samples.len())
        .collect();
    let n = lengths.iter().copied().min().unwrap_or(0);
    let dt = station.channels.first().map_or(1.0, |c| c.record.dt);
    if lengths.iter().any(|&l| l != n) {
        notes.push(format!(
            "channels of {} samples trimmed to the common first {n} ({:.2} s)",
            lengths
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", "),
            dt * n.saturating_sub(1) as f64
        ));
    }
    let first = ((start / dt).round() as usize).min(n);
    let last = if length.is_finite() {
        (first + (length / dt).ceil() as usize + 1).min(n)
    } else {
        n
    };
    if first > 0 || last < n {
        notes.push(format!(
            "the window {:.2}–{:.2} s of the {:.2} s record used (t = 0 at {:.2} s)",
            first as f64 * dt,
            last.saturating_sub(1) as f64 * dt,
            n.saturating_sub(1) as f64 * dt,
            first as f64 * dt
        ));
    }
    let needs_correction = station.level == Level::Uncorrected;
    notes.push(correction_note(needs_correction, processing));
    let mut channels = Vec::with_capacity(station.channels.len());
    let mut drift = Vec::with_capacity(station.channels.len());
    for c in &station.channels {
        let raw = &c.record.samples[..n];
        let window = &raw[first..last];
        let before = integrate(dt, window, Baseline::None);
        let used = if needs_correction {
            let m = ((PRE_EVENT_S / dt).round() as usize).clamp(1, n.max(1));
            let mean = raw[..m.min(n)].iter().sum::<f64>() / m as f64;
            match processing {
                Processing::Baseline(baseline) => {
                    let level: Vec<f64> = window.iter().map(|a| a - mean).collect();
                    integrate(dt, &level, baseline)
                }
                Processing::HighPass(filter) => {
                    let level: Vec<f64> = raw.iter().map(|a| a - mean).collect();
                    let filtered = filter.acausal(dt, &level);
                    integrate(dt, &filtered[first..last], Baseline::None)
                }
            }
        } else {
            integrate(dt, window, Baseline::None)
        };
        let end = |v: &[f64]| v.last().copied().unwrap_or(0.0);
        drift.push(Drift {
            velocity: [end(&before.vel), end(&used.vel)],
            displacement: [end(&before.disp), end(&used.disp)],
        });
        let mut record = c.record.clone();
        record.samples = used.acc;
        channels.push(Channel {
            orientation: c.orientation,
            record,
            line: c.line,
        });
    }
    PreparedStation {
        channels,
        drift,
        notes,
    }
}

/// What is done to the values: corrected or used as published.
fn correction_note(needs_correction: bool, processing: Processing) -> String {
    if !needs_correction {
        return "corrected by the agency: used as published".into();
    }
    format!(
        "uncorrected record: the mean of the file's first {PRE_EVENT_S} s removed from each channel, then {}",
        match processing {
            Processing::Baseline(Baseline::None) => "no baseline correction (as asked)".into(),
            Processing::Baseline(Baseline::Cubic) =>
                "the baseline correction \"cubic\" (the least-squares fit c2·t² + c3·t³ of the window's displacement subtracted)".into(),
            Processing::HighPass(filter) => format!("{} over the whole record", filter.describe()),
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientations_as_headers_write_them() {
        assert_eq!(
            Orientation::parse(" 90 Deg"),
            Some(Orientation::Azimuth(90.0))
        );
        assert_eq!(
            Orientation::parse("360 DEG"),
            Some(Orientation::Azimuth(360.0))
        );
        assert_eq!(Orientation::parse("Up"), Some(Orientation::Up));
        assert_eq!(Orientation::parse("DOWN"), Some(Orientation::Down));
        assert_eq!(
            Orientation::parse("N28W"),
            Some(Orientation::Azimuth(332.0))
        );
        assert_eq!(
            Orientation::parse("S10E"),
            Some(Orientation::Azimuth(170.0))
        );
        assert_eq!(Orientation::parse("sideways"), None);
        assert_eq!(Orientation::parse("400"), None);
        assert_eq!(Orientation::parse("360 Dig"), None);
    }

    fn channel(samples: Vec<f64>, orientation: Orientation) -> Channel {
        Channel {
            orientation,
            record: Record {
                dt: 0.1,
                samples,
                unit: super::super::AccelUnit::MetrePerSecond2,
                description: String::new(),
                note: String::new(),
            },
            line: 1,
        }
    }

    #[test]
    fn an_uncorrected_offset_is_removed_and_lengths_trimmed() {
        // A constant offset of 0.01 m/s² over 10 s drifts by 0.1 m/s and 0.5 m; the
        // pre-event mean removes it entirely.
        let s = StationRecord {
            format: "test",
            station: "S".into(),
            event: "E".into(),
            agency: "A".into(),
            level: Level::Uncorrected,
            channels: vec![
                channel(vec![0.01; 101], Orientation::Azimuth(0.0)),
                channel(vec![0.01; 103], Orientation::Up),
            ],
        };
        let p = prepare(&s, Baseline::Cubic);
        assert!(p.channels.iter().all(|c| c.record.samples.len() == 101));
        assert!(p.notes[0].contains("101, 103"), "{:?}", p.notes);
        let d = p.drift[0];
        assert!((d.velocity[0] - 0.1).abs() < 1e-12 && (d.displacement[0] - 0.5).abs() < 1e-12);
        assert!(d.velocity[1].abs() < 1e-15 && d.displacement[1].abs() < 1e-15);
        // Corrected: as published.
        let s = StationRecord {
            level: Level::Corrected,
            ..s
        };
        let p = prepare(&s, Baseline::Cubic);
        assert_eq!(p.channels[0].record.samples[..101], vec![0.01; 101][..]);
    }
}

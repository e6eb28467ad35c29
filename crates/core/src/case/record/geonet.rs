//! GeoNet (GNS Science, New Zealand) strong-motion volumes: V1A (uncorrected, at the
//! instrument's rate) and V2A (corrected and resampled), three channels a file, one block
//! each. A block is 16 text lines ("Uncorrected accelerogram … GNS Science" or "Corrected
//! accelerogram …"; line 2 "Site CODE …", line 3 the site's name, lines 7–9 the event,
//! line 13 "Component N10E" or "Component Up"), 40 integers as 10I8 on 4 lines, 60 reals
//! as 10F8 on 6 lines, then the accelerations in mm/s² as 10F8 — in a V2A followed by the
//! velocity (mm/s) and displacement (mm). Integer 34 counts the acceleration values, 35
//! and 36 the velocity and displacement values (0 in a V1A); real 26 is the sample
//! interval in seconds.

use std::path::Path;

use crate::error::InputError;

use super::fixed::{Layout, read_block};
use super::station::{Channel, Level, Orientation, StationRecord, is_blank};
use super::token::at;
use super::{AccelUnit, MIN_DT, Record};

/// Text lines of a channel's header.
const TEXT_LINES: usize = 16;
/// The integer header: 40 values, 10 a line of 8 characters.
const INTS: Layout = Layout::new(10, 8);
const INT_COUNT: usize = 40;
/// The real header: 60 values, 10 a line of 8 characters.
const REALS: Layout = Layout::new(10, 8);
const REAL_COUNT: usize = 60;
/// The samples: 10 a line of 8 characters.
const SAMPLES: Layout = Layout::new(10, 8);
/// 1-based integer fields: acceleration, velocity and displacement counts.
const ACC_COUNT: usize = 34;
const VEL_COUNT: usize = 35;
const DISP_COUNT: usize = 36;
/// 1-based real field: the sample interval, s.
const INTERVAL: usize = 26;

/// Parse a GeoNet V1A or V2A file of one or more channels.
pub(super) fn parse_geonet(path: &Path, text: &str) -> Result<StationRecord, InputError> {
    let lines: Vec<&str> = text.lines().collect();
    let level = level_of(lines.first().copied().unwrap_or("")).ok_or_else(|| {
        let mut e = at(
            path,
            1,
            Some(1),
            "expected \"Uncorrected accelerogram … GNS Science\" (V1A) or \"Corrected accelerogram … GNS Science\" (V2A)",
        );
        e.field = "text header line 1".into();
        e
    })?;
    let mut channels = Vec::new();
    let mut start = 0;
    while start < lines.len() && !is_blank(lines[start]) {
        let (channel, next) = channel_block(path, &lines, start, level)?;
        channels.push(channel);
        start = next;
    }
    let text = |i: usize| squeeze(lines.get(i).copied().unwrap_or(""));
    let code = lines
        .get(1)
        .and_then(|l| l.split_whitespace().nth(1))
        .unwrap_or("");
    Ok(StationRecord {
        format: match level {
            Level::Uncorrected => "GeoNet V1A",
            Level::Corrected => "GeoNet V2A",
        },
        station: squeeze(&format!("NZ.{code} {}", text(2))),
        event: squeeze(&format!("{}, {}; {}", text(7), text(6), text(8))),
        agency: "GNS Science (GeoNet)".into(),
        level,
        channels,
    })
}

/// Uncorrected or corrected, from a block's first line.
fn level_of(line: &str) -> Option<Level> {
    let lower = line.trim().to_ascii_lowercase();
    if !lower.contains("gns science") {
        return None;
    }
    if lower.starts_with("uncorrected accelerogram") {
        Some(Level::Uncorrected)
    } else if lower.starts_with("corrected accelerogram") {
        Some(Level::Corrected)
    } else {
        None
    }
}

/// Runs of blanks as one space, the ends trimmed.
fn squeeze(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// One channel's block from 0-based line `start`: the channel and the line after it.
fn channel_block(
    path: &Path,
    lines: &[&str],
    start: usize,
    level: Level,
) -> Result<(Channel, usize), InputError> {
    check_block_start(path, lines, start, level)?;
    let ints_at = start + TEXT_LINES;
    let orientation = component(path, lines, start + 12)?;
    let ints = read_block(path, lines, ints_at, INT_COUNT, INTS, "integer header")?;
    let reals_at = ints_at + INTS.lines(INT_COUNT);
    let reals = read_block(path, lines, reals_at, REAL_COUNT, REALS, "real header")?;
    let npts = header_count(path, &ints, ints_at, ACC_COUNT, 1.0)?;
    let (nvel, ndisp) = match level {
        Level::Uncorrected => (0, 0),
        Level::Corrected => (
            header_count(path, &ints, ints_at, VEL_COUNT, 0.0)?,
            header_count(path, &ints, ints_at, DISP_COUNT, 0.0)?,
        ),
    };
    let dt = sample_interval(path, &reals, reals_at)?;
    let data_at = reals_at + REALS.lines(REAL_COUNT);
    let values = read_block(path, lines, data_at, npts, SAMPLES, "acceleration values")?;
    let mut next = data_at + SAMPLES.lines(npts);
    for (n, what) in [(nvel, "velocity values"), (ndisp, "displacement values")] {
        if n > 0 {
            read_block(path, lines, next, n, SAMPLES, what)?;
            next += SAMPLES.lines(n);
        }
    }
    let unit = AccelUnit::MillimetrePerSecond2;
    let record = Record {
        dt,
        samples: values.iter().map(|a| a * unit.to_si()).collect(),
        unit,
        description: squeeze(lines[start + 12]),
        note: String::new(),
    };
    Ok((
        Channel {
            orientation,
            record,
            line: start + 1,
        },
        next,
    ))
}

/// A channel's block starts at 0-based line `start` with its text header whole, its
/// first line saying the file's level.
fn check_block_start(
    path: &Path,
    lines: &[&str],
    start: usize,
    level: Level,
) -> Result<(), InputError> {
    if start + TEXT_LINES > lines.len() {
        return Err(at(
            path,
            start + 1,
            None,
            format!(
                "a GeoNet channel has {TEXT_LINES} text header lines from line {}, but the file ends at line {}",
                start + 1,
                lines.len()
            ),
        ));
    }
    if level_of(lines[start]) == Some(level) {
        return Ok(());
    }
    let mut e = at(
        path,
        start + 1,
        Some(1),
        format!(
            "expected the next channel's first line, \"{}accelerogram … GNS Science\" as the file's first, found \"{}\"",
            if level == Level::Uncorrected {
                "Uncorrected "
            } else {
                "Corrected "
            },
            lines[start].trim()
        ),
    );
    e.field = "text header line 1".into();
    Err(e)
}

/// The integer header's value `k` (1-based) as a count of values, at least `least`; the
/// header starts at 0-based line `ints_at`.
fn header_count(
    path: &Path,
    ints: &[f64],
    ints_at: usize,
    k: usize,
    least: f64,
) -> Result<usize, InputError> {
    let n = ints[k - 1];
    if n.fract() == 0.0 && (least..=1e9).contains(&n) {
        return Ok(n as usize);
    }
    let mut e = at(
        path,
        ints_at + (k - 1) / 10 + 1,
        Some((k - 1) % 10 * 8 + 1),
        format!(
            "integer {k} (the number of {} values) is {n}: a whole number from {least}",
            match k {
                ACC_COUNT => "acceleration",
                VEL_COUNT => "velocity",
                _ => "displacement",
            }
        ),
    );
    e.field = format!("integer header[{k}]");
    Err(e)
}

/// The sample interval from the real header (from 0-based line `reals_at`), at least
/// [`MIN_DT`].
fn sample_interval(path: &Path, reals: &[f64], reals_at: usize) -> Result<f64, InputError> {
    let dt = reals[INTERVAL - 1];
    if dt < MIN_DT {
        let mut e = at(
            path,
            reals_at + (INTERVAL - 1) / 10 + 1,
            Some((INTERVAL - 1) % 10 * 8 + 1),
            format!("real {INTERVAL} (the sample interval) is {dt} s: at least {MIN_DT:e} s"),
        );
        e.field = format!("real header[{INTERVAL}]");
        return Err(e);
    }
    Ok(dt)
}

/// The orientation on the 0-based line `i`: "Component N10E", "Component S80W",
/// "Component Up" (what follows the bearing is a description).
fn component(path: &Path, lines: &[&str], i: usize) -> Result<Orientation, InputError> {
    let line = lines[i];
    let word = line.split_whitespace().nth(1).unwrap_or("");
    let column = line
        .find(word)
        .filter(|_| !word.is_empty())
        .map_or(1, |c| line[..c].chars().count() + 1);
    let is_component = line
        .trim_start()
        .to_ascii_lowercase()
        .starts_with("component");
    match Orientation::parse(word) {
        Some(o) if is_component => Ok(o),
        _ => {
            let mut e = at(
                path,
                i + 1,
                Some(column),
                format!(
                    "expected \"Component\" and a quadrant bearing (\"N10E\", \"S80W\") or \"Up\", found \"{}\"",
                    line.trim()
                ),
            );
            e.field = "component".into();
            Err(e)
        }
    }
}

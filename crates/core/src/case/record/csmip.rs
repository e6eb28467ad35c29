//! The CSMIP (California Geological Survey, formerly CDMG) fixed-format volumes, one
//! block a channel: Avol1 V1 (`.RAW`, `.V1`: "Uncorrected Accelerogram Data", 13 text
//! lines, 100 integers as 16I5 on 7 lines, 50 reals as 8F10 on 7 lines, then
//! "N Accelerogram points at R pts/sec in units of g. Format: (8f9.6)") and V2
//! ("CORRECTED ACCELEROGRAM", 25 text lines, 7 integer lines, 100 reals on 13 lines, then
//! "N POINTS OF ACCEL DATA EQUALLY SPACED AT Δt SEC. (UNITS: CM/SEC/SEC)" in 8F10, and
//! the velocity and displacement after it). Each block ends with a `/&` line. A channel's
//! orientation is its text header's `Chan  1:  90 Deg` line.

use std::path::Path;

use crate::error::InputError;

use super::fixed::{Layout, format_in, read_block};
use super::station::{Channel, Level, Orientation, StationRecord, is_blank};
use super::token::at;
use super::{AccelUnit, MIN_DT, Record};

/// The header sizes of a volume: text lines, integer lines, reals and their lines.
struct Volume {
    level: Level,
    format: &'static str,
    text_lines: usize,
    int_lines: usize,
    reals: usize,
}

const V1: Volume = Volume {
    level: Level::Uncorrected,
    format: "CSMIP Avol1 V1",
    text_lines: 13,
    int_lines: 7,
    reals: 50,
};

const V2: Volume = Volume {
    level: Level::Corrected,
    format: "CSMIP V2",
    text_lines: 25,
    int_lines: 7,
    reals: 100,
};

/// Parse a CSMIP V1 or V2 file of one or more channels.
pub(super) fn parse_csmip(path: &Path, text: &str) -> Result<StationRecord, InputError> {
    let lines: Vec<&str> = text.lines().collect();
    let first = lines[0].trim_start().to_ascii_uppercase();
    let volume = if first.starts_with("UNCORRECTED") {
        V1
    } else {
        V2
    };
    let mut channels = Vec::new();
    let mut start = 0;
    let mut header = None;
    while start < lines.len() && !is_blank(lines[start]) {
        let (channel, next) = channel_block(path, &lines, start, &volume)?;
        if header.is_none() {
            header = Some(describe(&lines[start..start + volume.text_lines], &volume));
        }
        channels.push(channel);
        start = next;
    }
    let (station, event, agency) = header.unwrap_or_default();
    Ok(StationRecord {
        format: volume.format,
        station,
        event,
        agency,
        level: volume.level,
        channels,
    })
}

/// One channel's block from 0-based line `start`: the channel and the line after its `/&`.
fn channel_block(
    path: &Path,
    lines: &[&str],
    start: usize,
    volume: &Volume,
) -> Result<(Channel, usize), InputError> {
    let text_end = start + volume.text_lines;
    if text_end >= lines.len() {
        return Err(at(
            path,
            start + 1,
            None,
            format!(
                "a {} channel has {} text header lines, but the file ends at line {}",
                volume.format,
                volume.text_lines,
                lines.len()
            ),
        ));
    }
    let orientation = orientation(path, lines, start, text_end)?;
    read_block(
        path,
        lines,
        text_end,
        100,
        Layout::new(16, 5),
        "integer header",
    )?;
    let reals_at = text_end + volume.int_lines;
    read_block(
        path,
        lines,
        reals_at,
        volume.reals,
        Layout::new(8, 10),
        "real header",
    )?;
    let points_at = reals_at + Layout::new(8, 10).lines(volume.reals);
    let data = points_line(path, lines, points_at)?;
    let values = read_block(
        path,
        lines,
        points_at + 1,
        data.npts,
        data.layout,
        "acceleration values",
    )?;
    let end = (points_at + 1 + data.layout.lines(data.npts)..lines.len())
        .find(|&i| lines[i].trim_start().starts_with("/&"))
        .map_or(lines.len(), |i| i + 1);
    let record = Record {
        dt: data.dt,
        samples: values.iter().map(|a| a * data.unit.to_si()).collect(),
        unit: data.unit,
        description: lines[start + 1].trim().to_string(),
        note: String::new(),
    };
    Ok((
        Channel {
            orientation,
            record,
            line: start + 1,
        },
        end,
    ))
}

/// The channel's orientation from its text header's line that starts with "Chan".
fn orientation(
    path: &Path,
    lines: &[&str],
    start: usize,
    end: usize,
) -> Result<Orientation, InputError> {
    let Some(i) = (start..end).find(|&i| {
        lines[i]
            .trim_start()
            .to_ascii_uppercase()
            .starts_with("CHAN")
    }) else {
        return Err(at(
            path,
            start + 1,
            None,
            "the channel's text header has no \"Chan  1:  90 Deg\" line: its orientation is unknown",
        ));
    };
    let line = lines[i];
    let colon = line.find(':');
    let said = colon.map_or("", |c| &line[c + 1..]);
    Orientation::parse(said).ok_or_else(|| {
        let mut e = at(
            path,
            i + 1,
            colon.map(|c| c + 2),
            format!(
                "the channel orientation \"{}\" is neither an azimuth in degrees (\"90 Deg\") nor \"Up\"/\"Down\"",
                said.trim()
            ),
        );
        e.field = "channel orientation".into();
        e
    })
}

/// The line before the samples, read: count, step, unit and layout.
struct Points {
    npts: usize,
    dt: f64,
    unit: AccelUnit,
    layout: Layout,
}

/// "35430 Accelerogram points at 100 pts/sec in units of g.  Format: (8f9.6)" (V1) or
/// "3251 POINTS OF ACCEL DATA EQUALLY SPACED AT  .020 SEC.  (UNITS: CM/SEC/SEC)" (V2).
fn points_line(path: &Path, lines: &[&str], i: usize) -> Result<Points, InputError> {
    let Some(line) = lines.get(i) else {
        return Err(at(
            path,
            lines.len(),
            None,
            "the file ends before the line that counts the acceleration points",
        ));
    };
    let upper = line.to_ascii_uppercase();
    let words: Vec<&str> = upper.split_whitespace().collect();
    let here = |column: usize, field: &str, reason: String| {
        let mut e = at(path, i + 1, Some(column), reason);
        e.field = field.into();
        e
    };
    let npts = match words.first().and_then(|w| w.parse::<usize>().ok()) {
        Some(n) if n >= 1 => n,
        _ => {
            return Err(here(
                1,
                "number of points",
                format!(
                    "expected the number of acceleration points first, found \"{}\"",
                    line.trim()
                ),
            ));
        }
    };
    let after = |key: &str| {
        words
            .iter()
            .position(|w| *w == key)
            .and_then(|k| words.get(k + 1))
            .and_then(|w| w.trim_end_matches('.').parse::<f64>().ok())
    };
    let dt = if upper.contains("PTS/SEC") || upper.contains("SAMPLES/SEC") {
        after("AT").map(|rate| 1.0 / rate)
    } else {
        after("AT")
    };
    let dt = match dt {
        Some(dt) if dt.is_finite() && dt >= MIN_DT => dt,
        _ => {
            return Err(here(
                upper.find(" AT ").map_or(1, |c| c + 2),
                "sample interval",
                format!(
                    "cannot read a sample rate (\"at 100 pts/sec\") or interval (\"SPACED AT .020 SEC\") of at least {MIN_DT:e} s here"
                ),
            ));
        }
    };
    let unit = if upper.contains("UNITS OF G") {
        AccelUnit::G
    } else if upper.contains("CM/SEC/SEC") || upper.contains("CM/SEC2") || upper.contains("CM/S/S")
    {
        AccelUnit::CentimetrePerSecond2
    } else {
        return Err(here(
            1,
            "units",
            "the points line does not say the unit (\"in units of g\" or \"(UNITS: CM/SEC/SEC)\")"
                .into(),
        ));
    };
    let layout = format_in(line).unwrap_or(Layout::new(8, 10));
    Ok(Points {
        npts,
        dt,
        unit,
        layout,
    })
}

/// Station, event and agency from a channel's text header.
fn describe(text: &[&str], volume: &Volume) -> (String, String, String) {
    let squeeze = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
    let station_at = text
        .iter()
        .position(|l| l.trim_start().to_ascii_uppercase().starts_with("STATION"));
    let station = station_at.map_or_else(String::new, |i| {
        let name = text.get(i + 1).map_or("", |l| l.trim());
        let name = if name.to_ascii_uppercase().starts_with("CHAN") {
            ""
        } else {
            name
        };
        squeeze(&format!("{} {}", text[i].trim(), name))
    });
    let event = if volume.level == Level::Uncorrected {
        let record = text[1].split('(').next().unwrap_or("");
        let id = text[3].split_whitespace().next().unwrap_or("");
        squeeze(&format!("{record} {id}"))
    } else {
        squeeze(&format!(
            "{} {}",
            text[2].trim(),
            text[3].split('(').next().unwrap_or("")
        ))
    };
    let agency = text
        .iter()
        .find_map(|l| {
            let upper = l.to_ascii_uppercase();
            let p = upper.find("PROCESSED:")?;
            l[p + 10..]
                .split(',')
                .nth(1)
                .map(|a| a.split_whitespace().next().unwrap_or("").to_string())
        })
        .unwrap_or_default();
    (station, event, agency)
}

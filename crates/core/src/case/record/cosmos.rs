//! COSMOS strong-motion files (format v01.20), V0 (raw), V1 (uncorrected) and V2
//! (corrected), one or more channels a file. A channel: its text header (the first line
//! says "(Format v01.20 with 13 text lines)"), "100 Integer-header values follow on 10
//! lines, Format= (10I8)" and the integers, the same for the reals, "2 Comment line(s)
//! follow", then "7000 acceleration pts, approx 70 secs, units=cm/sec2(04),
//! Format=(8F10.5)" and the samples, and an "End-of-data" line. Integer header value 54
//! is the sensor's azimuth (0–360, 400 up, 401 down), real header value 62 the sample
//! interval in milliseconds; −999 (or the header's own "unknown" value) means not given.

use std::path::Path;

use crate::error::InputError;

use super::fixed::{Layout, format_in, read_block};
use super::station::{Channel, Level, Orientation, StationRecord, is_blank};
use super::token::at;
use super::{AccelUnit, MIN_DT, Record};

/// 1-based integer header value holding the sensor azimuth.
const AZIMUTH_INT: usize = 54;
/// 1-based real header value holding the sample interval, ms.
const INTERVAL_REAL: usize = 62;

/// Parse a COSMOS file of one or more channels.
pub(super) fn parse_cosmos(path: &Path, text: &str) -> Result<StationRecord, InputError> {
    let lines: Vec<&str> = text.lines().collect();
    let first = lines[0].to_ascii_uppercase();
    let (level, format) = if first.starts_with("RAW") {
        (Level::Uncorrected, "COSMOS V0")
    } else if first.starts_with("UNCORRECTED") {
        (Level::Uncorrected, "COSMOS V1")
    } else {
        (Level::Corrected, "COSMOS V2")
    };
    let mut channels = Vec::new();
    let mut start = 0;
    while start < lines.len() && !is_blank(lines[start]) {
        let (channel, next) = channel_block(path, &lines, start)?;
        channels.push(channel);
        start = next;
    }
    let squeeze = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
    let line = |i: usize| lines.get(i).copied().unwrap_or("");
    let agency = line(4)
        .split("Code:")
        .nth(1)
        .and_then(|c| c.split_whitespace().nth(1))
        .unwrap_or("")
        .to_string();
    Ok(StationRecord {
        format,
        station: squeeze(line(4)),
        event: squeeze(line(1)),
        agency,
        level,
        channels,
    })
}

/// A count and layout line: "100 Integer-header values follow on 10 lines, Format= (10I8)".
fn counted(
    path: &Path,
    lines: &[&str],
    i: usize,
    what: &str,
) -> Result<(usize, Layout), InputError> {
    let line = lines.get(i).copied().unwrap_or("");
    let count = line
        .split_whitespace()
        .next()
        .and_then(|w| w.parse::<usize>().ok());
    let layout = format_in(line);
    match (count, layout) {
        (Some(c), Some(l)) => Ok((c, l)),
        _ => {
            let mut e = at(
                path,
                (i + 1).min(lines.len().max(1)),
                Some(1),
                format!(
                    "expected the {what} line (a count, then \"Format= (10I8)\"), found \"{}\"",
                    line.trim()
                ),
            );
            e.field = what.into();
            Err(e)
        }
    }
}

/// One channel from 0-based line `start`: the channel and the line after its end.
fn channel_block(
    path: &Path,
    lines: &[&str],
    start: usize,
) -> Result<(Channel, usize), InputError> {
    let text_lines = text_lines(path, lines[start], start)?;
    let ints_at = start + text_lines;
    let (n_int, int_layout) = counted(path, lines, ints_at, "integer header")?;
    let ints = read_block(
        path,
        lines,
        ints_at + 1,
        n_int,
        int_layout,
        "integer header",
    )?;
    let reals_at = ints_at + 1 + int_layout.lines(n_int);
    let (n_real, real_layout) = counted(path, lines, reals_at, "real header")?;
    let reals = read_block(
        path,
        lines,
        reals_at + 1,
        n_real,
        real_layout,
        "real header",
    )?;
    let comments_at = reals_at + 1 + real_layout.lines(n_real);
    let comments = lines
        .get(comments_at)
        .and_then(|l| l.split_whitespace().next())
        .and_then(|w| w.parse::<usize>().ok())
        .ok_or_else(|| {
            at(
                path,
                comments_at + 1,
                Some(1),
                "expected \"N Comment line(s) follow\"",
            )
        })?;
    let data_at = comments_at + 1 + comments;
    let (npts, layout) = counted(path, lines, data_at, "data")?;
    let unit = data_unit(path, lines, data_at)?;
    let orientation = azimuth(path, ints_at + 1, int_layout, &ints)?;
    let dt = interval(path, reals_at + 1, real_layout, &reals)?;
    let values = read_block(
        path,
        lines,
        data_at + 1,
        npts,
        layout,
        "acceleration values",
    )?;
    let after = data_at + 1 + layout.lines(npts);
    let end = match lines.get(after) {
        Some(l) if l.to_ascii_uppercase().starts_with("END-OF-DATA") || l.starts_with("/&") => {
            after + 1
        }
        _ => after,
    };
    let record = Record {
        dt,
        samples: values.iter().map(|a| a * unit.to_si()).collect(),
        unit,
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

/// The number of text lines the first line states, "(Format v01.20 with 13 text lines)".
fn text_lines(path: &Path, line: &str, start: usize) -> Result<usize, InputError> {
    let upper = line.to_ascii_uppercase();
    let n = upper
        .find("WITH")
        .and_then(|w| upper[w + 4..].split_whitespace().next())
        .and_then(|w| w.parse::<usize>().ok());
    match n {
        Some(n) if n >= 2 => Ok(n),
        _ => {
            let mut e = at(
                path,
                start + 1,
                upper.find("WITH").map(|c| c + 6),
                "expected \"(Format v01.20 with 13 text lines)\": the number of text lines of the channel's header",
            );
            e.field = "text lines".into();
            Err(e)
        }
    }
}

/// The unit of the data line, "units=cm/sec2(04)" or "units=g(02)"; counts (a V0 of raw
/// digitizer counts) are refused: they are not an acceleration until the instrument's
/// response is removed.
fn data_unit(path: &Path, lines: &[&str], i: usize) -> Result<AccelUnit, InputError> {
    let line = lines[i];
    let upper = line.to_ascii_uppercase();
    let at_units = upper.find("UNITS=").or_else(|| upper.find("UNITS ="));
    let said = at_units.map_or("", |u| upper[u..].split('=').nth(1).unwrap_or("").trim());
    let unit = if said.starts_with("CM/SEC2")
        || said.starts_with("CM/S/S")
        || said.starts_with("CM/SEC/SEC")
    {
        Some(AccelUnit::CentimetrePerSecond2)
    } else if said.starts_with("G(") || said.starts_with("G ") || said == "G" {
        Some(AccelUnit::G)
    } else if said.starts_with("M/SEC2") || said.starts_with("M/S/S") {
        Some(AccelUnit::MetrePerSecond2)
    } else {
        None
    };
    unit.ok_or_else(|| {
        let mut e = at(
            path,
            i + 1,
            at_units.map(|c| c + 1),
            format!(
                "the data are in \"{}\", not an acceleration (cm/sec2, g or m/sec2){}",
                said.split(',').next().unwrap_or("").trim(),
                if said.starts_with("COUNTS") {
                    ": a V0 of raw counts needs its instrument response removed; use the V1 or V2 of the record"
                } else {
                    ""
                }
            ),
        );
        e.field = "units".into();
        e
    })
}

/// Where a 1-based header value `k` sits: its line and column.
fn place(first_line: usize, layout: Layout, k: usize) -> (usize, usize) {
    let i = k - 1;
    (
        first_line + i / layout.per_line + 1,
        (i % layout.per_line) * layout.width + 1,
    )
}

/// The sensor's orientation from integer header value [`AZIMUTH_INT`].
fn azimuth(
    path: &Path,
    first: usize,
    layout: Layout,
    ints: &[f64],
) -> Result<Orientation, InputError> {
    let value = ints.get(AZIMUTH_INT - 1).copied();
    let orientation = match value {
        Some(a) if (0.0..=360.0).contains(&a) => Some(Orientation::Azimuth(a)),
        Some(400.0) => Some(Orientation::Up),
        Some(401.0) => Some(Orientation::Down),
        _ => None,
    };
    orientation.ok_or_else(|| {
        let (line, column) = place(first, layout, AZIMUTH_INT.min(ints.len().max(1)));
        let mut e = at(
            path,
            line,
            Some(column),
            format!(
                "integer header value {AZIMUTH_INT} (the sensor azimuth) is {}, but must be 0–360 (degrees from north), 400 (up) or 401 (down)",
                value.map_or("missing".to_string(), |v| v.to_string())
            ),
        );
        e.field = format!("integer header[{AZIMUTH_INT}]");
        e
    })
}

/// The sample interval, s, from real header value [`INTERVAL_REAL`] (ms).
fn interval(path: &Path, first: usize, layout: Layout, reals: &[f64]) -> Result<f64, InputError> {
    let value = reals.get(INTERVAL_REAL - 1).copied();
    match value {
        Some(ms) if ms / 1000.0 >= MIN_DT => Ok(ms / 1000.0),
        _ => {
            let (line, column) = place(first, layout, INTERVAL_REAL.min(reals.len().max(1)));
            let mut e = at(
                path,
                line,
                Some(column),
                format!(
                    "real header value {INTERVAL_REAL} (the sample interval, ms) is {}, but must be at least {} ms",
                    value.map_or("missing".to_string(), |v| v.to_string()),
                    MIN_DT * 1000.0
                ),
            );
            e.field = format!("real header[{INTERVAL_REAL}]");
            Err(e)
        }
    }
}

//! USGS SMC files: one channel a file. Eleven text lines (the first "2 CORRECTED
//! ACCELEROGRAM" or "1 UNCORRECTED ACCELEROGRAM"; the third the station code, the fourth
//! the event, the sixth "station = …, component= 360"), 48 integers as 8I10 on 6 lines,
//! 50 reals as 5E15.7 on 10 lines, the comment lines (integer 16 says how many), then the
//! samples in cm/s² as 8E10. Integer 17 is the number of samples, 13 the vertical
//! orientation (0 up, 180 down, 90 horizontal), 14 the horizontal azimuth; real 2 the
//! sample rate in samples a second; integer 1 and real 1 the "not given" values.

use std::path::Path;

use crate::error::InputError;

use super::fixed::{Layout, read_block};
use super::station::{Channel, Level, Orientation, StationRecord};
use super::token::at;
use super::{AccelUnit, MIN_DT, Record};

const TEXT_LINES: usize = 11;
const INTS: Layout = Layout::new(8, 10);
const REALS: Layout = Layout::new(5, 15);
const SAMPLES: Layout = Layout::new(8, 10);

/// Parse an SMC file.
pub(super) fn parse_smc(path: &Path, text: &str) -> Result<StationRecord, InputError> {
    let lines: Vec<&str> = text.lines().collect();
    let level = if lines[0].trim_start().starts_with('1') {
        Level::Uncorrected
    } else {
        Level::Corrected
    };
    let ints = read_block(path, &lines, TEXT_LINES, 48, INTS, "integer header")?;
    let reals_at = TEXT_LINES + INTS.lines(48);
    let reals = read_block(path, &lines, reals_at, 50, REALS, "real header")?;
    let data_at = reals_at + REALS.lines(50);
    let int_at = |k: usize| {
        let (line, column) = (TEXT_LINES + (k - 1) / 8 + 1, (k - 1) % 8 * 10 + 1);
        move |reason: String| {
            let mut e = at(path, line, Some(column), reason);
            e.field = format!("integer header[{k}]");
            e
        }
    };
    let comments = ints[15];
    if !(0.0..=1e6).contains(&comments) {
        return Err(int_at(16)(format!(
            "the number of comment lines is {comments}: a count of at least 0"
        )));
    }
    let npts = ints[16];
    if npts < 1.0 {
        return Err(int_at(17)(format!(
            "the number of samples is {npts}: at least 1"
        )));
    }
    let rate = reals[1];
    if !(rate > 0.0 && 1.0 / rate >= MIN_DT) || rate == reals[0] {
        let mut e = at(
            path,
            reals_at + 1,
            Some(16),
            format!(
                "the sample rate is {rate} samples/s: a positive rate up to {} samples/s",
                1.0 / MIN_DT
            ),
        );
        e.field = "real header[2]".into();
        return Err(e);
    }
    let orientation = orientation(&ints).ok_or_else(|| {
        int_at(13)(format!(
            "the orientation is vertical {} and horizontal {}: expected 0 (up), 180 (down), or 90 with an azimuth 0–360",
            ints[12], ints[13]
        ))
    })?;
    let start = data_at + comments as usize;
    let values = read_block(
        path,
        &lines,
        start,
        npts as usize,
        SAMPLES,
        "acceleration values",
    )?;
    let unit = AccelUnit::CentimetrePerSecond2;
    let squeeze = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
    let station_line = lines.get(5).copied().unwrap_or("");
    let station = station_line
        .split("component")
        .next()
        .unwrap_or("")
        .trim()
        .trim_start_matches("station =")
        .trim()
        .trim_end_matches(',');
    let code = lines.get(2).map_or("", |l| l.trim());
    let agency = lines
        .get(7)
        .and_then(|l| l.split("data source =").nth(1))
        .map_or("", str::trim);
    Ok(StationRecord {
        format: "USGS SMC",
        station: squeeze(&format!("{code} {station}")),
        event: squeeze(lines.get(3).copied().unwrap_or("")),
        agency: agency.to_string(),
        level,
        channels: vec![Channel {
            orientation,
            record: Record {
                dt: 1.0 / rate,
                samples: values.iter().map(|a| a * unit.to_si()).collect(),
                unit,
                description: squeeze(station_line),
                note: String::new(),
            },
            line: 1,
        }],
    })
}

/// Integer 13 (0 up, 180 down, 90 horizontal) and 14 (the azimuth).
fn orientation(ints: &[f64]) -> Option<Orientation> {
    match (ints[12], ints[13]) {
        (0.0, _) => Some(Orientation::Up),
        (180.0, _) => Some(Orientation::Down),
        (v, a) if v == 90.0 && (0.0..=360.0).contains(&a) => Some(Orientation::Azimuth(a)),
        _ => None,
    }
}

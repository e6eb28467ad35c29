//! PEER NGA `.AT2` files: four header lines (title; event, station; units; NPTS and DT),
//! then the values row by row.

use std::path::Path;

use crate::error::InputError;

use super::token::{at, number, parse_float, strip_bom, tokens};
use super::{AccelUnit, MIN_DT, Record};

/// A number of the fourth AT2 header line and its 1-based column (for errors about it).
#[derive(Debug, Clone, Copy, PartialEq)]
struct HeaderNumber {
    value: f64,
    column: usize,
}

/// NPTS and DT from the fourth AT2 header line, tolerant of its historical layouts:
/// `NPTS=  3930, DT= .00500 SEC` (NGA), `NPTS= 3930 DT= 0.005` (no comma),
/// `3930   .0050   NPTS, DT` (older PEER), case-insensitive, `DT=.005SEC` glued. A value
/// that is not finite is returned as read, for the caller to refuse by name.
fn npts_dt(line: &str) -> Option<(HeaderNumber, HeaderNumber)> {
    let words = header_words(line);
    let number = |i: usize| {
        let (offset, word) = words.get(i)?;
        parse_float(word).map(|value| HeaderNumber {
            value,
            column: line[..*offset].chars().count() + 1,
        })
    };
    let position = |key: &str| words.iter().position(|(_, w)| w == key);
    let after = |key: &str| position(key).and_then(|i| number(i + 1));
    if let (Some(n), Some(dt)) = (after("NPTS"), after("DT")) {
        return Some((n, dt));
    }
    // Older layout: the two numbers first, then the keywords "NPTS, DT" in that order.
    let numbers: Vec<HeaderNumber> = (0..words.len()).filter_map(number).collect();
    if numbers.len() == 2 && position("NPTS")? < position("DT")? {
        return Some((numbers[0], numbers[1]));
    }
    None
}

/// The words of the fourth header line, upper-cased, with their byte offsets: split on
/// whitespace, `=`, `,` and `:`; a unit glued to a number ("0.005SEC") cut off.
fn header_words(line: &str) -> Vec<(usize, String)> {
    let mut words = Vec::new();
    let mut push = |start: usize, end: usize| {
        let upper = line[start..end].to_ascii_uppercase();
        // "NPTS3930" is not a layout anyone wrote; "0.005SEC" is.
        let w = upper.trim_end_matches("SECONDS").trim_end_matches("SEC");
        if !w.is_empty() {
            words.push((start, w.to_string()));
        }
    };
    let mut start = None;
    for (i, c) in line.char_indices() {
        let separator = c.is_whitespace() || matches!(c, '=' | ',' | ':');
        match (separator, start) {
            (true, Some(s)) => {
                push(s, i);
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(s) = start {
        push(s, line.len());
    }
    words
}

/// Parse the text of a PEER NGA `.AT2` file: four header lines (title; event, date,
/// station, component; units; NPTS and DT), then the values row by row.
pub fn parse_at2(path: &Path, text: &str, unit: Option<AccelUnit>) -> Result<Record, InputError> {
    let text = strip_bom(text);
    let lines: Vec<&str> = text.lines().collect();
    if text.trim().is_empty() {
        return Err(at(
            path,
            1,
            None,
            "the file is empty: expected the four PEER header lines (title; event, station; units; NPTS and DT) and the values",
        ));
    }
    if lines.len() < 4 {
        return Err(at(
            path,
            lines.len(),
            None,
            format!(
                "the PEER header has four lines (title; event, station; units; NPTS and DT), but the file has only {}",
                lines.len()
            ),
        ));
    }
    let unit = at2_unit(path, lines[2], unit)?;
    let (npts, dt, npts_column) = at2_npts_dt(path, text, lines[3])?;
    let at_npts = |reason: String| at(path, 4, Some(npts_column), reason);
    let mut samples = Vec::with_capacity(npts);
    let mut last_line = 4;
    for (i, line) in lines.iter().enumerate().skip(4) {
        let line_no = i + 1;
        for (col, tok) in tokens(line) {
            let x = number(path, line_no, col, tok)?;
            if samples.len() == npts {
                return Err(at(
                    path,
                    line_no,
                    Some(col),
                    format!(
                        "more values than NPTS = {npts} (line 4): value {} is here",
                        npts + 1
                    ),
                ));
            }
            samples.push(x * unit.to_si());
            last_line = line_no;
        }
    }
    if samples.is_empty() {
        return Err(at_npts(format!(
            "the record has no values, but NPTS = {npts}"
        )));
    }
    if samples.len() != npts {
        return Err(at_npts(format!(
            "NPTS = {npts}, but the file has {} values (the last on line {last_line})",
            samples.len()
        )));
    }
    Ok(Record {
        dt,
        samples,
        unit,
        description: lines[1].trim().to_string(),
        note: String::new(),
    })
}

/// The unit of a PEER record: its header's units line (line 3) and the case's
/// `record_unit`, which must agree when both say one.
fn at2_unit(
    path: &Path,
    units_line: &str,
    unit: Option<AccelUnit>,
) -> Result<AccelUnit, InputError> {
    let upper = units_line.to_ascii_uppercase();
    let header_unit = if upper.contains("CM/S") || upper.contains("GAL") {
        Some(AccelUnit::CentimetrePerSecond2)
    } else if upper.contains("M/S") {
        Some(AccelUnit::MetrePerSecond2)
    } else if upper.contains("UNITS OF G") || upper.split_whitespace().last() == Some("G") {
        Some(AccelUnit::G)
    } else {
        None
    };
    match (header_unit, unit) {
        (Some(h), Some(u)) if h != u => Err(at(
            path,
            3,
            None,
            format!(
                "the header says the values are in {}, but the case's record_unit says {}",
                h.name(),
                u.name()
            ),
        )),
        (Some(h), _) => Ok(h),
        (None, Some(u)) => Ok(u),
        (None, None) => Err(at(
            path,
            3,
            None,
            format!(
                "cannot tell the unit from the header's units line \"{}\" (expected e.g. \"ACCELERATION TIME HISTORY IN UNITS OF G\"); give `record_unit`",
                units_line.trim()
            ),
        )),
    }
}

/// NPTS and DT of a PEER record's line 4, checked (a whole NPTS the file can hold, a
/// positive DT of at least [`MIN_DT`]): NPTS, DT and the column of NPTS.
fn at2_npts_dt(path: &Path, text: &str, line: &str) -> Result<(usize, f64, usize), InputError> {
    let Some((npts_at, dt_at)) = npts_dt(line) else {
        return Err(at(
            path,
            4,
            None,
            format!(
                "cannot read NPTS and DT from \"{}\" (expected e.g. \"NPTS=  3930, DT= .00500 SEC\")",
                line.trim()
            ),
        ));
    };
    let (npts, dt) = (npts_at.value, dt_at.value);
    let at_npts = |reason: String| at(path, 4, Some(npts_at.column), reason);
    if !(npts >= 1.0 && npts.fract() == 0.0) {
        return Err(at_npts(format!(
            "NPTS is {npts}, but must be a whole number of at least 1"
        )));
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(at(
            path,
            4,
            Some(dt_at.column),
            format!("DT is {dt} s, but must be a positive finite number"),
        ));
    }
    if dt < MIN_DT {
        return Err(at(
            path,
            4,
            Some(dt_at.column),
            format!("DT is {dt:e} s, below the smallest sample interval accepted ({MIN_DT:e} s)"),
        ));
    }
    // Each value takes at least two bytes (a digit and a separator): a larger NPTS cannot
    // be right, and must not be allocated.
    let room = text.len().div_ceil(2) as f64;
    if npts > room {
        return Err(at_npts(format!(
            "NPTS = {npts}, but the file ({} bytes) cannot hold more than {room} values",
            text.len()
        )));
    }
    Ok((npts as usize, dt, npts_at.column))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fourth_header_line_variants() {
        for (line, n, dt) in [
            ("NPTS=  3930, DT= .00500 SEC", 3930.0, 0.005),
            ("NPTS= 11177, DT= 0.0050 SEC", 11177.0, 0.005),
            ("npts=100 dt=0.01", 100.0, 0.01),
            ("NPTS = 2000, DT = .0100 SEC,", 2000.0, 0.01),
            ("  4000   .0100   NPTS, DT", 4000.0, 0.01),
            ("NPTS=  3930, DT=.00500SEC", 3930.0, 0.005),
        ] {
            let (npts, step) = npts_dt(line).unwrap_or_else(|| panic!("{line}"));
            assert_eq!((npts.value, step.value), (n, dt), "{line}");
        }
        assert_eq!(npts_dt("DT= 0.01"), None);
        // Columns of the values, for errors about them (1-based, in characters).
        let (n, dt) = npts_dt("NPTS=  3930, DT= .00500 SEC").unwrap();
        assert_eq!((n.column, dt.column), (8, 18));
        let (n, dt) = npts_dt("  4000   .0100   NPTS, DT").unwrap();
        assert_eq!((n.column, dt.column), (3, 10));
    }
}

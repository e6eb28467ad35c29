//! Results produced by another program, read as a [`Trace`]: rockslide's own trace CSV
//! (`time [s],rel_disp [m],…`, in any unit the catalogue's quantities accept — `mm`, `kN`,
//! `ms`, `deg`…), a CSV with foreign headers and a column map saying what each column is
//! (`"U1 (mm)" = "rel_disp [mm]"`), or a state topic of a rockslide MCAP file.
//!
//! Values are converted to SI on reading (`value × mul / div`, exact for SI columns, so a
//! trace written by rockslide reads back bit for bit). Sizes are checked before anything
//! is allocated: the file's bytes ([`MAX_EXTERNAL_BYTES`]), its columns
//! ([`MAX_EXTERNAL_COLUMNS`]) and rows ([`limits::max_steps`]). Every problem
//! is an input error naming the file, line, column and reason.

use std::path::Path;

use rockslide_core::case::limits;
use rockslide_core::case::{ExternalFormat, ExternalTrace};
use rockslide_core::error::{InputError, InputErrors, io_reason, line_col};
use rockslide_core::trace::{ColumnKind, ColumnMeaning, Quantity, Trace, Unit, parse_header};

use crate::mcap_file::{read_bounded, read_mcap};

/// Largest external results file read, bytes (256 MiB).
pub const MAX_EXTERNAL_BYTES: u64 = 256 << 20;

/// Most columns an external CSV may have.
pub const MAX_EXTERNAL_COLUMNS: usize = 1024;

/// Read an external results file: an MCAP file (by extension `.mcap`) or a CSV.
pub fn read_external(path: &Path, format: &ExternalFormat) -> Result<ExternalTrace, InputErrors> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
    {
        return read_external_mcap(path, format.topic.as_deref());
    }
    let bytes = read_bounded(path, MAX_EXTERNAL_BYTES).map_err(|e| {
        let why = io_reason(&e);
        InputError::new(path, "", format!("cannot read the results file: {why}"))
    })?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let (line, col) = line_col(
            &String::from_utf8_lossy(&e.as_bytes()[..e.utf8_error().valid_up_to()]),
            usize::MAX,
        );
        InputError::new(path, "", "is not UTF-8 text").at(line, col)
    })?;
    // a byte-order mark, as spreadsheet programs write it, is not part of the first header
    read_external_csv(path, text.strip_prefix('\u{feff}').unwrap_or(&text), format)
}

/// The state topic of a rockslide MCAP file as an external trace.
fn read_external_mcap(path: &Path, topic: Option<&str>) -> Result<ExternalTrace, InputErrors> {
    let contents = read_mcap(path)?;
    let candidates: Vec<&(String, Trace)> = contents
        .states
        .iter()
        .filter(|(t, _)| t != "/reference/state")
        .collect();
    let chosen = match topic {
        Some(t) => contents.states.iter().find(|(name, _)| name == t),
        None if candidates.len() == 1 => Some(candidates[0]),
        None => None,
    };
    let Some((name, trace)) = chosen else {
        let topics: Vec<&str> = contents.states.iter().map(|(t, _)| t.as_str()).collect();
        let what = match topic {
            Some(t) => format!("has no state topic \"{t}\""),
            None => format!(
                "has several state topics: name one (`{}#<topic>` on the command line, `topic = \"<topic>\"` in an [[external]] section)",
                path.display()
            ),
        };
        return Err(InputError::new(
            path,
            "topic",
            format!("{what}; its state topics: {}", topics.join(", ")),
        )
        .into());
    };
    if trace.is_empty() {
        return Err(InputError::new(path, "topic", format!("\"{name}\" has no messages")).into());
    }
    check_times(path, name, &trace.time)?;
    // the state alone, as from a CSV file: the contacts its messages carry stay out
    let notes = vec![format!(
        "rockslide MCAP topic {name}, {} samples",
        trace.len()
    )];
    let mut trace = trace.clone();
    trace.contacts = Default::default();
    Ok(ExternalTrace { trace, notes })
}

/// The fields of a line: each one's text (surrounding double quotes removed) and 1-based
/// character column. With `' '` as delimiter, runs of blanks separate fields (a header
/// with blanks in it is then quoted).
fn split_fields(line: &str, delimiter: char) -> Vec<(String, usize)> {
    let blanks = delimiter == ' ';
    let separates = |c: char| {
        if blanks {
            c == ' ' || c == '\t'
        } else {
            c == delimiter
        }
    };
    let chars: Vec<char> = line.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    loop {
        while blanks && i < chars.len() && separates(chars[i]) {
            i += 1;
        }
        if blanks && i == chars.len() {
            return out;
        }
        let start = i + 1;
        let mut field = String::new();
        let mut quoted = false;
        while i < chars.len() {
            let c = chars[i];
            if quoted {
                if c == '"' {
                    quoted = false;
                } else {
                    field.push(c);
                }
            } else if separates(c) {
                break;
            } else if c == '"' && field.trim().is_empty() {
                quoted = true;
            } else {
                field.push(c);
            }
            i += 1;
        }
        out.push((field, start));
        if i == chars.len() {
            return out;
        }
        i += 1; // the delimiter
    }
}

/// Whether a line carries no data: blank, or a `#` comment.
fn is_blank(line: &str) -> bool {
    let t = line.trim();
    t.is_empty() || t.starts_with('#')
}

/// Read a CSV results file from its text (see the module docs).
pub fn read_external_csv(
    path: &Path,
    text: &str,
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    let delimiter = format.delimiter.unwrap_or(',');
    let mut lines = text
        .lines()
        .enumerate()
        .skip(format.skip_lines)
        .filter(|(_, l)| !is_blank(l));
    let Some((header_index, header_line)) = lines.next() else {
        return Err(InputError::new(path, "", "has no header line (the file is empty)").into());
    };
    let header_line_no = header_index + 1;
    let headers = split_fields(header_line.trim_end_matches('\r'), delimiter);
    if headers.len() > MAX_EXTERNAL_COLUMNS {
        return Err(InputError::new(
            path,
            "",
            format!(
                "has {} columns; the limit is {MAX_EXTERNAL_COLUMNS}",
                headers.len()
            ),
        )
        .at(header_line_no, 1)
        .into());
    }
    let (meanings, mut notes) = column_meanings(path, header_line_no, &headers, format)?;
    let (time_index, channels) = time_and_channels(path, header_line_no, &meanings)?;
    let quantities: Vec<&'static Quantity> = channels.iter().map(|c| c.1).collect();
    let mut trace = Trace::with_channels(&quantities, 0);
    let mut values = vec![0.0; channels.len()];
    let max_rows = limits::max_steps();
    let time_unit = meanings[time_index].expect("time column").unit;
    for (index, raw) in lines {
        let line_no = index + 1;
        if trace.len() as u64 >= max_rows {
            return Err(InputError::new(
                path,
                "",
                format!(
                    "has more than {max_rows} rows (set {} to raise the limit)",
                    limits::MAX_STEPS_VARIABLE
                ),
            )
            .at(line_no, 1)
            .into());
        }
        let fields = split_fields(raw.trim_end_matches('\r'), delimiter);
        if fields.len() != headers.len() {
            let col = fields.last().map_or(1, |f| f.1);
            return Err(InputError::new(
                path,
                "",
                format!(
                    "has {} fields, but the header (line {header_line_no}) has {}",
                    fields.len(),
                    headers.len()
                ),
            )
            .at(line_no, col)
            .into());
        }
        let number = |i: usize| parse_value(path, line_no, &headers[i].0, &fields[i]);
        let t = time_unit.to_si(number(time_index)?);
        for (v, (i, _, unit)) in values.iter_mut().zip(&channels) {
            *v = unit.to_si(number(*i)?);
        }
        if let Some(&last) = trace.time.last()
            && t <= last
        {
            return Err(InputError::new(
                path,
                "",
                format!("time {t} s does not increase (the row before is at {last} s)"),
            )
            .at(line_no, fields[time_index].1)
            .into());
        }
        trace.push(t, &values);
    }
    if trace.is_empty() {
        return Err(InputError::new(path, "", "has a header but no data rows")
            .at(header_line_no, 1)
            .into());
    }
    notes.insert(0, format!("CSV, {} rows", trace.len()));
    Ok(ExternalTrace { trace, notes })
}

/// A column's index, quantity and unit.
type Channel = (usize, &'static Quantity, Unit);

/// The time column's index and the quantity columns of a header's `meanings` (line
/// `header_line_no`); no time column is an error.
fn time_and_channels(
    path: &Path,
    header_line_no: usize,
    meanings: &[Option<ColumnMeaning>],
) -> Result<(usize, Vec<Channel>), InputError> {
    let time_index = meanings
        .iter()
        .position(|m| m.is_some_and(|m| m.kind == ColumnKind::Time))
        .ok_or_else(|| {
            InputError::new(
                path,
                "",
                "has no time column (a rockslide header `time [s]`, or a column mapped to it)",
            )
            .at(header_line_no, 1)
        })?;
    let channels: Vec<Channel> = meanings
        .iter()
        .enumerate()
        .filter_map(|(i, m)| match m {
            Some(ColumnMeaning {
                kind: ColumnKind::Quantity(q),
                unit,
            }) => Some((i, *q, *unit)),
            _ => None,
        })
        .collect();
    Ok((time_index, channels))
}

/// The meaning of each column (`None`: ignored) and notes on units and ignored columns.
type Meanings = (Vec<Option<ColumnMeaning>>, Vec<String>);

fn column_meanings(
    path: &Path,
    line: usize,
    headers: &[(String, usize)],
    format: &ExternalFormat,
) -> Result<Meanings, InputErrors> {
    let mut meanings = Vec::with_capacity(headers.len());
    let (mut errors, mut ignored, mut converted) = (Vec::new(), Vec::new(), Vec::new());
    for (text, col) in headers {
        let target = if format.columns.is_empty() {
            Some(text.as_str())
        } else {
            format
                .columns
                .iter()
                .find(|(from, _)| from.trim() == text.trim())
                .map(|(_, to)| to.as_str())
        };
        let Some(target) = target else {
            ignored.push(format!("\"{text}\""));
            meanings.push(None);
            continue;
        };
        match parse_header(target) {
            Ok(m) => {
                if meanings
                    .iter()
                    .flatten()
                    .any(|o: &ColumnMeaning| o.key() == m.key())
                {
                    errors.push(
                        InputError::new(
                            path,
                            "",
                            format!("\"{text}\": a second {} column", m.key()),
                        )
                        .at(line, *col),
                    );
                }
                if m.unit.mul != 1.0 || m.unit.div != 1.0 {
                    converted.push(format!("{} [{}]", m.key(), m.unit.name));
                }
                meanings.push(Some(m));
            }
            Err(why) => {
                let reason = if format.columns.is_empty() {
                    format!("column header {why} (give a column map for foreign headers)")
                } else {
                    format!("column \"{text}\" mapped to {why}")
                };
                errors.push(InputError::new(path, "", reason).at(line, *col));
                meanings.push(None);
            }
        }
    }
    for (from, _) in &format.columns {
        if !headers.iter().any(|(h, _)| h.trim() == from.trim()) {
            errors.push(
                InputError::new(
                    path,
                    "",
                    format!("the column map names \"{from}\", but the header has no such column"),
                )
                .at(line, 1),
            );
        }
    }
    if !errors.is_empty() {
        return Err(InputErrors(errors));
    }
    let mut notes = Vec::new();
    if !converted.is_empty() {
        notes.push(format!("converted to SI: {}", converted.join(", ")));
    }
    if !ignored.is_empty() {
        notes.push(format!("columns ignored: {}", ignored.join(", ")));
    }
    Ok((meanings, notes))
}

/// One field as a finite number, or an error at its line and column.
fn parse_value(
    path: &Path,
    line: usize,
    header: &str,
    field: &(String, usize),
) -> Result<f64, InputError> {
    let (text, col) = field;
    let at = |reason: String| InputError::new(path, "", reason).at(line, *col);
    let s = text.trim();
    if s.is_empty() {
        return Err(at(format!(
            "column \"{header}\": empty value (a missing value is not zero)"
        )));
    }
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(at(format!(
            "column \"{header}\": \"{s}\" is not a finite number"
        ))),
        Err(_) => Err(at(format!("column \"{header}\": \"{s}\" is not a number"))),
    }
}

/// Times of an MCAP topic must be finite and strictly increasing (message `i`, 1-based).
fn check_times(path: &Path, topic: &str, time: &[f64]) -> Result<(), InputErrors> {
    for i in 0..time.len() {
        if !(time[i].is_finite() && (i == 0 || time[i] > time[i - 1])) {
            return Err(InputError::new(
                path,
                "topic",
                format!(
                    "{topic}: message {}: time {} s does not increase",
                    i + 1,
                    time[i]
                ),
            )
            .into());
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fmt(columns: &[(&str, &str)]) -> ExternalFormat {
        ExternalFormat {
            columns: columns
                .iter()
                .map(|(a, b)| (a.to_string(), b.to_string()))
                .collect(),
            ..Default::default()
        }
    }

    #[test]
    fn rockslide_headers_read_in_si_bit_for_bit() {
        let text = "time [s],rel_disp [m],slide [m]\n0,0,0\n0.1,0.0123456789012345,1e-300\n";
        let t = read_external_csv(Path::new("x.csv"), text, &ExternalFormat::default()).unwrap();
        assert_eq!(t.trace.time, vec![0.0, 0.1]);
        assert_eq!(t.trace.column("rel_disp").unwrap()[1], 0.0123456789012345);
        assert_eq!(t.trace.column("slide").unwrap()[1], 1e-300);
    }

    #[test]
    fn units_convert_by_division_for_sub_units() {
        let text = "time [ms],rel_disp [mm],resistance [kN],rotation [deg]\n0,12.5,2,180\n";
        let t = read_external_csv(Path::new("x.csv"), text, &ExternalFormat::default()).unwrap();
        assert_eq!(t.trace.column("rel_disp").unwrap()[0], 0.0125);
        assert_eq!(t.trace.column("resistance").unwrap()[0], 2000.0);
        assert_eq!(t.trace.column("rotation").unwrap()[0], std::f64::consts::PI);
    }

    #[test]
    fn a_column_map_reads_foreign_headers_and_lists_the_ignored() {
        let text = "TABLE: link\n\"Time (sec)\";U1 (mm);Note\n0;1.5;a\n0.01;2;b\n";
        let mut f = fmt(&[("Time (sec)", "time [s]"), ("U1 (mm)", "rel_disp [mm]")]);
        f.delimiter = Some(';');
        f.skip_lines = 1;
        let t = read_external_csv(Path::new("x.csv"), text, &f).unwrap();
        assert_eq!(t.trace.column("rel_disp").unwrap(), &[0.0015, 0.002]);
        assert!(
            t.notes.iter().any(|n| n.contains("\"Note\"")),
            "{:?}",
            t.notes
        );
    }

    #[test]
    fn blank_separated_columns() {
        let text = "  \"time [s]\"   \"slide [mm]\"\n 0  1\n 1e-3\t  2.5 \n";
        let f = ExternalFormat {
            delimiter: Some(' '),
            ..Default::default()
        };
        let t = read_external_csv(Path::new("x.csv"), text, &f).unwrap();
        assert_eq!(t.trace.column("slide").unwrap(), &[0.001, 0.0025]);
    }

    #[test]
    fn a_byte_order_mark_is_not_part_of_the_first_header() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bom.csv");
        std::fs::write(&path, "\u{feff}time [s],slide [mm]\r\n0,1\r\n").unwrap();
        let t = read_external(&path, &ExternalFormat::default()).unwrap();
        assert_eq!(t.trace.column("slide").unwrap(), &[0.001]);
    }

    #[test]
    fn errors_name_line_and_column() {
        let p = Path::new("r.csv");
        let e = |text: &str| {
            read_external_csv(p, text, &ExternalFormat::default())
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            e("time [s],slide [m]\n0,0\n1,x\n"),
            "r.csv:3:3: column \"slide [m]\": \"x\" is not a number"
        );
        assert_eq!(
            e("time [s],slide [m]\n0,0\n1,\n"),
            "r.csv:3:3: column \"slide [m]\": empty value (a missing value is not zero)"
        );
        assert_eq!(
            e("time [s],slide [m]\n0,0\n0,1\n"),
            "r.csv:3:1: time 0 s does not increase (the row before is at 0 s)"
        );
        assert_eq!(
            e("time [s],slide [m]\n0,0,3\n"),
            "r.csv:2:5: has 3 fields, but the header (line 1) has 2"
        );
        assert!(e("time [s],slide [kN]\n0,0\n").starts_with(
            "r.csv:1:10: column header \"slide\" cannot be in [kN]; accepted: [m], [mm]"
        ));
        assert!(e("slide [m]\n0\n").starts_with("r.csv:1:1: has no time column"));
        assert!(e("").contains("has no header line"));
    }
}

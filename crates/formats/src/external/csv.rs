//! CSV results files: rockslide's own headers (`time [s],rel_disp [mm],…`, any catalogued
//! unit), or foreign headers with a column map (`"U1 (mm)" = "rel_disp [mm]"`, a factor
//! where the program's sign or scale differs); `,`, `;`, tab or blank separators, decimal
//! commas where the separator is not a comma, blank and `#` lines skipped.

use std::path::Path;

use rockslide_core::case::limits;
use rockslide_core::case::{ColumnMap, ExternalFormat, ExternalTrace};
use rockslide_core::error::{InputError, InputErrors};
use rockslide_core::trace::{ColumnKind, ColumnMeaning, Quantity, Trace, Unit, parse_header};

use super::MAX_EXTERNAL_COLUMNS;
use super::number::{Decimal, parse_number};

/// The fields of a line: each one's text (surrounding double quotes removed) and 1-based
/// character column. With `' '` as delimiter, runs of blanks separate fields (a header
/// with blanks in it is then quoted).
pub(super) fn split_fields(line: &str, delimiter: char) -> Vec<(String, usize)> {
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
pub(super) fn is_blank(line: &str) -> bool {
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
    let decimal = Decimal::for_delimiter(delimiter);
    let mut commas = false;
    let time_unit = meanings[time_index].expect("time column").0.unit;
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
        let mut number = |i: usize| {
            let (x, comma) = parse_value(path, line_no, &headers[i].0, &fields[i], decimal)?;
            commas |= comma;
            Ok::<f64, InputError>(x)
        };
        let t = time_unit.to_si(number(time_index)?);
        for (v, (i, _, unit, scale)) in values.iter_mut().zip(&channels) {
            *v = unit.to_si(scaled(number(*i)?, *scale));
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
    if commas {
        notes.push("decimal commas read as decimal points".into());
    }
    notes.insert(0, format!("CSV, {} rows", trace.len()));
    Ok(ExternalTrace { trace, notes })
}

/// A column's index, quantity, unit and the map's factor.
type Channel = (usize, &'static Quantity, Unit, f64);

/// A value times the map's factor (exactly the value at factor 1).
pub(super) fn scaled(value: f64, scale: f64) -> f64 {
    if scale == 1.0 { value } else { value * scale }
}

/// The time column's index and the quantity columns of a header's `meanings` (line
/// `header_line_no`); no time column is an error.
fn time_and_channels(
    path: &Path,
    header_line_no: usize,
    meanings: &[Option<Meaning>],
) -> Result<(usize, Vec<Channel>), InputError> {
    let time_index = meanings
        .iter()
        .position(|m| m.is_some_and(|m| m.0.kind == ColumnKind::Time))
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
            Some((
                ColumnMeaning {
                    kind: ColumnKind::Quantity(q),
                    unit,
                },
                scale,
            )) => Some((i, *q, *unit, *scale)),
            _ => None,
        })
        .collect();
    Ok((time_index, channels))
}

/// A column's meaning and the map's factor on it.
type Meaning = (ColumnMeaning, f64);

/// The meaning of each column (`None`: ignored) and notes on units and ignored columns.
type Meanings = (Vec<Option<Meaning>>, Vec<String>);

fn column_meanings(
    path: &Path,
    line: usize,
    headers: &[(String, usize)],
    format: &ExternalFormat,
) -> Result<Meanings, InputErrors> {
    let mut meanings: Vec<Option<Meaning>> = Vec::with_capacity(headers.len());
    let (mut errors, mut ignored, mut converted) = (Vec::new(), Vec::new(), Vec::new());
    let mut factors = Vec::new();
    for (text, col) in headers {
        let target = if format.columns.is_empty() {
            Some((text.as_str(), 1.0))
        } else {
            format
                .columns
                .iter()
                .find(|c| c.from.trim() == text.trim())
                .map(|c| (c.to.as_str(), c.scale))
        };
        let Some((target, scale)) = target else {
            ignored.push(format!("\"{text}\""));
            meanings.push(None);
            continue;
        };
        match parse_header(target) {
            Ok(m) => {
                if meanings.iter().flatten().any(|o| o.0.key() == m.key()) {
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
                if scale != 1.0 {
                    factors.push(factor_note(text, scale, m.key()));
                }
                meanings.push(Some((m, scale)));
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
    errors.extend(unmatched(path, line, headers, &format.columns));
    if !errors.is_empty() {
        return Err(InputErrors(errors));
    }
    let mut notes = Vec::new();
    if !converted.is_empty() {
        notes.push(format!("converted to SI: {}", converted.join(", ")));
    }
    if !factors.is_empty() {
        notes.push(format!("sign and scale: {}", factors.join(", ")));
    }
    if !ignored.is_empty() {
        notes.push(format!("columns ignored: {}", ignored.join(", ")));
    }
    Ok((meanings, notes))
}

/// The map's factor in words: `"P" × -1 → normal`.
pub(super) fn factor_note(column: &str, scale: f64, key: &str) -> String {
    format!("\"{column}\" × {scale} → {key}")
}

/// An error for each map entry that names no column of the header.
fn unmatched(
    path: &Path,
    line: usize,
    headers: &[(String, usize)],
    columns: &[ColumnMap],
) -> Vec<InputError> {
    columns
        .iter()
        .filter(|c| !headers.iter().any(|(h, _)| h.trim() == c.from.trim()))
        .map(|c| {
            let from = &c.from;
            InputError::new(
                path,
                "",
                format!("the column map names \"{from}\", but the header has no such column"),
            )
            .at(line, 1)
        })
        .collect()
}

/// One field as a finite number (and whether it was written with a decimal comma), or an
/// error at its line and column.
fn parse_value(
    path: &Path,
    line: usize,
    header: &str,
    field: &(String, usize),
    decimal: Decimal,
) -> Result<(f64, bool), InputError> {
    let (text, col) = field;
    parse_number(text, decimal).map_err(|why| {
        InputError::new(path, "", format!("column \"{header}\": {why}")).at(line, *col)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::external::read_external;

    fn fmt(columns: &[(&str, &str)]) -> ExternalFormat {
        ExternalFormat {
            columns: columns
                .iter()
                .map(|(a, b)| ColumnMap::new(*a, *b))
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

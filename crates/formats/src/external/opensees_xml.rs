//! OpenSees recorder files written with `-xml` and `-binary`, in the layouts OpenSees's
//! output streams write (its sources: `XmlFileStream`, `BinaryFileStream`, and the
//! `NodeRecorder`/`ElementRecorder` that describe their columns to them).
//!
//! `-xml`: an `<OpenSees>` document whose header names the columns — `<TimeOutput>` with
//! `<ResponseType>time</ResponseType>` (with `-time`), then per node `<NodeOutput
//! nodeTag="2" …>` and per element `<ElementOutput eleTag="1" …>` with one
//! `<ResponseType>` per column (`D1`, `Px_1`, …) — and a `<Data>` element whose lines are
//! the rows, blank-separated. Columns are named `"node 2 D1"`, `"element 1 Px_1"`.
//!
//! `-binary`: no header; each row the values as 8-byte IEEE doubles in the machine's byte
//! order (little-endian on the x86 and ARM machines OpenSees runs on) followed by a line
//! feed. The row's width comes from the recorder command (`recorder` or `script`), else
//! from the file (the one width whose rows all end in a line feed); the columns are named
//! as for a text recorder file.

use std::path::Path;

use rockslide_core::case::{ExternalFormat, ExternalTrace};
use rockslide_core::error::{InputError, InputErrors};

use super::ansys::words;
use super::number::{Decimal, parse_number};
use super::sheet::Sheet;

/// Whether a recorder file's text is an `-xml` document.
pub(super) fn is_xml(text: &str) -> bool {
    text.trim_start().starts_with("<?xml")
}

/// The value of attribute `name` in a start tag's text (`nodeTag="2"`).
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let at = tag.find(&format!("{name}=\""))? + name.len() + 2;
    let rest = &tag[at..];
    Some(&rest[..rest.find('"')?])
}

/// A column the header names: its name and where (line, column).
type ColumnName = (String, usize, usize);

/// Read an `-xml` recorder file (see the module docs).
pub(super) fn read_xml(
    path: &Path,
    text: &str,
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    let mut sheet = Sheet::new(path, "OpenSees -xml recorder file", "time");
    let (names, first) = column_names(&sheet, text)?;
    sheet.notes.push(format!(
        "OpenSees -xml recorder: {} columns named by the file ({})",
        names.len() - 1,
        names[1..]
            .iter()
            .map(|n| format!("\"{}\"", n.0))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    let series: Vec<usize> = names[1..]
        .iter()
        .map(|(n, l, c)| sheet.series(n, None, (*l, *c)))
        .collect();
    read_data_rows(&mut sheet, text, first, names.len(), &series)?;
    sheet.assemble(format)
}

/// The header's column names, time first, and the index of the first line after `<Data>`.
fn column_names(sheet: &Sheet, text: &str) -> Result<(Vec<ColumnName>, usize), InputError> {
    let mut names: Vec<ColumnName> = Vec::new();
    let mut object: Option<String> = None;
    let mut data_from = None;
    for (index, raw) in text.lines().enumerate() {
        let at = (index + 1, raw.len() - raw.trim_start().len() + 1);
        let line = raw.trim();
        if line.starts_with("<Data") {
            data_from = Some(index + 1);
            break;
        }
        if line.starts_with("<TimeOutput") {
            object = Some(String::new());
        } else if line.starts_with("<NodeOutput") || line.starts_with("<ElementOutput") {
            object = Some(output_object(sheet, line, at)?);
        } else if let Some(rest) = line.strip_prefix("<ResponseType>") {
            let name = response_name(sheet, rest, object.as_deref(), at)?;
            names.push((name, at.0, at.1));
        }
    }
    let Some(first) = data_from else {
        let why = "has no <Data> element: an OpenSees -xml recorder file names its columns, then holds its rows in <Data>";
        return Err(sheet.error((1, 1), why));
    };
    if names.first().map(|n| n.0.as_str()) != Some("time") {
        let why = "its columns start with no <TimeOutput>: add `-time` to the recorder";
        return Err(sheet.error((1, 1), why));
    }
    Ok((names, first))
}

/// `"node 2"` or `"element 1"` from a `<NodeOutput nodeTag="2" …>` or `<ElementOutput
/// eleTag="1" …>` line.
fn output_object(sheet: &Sheet, line: &str, at: (usize, usize)) -> Result<String, InputError> {
    let (kind, key) = if line.starts_with("<NodeOutput") {
        ("node", "nodeTag")
    } else {
        ("element", "eleTag")
    };
    match attribute(line, key) {
        Some(tag) => Ok(format!("{kind} {tag}")),
        None => {
            let why = format!(
                "<{}> has no {key} attribute",
                &line[1..line.find([' ', '>']).unwrap_or(line.len())]
            );
            Err(sheet.error(at, why))
        }
    }
}

/// A column's name from the text after `<ResponseType>`, prefixed by its object.
fn response_name(
    sheet: &Sheet,
    rest: &str,
    object: Option<&str>,
    at: (usize, usize),
) -> Result<String, InputError> {
    let Some(end) = rest.find("</ResponseType>") else {
        return Err(sheet.error(at, "<ResponseType> is not closed on its line"));
    };
    let response = rest[..end].trim();
    match object {
        Some("") => Ok(response.to_string()),
        Some(o) => Ok(format!("{o} {response}")),
        None => {
            let why = "a <ResponseType> outside <TimeOutput>, <NodeOutput> or <ElementOutput>";
            Err(sheet.error(at, why))
        }
    }
}

/// The rows inside `<Data>`, from line index `first` to `</Data>`, into `series`.
fn read_data_rows(
    sheet: &mut Sheet,
    text: &str,
    first: usize,
    width: usize,
    series: &[usize],
) -> Result<(), InputError> {
    for (index, raw) in text.lines().enumerate().skip(first) {
        let line_no = index + 1;
        let line = raw.trim_end_matches('\r');
        if line.trim_start().starts_with("</Data>") {
            return Ok(());
        }
        let w = words(line);
        if w.is_empty() {
            continue;
        }
        if w.len() != width {
            let why = format!("has {} values, but the file names {width} columns", w.len());
            return Err(sheet.error((line_no, w[w.len() - 1].1), why));
        }
        let number = |sheet: &Sheet, (text, col): (&str, usize)| {
            parse_number(text, Decimal::Point)
                .map(|x| x.0)
                .map_err(|why| sheet.error((line_no, col), why))
        };
        let t = number(sheet, w[0])?;
        for (&s, &field) in series.iter().zip(&w[1..]) {
            let v = number(sheet, field)?;
            sheet.push(s, t, (line_no, w[0].1), v)?;
        }
    }
    let lines = text.lines().count();
    let why = "<Data> is not closed (</Data>): the file ends early (did the analysis stop before the recorder was closed?)";
    Err(sheet.error((lines.max(1), 1), why))
}

/// Most values a binary row may hold.
const MAX_BINARY_WIDTH: usize = 1024;

/// The width (values a row) of a binary recorder file: `given`, else the one width whose
/// rows all end in a line feed.
fn binary_width(bytes: &[u8], given: Option<usize>) -> Result<usize, String> {
    let fits = |w: usize| {
        let row = 8 * w + 1;
        bytes.len() % row == 0 && bytes.chunks(row).all(|r| r[row - 1] == b'\n')
    };
    if let Some(w) = given {
        return Ok(w);
    }
    let widths: Vec<usize> = (1..=MAX_BINARY_WIDTH).filter(|&w| fits(w)).collect();
    match widths.as_slice() {
        [w] => Ok(*w),
        [] => Err(format!(
            "is not an OpenSees -binary recorder file: no row width of 1 to {MAX_BINARY_WIDTH} values (8 bytes each, then a line feed) divides its {} bytes",
            bytes.len()
        )),
        several => Err(format!(
            "is an OpenSees -binary recorder file whose row width cannot be told from the file ({} values all fit): give the recorder command (`recorder` or `script`)",
            several
                .iter()
                .map(|w| w.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// Read a `-binary` recorder file (see the module docs); `width` from the recorder
/// command, and the columns' names (the time first excluded).
pub(super) fn read_binary(
    path: &Path,
    bytes: &[u8],
    width: Option<usize>,
    names: impl Fn(usize) -> Result<Vec<String>, String>,
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    let mut sheet = Sheet::new(path, "OpenSees -binary recorder file", "time");
    let width = binary_width(bytes, width).map_err(|why| InputError::new(path, "", why))?;
    let row_len = 8 * width + 1;
    let names = names(width).map_err(|why| InputError::new(path, "", why))?;
    let series: Vec<usize> = names
        .iter()
        .enumerate()
        .map(|(k, n)| sheet.series(n, None, (1, k + 2)))
        .collect();
    if bytes.len() % row_len != 0 {
        let rows = bytes.len() / row_len;
        let why = format!(
            "row {}: the file ends inside it ({} bytes; a row of {width} values is {row_len} bytes)",
            rows + 1,
            bytes.len()
        );
        return Err(sheet.error((rows + 1, 1), why).into());
    }
    for (r, row) in bytes.chunks(row_len).enumerate() {
        if row[row_len - 1] != b'\n' {
            let why = format!(
                "row {} (byte {}): does not end in a line feed after its {width} values: not a row of this width",
                r + 1,
                r * row_len + row_len - 1
            );
            return Err(sheet.error((r + 1, width + 1), why).into());
        }
        let value = |k: usize| {
            let b: [u8; 8] = row[8 * k..8 * k + 8].try_into().expect("8 bytes");
            f64::from_le_bytes(b)
        };
        let t = value(0);
        for (k, &s) in series.iter().enumerate() {
            sheet.push(s, t, (r + 1, 1), value(k + 1))?;
        }
    }
    sheet.notes.push(format!(
        "OpenSees -binary recorder: {} rows of {width} little-endian doubles",
        bytes.len() / row_len
    ));
    sheet.assemble(format)
}

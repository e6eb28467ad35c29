//! SAP2000, ETABS and CSiBridge tables exported to Excel (`.xlsx`): one sheet per table,
//! named by the table; row 1 the title `TABLE:  "Joint Displacements"`, row 2 the field
//! names, row 3 the units, then the long table. Each sheet's rows go through the table
//! export's reader (`csi`), so the pivot into one series per object and field, the map,
//! the output case and the step types are the TXT/CSV path's. Every table sheet is read,
//! in the workbook's order; the map's names (`"Link 1: P"`) say which sheets matter, and a
//! name no sheet holds is refused with the workbook's sheets.
//!
//! The workbook is read through `calamine`, cell by cell (no sheet is held whole). Before
//! that, every part of the zip archive is inflated once into nothing, so that the
//! archive's real unpacked size — not the one it declares — is checked against
//! [`MAX_EXTERNAL_BYTES`] before anything is kept. Errors name the file, the sheet and the
//! cell (`book.xlsx:5:8: sheet "Element Forces - Links", cell H5: …`).

use std::io::{Cursor, Read};
use std::path::Path;

use calamine::{DataRef, Reader as _, Xlsx};
use rockslide_core::case::{ExternalFormat, ExternalTrace};
use rockslide_core::error::{InputError, InputErrors};

use super::csi::{Reader, is_title};
use super::sheet::{FILE, Sheet};
use super::{MAX_EXTERNAL_BYTES, MAX_EXTERNAL_COLUMNS};

/// Whether `path` names an Excel workbook (`.xlsx`, `.xlsm`).
pub(super) fn is_workbook(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xlsx") || e.eq_ignore_ascii_case("xlsm"))
}

/// Most parts a workbook's archive may have.
const MAX_PARTS: usize = 4096;

/// Read a workbook's table sheets (see the module docs).
pub(super) fn read(
    path: &Path,
    bytes: &[u8],
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    let refuse = |why: String| -> InputErrors { InputError::new(path, "", why).into() };
    check_unpacked_size(bytes)
        .map_err(|why| refuse(format!("is not a readable XLSX workbook: {why}")))?;
    let mut book: Xlsx<_> = Xlsx::new(Cursor::new(bytes))
        .map_err(|e| refuse(format!("is not a readable XLSX workbook: {e}")))?;
    let names = book.sheet_names();
    let mut reader = Reader::new(
        Sheet::new(
            path,
            "SAP2000/ETABS/CSiBridge tables exported to Excel",
            "StepNum",
        ),
        format,
    );
    reader.for_workbook();
    let mut first_line = 0;
    let mut skipped = Vec::new();
    for name in &names {
        reader.sheet.start_worksheet(first_line, name);
        let mut cells = book
            .worksheet_cells_reader(name)
            .map_err(|e| refuse(format!("sheet \"{name}\": cannot be read: {e}")))?;
        let next_cell = || match cells.next_cell() {
            Ok(cell) => Ok(cell.map(|c| (c.get_position(), cell_text(c.get_value())))),
            Err(e) => Err(e.to_string()),
        };
        let rows = read_sheet(&mut reader, next_cell, first_line)?;
        if rows == 0 {
            skipped.push(name.clone());
        }
        first_line += rows;
    }
    if skipped.len() == names.len() {
        return Err(refuse(format!(
            "has no table sheets (a sheet whose row 1 is `TABLE: \"…\"`); its sheets: {}",
            quoted(&names)
        )));
    }
    if reader.read_rows() {
        check_map_names(&reader.sheet, format, &names)?;
    }
    if !skipped.is_empty() {
        let why = format!(
            "sheets without a `TABLE:` title in row 1 skipped: {}",
            quoted(&skipped)
        );
        reader.sheet.notes.push(why);
    }
    reader.finish(format)
}

/// A sheet's next cell: its position (row, column from 0) and its text.
type NextCell = Result<Option<((u32, u32), String)>, String>;

/// One sheet's rows into the reader, each non-empty row at line `first_line + row`, its
/// cells from `next_cell` in the sheet's order; returns the sheet's last row (0 for a
/// sheet that is not a table: skipped).
fn read_sheet(
    reader: &mut Reader,
    mut next_cell: impl FnMut() -> NextCell,
    first_line: usize,
) -> Result<usize, InputErrors> {
    let mut row: Vec<(String, usize)> = Vec::new();
    let mut row_no = 0; // 1-based row of `row`, 0 before the first
    let mut last_row = 0;
    loop {
        let next = next_cell().map_err(|e| {
            let at = (first_line + row_no.max(1), 1);
            InputErrors::from(reader.sheet.error(at, format!("cannot be read: {e}")))
        })?;
        let Some(((r, c), text)) = next else { break };
        let (r, c) = (r as usize + 1, c as usize + 1);
        if r != row_no {
            if r < row_no {
                let why = "rows out of order in the sheet's XML";
                return Err(reader.sheet.error((first_line + r, c), why).into());
            }
            if !take_row(reader, first_line, row_no, &row)? {
                return Ok(0);
            }
            row.clear();
            row_no = r;
        }
        if c > MAX_EXTERNAL_COLUMNS {
            let why = format!("has more than {MAX_EXTERNAL_COLUMNS} columns");
            return Err(reader.sheet.error((first_line + r, c), why).into());
        }
        if text.is_empty() {
            continue;
        }
        if c <= row.len() {
            let why = "a cell repeated or out of order in the sheet's XML";
            return Err(reader.sheet.error((first_line + r, c), why).into());
        }
        while row.len() < c - 1 {
            let col = row.len() + 1;
            row.push((String::new(), col));
        }
        row.push((text, c));
        last_row = r;
    }
    if !take_row(reader, first_line, row_no, &row)? {
        return Ok(0);
    }
    reader.end_table();
    Ok(last_row)
}

/// Row `row_no` of a sheet into the reader: its title (row 1) or its fields. `false` for
/// a sheet whose first row is no title (not a table).
fn take_row(
    reader: &mut Reader,
    first_line: usize,
    row_no: usize,
    row: &[(String, usize)],
) -> Result<bool, InputErrors> {
    if row.iter().all(|f| f.0.trim().is_empty()) {
        return Ok(true);
    }
    let line = first_line + row_no;
    let first = row[0].0.as_str();
    if is_title(first) && row[1..].iter().all(|f| f.0.trim().is_empty()) {
        reader.title(first);
        return Ok(true);
    }
    if !reader.in_table() {
        return Ok(false);
    }
    reader.fields(line, row)?;
    Ok(true)
}

/// A cell as the text the TXT export would hold: numbers in Rust's shortest round-trip
/// form (so read back to the same f64), text as written, booleans and errors as Excel
/// shows them.
fn cell_text(value: &DataRef<'_>) -> String {
    match value {
        DataRef::Empty => String::new(),
        DataRef::Int(i) => i.to_string(),
        DataRef::Float(x) => x.to_string(),
        DataRef::String(s) => s.clone(),
        DataRef::SharedString(s) => (*s).to_string(),
        DataRef::Bool(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
        DataRef::DateTime(d) => d.as_f64().to_string(),
        DataRef::DateTimeIso(s) | DataRef::DurationIso(s) => s.clone(),
        DataRef::Error(e) => e.to_string(),
    }
}

/// Inflate every part of the archive into nothing: the real unpacked size (at most
/// [`MAX_EXTERNAL_BYTES`] in all) and the parts' count, before the workbook is read.
fn check_unpacked_size(bytes: &[u8]) -> Result<(), String> {
    let mut zip =
        zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| format!("not a zip archive ({e})"))?;
    if zip.len() > MAX_PARTS {
        return Err(format!("has {} parts (at most {MAX_PARTS})", zip.len()));
    }
    let mut left = MAX_EXTERNAL_BYTES;
    for i in 0..zip.len() {
        let mut part = zip.by_index(i).map_err(|e| format!("part {i}: {e}"))?;
        let name = part.name().to_string();
        let read = std::io::copy(&mut (&mut part).take(left + 1), &mut std::io::sink())
            .map_err(|e| format!("part \"{name}\": {e}"))?;
        if read > left {
            let mib = MAX_EXTERNAL_BYTES >> 20;
            return Err(format!("unpacks to more than {mib} MiB"));
        }
        left -= read;
    }
    Ok(())
}

/// Every series the map names is in a table sheet, or the error lists the sheets.
fn check_map_names(
    sheet: &Sheet,
    format: &ExternalFormat,
    names: &[String],
) -> Result<(), InputErrors> {
    let missing: Vec<String> = format
        .columns
        .iter()
        .map(|c| c.from.trim())
        .filter(|&from| from != "StepNum" && !sheet.has_series(from))
        .map(|from| format!("\"{from}\""))
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    let why = format!(
        "the column map names {}, but no sheet of the workbook has such a series (export the \
         table that holds it); its sheets: {}",
        missing.join(", "),
        quoted(names)
    );
    Err(sheet.error(FILE, why).into())
}

/// Names in quotes, joined by commas.
fn quoted(names: &[String]) -> String {
    let q: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
    q.join(", ")
}

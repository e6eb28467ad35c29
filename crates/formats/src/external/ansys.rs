//! ANSYS POST26 `PRVAR` listings, as ANSYS prints them (to its output file or with
//! `/OUTPUT`): each page opens with the banner `***** ANSYS POST26 VARIABLE LISTING *****`
//! (`MAPDL` in newer releases), then a header `TIME  2 UX_2  3 FX_1` — the time and up to
//! six variables, each its number and the name given to `NSOL`/`ESOL`/`RFORCE` — possibly
//! a line of item labels, then rows of numbers in the `/FORMAT` set (`0.10000E-02`).
//!
//! Each variable is a series named as printed (`"UX_2"`); pages and several listings of
//! one file are joined on the time (the same variable on two pages must continue in
//! time). Text outside the listings (the rest of an output file) is skipped; inside a
//! listing a row of the wrong length or a field that is not a number is an error at its
//! line and column. ANSYS has no units: the map states them (`"UX_2" = "rel_disp [m]"`).

use std::path::Path;

use rockslide_core::case::{ExternalFormat, ExternalTrace};
use rockslide_core::error::InputErrors;

use super::number::{Decimal, parse_number};
use super::sheet::Sheet;

/// Whether a line is the POST26 listing banner.
pub(super) fn is_banner(line: &str) -> bool {
    let l = line.trim();
    l.starts_with("*****") && l.contains("POST26 VARIABLE LISTING")
}

/// The fields of a line separated by blanks, each with its 1-based column.
pub(super) fn words(line: &str) -> Vec<(&str, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (col, (i, c)) in line.char_indices().enumerate() {
        match (c.is_whitespace(), start) {
            (false, None) => start = Some((i, col + 1)),
            (true, Some((s, scol))) => {
                out.push((&line[s..i], scol));
                start = None;
            }
            _ => {}
        }
    }
    if let Some((s, scol)) = start {
        out.push((&line[s..], scol));
    }
    out
}

/// Whether every field of a line reads as a number (a data row).
pub(super) fn is_numeric(words: &[(&str, usize)]) -> bool {
    !words.is_empty()
        && words
            .iter()
            .all(|w| parse_number(w.0, Decimal::Point).is_ok())
}

/// Where the reader is in the file.
enum State {
    /// Outside a listing (before the first banner, or after a listing ended).
    Outside,
    /// After a banner, before its `TIME` header.
    Banner,
    /// Inside a listing: the series of its columns, the header's line, and whether a
    /// data row has been read yet.
    Listing(Vec<usize>, usize, bool),
}

/// Read a `PRVAR` listing (see the module docs).
pub(super) fn read(
    path: &Path,
    text: &str,
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    let mut sheet = Sheet::new(path, "ANSYS POST26 PRVAR listing", "TIME");
    let (mut state, mut pages) = (State::Outside, 0usize);
    for (index, raw) in text.lines().enumerate() {
        let line_no = index + 1;
        let line = raw.trim_end_matches('\r');
        if is_banner(line) {
            pages += 1;
            state = State::Banner;
            continue;
        }
        let w = words(line);
        if w.is_empty() {
            continue;
        }
        state = match state {
            State::Outside => State::Outside,
            State::Banner if w[0].0.eq_ignore_ascii_case("TIME") => {
                State::Listing(header(&mut sheet, line_no, &w)?, line_no, false)
            }
            State::Banner => State::Banner,
            State::Listing(series, header_line, started) => {
                if !started && !is_numeric(&w) && !starts_numeric(&w) {
                    // the item labels under the names
                    State::Listing(series, header_line, false)
                } else if !starts_numeric(&w) {
                    State::Outside // the listing ended
                } else {
                    row(&mut sheet, line_no, &w, &series, header_line)?;
                    State::Listing(series, header_line, true)
                }
            }
        };
    }
    if pages == 0 {
        let why = "has no `***** ANSYS POST26 VARIABLE LISTING *****` banner (list the \
                   variables with PRVAR)";
        return Err(sheet.error((1, 1), why).into());
    }
    sheet.notes.push(format!("{pages} listing page(s) joined"));
    sheet.assemble(format)
}

/// Whether a line's first field is a number.
fn starts_numeric(w: &[(&str, usize)]) -> bool {
    w.first()
        .is_some_and(|f| parse_number(f.0, Decimal::Point).is_ok())
}

/// The series of a header line `TIME  2 UX_2  3 FX_1` (a variable's number then its name).
fn header(
    sheet: &mut Sheet,
    line_no: usize,
    w: &[(&str, usize)],
) -> Result<Vec<usize>, InputErrors> {
    let mut names: Vec<(&str, usize)> = Vec::new();
    for &(word, col) in &w[1..] {
        if word.parse::<u32>().is_ok() {
            continue; // the variable's number
        }
        if names.iter().any(|n| n.0 == word) {
            let why = format!(
                "variable name \"{word}\" appears twice in the header: give each variable its \
                 own name (the Name argument of NSOL, ESOL, RFORCE)"
            );
            return Err(sheet.error((line_no, col), why).into());
        }
        names.push((word, col));
    }
    Ok(names
        .into_iter()
        .map(|(name, col)| sheet.series(name, None, (line_no, col)))
        .collect())
}

/// One data row: the time and each variable's value.
fn row(
    sheet: &mut Sheet,
    line_no: usize,
    w: &[(&str, usize)],
    series: &[usize],
    header_line: usize,
) -> Result<(), InputErrors> {
    if w.len() != series.len() + 1 {
        let why = format!(
            "has {} fields, but the header (line {header_line}) has {}",
            w.len(),
            series.len() + 1
        );
        return Err(sheet
            .error((line_no, w.last().map_or(1, |f| f.1)), why)
            .into());
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
    Ok(())
}

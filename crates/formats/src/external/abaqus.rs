//! Abaqus XY reports (`.rpt`, Report → XY in Abaqus/CAE or `session.writeXYReport`), as
//! Abaqus writes them: fixed-width columns, a header line `X` followed by the curves'
//! names (right-aligned, separated by two blanks or more, a name may hold single blanks:
//! `U:U1 PI: PART-1-1 N: 2`), then rows of numbers (`10.E-03`, `1.23456E-06`), `NoValue`
//! where a curve has no value at that X. Several blocks (each with its `X` header) are
//! joined on X.
//!
//! Each curve is a series named as in the header; X is the time. A time at which a mapped
//! curve has `NoValue` is skipped and counted in the notes (a missing value is not zero).
//! Abaqus has no units in the report: the map states them.

use std::path::Path;

use rockslide_core::case::{ExternalFormat, ExternalTrace};
use rockslide_core::error::InputErrors;

use super::ansys::words;
use super::number::{Decimal, parse_number};
use super::sheet::Sheet;

/// The entry Abaqus writes where a curve has no value.
const NO_VALUE: &str = "NoValue";

/// Read an XY report (see the module docs).
pub(super) fn read(
    path: &Path,
    text: &str,
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    let mut sheet = Sheet::new(path, "Abaqus XY report", "X");
    let mut block: Option<(Vec<usize>, usize)> = None;
    let mut no_values = 0usize;
    for (index, raw) in text.lines().enumerate() {
        let line_no = index + 1;
        let line = raw.trim_end_matches('\r');
        let w = words(line);
        if w.is_empty() {
            continue;
        }
        if w[0].0 == "X" {
            block = Some((header(&mut sheet, line_no, line)?, line_no));
            continue;
        }
        let Some((series, header_line)) = &block else {
            continue; // a title above the first block
        };
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
                .map_err(|why| sheet.error((line_no, col), format!("{why} (nor `{NO_VALUE}`)")))
        };
        let t = number(&sheet, w[0])?;
        for (&s, &field) in series.iter().zip(&w[1..]) {
            if field.0 == NO_VALUE {
                no_values += 1;
                continue;
            }
            let v = number(&sheet, field)?;
            sheet.push(s, t, (line_no, w[0].1), v)?;
        }
    }
    if block.is_none() {
        let why = "has no `X` header line (an Abaqus XY report: X and the curves' names)";
        return Err(sheet.error((1, 1), why).into());
    }
    if no_values > 0 {
        sheet.notes.push(format!("{no_values} `NoValue` entries"));
    }
    sheet.assemble(format)
}

/// The curves of a header line: names separated by two blanks or more, after `X`.
fn header(sheet: &mut Sheet, line_no: usize, line: &str) -> Result<Vec<usize>, InputErrors> {
    let chars: Vec<char> = line.chars().collect();
    let mut names: Vec<(String, usize)> = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        while i < chars.len() && chars[i].is_whitespace() {
            i += 1;
        }
        let start = i;
        while i < chars.len()
            && !(chars[i].is_whitespace() && chars.get(i + 1).is_none_or(|c| c.is_whitespace()))
        {
            i += 1;
        }
        if i > start {
            names.push((chars[start..i].iter().collect(), start + 1));
        }
    }
    let curves = &names[1..];
    for (k, (name, col)) in curves.iter().enumerate() {
        if curves[..k].iter().any(|o| &o.0 == name) {
            let why = format!("curve name \"{name}\" appears twice in the header");
            return Err(sheet.error((line_no, *col), why).into());
        }
    }
    Ok(curves
        .iter()
        .map(|(name, col)| sheet.series(name, None, (line_no, *col)))
        .collect())
}

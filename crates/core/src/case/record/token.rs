//! The text of a record's lines: the byte-order mark skipped, tokens with their columns,
//! numbers in Rust or Fortran float syntax, non-finite values refused at their line and column.

use std::path::Path;

use crate::error::InputError;

/// A number as records write them: Rust's float syntax, or Fortran's `D` exponent.
pub(super) fn parse_float(token: &str) -> Option<f64> {
    token.parse::<f64>().ok().or_else(|| {
        if token.contains(['D', 'd']) && !token.contains(['E', 'e']) {
            token.replace(['D', 'd'], "E").parse::<f64>().ok()
        } else {
            None
        }
    })
}

/// A record error at a 1-based line (and column, when known).
pub(super) fn at(
    path: &Path,
    line: usize,
    column: Option<usize>,
    reason: impl Into<String>,
) -> InputError {
    let mut e = InputError::new(path, "", reason);
    e.line = Some(line);
    e.column = column;
    e
}

/// Parse one numeric token, rejecting text and non-finite values (NaN, inf).
pub(super) fn number(
    path: &Path,
    line: usize,
    column: usize,
    token: &str,
) -> Result<f64, InputError> {
    match parse_float(token).ok_or(()) {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(x) => Err(at(
            path,
            line,
            Some(column),
            format!("value \"{token}\" is {x}: every sample must be a finite number"),
        )),
        Err(_) => Err(at(
            path,
            line,
            Some(column),
            format!("\"{token}\" is not a number"),
        )),
    }
}

/// Tokens of a line with their 1-based columns, split on whitespace and commas.
pub(super) fn tokens(line: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in line.char_indices() {
        let sep = c.is_whitespace() || c == ',' || c == ';';
        match (sep, start) {
            (true, Some(s)) => {
                out.push((s, &line[s..i]));
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, &line[s..]));
    }
    out.into_iter()
        .map(move |(s, t)| (line[..s].chars().count() + 1, t))
}

/// The text without a leading UTF-8 byte-order mark.
pub(super) fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

//! The first stage: the case's TOML read into the raw form, with every syntax and type
//! error located by the TOML parser, and every unknown key reported (not only the first).

use std::path::Path;

use super::super::locate::Locator;
use super::super::raw::RawCase;
use crate::error::{InputError, InputErrors, line_col};

/// Most unknown keys reported from one file before the rest are left unread.
const MAX_UNKNOWN_KEYS: usize = 64;

/// Deserialize a case, reporting every unknown key rather than only the first: each one
/// is recorded at its position, its line is blanked in a working copy (same byte offsets,
/// so later positions still point into `text`), and reading resumes. The unknown keys are
/// returned with the case, to be reported together with the validation errors; any other
/// error of the file is an error at once (with the unknown keys found before it).
pub(super) fn deserialize_case(
    path: &Path,
    text: &str,
) -> Result<(RawCase, Vec<InputError>), InputErrors> {
    let mut work = text.to_string();
    let mut unknown: Vec<InputError> = Vec::new();
    loop {
        let e = match toml::from_str::<RawCase>(&work) {
            Ok(raw) => return Ok((raw, unknown)),
            Err(e) => e,
        };
        let span = e
            .span()
            .filter(|_| e.message().starts_with("unknown field"));
        if let Some(span) = span
            && unknown.len() < MAX_UNKNOWN_KEYS
        {
            unknown.extend(syntax_error(path, text, &e).0);
            blank_to_end_of_line(&mut work, span.start);
            if work.parse::<toml::Table>().is_ok() {
                continue;
            }
            // the key's value spans several lines: stop at what was found
            return Err(InputErrors(unknown));
        }
        unknown.extend(syntax_error(path, text, &e).0);
        return Err(InputErrors(unknown));
    }
}

/// Replace the text from byte `start` to the end of its line by spaces, byte for byte.
fn blank_to_end_of_line(text: &mut String, start: usize) {
    let end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let blanks = " ".repeat(end - start);
    text.replace_range(start..end, &blanks);
}

fn syntax_error(path: &Path, text: &str, e: &toml::de::Error) -> InputErrors {
    let message = e.message().trim().to_string();
    let mut field = field_from_message(&message);
    if let Some(span) = e.span() {
        let table = Locator::new(path, text).path_at(span.start);
        if !table.is_empty() && !field.is_empty() && !field.starts_with(&table) {
            field = format!("{table}.{field}");
        } else if field.is_empty() {
            field = table;
        }
    }
    let mut err = InputError::new(path, field, message);
    if let Some(span) = e.span() {
        let (l, c) = line_col(text, span.start);
        err = err.at(l, c);
    }
    err.into()
}

/// serde's messages quote the field (`missing field `mass``); pull it out for the field slot.
fn field_from_message(message: &str) -> String {
    let mut parts = message.split('`');
    match (parts.next(), parts.next()) {
        (Some(_), Some(f)) if !f.contains(' ') => f.to_string(),
        _ => String::new(),
    }
}

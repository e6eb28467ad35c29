//! Finds the line and column of a field in a TOML text from its dotted path, so that a
//! semantic error found after parsing (a negative mass, an unknown variant) still points
//! at the place in the file where the user must look.

use std::path::{Path, PathBuf};

use toml::de::{DeTable, DeValue};

use crate::error::{InputError, line_col};

/// The text of a case file, kept to locate fields for error messages.
#[derive(Debug, Clone)]
pub struct Locator {
    file: PathBuf,
    text: String,
}

impl Locator {
    /// A locator over `text`, read from `file`.
    pub fn new(file: &Path, text: &str) -> Self {
        Self {
            file: file.to_path_buf(),
            text: text.to_string(),
        }
    }

    /// The file this locator reads.
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// An error on `field` (dotted path, array items as `tolerance[2].percent`),
    /// located at the field's value (or its nearest located parent).
    pub fn error(&self, field: &str, reason: impl Into<String>) -> InputError {
        let err = InputError::new(&self.file, field, reason);
        match self.offset_of(field) {
            Some(off) => {
                let (l, c) = line_col(&self.text, off);
                err.at(l, c)
            }
            None => err,
        }
    }

    /// Dotted path of the value or table at byte `offset` (for naming the field of a
    /// parser error: the value of a wrong type, or the table missing a field).
    pub fn path_at(&self, offset: usize) -> String {
        let (root, _) = DeTable::parse_recoverable(&self.text);
        let mut tables = Vec::new();
        collect_fields(root.get_ref(), "", &mut tables);
        // the table whose header is the last one before `offset` and whose extent holds it
        tables
            .into_iter()
            .filter(|(_, lo, hi)| *lo <= offset && offset < *hi)
            .max_by_key(|(_, lo, _)| *lo)
            .map(|(path, _, _)| path)
            .unwrap_or_default()
    }

    /// Byte offset of the value at `field`, or of its deepest existing ancestor.
    fn offset_of(&self, field: &str) -> Option<usize> {
        let root = DeTable::parse(&self.text).ok()?;
        let mut best = None;
        let mut table: &DeTable = root.get_ref();
        let mut parts = split_path(field).into_iter().peekable();
        while let Some((key, index)) = parts.next() {
            let Some((_, value)) = table.iter().find(|(k, _)| k.get_ref().as_ref() == key) else {
                break;
            };
            best = Some(value.span().start);
            let mut current = value.get_ref();
            if let Some(i) = index {
                if let DeValue::Array(items) = current {
                    let Some(item) = items.get(i) else { break };
                    best = Some(item.span().start);
                    current = item.get_ref();
                }
            }
            match current {
                DeValue::Table(t) if parts.peek().is_some() => table = t,
                _ => break,
            }
        }
        best
    }
}

/// Every table and scalar value under `table` as (dotted path, start of its header, first
/// key or value, end of its last value).
fn collect_fields(table: &DeTable, prefix: &str, out: &mut Vec<(String, usize, usize)>) -> usize {
    let mut hi = 0;
    for (k, v) in table.iter() {
        let path = if prefix.is_empty() {
            k.get_ref().to_string()
        } else {
            format!("{prefix}.{}", k.get_ref())
        };
        hi = hi.max(v.span().end);
        match v.get_ref() {
            DeValue::Table(t) => {
                let end = collect_fields(t, &path, out).max(v.span().end);
                out.push((path, v.span().start, end));
                hi = hi.max(end);
            }
            DeValue::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    if let DeValue::Table(t) = item.get_ref() {
                        let p = format!("{path}[{i}]");
                        let end = collect_fields(t, &p, out).max(item.span().end);
                        out.push((p, item.span().start, end));
                        hi = hi.max(end);
                    }
                }
            }
            _ => out.push((path, v.span().start, v.span().end)),
        }
    }
    hi
}

/// `a.b[2].c` → [("a", None), ("b", Some(2)), ("c", None)].
fn split_path(field: &str) -> Vec<(&str, Option<usize>)> {
    field
        .split('.')
        .map(|part| match part.split_once('[') {
            Some((key, rest)) => (key, rest.trim_end_matches(']').parse().ok()),
            None => (part, None),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locates_nested_fields_and_array_items() {
        let text =
            "[model]\nmass = -1.0\n\n[[tolerance]]\npercent = 1\n\n[[tolerance]]\npercent = -2\n";
        let loc = Locator::new(Path::new("x.toml"), text);
        let e = loc.error("model.mass", "must be positive");
        assert_eq!((e.line, e.column), (Some(2), Some(8)));
        let e = loc.error("tolerance[1].percent", "must be positive");
        assert_eq!((e.line, e.column), (Some(8), Some(11)));
        let e = loc.error("model.nothing", "missing");
        assert_eq!(e.line, Some(1), "falls back to the parent table");
    }
}

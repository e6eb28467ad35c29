//! Input errors: every problem with a case file, record or option carries the file, the
//! field, the line and column where the format gives them, and the reason — one line each,
//! `file:line:col: field: reason`, all problems of a file reported together. A problem
//! inside a file that a field names (a case's `excitation.record`) is located twice: at the
//! field, then inside the named file — `case:line:col: field: record:line:col: reason`.

use std::fmt;
use std::path::{Path, PathBuf};

/// One problem found in an input file.
#[derive(Debug, Clone, PartialEq)]
pub struct InputError {
    /// The file the problem is in.
    pub file: PathBuf,
    /// Dotted path of the offending field (`model.contact.mu`), empty if not field-specific.
    pub field: String,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// 1-based column, when known.
    pub column: Option<usize>,
    /// What is wrong, in a sentence that says what would be right.
    pub reason: String,
    /// Where the problem lies inside the file `field` names (a ground-motion record), when
    /// the problem is in that file rather than in this one (boxed: an error stays small).
    pub within: Option<Box<Within>>,
}

/// A place inside a file named by a field of another file: the record a case's
/// `excitation.record` names, with the line and column where the record's format gives them.
#[derive(Debug, Clone, PartialEq)]
pub struct Within {
    /// The named file.
    pub file: PathBuf,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// 1-based column, when known.
    pub column: Option<usize>,
}

impl InputError {
    /// A problem with no known location inside the file.
    pub fn new(file: &Path, field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self {
            file: file.to_path_buf(),
            field: field.into(),
            line: None,
            column: None,
            reason: reason.into(),
            within: None,
        }
    }

    /// The same problem, located at a 1-based line and column.
    pub fn at(mut self, line: usize, column: usize) -> Self {
        self.line = Some(line);
        self.column = Some(column);
        self
    }

    /// This problem, found in a file that a field of another file names (a record a case
    /// names), reported at that field: `at_field` gives the naming file, its line and
    /// column, and the field; this error's file, line and column become [`Self::within`].
    pub fn named_by(self, at_field: InputError) -> Self {
        let reason = if self.field.is_empty() {
            self.reason
        } else {
            format!("{}: {}", self.field, self.reason)
        };
        Self {
            within: Some(Box::new(Within {
                file: self.file,
                line: self.line,
                column: self.column,
            })),
            reason,
            ..at_field
        }
    }
}

/// `file`, `file:line` or `file:line:col`.
fn write_place(
    f: &mut fmt::Formatter<'_>,
    file: &Path,
    line: Option<usize>,
    column: Option<usize>,
) -> fmt::Result {
    write!(f, "{}", file.display())?;
    if let Some(line) = line {
        write!(f, ":{line}")?;
        if let Some(col) = column {
            write!(f, ":{col}")?;
        }
    }
    Ok(())
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_place(f, &self.file, self.line, self.column)?;
        if !self.field.is_empty() {
            write!(f, ": {}", self.field)?;
        }
        if let Some(w) = &self.within {
            write!(f, ": ")?;
            write_place(f, &w.file, w.line, w.column)?;
        }
        write!(f, ": {}", self.reason)
    }
}

/// An I/O error's message without the operating system's code: "No such file or directory",
/// not "No such file or directory (os error 2)".
pub fn io_reason(e: &std::io::Error) -> String {
    let text = e.to_string();
    match (e.raw_os_error(), text.rfind(" (os error ")) {
        (Some(_), Some(i)) => text[..i].to_string(),
        _ => text,
    }
}

/// All the problems found in one input, reported at once.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct InputErrors(pub Vec<InputError>);

impl fmt::Display for InputErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, e) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
}

impl From<InputError> for InputErrors {
    fn from(e: InputError) -> Self {
        Self(vec![e])
    }
}

/// 1-based line and column of a byte offset in `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

/// Errors of the tool itself (not of its input): I/O and the like.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The input was wrong; the user can fix it.
    #[error("{0}")]
    Input(#[from] InputErrors),
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// Anything else, with its explanation.
    #[error("{0}")]
    Other(String),
}

impl Error {
    /// An I/O error on `path`.
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}

/// Result with the tool's error.
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_from_one() {
        let t = "a = 1\nbb = 2\n";
        assert_eq!(line_col(t, 0), (1, 1));
        assert_eq!(line_col(t, 6), (2, 1));
        assert_eq!(line_col(t, 8), (2, 3));
    }

    #[test]
    fn display_is_file_line_col_field_reason() {
        let e = InputError::new(Path::new("c.toml"), "model.mass", "must be positive").at(3, 8);
        assert_eq!(e.to_string(), "c.toml:3:8: model.mass: must be positive");
    }

    #[test]
    fn a_problem_in_a_named_file_is_located_at_the_field_and_inside_the_file() {
        let inner = InputError::new(Path::new("r.AT2"), "", "not a number").at(7, 3);
        let field = InputError::new(Path::new("c.toml"), "excitation.record", "").at(12, 10);
        let e = inner.named_by(field);
        assert_eq!(
            e.to_string(),
            "c.toml:12:10: excitation.record: r.AT2:7:3: not a number"
        );
        assert_eq!((e.line, e.column), (Some(12), Some(10)));
        let w = e.within.unwrap();
        assert_eq!(
            (w.file.as_path(), w.line, w.column),
            (Path::new("r.AT2"), Some(7), Some(3))
        );
    }

    #[test]
    fn io_reasons_drop_the_os_code() {
        let e = std::io::Error::from_raw_os_error(2);
        assert!(e.to_string().ends_with("(os error 2)"), "{e}");
        assert!(!io_reason(&e).contains("os error"), "{}", io_reason(&e));
        assert!(!io_reason(&e).is_empty());
    }
}

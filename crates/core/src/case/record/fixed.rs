//! Fixed-format (Fortran) blocks of the agencies' files: a format such as `(8f9.6)`,
//! `(16I5)` or `(5E15.7)` read as so many fields of so many characters a line, each field
//! parsed at its own line and column, so that a malformed header field or sample is a
//! located error.

use std::path::Path;

use crate::error::InputError;

use super::token::{at, parse_float};

/// Fields a line and characters a field of a fixed-format block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Layout {
    /// Fields on a full line.
    pub per_line: usize,
    /// Characters a field.
    pub width: usize,
}

impl Layout {
    /// `per_line` fields of `width` characters.
    pub const fn new(per_line: usize, width: usize) -> Self {
        Self { per_line, width }
    }

    /// The Fortran format of a line, `(8f9.6)`, `8F10.5`, `(10I8)`, `(1E15.6)`: the
    /// repeat count and the field width; `None` for anything else.
    pub fn parse(format: &str) -> Option<Self> {
        let f = format.trim().trim_start_matches('(');
        let f = f.split(')').next()?.trim();
        let kind = f.find(|c: char| c.is_ascii_alphabetic())?;
        let per_line = if kind == 0 {
            1
        } else {
            f[..kind].trim().parse().ok()?
        };
        let rest = &f[kind + 1..];
        let width = rest.split('.').next()?.trim().parse().ok()?;
        (per_line >= 1 && width >= 1).then_some(Self::new(per_line, width))
    }

    /// Lines that `count` fields take.
    pub fn lines(&self, count: usize) -> usize {
        count.div_ceil(self.per_line)
    }
}

/// The format written in a line after `Format=`, `Format:` or `Format =`, if any.
pub(super) fn format_in(line: &str) -> Option<Layout> {
    let upper = line.to_ascii_uppercase();
    let at = upper.find("FORMAT")?;
    let rest = line[at + 6..].trim_start_matches([' ', '=', ':']);
    Layout::parse(rest)
}

/// A block of `count` numbers laid out by `layout`, from 0-based line `start` of `lines`:
/// the values and the number of lines read. `what` names the block in errors ("integer
/// header", "acceleration values"). A blank or unreadable field is an error at its line
/// and column; `-999`-style "unknown" values are returned as read.
pub(super) fn read_block(
    path: &Path,
    lines: &[&str],
    start: usize,
    count: usize,
    layout: Layout,
    what: &str,
) -> Result<Vec<f64>, InputError> {
    let needed = layout.lines(count);
    if start + needed > lines.len() {
        return Err(at(
            path,
            lines.len().max(1),
            None,
            format!(
                "the {what} needs {needed} lines of {} fields from line {}, but the file ends at line {}",
                layout.per_line,
                start + 1,
                lines.len()
            ),
        ));
    }
    let mut out = Vec::with_capacity(count);
    for (k, line) in lines[start..start + needed].iter().enumerate() {
        let line_no = start + k + 1;
        if !line.is_ascii() {
            return Err(at(
                path,
                line_no,
                None,
                format!(
                    "a line of the {what} is not ASCII: fixed-format fields cannot be found in it"
                ),
            ));
        }
        let fields = layout.per_line.min(count - out.len());
        for j in 0..fields {
            let column = j * layout.width + 1;
            let field = line
                .get(j * layout.width..((j + 1) * layout.width).min(line.len()))
                .unwrap_or("")
                .trim();
            let reason = |why: &str| {
                format!(
                    "field {} of the {what} ({} characters from column {column}) {why}",
                    out.len() + 1,
                    layout.width
                )
            };
            let located = |why: String| {
                let mut e = at(path, line_no, Some(column), why);
                e.field = format!("{what}[{}]", out.len() + 1);
                e
            };
            if field.is_empty() {
                return Err(located(reason("is blank")));
            }
            match parse_float(field) {
                Some(x) if x.is_finite() => out.push(x),
                _ => {
                    return Err(located(reason(&format!(
                        "is \"{field}\", not a finite number"
                    ))));
                }
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fortran_formats() {
        assert_eq!(Layout::parse("(8f9.6)"), Some(Layout::new(8, 9)));
        assert_eq!(Layout::parse("(8F10.5)  "), Some(Layout::new(8, 10)));
        assert_eq!(Layout::parse("(10I8)"), Some(Layout::new(10, 8)));
        assert_eq!(Layout::parse("(1E15.6)"), Some(Layout::new(1, 15)));
        assert_eq!(Layout::parse("(E15.6)"), Some(Layout::new(1, 15)));
        assert_eq!(Layout::parse("(x)"), None);
        assert_eq!(
            format_in("35430 Accelerogram points at 100 pts/sec in units of g.  Format: (8f9.6)"),
            Some(Layout::new(8, 9))
        );
    }

    #[test]
    fn fields_run_together_and_errors_are_located() {
        let lines = [
            " 20.000000 4.4937120      .000-999.00000",
            "-999.00000 x.0000000",
        ];
        let p = Path::new("r.v1");
        let v = read_block(p, &lines, 0, 4, Layout::new(4, 10), "real header").unwrap();
        assert_eq!(v, vec![20.0, 4.493712, 0.0, -999.0]);
        let e = read_block(p, &lines, 0, 6, Layout::new(4, 10), "real header").unwrap_err();
        assert_eq!((e.line, e.column), (Some(2), Some(11)));
        assert!(
            e.reason.contains("field 6 of the real header"),
            "{}",
            e.reason
        );
        assert_eq!(e.field, "real header[6]");
    }
}

//! `[[external]]`: other programs' results taking part like engines: the label, the
//! file's layout (delimiter, preamble, column map, MCAP topic) and the file itself, read
//! by the validator's reader so that a bad results file is an input error before any work.

use std::path::Path;

use super::super::external::{External, ExternalFormat, check_label};
use super::super::raw::RawExternal;
use super::validator::Validator;
use crate::error::InputError;
use crate::trace::parse_header;

/// The external file's layout from its `[[external]]` keys, or the reason for a bad key.
fn external_format(e: &RawExternal) -> Result<ExternalFormat, (&'static str, String)> {
    let delimiter = match e.delimiter.as_deref() {
        None | Some(",") => None,
        Some(";") => Some(';'),
        Some("tab") | Some("\t") => Some('\t'),
        Some("blanks") => Some(' '),
        Some(other) => {
            return Err((
                "delimiter",
                format!(
                    "is \"{other}\", but must be \",\" (default), \";\", \"tab\" or \"blanks\""
                ),
            ));
        }
    };
    let skip_lines = match e.skip_lines {
        None => 0,
        Some(n) if (0..=10_000).contains(&n) => n as usize,
        Some(n) => {
            return Err((
                "skip_lines",
                format!("is {n}, but must be between 0 and 10000"),
            ));
        }
    };
    for (from, to) in &e.columns {
        if let Err(why) = parse_header(to) {
            return Err(("columns", format!("\"{from}\" = \"{to}\": {why}")));
        }
    }
    Ok(ExternalFormat {
        columns: e
            .columns
            .iter()
            .map(|(a, b)| (a.clone(), b.clone()))
            .collect(),
        delimiter,
        skip_lines,
        topic: e.topic.clone(),
    })
}

impl Validator<'_> {
    /// Every `[[external]]`: label, layout and the file itself (relative to the case), read
    /// now so that a bad results file is an input error before any work.
    pub(super) fn externals(&mut self, raw: &[RawExternal], case_path: &Path) -> Vec<External> {
        let dir = case_path.parent().unwrap_or(Path::new(""));
        let mut out: Vec<External> = Vec::new();
        for (i, e) in raw.iter().enumerate() {
            let field = format!("external[{i}]");
            if let Err(why) = check_label(&e.label, self.engine_ids) {
                self.fail(&format!("{field}.label"), why);
                continue;
            }
            if raw[..i].iter().any(|o| o.label == e.label) {
                self.fail(
                    &format!("{field}.label"),
                    format!("\"{}\" is used twice", e.label),
                );
                continue;
            }
            let format = match external_format(e) {
                Ok(f) => f,
                Err((key, why)) => {
                    self.fail(&format!("{field}.{key}"), why);
                    continue;
                }
            };
            let file = dir.join(&e.file);
            let mcap = file
                .extension()
                .is_some_and(|x| x.eq_ignore_ascii_case("mcap"));
            if e.topic.is_some() && !mcap {
                self.fail(
                    &format!("{field}.topic"),
                    "applies to an MCAP results file (`.mcap`) only; this file is read as CSV, \
                     which has no topics",
                );
                continue;
            }
            match (self.read_external)(&file, &format) {
                Ok(read) => out.push(External {
                    label: e.label.clone(),
                    program: e.program.clone(),
                    element: e.element.clone().unwrap_or_else(|| "not stated".into()),
                    file,
                    read,
                    field,
                }),
                Err(errs) => {
                    // The results file's own errors, located at the case's field (`file`,
                    // or the option that names the column) and in the results file.
                    for err in errs.0 {
                        let case_field = match err.field.as_str() {
                            "" => format!("{field}.file"),
                            inner => format!("{field}.{inner}"),
                        };
                        let in_file = InputError {
                            field: String::new(),
                            ..err
                        };
                        self.errors
                            .push(in_file.named_by(self.loc.error(&case_field, "")));
                    }
                }
            }
        }
        out
    }
}

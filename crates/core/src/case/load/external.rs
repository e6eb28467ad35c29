//! `[[external]]`: other programs' results taking part like engines: the label, the
//! file's layout (the program's format, delimiter, preamble, column map with signs and
//! scales, MCAP topic, SAP2000 output case, OpenSees recorder or script) and the file
//! itself, read by the validator's reader so that a bad results file is an input error
//! before any work.

use std::path::Path;

use super::super::external::{ColumnMap, External, ExternalFormat, ExternalLayout, check_label};
use super::super::raw::{RawColumn, RawExternal};
use super::validator::Validator;
use crate::error::InputError;
use crate::trace::parse_header;

/// The external file's layout from its `[[external]]` keys (`dir`: the case's folder,
/// against which a `script` resolves), or the reason for a bad key.
fn external_format(
    e: &RawExternal,
    dir: &Path,
    run_dt: f64,
) -> Result<ExternalFormat, (&'static str, String)> {
    let layout = match e.format.as_deref() {
        None => None,
        Some(key) => Some(ExternalLayout::from_key(key).ok_or_else(|| {
            let keys = ExternalLayout::KEYS;
            ("format", format!("is \"{key}\", but must be one of {keys}"))
        })?),
    };
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
    let columns = column_map(e)?;
    let opensees_only = |key: &'static str, given: bool| {
        if given && layout != Some(ExternalLayout::OpenSeesRecorder) {
            Err((
                key,
                "applies to OpenSees recorder files only (format = \"opensees\")".to_string(),
            ))
        } else {
            Ok(())
        }
    };
    opensees_only("recorder", e.recorder.is_some())?;
    opensees_only("script", e.script.is_some())?;
    if e.output_case.is_some() && layout != Some(ExternalLayout::CsiTables) {
        return Err((
            "output_case",
            "applies to SAP2000/ETABS/CSiBridge tables only (format = \"sap2000\")".into(),
        ));
    }
    if let Some(dt) = e.step_dt {
        if layout != Some(ExternalLayout::CsiTables) {
            return Err((
                "step_dt",
                "applies to SAP2000/ETABS/CSiBridge tables only (format = \"sap2000\")".into(),
            ));
        }
        if !(dt.is_finite() && dt > 0.0) {
            return Err((
                "step_dt",
                format!("is {dt}, but must be a positive time (s)"),
            ));
        }
    }
    Ok(ExternalFormat {
        layout,
        columns,
        delimiter,
        skip_lines,
        topic: e.topic.clone(),
        output_case: e.output_case.clone(),
        recorder: e.recorder.clone(),
        script: e.script.as_ref().map(|s| dir.join(s)),
        step_dt: e
            .step_dt
            .or(Some(run_dt).filter(|dt| dt.is_finite() && *dt > 0.0)),
    })
}

/// The column map: each entry's rockslide header checked, its factor finite and non-zero.
fn column_map(e: &RawExternal) -> Result<Vec<ColumnMap>, (&'static str, String)> {
    let mut out = Vec::with_capacity(e.columns.len());
    for (from, column) in &e.columns {
        let (to, scale) = match column {
            RawColumn::Header(to) => (to, 1.0),
            RawColumn::Scaled(s) => (&s.quantity, s.scale),
        };
        if let Err(why) = parse_header(to) {
            return Err(("columns", format!("\"{from}\" = \"{to}\": {why}")));
        }
        if !(scale.is_finite() && scale != 0.0) {
            return Err((
                "columns",
                format!("\"{from}\": scale is {scale}, but must be a finite number other than 0"),
            ));
        }
        out.push(ColumnMap {
            from: from.clone(),
            to: to.clone(),
            scale,
        });
    }
    Ok(out)
}

impl Validator<'_> {
    /// Every `[[external]]`: label, layout and the file itself (relative to the case), read
    /// now so that a bad results file is an input error before any work.
    pub(super) fn externals(
        &mut self,
        raw: &[RawExternal],
        case_path: &Path,
        run_dt: f64,
    ) -> Vec<External> {
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
            let format = match external_format(e, dir, run_dt) {
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

//! A case loaded with its other programs' results read: core validates the case and hands
//! each `[[external]]` results file to [`read_external`]; a results file named on the
//! command line (`--external LABEL=PATH`) is read and checked the same way.

use std::path::Path;

use rockslide_core::case::{
    Case, External, ExternalFormat, check_label, load_case_with, parse_case_with,
};
use rockslide_core::error::{InputError, InputErrors};

use crate::external::read_external;

/// Read and validate the case file at `path`, its `[[external]]` results files read;
/// `engine_ids` are the engines a case may name (the registry's, so that there is one
/// list).
pub fn load_case(path: &Path, engine_ids: &[&str]) -> Result<Case, InputErrors> {
    load_case_with(path, engine_ids, read_external)
}

/// Validate a case from its text (`path` names it in messages, sets the default name and
/// the folder its `[[external]]` files are read from).
pub fn parse_case(path: &Path, text: &str, engine_ids: &[&str]) -> Result<Case, InputErrors> {
    parse_case_with(path, text, engine_ids, read_external)
}

/// Read a results file named on the command line (`--external LABEL=PATH`: rockslide's
/// own CSV headers, or a state topic of a rockslide MCAP file — `topic`, needed when it
/// has several) and validate its label against the engines and the case's participants.
pub fn read_external_participant(
    case: &Case,
    label: &str,
    file: &Path,
    topic: Option<&str>,
    engine_ids: &[&str],
) -> Result<External, InputErrors> {
    let field = format!("--external {label}");
    let flag_error = |why: String| InputError::new(file, field.clone(), why);
    check_label(label, engine_ids).map_err(|why| flag_error(format!("label {why}")))?;
    if case.externals.iter().any(|e| e.label == label) {
        return Err(flag_error(format!(
            "label \"{label}\" is already a participant of {}",
            case.path.display()
        ))
        .into());
    }
    let format = ExternalFormat {
        topic: topic.map(str::to_string),
        step_dt: Some(case.run.dt),
        ..Default::default()
    };
    let read = read_external(file, &format)?;
    Ok(External {
        label: label.to_string(),
        program: "a program not stated (given on the command line)".into(),
        element: "not stated".into(),
        file: file.to_path_buf(),
        read,
        field,
    })
}

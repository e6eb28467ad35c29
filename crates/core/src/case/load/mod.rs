//! Loading a case, in two stages: read the file and parse the raw form (syntax and type
//! errors located by the TOML parser, `syntax`), then validate every field, section by
//! section (semantic errors located by [`Locator`]). All problems of a file are returned
//! together, in the order of the sections below.
//!
//! | module | validates |
//! |---|---|
//! | `syntax` | the TOML itself: syntax, types, every unknown key |
//! | `validator` | the validator's state; a number against its rule (range and unit) |
//! | `model` | `[model]`: oscillator, rocking body, rigid block; contacts |
//! | `excitation` | `[excitation]`: kind and signal (sine pulse or record) |
//! | `record_signal` | a recorded excitation: unit, polarity, PGA, column, the file |
//! | `vertical` | `[excitation.vertical]`: vertical ground motion, normal force |
//! | `spatial` | 3D scenes: azimuth, `[excitation.y]`, depth, inertias |
//! | `station` | `[excitation.station]`: a station file's channels on x, y and z |
//! | `run` | `name`, `[run]`: duration, steps, output step |
//! | `engines` | `[engines.<id>]`: step, variants, options |
//! | `tolerances` | `[[tolerance]]`, `[[expected_outcome]]`, `[[expected_violation]]`, `[[expected_disagreement]]` |
//! | `external` | `[[external]]`: label, layout, the results file (read by the given reader) |

use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

use super::external::{ExternalFormat, ExternalTrace, ReadExternal};
use super::locate::Locator;
use super::scene::{Case, Scene};
use crate::error::{InputError, InputErrors};

mod engines;
mod excitation;
mod external;
mod model;
mod record_signal;
mod run;
mod spatial;
pub(crate) mod station;
mod syntax;
mod tolerances;
mod validator;
mod vertical;

use syntax::deserialize_case;
use validator::Validator;

/// Read and validate the case file at `path`; `engine_ids` are the engines a case may name
/// (the registry's, passed in so that there is one list).
///
/// Results files of other programs (`[[external]]`) are not read here: the file formats
/// are not core's. A case naming one gets an error at `external[i].file`; load it through
/// [`load_case_with`] and the reader of the crate that holds the formats.
pub fn load_case(path: &Path, engine_ids: &[&str]) -> Result<Case, InputErrors> {
    load_case_with(path, engine_ids, no_external_reader)
}

/// [`load_case`] reading each `[[external]]` results file with `read_external`.
pub fn load_case_with(
    path: &Path,
    engine_ids: &[&str],
    read_external: ReadExternal,
) -> Result<Case, InputErrors> {
    let text = read_input_text(path, "case file")?;
    parse_case_with(path, &text, engine_ids, read_external)
}

/// The reader of a loader without the file formats ([`load_case`], [`parse_case`]): every
/// results file is refused, located at its `[[external]]`.
fn no_external_reader(path: &Path, _: &ExternalFormat) -> Result<ExternalTrace, InputErrors> {
    Err(InputError::new(
        path,
        "",
        "results files of other programs are not read by the case loader of rockslide-core \
         alone: load the case through rockslide-formats",
    )
    .into())
}

/// Largest case or grid file read, bytes: a case is a page of TOML; anything far larger
/// is not one.
pub const MAX_CASE_BYTES: u64 = 4 << 20;

/// The text of a TOML input (`what`: "case file", "grid file"): a regular file (not a
/// device such as `/dev/zero`) of at most [`MAX_CASE_BYTES`], UTF-8 (else the error names
/// the line and column of the first bad byte).
pub fn read_input_text(path: &Path, what: &str) -> Result<String, InputError> {
    use std::io::Read;
    let cannot =
        |e: std::io::Error| InputError::new(path, "", format!("cannot read the {what}: {e}"));
    if !std::fs::metadata(path).map_err(cannot)?.is_file() {
        return Err(InputError::new(
            path,
            "",
            format!("the {what} is not a regular file (a device, pipe or folder)"),
        ));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .map_err(cannot)?
        .take(MAX_CASE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > MAX_CASE_BYTES {
        return Err(InputError::new(
            path,
            "",
            format!("the {what} is larger than {MAX_CASE_BYTES} bytes: not read"),
        ));
    }
    String::from_utf8(bytes).map_err(|e| {
        let (line, column) = super::record::first_invalid_utf8(&e);
        let mut err = InputError::new(
            path,
            "",
            format!("the {what} is not UTF-8 text (an invalid byte here): save it as UTF-8"),
        );
        err.line = Some(line);
        err.column = column;
        err
    })
}

/// Validate a case from its text (`path` names it in messages and sets the default name);
/// results files of other programs are refused, as by [`load_case`].
pub fn parse_case(path: &Path, text: &str, engine_ids: &[&str]) -> Result<Case, InputErrors> {
    parse_case_with(path, text, engine_ids, no_external_reader)
}

/// [`parse_case`] reading each `[[external]]` results file with `read_external`.
pub fn parse_case_with(
    path: &Path,
    text: &str,
    engine_ids: &[&str],
    read_external: ReadExternal,
) -> Result<Case, InputErrors> {
    let (raw, unknown_keys) = deserialize_case(path, text)?;
    let locator = Locator::new(path, text);
    let mut v = Validator {
        loc: &locator,
        engine_ids,
        external_labels: raw.external.iter().map(|e| e.label.clone()).collect(),
        errors: unknown_keys,
        read_external,
    };
    let model = v.model(&raw.model);
    let motion = v.ground_motion(&raw.excitation, model.as_ref(), raw.run.duration, path);
    let (excitation, vertical, station_y, azimuths) = (
        motion.excitation,
        motion.vertical,
        motion.y,
        motion.azimuths,
    );
    let spatial = v.spatial(&raw.model, &raw.excitation, model.as_ref(), station_y, path);
    let run = v.run(raw.run.duration, raw.run.dt, raw.run.output_dt);
    let engines = v.engines(&raw.engines, raw.run.duration, raw.run.output_dt);
    let name = v.name(raw.name.as_deref(), path);
    let tolerances = raw
        .tolerance
        .iter()
        .enumerate()
        .filter_map(|(i, t)| v.tolerance(i, t))
        .collect();
    let expected_outcomes = raw
        .expected_outcome
        .iter()
        .enumerate()
        .map(|(i, o)| v.expected_outcome(i, o))
        .collect();
    let expected_violations = raw
        .expected_violation
        .iter()
        .enumerate()
        .map(|(i, o)| v.expected_violation(i, o))
        .collect();
    let expected_disagreements = raw
        .expected_disagreement
        .iter()
        .enumerate()
        .map(|(i, o)| v.expected_disagreement(i, o))
        .collect();
    let externals = v.externals(&raw.external, path, raw.run.dt);
    if !v.errors.is_empty() {
        return Err(InputErrors(v.errors));
    }
    let (Some(model), Some(excitation)) = (model, excitation) else {
        unreachable!("a missing model or excitation always records an error")
    };
    let mut case = Case {
        title: raw.title.unwrap_or_else(|| name.clone()),
        name,
        source: raw.source.unwrap_or_default(),
        requirement: raw.requirement.unwrap_or_default(),
        path: path.to_path_buf(),
        sha256: format!("{:x}", Sha256::digest(text.as_bytes())),
        text: text.to_string(),
        scene: Scene {
            model,
            excitation,
            vertical,
            spatial,
        },
        run,
        engines,
        tolerances,
        expected_outcomes,
        expected_violations,
        expected_disagreements,
        locator,
        externals: Vec::new(),
        parsed_options: Default::default(),
        azimuths,
    };
    for e in externals {
        case.add_external(e);
    }
    Ok(case)
}

/// All case files (`*.toml`) under `dir`, sorted, skipping `README`s and study grids.
pub fn discover(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.extension().is_some_and(|e| e == "toml") {
            found.push(path);
        }
    }
    found.sort();
    Ok(found)
}

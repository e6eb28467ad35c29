//! The predictor-corrector's section of a case, `[engines.predictor-corrector]`: the
//! paper's method has no options of its own, only the common `dt` and `variants`, so every
//! other key is a located error (as the other engines reject keys they do not know) —
//! never silently ignored.

use rockslide_core::case::Case;
use rockslide_core::error::InputError;

/// The engine id as written in case files.
pub const ID: &str = "predictor-corrector";

/// The options of the paper's method: none (what a valid section parses to).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PcOptions;

/// The section parsed: every key beside `dt` and `variants` is an error.
pub fn parse(case: &Case) -> Result<PcOptions, Vec<InputError>> {
    let errors = unknown_keys(case);
    if errors.is_empty() {
        Ok(PcOptions)
    } else {
        Err(errors)
    }
}

/// Every key of `[engines.predictor-corrector]` beside `dt` and `variants`, as an error.
fn unknown_keys(case: &Case) -> Vec<InputError> {
    let Some(request) = case.engine(ID) else {
        return Vec::new();
    };
    request
        .options
        .keys()
        .map(|k| {
            case.field_error(
                &format!("engines.{ID}.{k}"),
                "unknown option of the predictor-corrector: the paper's method takes only \
                 `dt` and `variants`",
            )
        })
        .collect()
}

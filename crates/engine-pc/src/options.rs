//! The predictor-corrector's section of a case, `[engines.predictor-corrector]`: the
//! paper's method has no options of its own, only the common `dt` and `variants`, so every
//! other key is a located error (as the other engines reject keys they do not know) —
//! never silently ignored.

use rockslide_core::case::Case;
use rockslide_core::error::InputError;

/// The engine id as written in case files.
pub const ID: &str = "predictor-corrector";

/// Every key of `[engines.predictor-corrector]` beside `dt` and `variants`, as an error.
pub fn check(case: &Case) -> Vec<InputError> {
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

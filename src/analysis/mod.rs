//! Analysis: response quantities read off a trace (peaks, residuals, event times), the
//! discrepancies between runs and against the reference, whole-history differences, and
//! tolerance checks.

mod checks;
mod metrics;

pub use checks::{Check, Verdict, evaluate_tolerances};
pub use metrics::{
    QUANTITY_KEYS, QuantityDef, Responses, discrepancy_percent, history_difference, quantity_def,
    responses,
};

//! Analysis: response quantities read off a trace (peaks, residuals, event times), the
//! discrepancies between runs and against the reference, whole-history differences, and
//! tolerance checks; the Δt ladder and observed order (`sweep`), stability classes
//! (`stability`) and the energy audit (`energy`).

mod checks;
pub mod energy;
pub mod envelope;
mod metrics;
pub mod stability;
pub mod streamed;
pub mod sweep;

pub use checks::{Check, Verdict, evaluate_tolerances};
pub use metrics::{
    EPISODE_MIN_SLIP, Responses, discrepancy_percent, history_difference, responses,
};
pub use rockslide_core::response::{QUANTITY_KEYS, QuantityDef, quantity_def};

//! The gate: which gated checks of a run of the suite failed, one line each (case,
//! quantity, runs compared, value, tolerance), and the same as JUnit XML for CI systems.
//! `rockslide check` exits 1 when [`failures`] is not empty.
//!
//! A gated check fails when its discrepancy exceeds the tolerance, and also when it could
//! not be evaluated (a run diverged, a quantity is missing) or when a gated tolerance
//! matched no run at all — a check that checks nothing is itself a failure (the Code_Aster
//! TEST_RESU convention).

mod junit;
mod step_summary;

pub use junit::{junit_report, write_junit};
pub use rockslide_verify::failure::Failure;
pub use rockslide_verify::verdict::{failures, informative, limit_text};
pub use step_summary::{REPORTS_URL, step_summary_links, write_step_summary};

//! # rockslide-verify — running cases and judging them
//!
//! ```text
//! case file ─▶ Case ─▶ registry (engines) ─▶ suite::run_case ─▶ CaseResult ─▶ verdict
//!                   └─▶ rockslide-reference (exact, independent) ──┘
//! ```
//!
//! - [`registry`]: the engines and the case loader that knows them.
//! - [`suite`]: plan a case's runs, run them (guarded and timed), solve the reference, read
//!   responses, apply tolerances.
//! - [`analysis`]: response quantities, discrepancies, tolerance checks, the energy audit,
//!   Δt ladders and observed orders, stability classes — numbers, no I/O.
//! - [`verdict`]: the one pass/fail rule.
//! - [`sweep`]: work-precision and stability commands; [`study`]: record/PGA/μ grids.

#![warn(missing_docs)]

pub mod analysis;
pub mod registry;
pub mod study;
pub mod suite;
pub mod sweep;
pub mod verdict;

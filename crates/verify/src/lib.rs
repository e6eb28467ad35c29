//! # rockslide-verify — running cases and judging them
//!
//! ```text
//! case file ─▶ Case ─▶ registry (engines) ─▶ suite::run_case ─▶ CaseResult ─▶ verdict
//!                   └─▶ rockslide-reference (exact, independent) ──┘
//! ```
//!
//! - [`registry`]: the engines and the case loader that knows them.
//! - [`footprint`]: the memory and disk a plan needs, refused over a limit before any work.
//! - [`run`]: the one guarded, timed engine run every command goes through.
//! - [`suite`]: plan a case's runs, run them, solve the reference, read responses, apply
//!   tolerances; [`azimuths`]: a case run at each azimuth of its set, and the maxima.
//! - [`analysis`]: response quantities, discrepancies, tolerance checks, the energy audit,
//!   Δt ladders and observed orders, stability classes — numbers, no I/O.
//! - [`disagreement`]: design quantities of each participant against the basis, declared
//!   or failing.
//! - [`external`]: other programs' results as runs, gated like an engine's;
//!   [`opensees`] and [`calculix`]: those programs run live on the exported scene, what
//!   they share in [`live`].
//! - [`verdict`]: the one pass/fail rule, its lines [`failure::Failure`]; [`record`]: a
//!   case result as a typed record (`result.json`), a check in it [`check_record`], a set
//!   of azimuths in it [`azimuth_record`].
//! - [`timings`]: opt-in wall and CPU time of a command's stages (`--timings`).
//! - [`sweep`]: work-precision sweeps and stability studies; [`study`]: record/PGA/μ grids.
//!   Their results are typed serde structs, saved and read back as JSON ([`json`]);
//!   `rockslide-present` renders them.

#![warn(missing_docs)]

pub mod analysis;
pub mod azimuth_record;
pub mod azimuths;
pub mod calculix;
pub mod check_record;
pub mod disagreement;
pub mod external;
pub mod failure;
pub mod footprint;
pub mod invariants;
pub mod json;
pub mod live;
pub mod opensees;
pub mod plan;
pub mod progress;
pub mod record;
pub mod reference;
pub mod registry;
pub mod result;
pub mod run;
pub mod study;
pub mod suite;
pub mod sweep;
pub mod timings;
pub mod verdict;

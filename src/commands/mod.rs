//! The commands, one file each: each takes its parsed arguments ([`crate::args`]), loads
//! and checks its input before any work, asks `rockslide-verify` for typed results,
//! saves them as JSON where other commands read them back, asks `rockslide-present` to
//! render the human files, and prints a few lines. Returns the exit code.
//!
//! - [`everything`]: `rockslide` with no command (the complete document);
//! - [`run`], [`check`]: cases run and reported; `check` gates on their tolerances;
//! - [`list`]: the cases and the engines that apply to each;
//! - [`reference`]: a case's reference solution as a CSV trace;
//! - [`sweep`]: work-precision over a Δt ladder;
//! - [`stability`]: classes and limits on stiff scenes;
//! - [`study`], [`study_merge`]: many records × PGA × μ, sharded and merged;
//! - [`newmark`]: Newmark's rigid block on a record;
//! - [`trace_info`]: what an MCAP trace holds;
//! - [`export`]: a case's scene as another program's input.

pub mod check;
pub mod everything;
pub mod export;
pub mod list;
pub mod newmark;
pub mod reference;
pub mod run;
pub mod stability;
pub mod study;
pub mod study_merge;
pub mod sweep;
pub mod trace_info;

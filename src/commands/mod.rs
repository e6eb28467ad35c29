//! The many-run commands. Each loads its input, asks `rockslide-verify` for a typed
//! result, saves it as JSON (the contract the reports read back), asks
//! `rockslide-present` to render the human files, and prints a few lines.
//!
//! - [`sweep`]: `rockslide sweep` (work-precision over a Δt ladder);
//! - [`stability`]: `rockslide stability` (classes and limits on stiff scenes);
//! - [`export`]: `rockslide export` (a case's scene as another program's input);
//! - [`study`]: `rockslide study`, `study-merge` and `newmark` (records).

pub mod export;
pub mod stability;
pub mod study;
pub mod sweep;

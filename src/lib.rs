//! # rockslide — cross-code verification of seismic sliding and rocking
//!
//! The command line ([`args`] its definitions, [`cli`] the dispatch, [`commands`] one
//! file per command) and a façade over the workspace, so that tests, benchmarks,
//! examples and library users find every part under one name. The architecture lives in
//! the crates, one way from `rockslide-core` through the engines and the references to
//! `rockslide-verify` and `rockslide-present`: ARCHITECTURE.md draws the graph and its
//! table, checked against the manifests, says which crate may name which.

#![warn(missing_docs)]

/// Print one line on stdout; a reader that went away (`rockslide list | head -1`) is not an
/// error: the rest of the output is dropped (every command prints through this, never
/// `println!`, which panics on a closed pipe).
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout().lock(), $($arg)*);
    }};
}

pub mod args;
pub mod cli;
pub mod commands;
mod input;
mod schedule;
mod suite_run;
pub mod timings;

pub use rockslide_core::{error, io, response, trace};
/// Scene export (`rockslide export`): another program's input written from a case.
pub use rockslide_export as export;
/// The trace's files (CSV, MCAP, the Foxglove 3D scene) and other programs' results read
/// as traces.
pub use rockslide_formats as formats;
/// The renderers of every human output (`present::sweep`, `present::stability`,
/// `present::study` beside the reports).
pub use rockslide_present as present;
pub use rockslide_present::{gate, report, stamp};
pub use rockslide_reference as reference;
pub use rockslide_verify::{
    analysis, azimuths, calculix, external, invariants, json, opensees, record, registry, run,
    study, suite, sweep, verdict,
};

/// Case files; [`case::load_case`] and [`case::parse_case`] validate against the engine
/// registry.
pub mod case {
    pub use rockslide_core::case::*;
    pub use rockslide_verify::registry::{load_case, parse_case};
}

/// The engines behind one interface, and the registry.
pub mod engine {
    pub use rockslide_engine_api::*;
    pub use rockslide_engine_fe as fe;
    pub use rockslide_engine_pc as predictor_corrector;
    pub use rockslide_engine_rapier as rigid_body;
    pub use rockslide_verify::registry::{ENGINE_IDS, all};
}

//! Many-run studies: one model (a base case) under many records, PGA levels or scale
//! factors, friction coefficients and polarities, from a small TOML grid (`grid`). Points
//! run in parallel and resume after interruption (`runner`), split into shards for cluster
//! job arrays, and are gathered back into one typed [`Study`] (`collect`), written as
//! `study.json` and rendered by `rockslide-present`. `newmark` is the SLAMMER-style
//! rigid-block table of one record. User documentation: docs/records-and-studies.md.

mod collect;
mod grid;
mod newmark;
mod runner;

pub use collect::{
    Compared, FILE, Headline, RIGID, SAME_TO, Stamp, Statistics, Study, agreement, agreement_on,
    collect, headline, label, statistics, summary_statistics,
};
pub use grid::{Amplitude, DEFAULT_TAIL, Grid, GridPoint, GridRecord, load_grid, short_name};
pub use newmark::{NewmarkArgs, newmark_command};
pub use runner::{
    EXACT, PointResult, RunSummary, StudyOptions, StudyOutcome, read_result, result_path,
    run_study, runs_dir, yield_acceleration,
};

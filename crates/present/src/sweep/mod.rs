//! The human outputs of a sweep (`rockslide sweep`), rendered from its typed result
//! ([`SweepResult`], which the command saves as `sweep.json`): `sweep.md` and
//! `sweep.html` through the one document model, `sweep.csv` (one row per rung, through
//! `csv::Writer`) and the figure `sweep.svg`; and the work-precision section of the case
//! report.
//!
//! - `document`: the sweep's page and the case report's section; `figure`: the figure.

mod document;
mod figure;

pub(crate) use document::case_section;

use std::path::Path;

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;
use rockslide_verify::sweep::SweepResult;

use crate::doc::files::{csv_bytes, csv_e, write_document};

/// Columns of `sweep.csv`.
pub const CSV_HEADER: [&str; 17] = [
    "series",
    "dt_s",
    "dt_over_T",
    "status",
    "max_error",
    "rms_error",
    "residual_sliding_error_m",
    "event_time_error_s",
    "energy_relative_error",
    "time_median_s",
    "time_min_s",
    "time_max_s",
    "steps",
    "deterministic",
    "change_to_next",
    "substeps_per_step",
    "repeats",
];

/// The sweep as CSV, one row per rung (SI, full precision).
pub fn sweep_csv(r: &SweepResult) -> Result<Vec<u8>, Error> {
    let rows = r.series.iter().flat_map(|se| {
        se.rungs.iter().map(move |g| {
            let e = g.error;
            vec![
                se.label.clone(),
                format!("{:e}", g.dt),
                format!("{:e}", g.dt_over_t),
                g.outcome.label().to_string(),
                csv_e(e.map(|e| e.max)),
                csv_e(e.map(|e| e.rms)),
                csv_e(e.and_then(|e| e.residual_sliding)),
                csv_e(e.and_then(|e| e.event_time)),
                csv_e(g.energy.as_ref().ok().map(|e| e.relative_error)),
                csv_e(g.seconds.map(|s| s.median)),
                csv_e(g.seconds.map(|s| s.min)),
                csv_e(g.seconds.map(|s| s.max)),
                g.steps.to_string(),
                g.deterministic.to_string(),
                csv_e(g.change),
                csv_e(g.substeps),
                g.repeats.to_string(),
            ]
        })
    });
    csv_bytes(&CSV_HEADER, rows)
}

/// Write `sweep.md`, `sweep.html`, `sweep.csv` and `sweep.svg` into `dir` (the case's
/// output folder).
pub fn write_sweep(r: &SweepResult, dir: &Path) -> Result<(), Error> {
    write_atomically(&dir.join("sweep.csv"), &sweep_csv(r)?)?;
    write_document(
        dir,
        "sweep",
        &format!("rockslide — {}: error against run time", r.case),
        &document::document(r),
    )
}

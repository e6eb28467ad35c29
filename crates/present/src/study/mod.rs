//! The human outputs of a study (`rockslide study`, `study-merge`), rendered from its
//! typed result ([`Study`], which the command saves as `study.json`): `summary.md` and
//! `summary.html` through the one document model, `summary.csv` (one row per point and
//! run, through `csv::Writer`) and the residual-sliding figures.
//!
//! - `document`: the summary page and the headline sentences; `figure`: the plots.

mod document;
mod figure;

pub use document::{headline_sentences, sentence};

use std::path::Path;

use rockslide_core::case::record::STANDARD_GRAVITY;
use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;
use rockslide_verify::study::{Study, short_name};

use crate::doc::files::{csv_bytes, write_document};

/// Columns of `summary.csv`.
pub const CSV_HEADER: [&str; 24] = [
    "point",
    "record",
    "pga_m_s2",
    "pga_g",
    "scale_factor",
    "mu",
    "polarity",
    "engine",
    "variant",
    "dt_s",
    "status",
    "residual_sliding_m",
    "residual_sliding_cm",
    "peak_abs_sliding_m",
    "peak_relative_displacement_m",
    "slip_episodes",
    "total_slid_m",
    "slip_start_s",
    "slip_end_s",
    "steps",
    "peak_resultant_sliding_m",
    "residual_resultant_sliding_m",
    "peak_uplift_m",
    "peak_rotation_rad",
];

/// The summary table as CSV (SI values at full precision, plus cm and g columns).
pub fn summary_csv(c: &Study) -> Result<Vec<u8>, Error> {
    let opt = |x: Option<f64>| x.map_or_else(String::new, |v| format!("{v}"));
    let rows = c.rows().map(|(r, run)| {
        vec![
            r.point.id(),
            short_name(&r.record),
            format!("{}", r.pga),
            format!("{}", r.pga / STANDARD_GRAVITY),
            format!("{}", r.scale_factor),
            format!("{}", r.mu),
            format!("{}", r.point.polarity),
            run.engine.clone(),
            run.variant.clone(),
            format!("{}", run.dt),
            run.status.clone(),
            opt(run.residual_sliding),
            opt(run.residual_sliding.map(|m| m * 100.0)),
            opt(run.peak_abs_sliding),
            opt(run.peak_relative_displacement),
            run.slip_episodes
                .map_or_else(String::new, |n| n.to_string()),
            opt(run.total_slid),
            opt(run.slip_start),
            opt(run.slip_end),
            run.steps.to_string(),
            opt(run.peak_resultant_sliding),
            opt(run.residual_resultant_sliding),
            opt(run.peak_uplift),
            opt(run.peak_rotation),
        ]
    });
    csv_bytes(&CSV_HEADER, rows)
}

/// Write `summary.csv`, `summary.md`, `summary.html` and the figures
/// (`residual-vs-pga.svg`, and with more than one engine variant
/// `residual-vs-pga-<engine>-<variant>.svg` for each) into `out`.
pub fn write_summary(c: &Study, out: &Path) -> Result<(), Error> {
    write_atomically(&out.join("summary.csv"), &summary_csv(c)?)?;
    write_document(
        out,
        "summary",
        &format!("rockslide — study: {}", c.title),
        &document::document(c),
    )
}

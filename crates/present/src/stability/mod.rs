//! The human outputs of a stability study (`rockslide stability`), rendered from its
//! typed result ([`StabilityResult`], which the command saves as `stability.json`):
//! `stability.md` and `stability.html` through the one document model, `stability.csv`
//! (one row per run, through `csv::Writer`) and the map `stability.svg`; and the
//! stability section of the suite report.
//!
//! - `document`: the study's page and the suite report's section; `figure`: the map.

mod document;
mod figure;

pub(crate) use document::suite_section;

use std::path::Path;

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;
use rockslide_verify::sweep::StabilityResult;

use crate::report::files::{csv_bytes, csv_e, write_document};

/// Columns of `stability.csv`.
pub const CSV_HEADER: [&str; 9] = [
    "scene",
    "series",
    "dt_over_T",
    "dt_s",
    "class",
    "time_s",
    "max_error",
    "energy_relative_error",
    "reason",
];

/// The study as CSV, one row per run.
pub fn stability_csv(r: &StabilityResult) -> Result<Vec<u8>, Error> {
    let rows = r.runs.iter().map(|q| {
        vec![
            q.case.clone(),
            q.series.clone(),
            format!("{}", q.dt_over_t),
            format!("{:e}", q.dt),
            q.class.label().to_string(),
            csv_e(q.class.time()),
            csv_e(q.error),
            csv_e(q.energy.as_ref().ok().map(|e| e.relative_error)),
            q.class.reason().to_string(),
        ]
    });
    csv_bytes(&CSV_HEADER, rows)
}

/// Write `stability.md`, `stability.html`, `stability.csv` and `stability.svg` into
/// `dir` (`<out>/stability/`).
pub fn write_stability(r: &StabilityResult, dir: &Path) -> Result<(), Error> {
    write_atomically(&dir.join("stability.csv"), &stability_csv(r)?)?;
    write_document(
        dir,
        "stability",
        "rockslide — stability on stiff and extreme scenes",
        &document::document(r),
    )
}

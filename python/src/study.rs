//! Studies from Python: a grid file's points run in parallel across cores with the GIL
//! released (resumable: a point with a result in `<out>/runs/` is not run again), then
//! gathered into `<out>/study.json` and its summary pages, as `rockslide study` does.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use rockslide_core::error::Error;
use rockslide_verify::study::{StudyOptions, collect, load_grid, run_study as run_grid};

use crate::errors::{input_error, to_py};

/// Run the study `grid` (a study TOML file) into `out`, or only shard `(k, n)` of it;
/// unsharded, gather and write `study.json` and the summary. Returns the counts
/// (`points`, `assigned`, `executed`, `skipped`, `runs`) and, unsharded, the study
/// (`study`, the content of `study.json`).
#[pyfunction]
#[pyo3(signature = (grid, out, shard=None))]
pub fn run_study<'py>(
    py: Python<'py>,
    grid: PathBuf,
    out: PathBuf,
    shard: Option<(usize, usize)>,
) -> PyResult<Bound<'py, PyDict>> {
    let grid = load_grid(&grid).map_err(|e| input_error(&e))?;
    if let Some((k, n)) = shard
        && (n == 0 || k >= n)
    {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "shard ({k}, {n}): need 0 ≤ k < n"
        )));
    }
    let (outcome, study) = py
        .detach(|| -> Result<_, Error> {
            let options = StudyOptions {
                out: out.clone(),
                shard,
                progress: false,
            };
            let outcome = run_grid(&grid, &options)?;
            let study = match shard {
                Some(_) => None,
                None => {
                    let study = collect(&grid, &[], &out)?;
                    study.save(&out)?;
                    rockslide_present::study::write_summary(&study, &out)?;
                    Some(serde_json::to_string(&study).map_err(|e| Error::Other(e.to_string()))?)
                }
            };
            Ok((outcome, study))
        })
        .map_err(to_py)?;
    let d = PyDict::new(py);
    d.set_item("points", outcome.points)?;
    d.set_item("assigned", outcome.assigned)?;
    d.set_item("executed", outcome.executed)?;
    d.set_item("skipped", outcome.skipped)?;
    d.set_item("runs", outcome.runs)?;
    if let Some(json) = study {
        d.set_item("study", py.import("json")?.call_method1("loads", (json,))?)?;
    }
    Ok(d)
}

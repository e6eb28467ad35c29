//! Ground-motion records read into `(dt, samples)`: PEER NGA `.AT2` by its extension,
//! anything else as CSV (time, acceleration[, more components]), samples in m/s².

use std::path::{Path, PathBuf};

use numpy::PyArray1;
use pyo3::prelude::*;

use rockslide_core::case::record::{AccelUnit, read_record_column};
use rockslide_core::error::InputError as Problem;

use crate::errors::{input_error, one_problem};

/// Read a record file into `(dt, samples)`, samples in m/s². `unit` (`"g"`, `"m/s2"`,
/// `"cm/s2"`) is required for a CSV and checked against an AT2 header; `column` picks
/// acceleration column N (1-based, after time) of a CSV with several.
#[pyfunction]
#[pyo3(signature = (path, unit=None, column=None))]
pub fn read_record<'py>(
    py: Python<'py>,
    path: PathBuf,
    unit: Option<&str>,
    column: Option<usize>,
) -> PyResult<(f64, Bound<'py, PyArray1<f64>>)> {
    let unit = unit.map(|u| parse_unit(&path, u)).transpose()?;
    let record = py
        .detach(|| read_record_column(&path, unit, column))
        .map_err(|e| input_error(&e))?;
    Ok((record.dt, PyArray1::from_vec(py, record.samples)))
}

fn parse_unit(path: &Path, name: &str) -> PyResult<AccelUnit> {
    AccelUnit::parse(name).ok_or_else(|| {
        one_problem(Problem::new(
            path,
            "unit",
            format!(
                "\"{name}\" is not an acceleration unit; use one of {}",
                AccelUnit::NAMES.join(", ")
            ),
        ))
    })
}

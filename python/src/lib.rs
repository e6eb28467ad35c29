//! # rockslide's Python module (`rockslide._rockslide`)
//!
//! The workspace as a Python user needs it: a case from a file, TOML text or a dict
//! ([`case`]); its runs with every participant's time and quantities as numpy arrays, the
//! response quantities, the checks, the verdict and the report ([`result`]); the exact
//! references on numpy inputs and records read into `(dt, samples)` ([`references`],
//! [`records`]); studies ([`study`]). Every long computation releases the GIL. An input
//! problem raises `rockslide.InputError` carrying its file, line, column, field and reason
//! ([`errors`]). The pure-Python package `rockslide/` re-exports all of it with the
//! type stubs beside it.

use pyo3::prelude::*;

pub mod arrays;
pub mod case;
pub mod errors;
pub mod records;
pub mod references;
pub mod result;
pub mod study;

/// The module `rockslide._rockslide`.
#[pymodule]
fn _rockslide(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("InputError", py.get_type::<errors::InputError>())?;
    m.add("ENGINES", rockslide_verify::registry::ENGINE_IDS.to_vec())?;
    m.add_class::<case::Case>()?;
    m.add_class::<result::CaseResult>()?;
    m.add_function(wrap_pyfunction!(case::load_case, m)?)?;
    m.add_function(wrap_pyfunction!(case::case_from_toml, m)?)?;
    m.add_function(wrap_pyfunction!(case::case_from_dict, m)?)?;
    m.add_function(wrap_pyfunction!(case::run, m)?)?;
    m.add_function(wrap_pyfunction!(arrays::quantities, m)?)?;
    m.add_function(wrap_pyfunction!(records::read_record, m)?)?;
    m.add_function(wrap_pyfunction!(references::reference, m)?)?;
    m.add_function(wrap_pyfunction!(references::epo_record, m)?)?;
    m.add_function(wrap_pyfunction!(references::rigid_block, m)?)?;
    m.add_function(wrap_pyfunction!(references::housner, m)?)?;
    m.add_function(wrap_pyfunction!(references::plan_block, m)?)?;
    m.add_function(wrap_pyfunction!(references::plan_oscillator, m)?)?;
    m.add_function(wrap_pyfunction!(study::run_study, m)?)?;
    Ok(())
}

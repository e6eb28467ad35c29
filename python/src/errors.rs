//! rockslide's errors as Python exceptions: an input problem is `rockslide.InputError`
//! (a `ValueError`) whose message is every problem, one `file:line:col: field: reason` line
//! each, and whose attributes locate the first (`file`, `line`, `column`, `field`,
//! `reason`) and list them all (`errors`, a list of dicts); a failed read or write is an
//! `OSError`, anything else a `RuntimeError`.

use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use rockslide_core::error::{Error, InputError as Problem, InputErrors};

pyo3::create_exception!(
    _rockslide,
    InputError,
    PyValueError,
    "A case, record or argument that cannot be used, located: `file`, `line`, `column`, `field`, `reason` of the first problem, `errors` every problem as a dict."
);

/// One problem as a dict: file, line, column, field, reason (and, for a problem inside a
/// file a field names, `within_file`, `within_line`, `within_column`).
fn problem_dict<'py>(py: Python<'py>, p: &Problem) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("file", p.file.display().to_string())?;
    d.set_item("line", p.line)?;
    d.set_item("column", p.column)?;
    d.set_item("field", &p.field)?;
    d.set_item("reason", &p.reason)?;
    if let Some(w) = &p.within {
        d.set_item("within_file", w.file.display().to_string())?;
        d.set_item("within_line", w.line)?;
        d.set_item("within_column", w.column)?;
    }
    Ok(d)
}

/// Every problem as one `InputError`, located by its first.
pub fn input_error(errors: &InputErrors) -> PyErr {
    Python::attach(|py| {
        let err = InputError::new_err(errors.to_string());
        if let Err(e) = locate(py, &err, errors) {
            return e;
        }
        err
    })
}

fn locate(py: Python<'_>, err: &PyErr, errors: &InputErrors) -> PyResult<()> {
    let value = err.value(py);
    let all: Vec<Bound<'_, PyDict>> = errors
        .0
        .iter()
        .map(|p| problem_dict(py, p))
        .collect::<PyResult<_>>()?;
    if let Some(first) = all.first() {
        for key in ["file", "line", "column", "field", "reason"] {
            value.setattr(key, first.get_item(key)?)?;
        }
    }
    value.setattr("errors", all)?;
    Ok(())
}

/// A single located problem (an argument of a Python call, say) as an `InputError`.
pub fn one_problem(p: Problem) -> PyErr {
    input_error(&InputErrors(vec![p]))
}

/// A rockslide error as the Python exception that fits it.
pub fn to_py(e: Error) -> PyErr {
    match e {
        Error::Input(errors) => input_error(&errors),
        Error::Io { .. } => PyOSError::new_err(e.to_string()),
        Error::Other(message) => PyRuntimeError::new_err(message),
    }
}

/// A reason a reference or a computation cannot proceed, as a `ValueError`.
pub fn refused(reason: String) -> PyErr {
    PyValueError::new_err(reason)
}

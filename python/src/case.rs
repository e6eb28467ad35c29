//! A case from Python: read from a file, parsed from TOML text or written from a dict
//! (the dict is the TOML file's tables as nested dicts, lists and numbers), validated
//! against the engines exactly as the command line validates it, and run (`run`,
//! `Case.run`) into a [`CaseResult`].

use std::path::{Path, PathBuf};

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use rockslide_core::case::Case as Scene;
use rockslide_verify::registry;

use crate::errors::input_error;
use crate::result::{CaseResult, run_case};

/// The name a case given as text or a dict is reported under when no path is given
/// (relative record paths then resolve against the working folder).
const UNNAMED: &str = "<case>.toml";

/// A validated case.
#[pyclass(module = "rockslide", frozen, name = "Case")]
#[derive(Clone)]
pub struct Case {
    pub(crate) inner: Scene,
}

#[pymethods]
impl Case {
    /// Read and validate a case file.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        load_case(path)
    }

    /// Parse and validate TOML text; `path` names it in errors and anchors relative
    /// record paths.
    #[staticmethod]
    #[pyo3(signature = (text, path=None))]
    fn from_toml(text: &str, path: Option<PathBuf>) -> PyResult<Self> {
        case_from_toml(text, path)
    }

    /// Write a dict as the case's TOML and validate it.
    #[staticmethod]
    #[pyo3(signature = (tables, path=None))]
    fn from_dict(tables: &Bound<'_, PyDict>, path: Option<PathBuf>) -> PyResult<Self> {
        case_from_dict(tables, path)
    }

    /// The case's name (its file's stem), the name of its report folder.
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }

    /// The case's title.
    #[getter]
    fn title(&self) -> &str {
        &self.inner.title
    }

    /// The case file, as given.
    #[getter]
    fn path(&self) -> PathBuf {
        self.inner.path.clone()
    }

    /// The case's TOML text.
    #[getter]
    fn text(&self) -> &str {
        &self.inner.text
    }

    /// Simulated duration, s.
    #[getter]
    fn duration(&self) -> f64 {
        self.inner.run.duration
    }

    /// Run the case (every engine it names, or `engines`), see `rockslide.run`.
    #[pyo3(signature = (engines=None))]
    fn run(&self, py: Python<'_>, engines: Option<Vec<String>>) -> PyResult<CaseResult> {
        run_case(py, self.inner.clone(), engines)
    }

    fn __repr__(&self) -> String {
        format!(
            "Case({:?}, path={:?})",
            self.inner.name,
            self.inner.path.display().to_string()
        )
    }
}

/// Run a case: every engine it names (all that apply when it names none), or only
/// `engines` (ids among `rockslide.ENGINES`), the GIL released while they run.
#[pyfunction]
#[pyo3(signature = (case, engines=None))]
pub fn run(py: Python<'_>, case: &Case, engines: Option<Vec<String>>) -> PyResult<CaseResult> {
    run_case(py, case.inner.clone(), engines)
}

/// Read and validate a case file.
#[pyfunction]
pub fn load_case(path: PathBuf) -> PyResult<Case> {
    registry::load_case(&path)
        .map(|inner| Case { inner })
        .map_err(|e| input_error(&e))
}

/// Parse and validate a case from TOML text.
#[pyfunction]
#[pyo3(signature = (text, path=None))]
pub fn case_from_toml(text: &str, path: Option<PathBuf>) -> PyResult<Case> {
    let path = path.unwrap_or_else(|| PathBuf::from(UNNAMED));
    parse(&path, text)
}

/// Write a dict as the case's TOML, then parse and validate it.
#[pyfunction]
#[pyo3(signature = (tables, path=None))]
pub fn case_from_dict(tables: &Bound<'_, PyDict>, path: Option<PathBuf>) -> PyResult<Case> {
    let table = table_of(tables, "", 0)?;
    let text = toml::to_string(&table).map_err(|e| {
        PyTypeError::new_err(format!("the case dict cannot be written as TOML: {e}"))
    })?;
    case_from_toml(&text, path)
}

fn parse(path: &Path, text: &str) -> PyResult<Case> {
    registry::parse_case(path, text)
        .map(|inner| Case { inner })
        .map_err(|e| input_error(&e))
}

/// Deepest nesting of dicts and lists a case dict may have: a case file's deepest value
/// is a list inside a table inside a table (`[engines.fe] variants = [...]`), so this is
/// ample, and it keeps a pathologically deep dict from exhausting the stack.
const MAX_DEPTH: usize = 32;

/// A dict as a TOML table; `at` is its dotted place in the case, for errors.
fn table_of(d: &Bound<'_, PyDict>, at: &str, depth: usize) -> PyResult<toml::Table> {
    within_depth(at, depth)?;
    let mut table = toml::Table::new();
    for (key, value) in d.iter() {
        let key: String = key.extract().map_err(|_| {
            PyTypeError::new_err(format!("case dict{}: keys must be strings", place(at)))
        })?;
        let here = if at.is_empty() {
            key.clone()
        } else {
            format!("{at}.{key}")
        };
        if value.is_none() {
            continue;
        }
        table.insert(key, value_of(&value, &here, depth + 1)?);
    }
    Ok(table)
}

/// `Err` when a dict or list at `at` lies `depth` levels deep, beyond [`MAX_DEPTH`].
fn within_depth(at: &str, depth: usize) -> PyResult<()> {
    if depth > MAX_DEPTH {
        return Err(PyValueError::new_err(format!(
            "case dict{}: nested more than {MAX_DEPTH} levels deep; a case file is never this deep",
            place(at)
        )));
    }
    Ok(())
}

fn place(at: &str) -> String {
    if at.is_empty() {
        String::new()
    } else {
        format!(" `{at}`")
    }
}

/// A Python value as a TOML value: bool, int, float, str, dict, list or tuple.
fn value_of(v: &Bound<'_, PyAny>, at: &str, depth: usize) -> PyResult<toml::Value> {
    use toml::Value;
    if v.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return v.extract().map(Value::Integer).map_err(|_| {
            PyValueError::new_err(format!(
                "case dict{}: the integer {} does not fit a case file's 64-bit integers",
                place(at),
                v.str().map(|s| s.to_string()).unwrap_or_default()
            ))
        });
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(Value::String(v.extract()?));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return Ok(Value::Table(table_of(d, at, depth)?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        within_depth(at, depth)?;
        let items: Vec<Bound<'_, PyAny>> = v.try_iter()?.collect::<PyResult<_>>()?;
        let values = items
            .iter()
            .enumerate()
            .map(|(i, item)| value_of(item, &format!("{at}[{i}]"), depth + 1))
            .collect::<PyResult<_>>()?;
        return Ok(Value::Array(values));
    }
    // numpy scalars and other numbers
    if let Ok(x) = v.extract::<f64>() {
        return Ok(Value::Float(x));
    }
    Err(PyTypeError::new_err(format!(
        "case dict{}: a {} cannot be written in a case file (bool, int, float, str, dict or list)",
        place(at),
        v.get_type().name()?
    )))
}

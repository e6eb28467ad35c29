//! A case's result from Python: every participant's trace as numpy arrays (the engine
//! runs, the external programs and the reference), their response quantities, the
//! tolerance checks, the verdict, the typed record the command line writes as
//! `result.json`, and the report written to a folder.

use std::path::PathBuf;

use pyo3::exceptions::{PyImportError, PyKeyError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use rockslide_core::case::Case as Scene;
use rockslide_core::trace::Trace;
use rockslide_engine_api::Engine;
use rockslide_verify::analysis::Responses;
use rockslide_verify::record::CaseRecord;
use rockslide_verify::registry;
use rockslide_verify::suite::{self, CaseResult as Outcome};

use crate::arrays::trace_dict;
use crate::errors::{input_error, to_py};

/// The label of the reference among the participants.
use rockslide_core::case::REFERENCE_LABEL as REFERENCE;

/// Everything known about a case after running it.
#[pyclass(module = "rockslide", frozen, name = "Result")]
pub struct CaseResult {
    inner: Outcome,
}

/// Run a case's scene: every engine it names (all that apply when it names none), or
/// only `engines` (ids among `rockslide.ENGINES`), the GIL released while they run.
pub(crate) fn run_case(
    py: Python<'_>,
    case: Scene,
    engines: Option<Vec<String>>,
) -> PyResult<CaseResult> {
    let chosen = chosen_engines(engines)?;
    let outcome = py.detach(move || match chosen {
        None => suite::run_case(case),
        Some(engines) => suite::run_case_with(case, &engines),
    });
    outcome
        .map(|inner| CaseResult { inner })
        .map_err(|e| input_error(&e))
}

/// The engines asked for, in the registry's order; an unknown id is refused.
fn chosen_engines(ids: Option<Vec<String>>) -> PyResult<Option<Vec<Box<dyn Engine>>>> {
    let Some(ids) = ids else { return Ok(None) };
    if let Some(unknown) = ids
        .iter()
        .find(|id| !registry::ENGINE_IDS.contains(&id.as_str()))
    {
        return Err(PyValueError::new_err(format!(
            "no engine \"{unknown}\"; engines: {}",
            registry::ENGINE_IDS.join(", ")
        )));
    }
    Ok(Some(
        registry::all()
            .into_iter()
            .filter(|e| ids.iter().any(|id| id == e.id()))
            .collect(),
    ))
}

impl CaseResult {
    /// The trace of a participant: a run by `engine/variant` (or an external program's
    /// label), or the reference.
    fn trace_of(&self, label: &str) -> PyResult<&Trace> {
        if label == REFERENCE {
            let r =
                self.inner.reference.as_ref().map_err(|why| {
                    PyKeyError::new_err(format!("this case has no reference: {why}"))
                })?;
            return Ok(if r.output.is_empty() {
                &r.trace
            } else {
                &r.output
            });
        }
        self.inner
            .runs
            .iter()
            .find(|r| r.label() == label)
            .map(|r| &r.trace)
            .ok_or_else(|| {
                PyKeyError::new_err(format!(
                    "no participant \"{label}\"; participants: {}",
                    self.labels().join(", ")
                ))
            })
    }

    fn labels(&self) -> Vec<String> {
        let mut labels: Vec<String> = self.inner.runs.iter().map(|r| r.label()).collect();
        if self.inner.reference.is_ok() {
            labels.push(REFERENCE.to_string());
        }
        labels
    }

    fn record(&self) -> CaseRecord {
        CaseRecord::of(&self.inner)
    }
}

fn responses_dict<'py>(py: Python<'py>, r: &Responses) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (key, value) in r {
        d.set_item(*key, *value)?;
    }
    Ok(d)
}

/// A JSON text as Python values (`json.loads`).
fn from_json<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

#[pymethods]
impl CaseResult {
    /// The case's name.
    #[getter]
    fn case(&self) -> &str {
        &self.inner.case.name
    }

    /// Every participant: each run as `engine/variant` (external programs by their
    /// label), then `reference` when the case has one.
    #[getter]
    fn participants(&self) -> Vec<String> {
        self.labels()
    }

    /// A participant's trace: `{"time": array, quantity: array, …}`, SI.
    fn trace<'py>(&self, py: Python<'py>, participant: &str) -> PyResult<Bound<'py, PyDict>> {
        trace_dict(py, self.trace_of(participant)?)
    }

    /// Every participant's trace, by participant.
    fn traces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for label in self.labels() {
            d.set_item(&label, trace_dict(py, self.trace_of(&label)?)?)?;
        }
        Ok(d)
    }

    /// The response quantities of every participant: `{participant: {quantity: value}}`,
    /// SI (the reference's event times exact).
    #[getter]
    fn responses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (run, r) in self.inner.runs.iter().zip(&self.inner.run_responses) {
            d.set_item(run.label(), responses_dict(py, r)?)?;
        }
        if let Ok(reference) = &self.inner.reference {
            d.set_item(REFERENCE, responses_dict(py, &reference.responses)?)?;
        }
        Ok(d)
    }

    /// Each run's outcome: `{participant: "completed" | "diverged" | "not converged"}`.
    #[getter]
    fn statuses(&self) -> Vec<(String, String)> {
        self.inner
            .runs
            .iter()
            .map(|r| (r.label(), r.status.label().to_string()))
            .collect()
    }

    /// Engines that do not apply to the case, and why: `{engine: reason}`.
    #[getter]
    fn not_applicable(&self) -> Vec<(String, String)> {
        self.inner
            .not_applicable
            .iter()
            .map(|(e, why)| (e.to_string(), why.clone()))
            .collect()
    }

    /// The tolerance checks, as `result.json` lists them (list of dicts).
    #[getter]
    fn checks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let json = serde_json::to_string(&self.record().checks)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        from_json(py, &json)
    }

    /// A case with a set of azimuths (`x_azimuths_deg`): every participant's figures at
    /// each azimuth, their maxima over the set and the governing azimuth, as `result.json`
    /// holds them under `azimuths` (a dict); `None` for any other case. The traces and
    /// responses above are the governing azimuth's.
    #[getter]
    fn azimuths<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let Some(sweep) = self.record().azimuths else {
            return Ok(None);
        };
        let json =
            serde_json::to_string(&sweep).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        from_json(py, &json).map(Some)
    }

    /// Whether the case passes the gate (`rockslide check`'s verdict).
    #[getter]
    fn passed(&self) -> bool {
        self.inner.gate_passed()
    }

    /// The gate's failure lines (gated and informative), as `rockslide check` prints them.
    #[getter]
    fn failures(&self) -> Vec<String> {
        self.record().failures
    }

    /// The typed record the command line writes as `<case>/result.json`, as JSON text
    /// (the same serialisation, digit for digit).
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.record())
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// The typed record (`result.json`) as Python values.
    fn record_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.to_json()?)
    }

    /// Write the case's report, traces (CSV, MCAP with its Foxglove layout) and
    /// `result.json` into `<folder>/<case>/`, as `rockslide run --out folder` does; returns
    /// that folder.
    fn write_report(&self, py: Python<'_>, folder: PathBuf) -> PyResult<PathBuf> {
        let inner = &self.inner;
        py.detach(|| rockslide_present::report::write_case_outputs(inner, &folder))
            .map_err(to_py)
    }

    /// A participant's trace as a pandas DataFrame indexed by time (pandas must be
    /// installed: it is not a dependency of rockslide).
    fn to_pandas<'py>(&self, py: Python<'py>, participant: &str) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py
            .import("pandas")
            .map_err(|_| PyImportError::new_err("to_pandas needs pandas: pip install pandas"))?;
        let columns = self.trace(py, participant)?;
        let time = columns.get_item("time")?;
        columns.del_item("time")?;
        let index = pandas.call_method1("Index", (time,))?;
        index.setattr("name", "time")?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("index", index)?;
        pandas.call_method("DataFrame", (columns,), Some(&kwargs))
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let participants = PyList::new(py, self.labels())
            .map(|l| l.to_string())
            .unwrap_or_default();
        format!(
            "Result(case={:?}, passed={}, participants={participants})",
            self.inner.case.name,
            if self.passed() { "True" } else { "False" }
        )
    }
}

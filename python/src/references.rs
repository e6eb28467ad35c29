//! The exact references from Python, on numpy inputs: a case's own reference; the
//! elastic-perfectly-plastic oscillator under a ground-acceleration record; the rigid
//! block under a record, sliding both ways or one way (Newmark, SLAMMER's rigid block);
//! Housner's rocking block under a ground-acceleration sine pulse; the block and the
//! oscillator on an isotropic friction cone under two horizontal components (plan motion).
//! Each checks its numbers first (`rockslide_reference::plain`: a reason, never a crash),
//! solves with the GIL released and returns its trace as a dict of arrays (SI).

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use rockslide_reference::bidirectional::DEFAULT_STEP;
use rockslide_reference::newmark_record::{Sliding, rigid_block as solve_block};
use rockslide_reference::{ExactSolution, plain, sample};

use crate::arrays::trace_dict;
use crate::errors::refused;

/// Standard gravity, m/s², the default of every reference.
const G: f64 = 9.80665;

/// Sample `solution` at `times` (default: `n + 1` uniform instants over `[0, end]`) as a
/// dict of arrays, with its exactly known quantities (event times) under `"exact"`.
fn sampled<'py>(
    py: Python<'py>,
    solution: &dyn ExactSolution,
    times: Option<Vec<f64>>,
    end: f64,
    n: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let times = plain::times(times, end, n).map_err(refused)?;
    let trace = py.detach(|| sample(solution, &times));
    let d = trace_dict(py, &trace)?;
    let exact = PyDict::new(py);
    for (key, value) in solution.exact_quantities() {
        exact.set_item(key, value)?;
    }
    d.set_item("exact", exact)?;
    Ok(d)
}

fn owned(a: Option<PyReadonlyArray1<'_, f64>>) -> PyResult<Option<Vec<f64>>> {
    a.map(|a| Ok(a.as_slice()?.to_vec())).transpose()
}

fn samples(a: &PyReadonlyArray1<'_, f64>) -> PyResult<Vec<f64>> {
    Ok(a.as_slice()?.to_vec())
}

/// Intervals of a uniform grid of step about `dt` over `[0, end]`, within the step limit.
fn intervals(end: f64, dt: f64) -> PyResult<usize> {
    plain::intervals(end, dt).map_err(refused)
}

/// The exact reference of a case (the one its report compares with), sampled at `times`
/// (default: every step of the case's `[run] dt`).
#[pyfunction]
#[pyo3(signature = (case, times=None))]
pub fn reference<'py>(
    py: Python<'py>,
    case: &crate::case::Case,
    times: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let c = &case.inner;
    let solution = py
        .detach(|| rockslide_reference::for_case(c))
        .map_err(refused)?;
    let n = intervals(c.run.duration, c.run.dt)?;
    sampled(py, solution.as_ref(), owned(times)?, c.run.duration, n)
}

/// The undamped elastic-perfectly-plastic oscillator (mass `mass` kg, stiffness
/// `stiffness` N/m, friction limit `mu`·`mass`·`gravity`) under the ground acceleration
/// `acceleration` (m/s², every `dt` s, linear in between), exact event by event over
/// `[0, duration]` (default: the record's end).
#[pyfunction]
#[pyo3(signature = (dt, acceleration, mass, stiffness, mu, gravity=G, duration=None, times=None))]
#[allow(clippy::too_many_arguments)]
pub fn epo_record<'py>(
    py: Python<'py>,
    dt: f64,
    acceleration: PyReadonlyArray1<'py, f64>,
    mass: f64,
    stiffness: f64,
    mu: f64,
    gravity: f64,
    duration: Option<f64>,
    times: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let ground = samples(&acceleration)?;
    let osc = plain::oscillator(mass, stiffness, mu, gravity).map_err(refused)?;
    let (solution, end) = py
        .detach(|| plain::epo_record(dt, ground, &osc, duration))
        .map_err(refused)?;
    sampled(py, &solution, owned(times)?, end, intervals(end, dt)?)
}

/// The rigid block under the drive `acceleration` (m/s², every `dt` s, linear in between,
/// then `tail` s of zero), yield acceleration `ky` (m/s²), sliding both ways or, with
/// `one_way`, only downslope (SLAMMER's rigid block). Returns `time`, the sliding
/// `velocity` and `displacement` at the samples (m/s, m), the `slides` as
/// `(start, end, direction, distance)` and the continuous-time `peak` |displacement|.
#[pyfunction]
#[pyo3(signature = (dt, acceleration, ky, one_way=false, tail=0.0))]
pub fn rigid_block<'py>(
    py: Python<'py>,
    dt: f64,
    acceleration: PyReadonlyArray1<'py, f64>,
    ky: f64,
    one_way: bool,
    tail: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let acc = samples(&acceleration)?;
    let sliding = if one_way {
        Sliding::OneWay
    } else {
        Sliding::TwoWay
    };
    let run = py
        .detach(|| solve_block(dt, &acc, ky, sliding, tail))
        .map_err(refused)?;
    let d = PyDict::new(py);
    let time: Vec<f64> = (0..run.disp.len()).map(|i| dt * i as f64).collect();
    d.set_item("time", PyArray1::from_vec(py, time))?;
    d.set_item("velocity", PyArray1::from_slice(py, &run.vel))?;
    d.set_item("displacement", PyArray1::from_slice(py, &run.disp))?;
    let slides: Vec<(f64, f64, f64, f64)> = run
        .slides
        .iter()
        .map(|s| (s.start, s.end, s.direction, s.distance))
        .collect();
    d.set_item("slides", slides)?;
    d.set_item("peak", run.peak_abs)?;
    Ok(d)
}

/// Housner's rocking block (half-width `half_width`, half-height `half_height`, m;
/// restitution from Housner's angular-momentum rule) under the ground acceleration
/// `amplitude`·sin(`omega`·t) for `cycles` cycles, from tilt `initial_tilt` rad, over
/// `[0, duration]`, sampled `samples` + 1 times or at `times`.
#[pyfunction]
#[pyo3(signature = (half_width, half_height, amplitude, omega, duration, cycles=0.5, gravity=G, initial_tilt=0.0, samples=2000, times=None))]
#[allow(clippy::too_many_arguments)]
pub fn housner<'py>(
    py: Python<'py>,
    half_width: f64,
    half_height: f64,
    amplitude: f64,
    omega: f64,
    duration: f64,
    cycles: f64,
    gravity: f64,
    initial_tilt: f64,
    samples: usize,
    times: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let solution = py
        .detach(|| {
            plain::housner(
                half_width,
                half_height,
                amplitude,
                omega,
                duration,
                cycles,
                gravity,
                initial_tilt,
            )
        })
        .map_err(refused)?;
    sampled(py, &solution, owned(times)?, duration, samples)
}

/// The rigid block on an isotropic friction cone (`mu`) under the ground accelerations
/// `acceleration_x` and `acceleration_y` (m/s², every `dt` s), integrated over
/// `[0, duration]` with steps of at most `step` s.
#[pyfunction]
#[pyo3(signature = (dt, acceleration_x, acceleration_y, mu, gravity=G, duration=None, step=DEFAULT_STEP, times=None))]
#[allow(clippy::too_many_arguments)]
pub fn plan_block<'py>(
    py: Python<'py>,
    dt: f64,
    acceleration_x: PyReadonlyArray1<'py, f64>,
    acceleration_y: PyReadonlyArray1<'py, f64>,
    mu: f64,
    gravity: f64,
    duration: Option<f64>,
    step: f64,
    times: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (x, y) = (samples(&acceleration_x)?, samples(&acceleration_y)?);
    let (solution, end) = py
        .detach(|| plain::plan_block(dt, x, y, mu, gravity, duration, step))
        .map_err(refused)?;
    sampled(py, &solution, owned(times)?, end, intervals(end, dt)?)
}

/// The elastic-perfectly-plastic oscillator on an isotropic friction cone (stiffness
/// `stiffness` N/m in every horizontal direction, limit `mu`·`mass`·`gravity`) under the
/// ground accelerations `acceleration_x` and `acceleration_y` (m/s², every `dt` s).
#[pyfunction]
#[pyo3(signature = (dt, acceleration_x, acceleration_y, mass, stiffness, mu, gravity=G, duration=None, step=DEFAULT_STEP, times=None))]
#[allow(clippy::too_many_arguments)]
pub fn plan_oscillator<'py>(
    py: Python<'py>,
    dt: f64,
    acceleration_x: PyReadonlyArray1<'py, f64>,
    acceleration_y: PyReadonlyArray1<'py, f64>,
    mass: f64,
    stiffness: f64,
    mu: f64,
    gravity: f64,
    duration: Option<f64>,
    step: f64,
    times: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (x, y) = (samples(&acceleration_x)?, samples(&acceleration_y)?);
    let osc = plain::oscillator(mass, stiffness, mu, gravity).map_err(refused)?;
    let (solution, end) = py
        .detach(|| plain::plan_oscillator(dt, x, y, &osc, duration, step))
        .map_err(refused)?;
    sampled(py, &solution, owned(times)?, end, intervals(end, dt)?)
}

//! The references on plain numbers: a record as a sample interval and a list of
//! accelerations, a body as its mass, stiffness and friction, an answer sampled at given
//! or uniform times. This is what the Python package's reference functions call, so that
//! every number a script passes is checked here, in Rust, with a reason — before anything
//! is allocated or solved — and never reaches a solver as a NaN, a zero interval or a
//! sample count that memory cannot hold.
//!
//! Counts are held to the step limit ([`limits::max_steps`]): the samples of a record,
//! the instants an answer is sampled at and the intervals `end / dt` a uniform grid has.

use std::sync::Arc;

use rockslide_core::case::limits;
use rockslide_core::case::record::MIN_DT;
use rockslide_core::case::{Contact, Oscillator, RigidBlock, Signal};

use crate::bidirectional::{PlanBlock, PlanDrive, PlanEpo};
use crate::{EpoRecord, HousnerRocking, SineForcing};

/// `Err` naming `what` unless `value` is a finite number.
fn finite(what: &str, value: f64) -> Result<f64, String> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("{what} {value} is not a finite number"))
    }
}

/// `Err` naming `what` unless `value` is a positive finite number.
fn positive(what: &str, value: f64) -> Result<f64, String> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(format!("{what} {value:e} is not a positive finite number"))
    }
}

/// `Err` naming `what` unless `value` is a finite number ≥ 0.
fn non_negative(what: &str, value: f64) -> Result<f64, String> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(format!("{what} {value:e} is not a finite number ≥ 0"))
    }
}

/// `Err` when `count` items of `what` exceed the step limit.
fn within_limit(what: &str, count: f64) -> Result<usize, String> {
    let limit = limits::max_steps();
    if count.is_nan() || count > limit as f64 {
        return Err(format!(
            "{count:.3e} {what}: more than the limit of {limit} (set {} to raise it)",
            limits::MAX_STEPS_VARIABLE
        ));
    }
    Ok(count as usize)
}

/// A record's accelerations, m/s², every `dt` s: `dt` at least a record's smallest sample
/// interval ([`MIN_DT`]), at least one sample, each finite, at most the step limit of them.
pub fn record(dt: f64, samples: &[f64]) -> Result<(), String> {
    positive("the sample interval", dt)?;
    if dt < MIN_DT {
        return Err(format!(
            "the sample interval {dt:e} s is below the smallest a record may have ({MIN_DT:e} s)"
        ));
    }
    if samples.is_empty() {
        return Err("the record has no samples".into());
    }
    within_limit("record samples", samples.len() as f64)?;
    if let Some(i) = samples.iter().position(|a| !a.is_finite()) {
        return Err(format!("sample {i} of the record is not finite"));
    }
    Ok(())
}

/// The end of the analysis: `duration` when given (positive, finite), else the record's
/// last sample instant (`dt` past the start for a record of one sample).
pub fn end_of(dt: f64, len: usize, duration: Option<f64>) -> Result<f64, String> {
    match duration {
        Some(d) => positive("the duration", d),
        None => Ok(dt * len.saturating_sub(1).max(1) as f64),
    }
}

/// Intervals of a uniform grid of step about `dt` over `[0, end]` (at least one), held to
/// the step limit.
pub fn intervals(end: f64, dt: f64) -> Result<usize, String> {
    let n = (end / dt).round().max(1.0);
    within_limit("sample instants (the duration over the sample interval)", n)
}

/// The instants an answer is sampled at: `times` as given (each finite, at most the step
/// limit of them), else `intervals` + 1 uniform instants over `[0, end]`.
pub fn times(times: Option<Vec<f64>>, end: f64, intervals: usize) -> Result<Vec<f64>, String> {
    match times {
        Some(t) => {
            within_limit("sample instants", t.len() as f64)?;
            if let Some(i) = t.iter().position(|x| !x.is_finite()) {
                return Err(format!("time {i} ({}) is not finite", t[i]));
            }
            Ok(t)
        }
        None => {
            within_limit("sample instants", intervals as f64 + 1.0)?;
            let n = intervals.max(1);
            Ok((0..=n).map(|i| end * i as f64 / n as f64).collect())
        }
    }
}

/// The undamped oscillator of mass `mass`, stiffness `stiffness` (both directions) and
/// friction limit `mu`·`mass`·`gravity`.
pub fn oscillator(mass: f64, stiffness: f64, mu: f64, gravity: f64) -> Result<Oscillator, String> {
    Ok(Oscillator {
        mass: positive("the mass", mass)?,
        gravity: positive("gravity", gravity)?,
        damping_ratio: 0.0,
        contact: Contact {
            kx: positive("the stiffness", stiffness)?,
            kz: stiffness,
            mu: non_negative("the friction coefficient", mu)?,
        },
        double: None,
    })
}

/// The elastic-perfectly-plastic oscillator under a record, exact event by event over
/// `[0, end]`, and `end` (`duration`, else the record's end).
pub fn epo_record(
    dt: f64,
    acceleration: Vec<f64>,
    osc: &Oscillator,
    duration: Option<f64>,
) -> Result<(EpoRecord, f64), String> {
    record(dt, &acceleration)?;
    let end = end_of(dt, acceleration.len(), duration)?;
    intervals(end, dt)?;
    Ok((EpoRecord::new(osc, dt, acceleration, end)?, end))
}

/// Housner's rocking block under the ground acceleration `amplitude`·sin(`omega`·t) for
/// `cycles` cycles, from tilt `initial_tilt`, over `[0, duration]`.
#[allow(clippy::too_many_arguments)]
pub fn housner(
    half_width: f64,
    half_height: f64,
    amplitude: f64,
    omega: f64,
    duration: f64,
    cycles: f64,
    gravity: f64,
    initial_tilt: f64,
) -> Result<HousnerRocking, String> {
    let mass = 1.0;
    let block = RigidBlock {
        mass,
        gravity: positive("gravity", gravity)?,
        half_width: positive("the half-width", half_width)?,
        half_height: positive("the half-height", half_height)?,
        mu: f64::INFINITY,
        initial_tilt: finite("the initial tilt", initial_tilt)?,
    };
    let forcing = SineForcing {
        // a ground acceleration a is a force −M·a on the body in relative coordinates
        p0: -mass * finite("the amplitude", amplitude)?,
        theta: positive("the circular frequency", omega)?,
        td: non_negative("the number of cycles", cycles)? * 2.0 * std::f64::consts::PI / omega,
        velocity_jumps: vec![],
        ground_amplitude: None,
    };
    HousnerRocking::new(&block, forcing, positive("the duration", duration)?)
}

/// The plan drive of two ground-acceleration records along x and y, each checked.
pub fn plan_drive(dt: f64, x: Vec<f64>, y: Vec<f64>) -> Result<PlanDrive, String> {
    record(dt, &x).map_err(|why| format!("x: {why}"))?;
    record(dt, &y).map_err(|why| format!("y: {why}"))?;
    let signal = |samples: Vec<f64>, label: &str| Signal::Record {
        dt,
        samples: Arc::from(samples),
        label: label.to_string(),
    };
    Ok(PlanDrive::new(
        Some(signal(x, "x")),
        [1.0, 0.0],
        Some(signal(y, "y")),
        [0.0, 1.0],
        -1.0,
    ))
}

/// The end of a plan analysis and its integration step, checked: the step positive and
/// no more than the step limit of them over `[0, end]`.
fn plan_steps(dt: f64, len: usize, duration: Option<f64>, step: f64) -> Result<f64, String> {
    let end = end_of(dt, len, duration)?;
    positive("the integration step", step)?;
    within_limit("integration steps", (end / step).ceil())?;
    intervals(end, dt)?;
    Ok(end)
}

/// The rigid block on an isotropic friction cone `mu` under two records, over `[0, end]`
/// with steps of at most `step`; and `end`.
pub fn plan_block(
    dt: f64,
    x: Vec<f64>,
    y: Vec<f64>,
    mu: f64,
    gravity: f64,
    duration: Option<f64>,
    step: f64,
) -> Result<(PlanBlock, f64), String> {
    let end = plan_steps(dt, x.len().max(y.len()), duration, step)?;
    let (mu, gravity) = (
        non_negative("the friction coefficient", mu)?,
        positive("gravity", gravity)?,
    );
    let drive = plan_drive(dt, x, y)?;
    Ok((PlanBlock::solve(mu, gravity, &drive, end, step)?, end))
}

/// The elastic-perfectly-plastic oscillator on an isotropic friction cone under two
/// records, over `[0, end]` with steps of at most `step`; and `end`.
pub fn plan_oscillator(
    dt: f64,
    x: Vec<f64>,
    y: Vec<f64>,
    osc: &Oscillator,
    duration: Option<f64>,
    step: f64,
) -> Result<(PlanEpo, f64), String> {
    let end = plan_steps(dt, x.len().max(y.len()), duration, step)?;
    let drive = plan_drive(dt, x, y)?;
    Ok((PlanEpo::solve(osc, &drive, end, step)?, end))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_beyond_the_step_limit_are_refused_before_anything_is_allocated() {
        let why = intervals(1e15, 1.0).unwrap_err();
        assert!(why.contains("1.000e15 sample instants"), "{why}");
        assert!(times(None, 1.0, usize::MAX).is_err());
        let ok = times(None, 2.0, 4).unwrap();
        assert_eq!(ok, vec![0.0, 0.5, 1.0, 1.5, 2.0]);
    }

    #[test]
    fn non_finite_or_empty_inputs_are_refused_with_the_number() {
        assert_eq!(record(0.01, &[]).unwrap_err(), "the record has no samples");
        assert_eq!(
            record(0.0, &[1.0]).unwrap_err(),
            "the sample interval 0e0 is not a positive finite number"
        );
        // found by the fuzz target: 8e-317 s, a subnormal, with a tail of 7e-310 s was 8.8e6
        // legitimate steps, seconds of work for nothing a record can be sampled at
        assert!(
            record(8.3e-317, &[1.0])
                .unwrap_err()
                .contains("below the smallest a record may have (1e-6 s)")
        );
        assert!(
            times(Some(vec![0.0, f64::NAN]), 1.0, 1)
                .unwrap_err()
                .contains("time 1")
        );
        assert!(oscillator(1.0, 1e6, f64::NAN, 9.81).is_err());
    }
}

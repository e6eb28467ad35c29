//! The inputs of the vertical references as two piecewise-linear histories on one grid:
//! the horizontal drive d(t) (force per unit mass in relative coordinates: −a_g for a
//! ground acceleration, +a for a mass acceleration, 0 for none) and the vertical ground
//! acceleration a_v(t) (positive upward).
//!
//! The grid step: a record's own sample interval (both records of a pair must share it);
//! for analytic pulses alone the stated fine step [`PULSE_STEP`], the pulse sampled there
//! and taken linear in between (its interpolation error is ≈ h²·θ²/8 of its amplitude:
//! 3e-7 for the paper's θ = 15.7 rad/s); a pulse beside a record is sampled on the record's
//! interval cut into equal parts no longer than [`PULSE_STEP`]. Past the end of a signal
//! its value is zero (the interval after a record's last sample ramps to zero).

use rockslide_core::case::{Excitation, Scene, Signal};

/// Grid step on which analytic pulses are sampled, s.
pub const PULSE_STEP: f64 = 1e-4;
/// Most grid intervals a reference solves.
const MAX_INTERVALS: f64 = 5e7;

/// Drive and vertical acceleration at the grid points `i·h`, i = 0…n.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearInputs {
    /// Grid step h, s.
    pub h: f64,
    /// Horizontal drive per unit mass, m/s².
    pub drive: Vec<f64>,
    /// Vertical ground acceleration, m/s² (positive upward).
    pub vertical: Vec<f64>,
    /// How the pulses were sampled, in words.
    pub note: String,
}

impl LinearInputs {
    /// The scene's two components over `[0, duration]`, or why there is no reference.
    pub fn of_scene(scene: &Scene, duration: f64) -> Result<Self, String> {
        let (sign, horizontal) = match &scene.excitation {
            Excitation::None => (0.0, None),
            Excitation::MassAcceleration(s) => (1.0, Some(s)),
            Excitation::GroundAcceleration(s) => (-1.0, Some(s)),
            Excitation::GroundDisplacement(_) => {
                return Err(
                    "no vertical reference for a ground-displacement pulse (its velocity jumps)"
                        .into(),
                );
            }
        };
        let vertical = &scene
            .vertical
            .as_ref()
            .ok_or("the scene has no vertical component")?
            .signal;
        let (h, note) = grid_step(horizontal, vertical)?;
        Self::sample(h, duration, note, |t| {
            (
                horizontal.map_or(0.0, |s| sign * s.value(t)),
                vertical.value(t),
            )
        })
    }

    /// Sample `at(t) = (drive, vertical)` every `h` over `[0, duration]` (one interval more
    /// when `duration` is not a multiple of `h`).
    pub fn sample(
        h: f64,
        duration: f64,
        note: String,
        at: impl Fn(f64) -> (f64, f64),
    ) -> Result<Self, String> {
        if !(h > 0.0 && h.is_finite() && duration >= 0.0 && duration.is_finite()) {
            return Err(format!(
                "grid step {h} s or duration {duration} s is not valid"
            ));
        }
        let intervals = (duration / h - 1e-9).ceil().max(1.0);
        if intervals > MAX_INTERVALS {
            return Err(format!(
                "{intervals:.3e} grid intervals of {h} s: more than {MAX_INTERVALS:.0e}"
            ));
        }
        let n = intervals as usize;
        let (mut drive, mut vertical) = (Vec::with_capacity(n + 1), Vec::with_capacity(n + 1));
        for i in 0..=n {
            let (d, v) = at(i as f64 * h);
            if !(d.is_finite() && v.is_finite()) {
                return Err(format!(
                    "the excitation is not finite at t = {} s",
                    i as f64 * h
                ));
            }
            drive.push(d);
            vertical.push(v);
        }
        Ok(LinearInputs {
            h,
            drive,
            vertical,
            note,
        })
    }

    /// Number of grid intervals.
    pub fn intervals(&self) -> usize {
        self.drive.len() - 1
    }

    /// (drive, vertical) at `t`, linear on the grid, the last values held past its end.
    pub fn at(&self, t: f64) -> (f64, f64) {
        let n = self.intervals();
        let x = (t / self.h).clamp(0.0, n as f64);
        let i = (x.floor() as usize).min(n.saturating_sub(1));
        let f = x - i as f64;
        let lerp = |v: &[f64]| v[i] * (1.0 - f) + v[i + 1] * f;
        (lerp(&self.drive), lerp(&self.vertical))
    }
}

/// The grid step for a horizontal signal (if any) and the vertical one, with a note.
fn grid_step(horizontal: Option<&Signal>, vertical: &Signal) -> Result<(f64, String), String> {
    let record_dt = |s: &Signal| match s {
        Signal::Record { dt, .. } => Some(*dt),
        Signal::SinePulse { .. } => None,
    };
    let dts: Vec<f64> = horizontal
        .into_iter()
        .chain(Some(vertical))
        .filter_map(record_dt)
        .collect();
    let analytic = horizontal
        .into_iter()
        .chain(Some(vertical))
        .any(|s| matches!(s, Signal::SinePulse { .. }));
    match dts.as_slice() {
        [] => Ok((
            PULSE_STEP,
            format!("pulses sampled every {PULSE_STEP} s, linear in between"),
        )),
        [a, b] if a != b => Err(format!(
            "the horizontal and vertical records have different sample intervals ({a} s and {b} s): no common grid for the exact reference"
        )),
        [dt, ..] if analytic => {
            let parts = (dt / PULSE_STEP).ceil();
            let h = dt / parts;
            Ok((
                h,
                format!(
                    "record linear between its samples; pulse sampled every {h} s ({parts} per record interval), linear in between"
                ),
            ))
        }
        [dt, ..] => Ok((*dt, "records linear between their samples".into())),
    }
}

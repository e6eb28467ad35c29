//! References: exact and closed-form solutions that anchor the engines where they exist.
//! They share no code with any engine (only the scene definition and the trace format),
//! so a mistake in an engine's physics cannot be repeated here.

#![warn(missing_docs)]

pub mod bidirectional;
mod block_case;
pub mod block_record;
mod cursor;
mod duhamel;
mod epo_exact;
mod epo_record;
mod housner;
mod newmark_block;
pub mod newmark_record;
pub mod plain;
mod root;
pub mod vertical;

pub use block_case::BlockOnRecord;
pub use duhamel::Duhamel;
pub use epo_exact::{EpoExact, Phase, Segment};
pub use epo_record::{EpoRecord, Slip};
pub use housner::HousnerRocking;
pub use newmark_block::{BlockSegment, NewmarkBlock};

use rockslide_core::case::{Case, Excitation, Model, Signal};
use rockslide_core::trace::{Quantity, Trace};

/// A solution that can be evaluated exactly at any time.
pub trait ExactSolution: Send + Sync {
    /// Short name for report columns.
    fn name(&self) -> &'static str;
    /// How it is computed, with its source, in one sentence.
    fn method(&self) -> String;
    /// The quantities it provides, in `eval` order.
    fn channels(&self) -> Vec<&'static Quantity>;
    /// Values at time `t`, in channel order.
    fn eval(&self, t: f64, out: &mut [f64]);
    /// Quantities known exactly rather than by sampling (event times), by quantity key.
    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        Vec::new()
    }
    /// Append the values at each of `times` to `trace` (whose channels are
    /// [`ExactSolution::channels`]): [`ExactSolution::eval`] at each time, bit for bit. A
    /// solution stored in pieces overrides it to find each time's piece by walking on
    /// from the last one when the times ascend, instead of a binary search per time.
    fn sample_into(&self, times: &[f64], trace: &mut Trace) {
        each_row(trace, times, |t, out| self.eval(t, out));
    }
}

/// Push one row a time to `trace` at ascending `times`, as [`each_row`], for a solution
/// stored in pieces: `write(i, t, row)` gets `i`, the partition point of `pieces` at `t`
/// (`starts_by(piece, t)` is true on the pieces that start at or before `t`), found by a
/// [`cursor::Cursor`] walking on from the last one — the index a binary search gives.
fn each_row_by_piece<T>(
    trace: &mut Trace,
    times: &[f64],
    pieces: &[T],
    starts_by: impl Fn(&T, f64) -> bool,
    mut write: impl FnMut(usize, f64, &mut [f64]),
) {
    let mut cursor = cursor::Cursor::default();
    each_row(trace, times, |t, out| {
        let i = cursor.partition_point(pieces, |p| starts_by(p, t));
        write(i, t, out);
    });
}

/// Push one row a time to `trace`, its values written by `eval(t, row)`.
fn each_row(trace: &mut Trace, times: &[f64], mut eval: impl FnMut(f64, &mut [f64])) {
    let mut row = vec![0.0; trace.channels.len()];
    for &t in times {
        eval(t, &mut row);
        trace.push(t, &row);
    }
}

/// The reference for a case, or why there is none.
pub fn for_case(case: &Case) -> Result<Box<dyn ExactSolution>, String> {
    let scene = &case.scene;
    if scene.spatial().is_some() {
        return bidirectional::for_case(case);
    }
    if scene.vertical().is_some() {
        return vertical::for_case(case);
    }
    match &scene.model {
        Model::Oscillator(osc) if is_record(&scene.excitation) => Ok(Box::new(
            EpoRecord::for_excitation(osc, &scene.excitation, case.run.duration)?,
        )),
        Model::Oscillator(osc) => {
            let forcing = SineForcing::of(&scene.excitation, osc.mass)?;
            if osc.contact.mu.is_infinite() {
                Ok(Box::new(Duhamel::new(osc, forcing, case.run.duration)?))
            } else {
                Ok(Box::new(EpoExact::new(osc, forcing, case.run.duration)?))
            }
        }
        Model::RockingBody(_) => Err(
            "no exact solution exists for the rocking elastic-plastic oscillator: engines are compared with each other and with their own converged solutions".into(),
        ),
        Model::RigidBlock(block) if is_record(&scene.excitation) => Ok(Box::new(
            BlockOnRecord::for_excitation(block, &scene.excitation, case.run.duration)?,
        )),
        Model::RigidBlock(block) => {
            let forcing = SineForcing::of(&scene.excitation, block.mass)?;
            // Rocking starts from a tilt, or when the driving acceleration exceeds g·b/h
            // (Housner 1963); otherwise the block can only slide (Newmark 1965).
            let rocks = block.initial_tilt != 0.0
                || (forcing.p0 / block.mass).abs() > block.gravity * block.half_width / block.half_height;
            if rocks {
                Ok(Box::new(HousnerRocking::new(block, forcing, case.run.duration)?))
            } else {
                Ok(Box::new(NewmarkBlock::new(block, forcing, case.run.duration)?))
            }
        }
    }
}

/// Whether an excitation is a sampled record.
fn is_record(excitation: &Excitation) -> bool {
    matches!(excitation.signal(), Some(Signal::Record { .. }))
}

/// Sample a solution at the given times (e.g. an engine's output times).
pub fn sample(solution: &dyn ExactSolution, times: &[f64]) -> Trace {
    let channels = solution.channels();
    let mut trace = Trace::with_channels(&channels, times.len());
    solution.sample_into(times, &mut trace);
    trace
}

/// Sample a solution on a uniform grid of `n` intervals over `[0, duration]`.
pub fn sample_uniform(solution: &dyn ExactSolution, duration: f64, n: usize) -> Trace {
    let times: Vec<f64> = (0..=n).map(|i| duration * i as f64 / n as f64).collect();
    sample(solution, &times)
}

/// A sine-pulse force on the mass in relative coordinates, `p0·sin(θt)` for `0 ≤ t < td`,
/// with the relative-velocity jumps a ground-displacement pulse causes.
#[derive(Debug, Clone, PartialEq)]
pub struct SineForcing {
    /// Force amplitude, N.
    pub p0: f64,
    /// Circular frequency θ, rad/s.
    pub theta: f64,
    /// Pulse end td, s.
    pub td: f64,
    /// (time, jump of the relative velocity) pairs.
    pub velocity_jumps: Vec<(f64, f64)>,
    /// Ground displacement amplitude A (ground-displacement pulses), m.
    pub ground_amplitude: Option<f64>,
}

impl SineForcing {
    /// The forcing of an excitation on mass `m`, if it is a sine pulse.
    pub fn of(excitation: &Excitation, m: f64) -> Result<Self, String> {
        let pulse = |s: &Signal| match s {
            Signal::SinePulse {
                amplitude,
                omega,
                cycles,
            } => Ok((
                *amplitude,
                *omega,
                cycles * 2.0 * std::f64::consts::PI / omega,
            )),
            Signal::Record { .. } => {
                Err("no exact reference for a recorded excitation".to_string())
            }
        };
        Ok(match excitation {
            Excitation::None => SineForcing {
                p0: 0.0,
                theta: 1.0,
                td: 0.0,
                velocity_jumps: vec![],
                ground_amplitude: None,
            },
            Excitation::MassAcceleration(s) => {
                let (a, theta, td) = pulse(s)?;
                SineForcing {
                    p0: m * a,
                    theta,
                    td,
                    velocity_jumps: vec![],
                    ground_amplitude: None,
                }
            }
            Excitation::GroundAcceleration(s) => {
                let (a, theta, td) = pulse(s)?;
                SineForcing {
                    p0: -m * a,
                    theta,
                    td,
                    velocity_jumps: vec![],
                    ground_amplitude: None,
                }
            }
            Excitation::GroundDisplacement(s) => {
                // xg = A sin θt: ag = −Aθ² sin θt, so −M·ag = M·A·θ²·sin θt; the ground
                // velocity jumps by +Aθ at 0 and by −Aθ·cos θtd at td, the mass's does
                // not, so the relative velocity jumps by the opposite.
                let (a, theta, td) = pulse(s)?;
                SineForcing {
                    p0: m * a * theta * theta,
                    theta,
                    td,
                    velocity_jumps: vec![(0.0, -a * theta), (td, a * theta * (theta * td).cos())],
                    ground_amplitude: Some(a),
                }
            }
        })
    }

    /// Force at `t` (right-continuous).
    pub fn at(&self, t: f64) -> f64 {
        if (0.0..self.td).contains(&t) {
            self.p0 * (self.theta * t).sin()
        } else {
            0.0
        }
    }

    /// Ground displacement at `t`, if the ground moves.
    pub fn ground(&self, t: f64) -> Option<f64> {
        self.ground_amplitude.map(|a| {
            if (0.0..=self.td).contains(&t) {
                a * (self.theta * t).sin()
            } else {
                0.0
            }
        })
    }
}

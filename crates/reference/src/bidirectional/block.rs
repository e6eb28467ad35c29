//! The rigid-plastic block on an isotropic friction cone under a plan drive d(t).
//!
//! Relative to the ground, with a_f(t) = μ·(g + a_v(t)) the friction limit per unit mass:
//! - stick (ṡ = 0) while |d(t)| ≤ a_f(t);
//! - slip onset when |d| reaches a_f: the block starts along d̂ (the only direction in
//!   which d − a_f·ṡ/|ṡ| can start a motion from rest);
//! - sliding: s̈ = d(t) − a_f(t)·ṡ/|ṡ|;
//! - stop when |ṡ| reaches 0, which it does in finite time with nonzero slope (d|ṡ|/dt =
//!   d·ŝ − a_f < 0 near a stop). At the stop the block sticks if |d| ≤ a_f, else it slides
//!   on along the new d̂.
//!
//! Sliding is integrated by the three-stage Radau IIA method with the stage velocities in
//! polar form, speed ρ and direction θ ([`super::radau`]): the direction relaxes toward d̂
//! at the rate a_f/|ṡ|, stiff near rest, which the L-stable implicit stages damp as the
//! exact flow does; ρ < 0 continues the motion past a stop with the friction still along
//! θ, so the stop is the smooth root of the stage speeds, located by bisection on the
//! step's length. The one limit on the order: at a stop the direction turns toward d̂ as
//! (t_stop − t)^α, α = |d|/(a_f − |d|), so the slide has a term (t_stop − t)^(2+α) that no
//! polynomial step resolves (docs/bidirectional.md, "Measured"). Where |d| > a_f nearly
//! opposes the motion the speed dips almost to zero without stopping and the direction
//! turns by up to 180° far inside one step (a near-stop): a step that reaches a stage
//! speed of zero or turns sharply is taken again in substeps under error control (step
//! doubling), so that near-stops and stops hold the accuracy of the smooth steps.
//!
//! With a vertical component the cone's radius follows μ·(g + a_v); the reference stops
//! with an error if g + a_v ≤ 0 (the block would lift off, not modelled here).

use super::drive::PlanDrive;
use super::integrate::{Sample, bracket, grid, hermite, locate, march, norm};
use super::radau;
use crate::ExactSolution;
use rockslide_core::trace::{Quantity, q};

/// The speed below which a step cut where a stage speed reaches zero ends in a stop, as
/// a fraction of h·(a_f + |d|), the largest change of speed in the step (at a stop the
/// bisection leaves a speed of a few ε of it).
const STOP_SPEED: f64 = 1e-9;

/// A step whose least stage speed falls below this fraction of the speed it can change by
/// (h·(a_f + |d|)) is near a stop and taken under
/// error control ([`PlanBlock::slide_controlled`]).
const NEAR_STOP: f64 = 0.5;

/// A step whose direction turns by more than this (rad) is taken under error control.
const TURN: f64 = 0.05;

/// The largest gap of a substep's velocity (or slide per length) to two half substeps',
/// as a fraction of h·(a_f + |d|), the most the speed can change in a grid step.
const SUBSTEP_TOLERANCE: f64 = 1e-12;

/// Most halvings of one substep (2⁻⁴⁰ of a grid step).
const SUBSTEP_HALVINGS: usize = 40;

/// Most substeps of one grid step before the reference declares it is not progressing.
const MOST_SUBSTEPS: usize = 100_000;

/// No substep is halved below this fraction of the time: 64 of its floats.
const SMALLEST_SUBSTEP: f64 = 64.0 * f64::EPSILON;

/// Stick or slide.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlanBlockPhase {
    /// At rest on the ground.
    Stick,
    /// Sliding.
    Slide,
}

/// One slide: when it starts and stops (the end of the run if it never stops).
pub type SlideSpan = (f64, f64);

/// The block's history, integrated.
#[derive(Debug, Clone)]
pub struct PlanBlock {
    /// Every grid node and event, in time order.
    pub samples: Vec<Sample>,
    /// The slides, in time order.
    pub slides: Vec<SlideSpan>,
    /// The largest integration step, s.
    pub step: f64,
    law: BlockLaw,
}

/// The block's friction law and drive.
#[derive(Debug, Clone)]
struct BlockLaw {
    drive: PlanDrive,
    mu: f64,
    gravity: f64,
}

impl PlanBlock {
    /// Integrate the block with friction coefficient `mu` and gravity `gravity` under
    /// `drive` over [0, duration], steps of at most `step`.
    pub fn solve(
        mu: f64,
        gravity: f64,
        drive: &PlanDrive,
        duration: f64,
        step: f64,
    ) -> Result<Self, String> {
        if !(mu.is_finite() && mu >= 0.0 && gravity > 0.0 && gravity.is_finite()) {
            return Err(format!(
                "the plan-motion block needs a finite μ ≥ 0 and gravity > 0 (μ = {mu}, g = {gravity})"
            ));
        }
        if !(duration > 0.0 && step > 0.0) {
            return Err("duration and step must be positive".into());
        }
        let mut b = PlanBlock {
            samples: Vec::new(),
            slides: Vec::new(),
            step,
            law: BlockLaw {
                drive: drive.clone(),
                mu,
                gravity,
            },
        };
        b.integrate(duration)?;
        Ok(b)
    }

    fn push(samples: &mut Vec<Sample>, t: f64, y: &[f64; 4], acc: [f64; 2]) {
        samples.push(Sample {
            t,
            pos: [y[0], y[1]],
            vel: [y[2], y[3]],
            acc,
            slip: [y[0], y[1]],
            slip_rate: [y[2], y[3]],
        });
    }

    fn integrate(&mut self, duration: f64) -> Result<(), String> {
        let nodes = grid(&self.law.drive.kinks(duration), duration, self.step);
        let mut y = [0.0; 4];
        let mut phase = PlanBlockPhase::Stick;
        Self::push(&mut self.samples, 0.0, &y, [0.0; 2]);
        march(&nodes, &mut y, &mut phase, |t, t1, y, phase| match phase {
            PlanBlockPhase::Stick => self.stick_until(t, t1, y),
            PlanBlockPhase::Slide => self.slide_until(t, t1, y),
        })?;
        if phase == PlanBlockPhase::Slide
            && let Some(last) = self.slides.last_mut()
            && last.1.is_nan()
        {
            last.1 = duration;
        }
        Ok(())
    }

    /// Stuck from `t`: to the slip onset if it comes before `t1`, else to `t1`.
    fn stick_until(
        &mut self,
        t: &mut f64,
        t1: f64,
        y: &mut [f64; 4],
    ) -> Result<PlanBlockPhase, String> {
        let t0 = *t;
        let margin = |s: f64| -> f64 {
            let d = self.law.drive.at(s);
            self.law.mu * (self.law.gravity + self.law.drive.vertical(s)) - norm(d)
        };
        self.law.limit(t1)?;
        if margin(t0) < 0.0 {
            self.slides.push((t0, f64::NAN));
            return Ok(PlanBlockPhase::Slide);
        }
        if margin(t1) >= 0.0 {
            *t = t1;
            Self::push(&mut self.samples, t1, y, [0.0; 2]);
            return Ok(PlanBlockPhase::Stick);
        }
        let tau = locate(t1 - t0, |tau| margin(t0 + tau) + f64::MIN_POSITIVE);
        *t = t0 + tau;
        Self::push(&mut self.samples, *t, y, [0.0; 2]);
        self.slides.push((*t, f64::NAN));
        Ok(PlanBlockPhase::Slide)
    }

    /// Sliding from `t`: one Radau IIA step to `t1`, or to the stop if it comes first; a
    /// step that turns sharply or reaches a stage speed of zero is taken again in
    /// substeps under error control ([`Self::slide_controlled`]).
    ///
    /// The stop is the root of the stage speeds ρ (smooth through it: past it the friction
    /// keeps opposing the direction of the motion, [`radau`]), located by bisection on the
    /// step's length; the block is put at rest at the last length with every ρ > 0 when
    /// its speed there is nil ([`STOP_SPEED`]).
    fn slide_until(
        &mut self,
        t: &mut f64,
        t1: f64,
        y: &mut [f64; 4],
    ) -> Result<PlanBlockPhase, String> {
        let t0 = *t;
        self.law.limit(t0)?;
        self.law.limit(t1)?;
        let Some(angle) = self.start_angle(t0, y) else {
            // no drive and at rest: nothing to slide
            return Ok(PlanBlockPhase::Stick);
        };
        let h = t1 - t0;
        let (tau, st) = self.step_or_cut(t0, y, angle, h)?;
        if self.turns_sharply(t0, angle, h, &st) {
            return self.slide_controlled(t, t1, y, h);
        }
        let stopped = self.stop_speed(t0, h);
        Ok(self.end_step(t, y, (t0, tau < h, stopped), (tau, st))?.0)
    }

    /// The speed below which a cut step ends in a stop, for a grid step of `h` from `t0`
    /// ([`STOP_SPEED`]).
    fn stop_speed(&self, t0: f64, h: f64) -> f64 {
        STOP_SPEED * h * (self.law.friction(t0) + norm(self.law.drive.at(t0)))
    }

    /// The direction the slide starts along from state `y` at `t0`: its velocity's, or at
    /// rest the drive's (`None`: at rest with no drive).
    fn start_angle(&self, t0: f64, y: &[f64; 4]) -> Option<f64> {
        let (v0, d0) = ([y[2], y[3]], self.law.drive.at(t0));
        if norm(v0) > 0.0 {
            Some(v0[1].atan2(v0[0]))
        } else if norm(d0) > 0.0 {
            Some(d0[1].atan2(d0[0]))
        } else {
            None
        }
    }

    /// One Radau IIA step of length `h` from state `y` at `t0`, or, when a stage speed
    /// reaches zero inside it, the step to the last length with every stage speed positive
    /// (the cut, by bisection): its length and result.
    fn step_or_cut(
        &self,
        t0: f64,
        y: &[f64; 4],
        angle: f64,
        h: f64,
    ) -> Result<(f64, radau::Step), String> {
        let s0 = [y[0], y[1]];
        let speed = norm([y[2], y[3]]);
        let law = |t: f64| (self.law.drive.at(t), self.law.friction(t));
        let solve = |tau: f64| radau::step(&law, t0, s0, speed, angle, tau);
        // the least stage speed (−1 when the step cannot be solved)
        let ahead = |st: &Option<radau::Step>| {
            st.map_or(-1.0, |st| {
                st.speed.into_iter().fold(f64::INFINITY, f64::min)
            })
        };
        let full = solve(h);
        match full {
            Some(st) if ahead(&full) > 0.0 => Ok((h, st)),
            _ => {
                let (cut, _) = bracket(h, |tau| ahead(&solve(tau)));
                match solve(cut) {
                    Some(st) if cut > 0.0 => Ok((cut, st)),
                    _ => Err(format!(
                        "the sliding block cannot be advanced from t = {t0:.9} s (the stage equations have no solution)"
                    )),
                }
            }
        }
    }

    /// Whether a step of length `h` from `t0` (result `st`) needs error control: a stage
    /// speed reached zero in it (a stop, or a near-stop where the speed dips almost to
    /// zero and the direction turns), or its direction turned by more than [`TURN`].
    fn turns_sharply(&self, t0: f64, angle: f64, h: f64, st: &radau::Step) -> bool {
        let reach = h * (self.law.friction(t0) + norm(self.law.drive.at(t0)));
        let slowest = st.speed.into_iter().fold(f64::INFINITY, f64::min);
        let turned = st
            .angle
            .into_iter()
            .fold(0.0_f64, |m, a| m.max((a - angle).abs()));
        slowest < NEAR_STOP * reach || turned > TURN
    }

    /// Sliding from `t` toward `t1` in substeps whose velocity and slide agree with two
    /// half steps' to [`SUBSTEP_TOLERANCE`] (step doubling; the single step is kept, so a
    /// substep is a plain Radau step): each substep is halved until it does, at most
    /// [`SUBSTEP_HALVINGS`] times, and the next one tried twice as long. Ends at `t1`, or
    /// at a stop (a cut whose speed is nil) with the phase after it.
    fn slide_controlled(
        &mut self,
        t: &mut f64,
        t1: f64,
        y: &mut [f64; 4],
        h: f64,
    ) -> Result<PlanBlockPhase, String> {
        let scale = h * (self.law.friction(*t) + norm(self.law.drive.at(*t)));
        let stopped = self.stop_speed(*t, h);
        let mut tau = 0.5 * h;
        let mut substeps = 0;
        while *t < t1 {
            let t0 = *t;
            let Some(angle) = self.start_angle(t0, y) else {
                return Ok(PlanBlockPhase::Stick);
            };
            let mut halvings = 0;
            let (tried, len, st) = loop {
                let tried = tau.min(t1 - t0);
                let (len, st) = self.step_or_cut(t0, y, angle, tried)?;
                let tolerance = SUBSTEP_TOLERANCE * scale;
                if halvings == SUBSTEP_HALVINGS
                    || len <= SMALLEST_SUBSTEP * t1.abs()
                    || self.agrees_with_halves(t0, y, (angle, len, tolerance), &st)
                {
                    break (tried, len, st);
                }
                tau = 0.5 * len;
                halvings += 1;
            };
            let reached = tried == t1 - t0 && len == tried;
            let (phase, stop) = self.end_step(t, y, (t0, len < tried, stopped), (len, st))?;
            substeps += 1;
            if substeps > MOST_SUBSTEPS {
                return Err(format!("no progress at t = {t0:.9} s"));
            }
            if stop || reached {
                return Ok(phase);
            }
            tau = 2.0 * len;
        }
        Ok(PlanBlockPhase::Slide)
    }

    /// Whether one step of length `len` from `y` (result `st`) agrees with two of half
    /// that length to `tolerance` (m/s) in velocity, and in slide to `tolerance`·`len`
    /// beyond the slide's round-off.
    fn agrees_with_halves(
        &self,
        t0: f64,
        y: &[f64; 4],
        (angle, len, tolerance): (f64, f64, f64),
        st: &radau::Step,
    ) -> bool {
        let law = |t: f64| (self.law.drive.at(t), self.law.friction(t));
        let half = 0.5 * len;
        let Some(a) = radau::step(&law, t0, [y[0], y[1]], norm([y[2], y[3]]), angle, half) else {
            return false;
        };
        let Some(b) = radau::step(&law, t0 + half, a.pos, a.speed[2], a.angle[2], half) else {
            return false;
        };
        let (v, w) = (st.velocity(), b.velocity());
        let dv = norm([v[0] - w[0], v[1] - w[1]]);
        let ds = norm([st.pos[0] - b.pos[0], st.pos[1] - b.pos[1]]);
        dv <= tolerance && ds <= tolerance * len + 8.0 * f64::EPSILON * norm(st.pos)
    }

    /// Take the step (result `st`) from `t0`, its length `tau`: slide on from its end, or,
    /// at a cut (`cut`) whose speed is at most `stopped`, stop there and stick or slide on
    /// along the drive. The phase after, and whether it stopped.
    fn end_step(
        &mut self,
        t: &mut f64,
        y: &mut [f64; 4],
        (t0, cut, stopped): (f64, bool, f64),
        (tau, st): (f64, radau::Step),
    ) -> Result<(PlanBlockPhase, bool), String> {
        *t = t0 + tau;
        // a stop: the speed falls linearly into it and the bisection ends within a float
        // of it, so it is nil there to round-off; anything else (a stage equation without
        // a solution, a speed that dips to zero inside the step and rises again) goes on
        // sliding from the last solvable length
        if !cut || st.speed[2] > stopped {
            let v = st.velocity();
            *y = [st.pos[0], st.pos[1], v[0], v[1]];
            let d = self.law.drive.at(*t);
            let af = self.law.friction(*t);
            let (sn, cs) = st.angle[2].sin_cos();
            Self::push(&mut self.samples, *t, y, [d[0] - af * cs, d[1] - af * sn]);
            return Ok((PlanBlockPhase::Slide, false));
        }
        *y = [st.pos[0], st.pos[1], 0.0, 0.0];
        if let Some(last) = self.slides.last_mut() {
            last.1 = *t;
        }
        Self::push(&mut self.samples, *t, y, [0.0; 2]);
        let d = self.law.drive.at(*t);
        if norm(d) <= self.law.limit(*t)? {
            Ok((PlanBlockPhase::Stick, true))
        } else {
            self.slides.push((*t, f64::NAN));
            Ok((PlanBlockPhase::Slide, true))
        }
    }

    /// Slide and sliding velocity at `t` (Hermite between the samples).
    pub fn state(&self, t: f64) -> ([f64; 2], [f64; 2]) {
        let (s, v, _) = hermite(&self.samples, t);
        (s, v)
    }

    /// The slide at the end of the run, m.
    pub fn residual(&self) -> [f64; 2] {
        self.samples.last().map_or([0.0; 2], |s| s.pos)
    }

    /// The largest resultant slide |s| over the samples, m, and its azimuth (degrees from
    /// +x toward +y).
    pub fn peak_resultant(&self) -> (f64, f64) {
        peak_resultant(self.samples.iter().map(|s| s.pos))
    }
}

impl BlockLaw {
    /// Friction limit per unit mass a_f(t) = μ·(g + a_v(t)), or an error at lift-off.
    fn limit(&self, t: f64) -> Result<f64, String> {
        let ge = self.gravity + self.drive.vertical(t);
        if ge <= 0.0 {
            return Err(format!(
                "the effective gravity g + a_v is {ge:.6} m/s² at t = {t:.6} s: the block would lift off, which this reference does not model"
            ));
        }
        Ok(self.mu * ge)
    }

    /// a_f(t) = μ·(g + a_v(t)), unchecked (for the stages inside a checked step).
    fn friction(&self, t: f64) -> f64 {
        self.mu * (self.gravity + self.drive.vertical(t))
    }
}

/// The largest |p| of a sequence of plane vectors and its azimuth in degrees.
pub(crate) fn peak_resultant(points: impl Iterator<Item = [f64; 2]>) -> (f64, f64) {
    let mut best = (0.0, 0.0);
    for p in points {
        let r = norm(p);
        if r > best.0 {
            best = (r, p[1].atan2(p[0]).to_degrees());
        }
    }
    best
}

impl ExactSolution for PlanBlock {
    fn name(&self) -> &'static str {
        "plan block (Radau IIA, events)"
    }

    fn method(&self) -> String {
        // With a vertical component the cone's radius per unit mass is μ·(g + a_v(t)).
        let limit = if self.law.drive.has_vertical() {
            "μ·(g + a_v)"
        } else {
            "μ·g"
        };
        format!(
            "rigid-plastic block on an isotropic friction cone (s̈ = d − {limit}·ṡ/|ṡ| while sliding, stick while |d| ≤ {limit}): three-stage Radau IIA (order 5, L-stable) with Newton on the stage equations, steps ≤ {} s with a node at every kink of the drive, slip onsets and stops located by bisection; {} slides (slip episodes of the plan slip: onset to stop). {SLIP_EPISODES_RESPONSE}",
            self.step,
            self.slides.len()
        )
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        plan_channels()
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        let (s, v) = self.state(t);
        write_plan(out, s, s, v);
    }

    fn sample_into(&self, times: &[f64], trace: &mut rockslide_core::trace::Trace) {
        let samples = &self.samples;
        crate::each_row_by_piece(
            trace,
            times,
            samples,
            |s, t| s.t <= t,
            |i, t, out| {
                let (s, v, _) = super::integrate::hermite_at(samples, i, t);
                write_plan(out, s, s, v);
            },
        );
    }

    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        let (peak, _) = self.peak_resultant();
        vec![
            ("peak_resultant_sliding", peak),
            ("residual_resultant_sliding", norm(self.residual())),
        ]
    }
}

/// The channels of a plan-motion reference.
pub(crate) fn plan_channels() -> Vec<&'static Quantity> {
    vec![
        &q::REL_DISP,
        &q::SLIDE,
        &q::VEL,
        &q::REL_DISP_Y,
        &q::SLIDE_Y,
        &q::VEL_Y,
        &q::SLIDE_RESULTANT,
    ]
}

/// What a plan reference's note says of the `slip_episodes` response beside its own count
/// of slip episodes. The response reads the planar slip rate along the slip path, so it
/// meets the note's count where every stick is longer than a sample and every slide faster
/// than 1e-3 of the fastest: on the PEPO under the Chino Hills pair 93 plastic phases and
/// 93 runs sampled every 0.25, 1, 5 or 10 ms (91 every 20 ms); on the block 13 slides and
/// 12 runs (one slide peaks at 5.8e-4 of the fastest slide rate).
pub(crate) const SLIP_EPISODES_RESPONSE: &str = "The response \"Slip episodes\" (slip_episodes) is read off a sampled trace as for every engine: runs of samples whose planar slip rate along the slip path, |(Δslide, Δslide_y)|/Δt, exceeds 1e-3 of its largest, so a slip that turns across x stays one episode, a stick that holds no whole sample step joins its neighbours, a slide slower than 1e-3 of the fastest is not counted, nor a run that slides 1 µm or less (a graze of the friction limit)";

/// Fill the channels of [`plan_channels`].
pub(crate) fn write_plan(out: &mut [f64], u: [f64; 2], slip: [f64; 2], v: [f64; 2]) {
    out[0] = u[0];
    out[1] = slip[0];
    out[2] = v[0];
    out[3] = u[1];
    out[4] = slip[1];
    out[5] = v[1];
    out[6] = norm(slip);
}

//! The rigid-plastic block on an isotropic friction cone under a plan drive d(t).
//!
//! Relative to the ground, with a_f(t) = μ·(g + a_v(t)) the friction limit per unit mass:
//! - stick (ṡ = 0) while |d(t)| ≤ a_f(t);
//! - slip onset when |d| reaches a_f: the block starts along d̂ (the only direction in
//!   which d − a_f·ṡ/|ṡ| can start a motion from rest);
//! - sliding: s̈ = d(t) − a_f(t)·ṡ/|ṡ|;
//! - stop when |ṡ| reaches 0, which it does in finite time with nonzero slope (d|ṡ|/dt =
//!   d·ŝ − a_f < 0 near a stop): the event function is ṡ·u₀, u₀ the sliding direction at
//!   the start of the step, and for the stages of a step that would pass the stop the
//!   friction keeps opposing u₀ (the smooth continuation of the motion into the stop), so
//!   the event function is smooth through its root. At the stop the block sticks if
//!   |d| ≤ a_f, else it slides on along the new d̂.
//!
//! With a vertical component the cone's radius follows μ·(g + a_v); the reference stops
//! with an error if g + a_v ≤ 0 (the block would lift off, not modelled here).

use super::drive::PlanDrive;
use super::integrate::{Sample, dot, grid, hermite, locate, norm, rk4};
use crate::ExactSolution;
use rockslide_core::trace::{Quantity, q};

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

/// Most events in one grid step before the integrator declares it is not progressing.
const EVENTS_PER_STEP: usize = 64;

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
        let mut t = 0.0;
        let mut phase = PlanBlockPhase::Stick;
        Self::push(&mut self.samples, 0.0, &y, [0.0; 2]);
        for &t1 in &nodes[1..] {
            let mut events = 0;
            while t < t1 {
                events += 1;
                if events > EVENTS_PER_STEP {
                    return Err(format!("no progress at t = {t:.9} s"));
                }
                phase = match phase {
                    PlanBlockPhase::Stick => self.stick_until(&mut t, t1, &y)?,
                    PlanBlockPhase::Slide => self.slide_until(&mut t, t1, &mut y)?,
                };
            }
        }
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
        y: &[f64; 4],
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

    /// Sliding from `t`: to the stop if it comes before `t1`, else to `t1`.
    fn slide_until(
        &mut self,
        t: &mut f64,
        t1: f64,
        y: &mut [f64; 4],
    ) -> Result<PlanBlockPhase, String> {
        let t0 = *t;
        self.law.limit(t0)?;
        let v0 = [y[2], y[3]];
        let u0 = if norm(v0) > 0.0 {
            [v0[0] / norm(v0), v0[1] / norm(v0)]
        } else {
            let d = self.law.drive.at(t0);
            let n = norm(d);
            if n == 0.0 {
                // no drive and at rest: nothing to slide
                return Ok(PlanBlockPhase::Stick);
            }
            [d[0] / n, d[1] / n]
        };
        let h = t1 - t0;
        // The direction of sliding relaxes toward d̂ at the rate a_f/|ṡ|: stiff near rest,
        // where an explicit stage is stable only for h·a_f/|ṡ| < 2. Below |ṡ| = 2·a_f·h
        // the direction is taken slaved, ±d̂(t) on the side of the motion (its limit at
        // rest: the motion starts along d̂ and stops along ±d̂); above, ṡ/|ṡ|.
        let slaved = 2.0 * self.law.limit(t0)? * self.step;
        let f = self.law.sliding_rhs(u0, slaved);
        let end = rk4(&f, t0, y, h);
        let along = |z: &[f64; 4]| z[2] * u0[0] + z[3] * u0[1];
        if along(&end) > 0.0 {
            *t = t1;
            *y = end;
            let a = f(t1, y);
            Self::push(&mut self.samples, t1, y, [a[2], a[3]]);
            return Ok(PlanBlockPhase::Slide);
        }
        let tau = locate(h, |tau| along(&rk4(&f, t0, y, tau)));
        let mut z = rk4(&f, t0, y, tau);
        z[2] = 0.0;
        z[3] = 0.0;
        *t = t0 + tau;
        *y = z;
        if let Some(last) = self.slides.last_mut() {
            last.1 = *t;
        }
        let d = self.law.drive.at(*t);
        if norm(d) <= self.law.limit(*t)? {
            Self::push(&mut self.samples, *t, y, [0.0; 2]);
            Ok(PlanBlockPhase::Stick)
        } else {
            Self::push(&mut self.samples, *t, y, [0.0; 2]);
            self.slides.push((*t, f64::NAN));
            Ok(PlanBlockPhase::Slide)
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

    /// The friction direction for velocity `v` at drive `d` in a step that started
    /// sliding along `u0`: below |v| = `slaved`, the slaved direction ±d̂ on u₀'s side (u₀
    /// if d = 0);
    /// above it v̂ while the motion stays within 60° of u₀, else u₀ (the continuation of
    /// the motion past a stop, for the event function).
    fn direction(v: [f64; 2], d: [f64; 2], u0: [f64; 2], slaved: f64) -> [f64; 2] {
        let n = norm(v);
        if n < slaved {
            // ±d̂, on the side of the motion (at a stop the drive usually opposes it)
            let m = norm(d).copysign(dot(d, u0));
            return if m != 0.0 { [d[0] / m, d[1] / m] } else { u0 };
        }
        if dot(v, u0) > 0.5 * n {
            [v[0] / n, v[1] / n]
        } else {
            u0
        }
    }

    fn sliding_rhs(&self, u0: [f64; 2], slaved: f64) -> impl Fn(f64, &[f64; 4]) -> [f64; 4] + '_ {
        move |t, y| {
            let d = self.drive.at(t);
            let af = self.mu * (self.gravity + self.drive.vertical(t));
            let e = BlockLaw::direction([y[2], y[3]], d, u0, slaved);
            [y[2], y[3], d[0] - af * e[0], d[1] - af * e[1]]
        }
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
        "plan block (RK4, events)"
    }

    fn method(&self) -> String {
        format!(
            "rigid-plastic block on an isotropic friction cone (s̈ = d − μ·g·ṡ/|ṡ| while sliding, stick while |d| ≤ μ·g): classical RK4, steps ≤ {} s with a node at every kink of the drive, slip onsets and stops located by bisection; {} slides",
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

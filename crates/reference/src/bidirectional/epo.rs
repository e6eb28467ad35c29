//! The elastic-perfectly-plastic oscillator with a circular yield surface (the PEPO in
//! both horizontal directions): a mass M on an isotropic contact of stiffness K, plastic
//! slip p, elastic force F = K·(u − p), |F| ≤ R = μ·M·g, viscous damping C.
//!
//! M·ü + C·u̇ + F = M·d(t). Elastic (|F| < R, or |F| = R unloading): ṗ = 0. Plastic
//! (|F| = R and n·u̇ > 0, n = F/|F|): associated flow ṗ = λ·n, λ ≥ 0, and the consistency
//! condition d|F|/dt = n·Ḟ = K·n·(u̇ − ṗ) = 0 gives λ = n·u̇, so
//! ṗ = (n·u̇)·n — the slip rate is the velocity's component along the force, and the force
//! turns with the velocity's component across it: Ḟ = K·(u̇ − (n·u̇)·n). Events: yield when
//! |F| reaches R (elastic → plastic), unloading when λ = n·u̇ reaches 0 (plastic →
//! elastic). After each plastic step p is put back on the circle, p = u − R·n/K (the exact
//! flow keeps |F| = R; this removes the integrator's drift of |F|, which is O(h⁵) a step).

use super::block::{SLIP_EPISODES_RESPONSE, peak_resultant, plan_channels, write_plan};
use super::drive::PlanDrive;
use super::integrate::{Sample, dot, grid, hermite, locate, march, norm, rk4};
use crate::ExactSolution;
use rockslide_core::case::Oscillator;
use rockslide_core::trace::Quantity;

/// Elastic or yielding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlanEpoPhase {
    /// |F| < R, or unloading from it: the slip does not change.
    Elastic,
    /// On the yield circle, slipping along the force.
    Plastic,
}

/// The oscillator's history, integrated.
#[derive(Debug, Clone)]
pub struct PlanEpo {
    /// Every grid node and event, in time order.
    pub samples: Vec<Sample>,
    /// The plastic (slip) episodes: start and end times.
    pub slips: Vec<(f64, f64)>,
    /// The largest integration step, s.
    pub step: f64,
    law: EpoLaw,
}

/// The oscillator's constants and drive.
#[derive(Debug, Clone)]
struct EpoLaw {
    drive: PlanDrive,
    mass: f64,
    k: f64,
    c: f64,
    r: f64,
}

impl PlanEpo {
    /// Integrate `osc` (isotropic: kx in every horizontal direction, μ·M·g the cone)
    /// under `drive` over [0, duration], steps of at most `step`.
    pub fn solve(
        osc: &Oscillator,
        drive: &PlanDrive,
        duration: f64,
        step: f64,
    ) -> Result<Self, String> {
        if !(duration > 0.0 && step > 0.0) {
            return Err("duration and step must be positive".into());
        }
        let mut e = PlanEpo {
            samples: Vec::new(),
            slips: Vec::new(),
            step,
            law: EpoLaw {
                drive: drive.clone(),
                mass: osc.mass,
                k: osc.contact.kx,
                c: osc.damping(),
                r: osc.friction_limit(),
            },
        };
        e.integrate(duration)?;
        Ok(e)
    }

    fn push(samples: &mut Vec<Sample>, law: &EpoLaw, t: f64, y: &[f64; 6], phase: PlanEpoPhase) {
        let r = law.rhs(phase)(t, y);
        samples.push(Sample {
            t,
            pos: [y[0], y[1]],
            vel: [y[2], y[3]],
            acc: [r[2], r[3]],
            slip: [y[4], y[5]],
            slip_rate: [r[4], r[5]],
        });
    }

    fn integrate(&mut self, duration: f64) -> Result<(), String> {
        let nodes = grid(&self.law.drive.kinks(duration), duration, self.step);
        let mut y = [0.0; 6];
        let mut phase = PlanEpoPhase::Elastic;
        Self::push(&mut self.samples, &self.law, 0.0, &y, phase);
        march(&nodes, &mut y, &mut phase, |t, t1, y, phase| {
            Ok(self.advance(t, t1, y, phase))
        })?;
        if phase == PlanEpoPhase::Plastic
            && let Some(last) = self.slips.last_mut()
        {
            last.1 = duration;
        }
        Ok(())
    }

    /// One step from `t` toward `t1` in `phase`, stopped at the phase's event if any.
    fn advance(
        &mut self,
        t: &mut f64,
        t1: f64,
        y: &mut [f64; 6],
        phase: PlanEpoPhase,
    ) -> PlanEpoPhase {
        let t0 = *t;
        let h = t1 - t0;
        let law = &self.law;
        let f = law.rhs(phase);
        // the event function: > 0 while the phase holds
        let g = |z: &[f64; 6]| match phase {
            PlanEpoPhase::Elastic => law.r - norm(law.force(z)),
            PlanEpoPhase::Plastic => law.lambda(z),
        };
        let end = rk4(&f, t0, y, h);
        let (tau, next) = if g(&end) > 0.0 {
            (h, phase)
        } else {
            let tau = locate(h, |tau| g(&rk4(&f, t0, y, tau)));
            let next = match phase {
                PlanEpoPhase::Elastic => PlanEpoPhase::Plastic,
                PlanEpoPhase::Plastic => PlanEpoPhase::Elastic,
            };
            (tau, next)
        };
        let mut z = if tau == h { end } else { rk4(&f, t0, y, tau) };
        if phase == PlanEpoPhase::Plastic || next == PlanEpoPhase::Plastic {
            law.onto_circle(&mut z);
        }
        *t = t0 + tau;
        *y = z;
        match (phase, next) {
            (PlanEpoPhase::Elastic, PlanEpoPhase::Plastic) => self.slips.push((*t, f64::NAN)),
            (PlanEpoPhase::Plastic, PlanEpoPhase::Elastic) => {
                if let Some(last) = self.slips.last_mut() {
                    last.1 = *t;
                }
            }
            _ => {}
        }
        Self::push(&mut self.samples, &self.law, *t, y, next);
        next
    }

    /// Displacement u, velocity u̇ and plastic slip p at `t` (Hermite between samples).
    pub fn state(&self, t: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
        hermite(&self.samples, t)
    }

    /// The slip at the end of the run, m.
    pub fn residual(&self) -> [f64; 2] {
        self.samples.last().map_or([0.0; 2], |s| s.slip)
    }

    /// The largest resultant slip |p| over the samples, m, and its azimuth in degrees.
    pub fn peak_resultant(&self) -> (f64, f64) {
        peak_resultant(self.samples.iter().map(|s| s.slip))
    }
}

impl EpoLaw {
    fn rhs(&self, phase: PlanEpoPhase) -> impl Fn(f64, &[f64; 6]) -> [f64; 6] + '_ {
        move |t, y| {
            let d = self.drive.at(t);
            let f = [self.k * (y[0] - y[4]), self.k * (y[1] - y[5])];
            let pdot = match phase {
                PlanEpoPhase::Elastic => [0.0, 0.0],
                PlanEpoPhase::Plastic => {
                    let n = norm(f);
                    let e = [f[0] / n, f[1] / n];
                    let lambda = dot(e, [y[2], y[3]]);
                    [lambda * e[0], lambda * e[1]]
                }
            };
            [
                y[2],
                y[3],
                d[0] - (self.c * y[2] + f[0]) / self.mass,
                d[1] - (self.c * y[3] + f[1]) / self.mass,
                pdot[0],
                pdot[1],
            ]
        }
    }

    fn force(&self, y: &[f64; 6]) -> [f64; 2] {
        [self.k * (y[0] - y[4]), self.k * (y[1] - y[5])]
    }

    /// λ = n·u̇ (the yield rate along the force).
    fn lambda(&self, y: &[f64; 6]) -> f64 {
        let f = self.force(y);
        dot(f, [y[2], y[3]]) / norm(f)
    }

    /// Put p back on the yield circle: p = u − R·n/K.
    fn onto_circle(&self, y: &mut [f64; 6]) {
        let f = self.force(y);
        let n = norm(f);
        y[4] = y[0] - self.r * f[0] / n / self.k;
        y[5] = y[1] - self.r * f[1] / n / self.k;
    }
}

impl ExactSolution for PlanEpo {
    fn name(&self) -> &'static str {
        "plan EPO (RK4, events)"
    }

    fn method(&self) -> String {
        format!(
            "elastic-perfectly-plastic oscillator with a circular yield surface (ṗ = (n·u̇)·n on |K(u − p)| = μ·M·g): classical RK4, steps ≤ {} s with a node at every kink of the drive, yield and unloading located by bisection; {} plastic phases (slip episodes of the plan slip: yield to unloading). {SLIP_EPISODES_RESPONSE}",
            self.step,
            self.slips.len()
        )
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        plan_channels()
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        let (u, v, p) = self.state(t);
        write_plan(out, u, p, v);
    }

    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        let (peak, _) = self.peak_resultant();
        vec![
            ("peak_resultant_sliding", peak),
            ("residual_resultant_sliding", norm(self.residual())),
        ]
    }
}

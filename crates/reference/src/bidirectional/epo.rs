//! The elastic-perfectly-plastic oscillator with a circular yield surface (the PEPO in
//! both horizontal directions): a mass M on an isotropic contact of stiffness K, plastic
//! slip p, elastic force F = K·(u − p), |F| ≤ R(t) = μ·N(t), viscous damping C.
//!
//! M·ü + C·u̇ + F = M·d(t). Elastic (|F| < R, or |F| = R unloading): ṗ = 0. Plastic
//! (|F| = R and λ > 0, n = F/|F|): associated flow ṗ = λ·n, λ ≥ 0, and the consistency
//! condition d|F|/dt = n·Ḟ = K·n·(u̇ − ṗ) = Ṙ gives λ = n·u̇ − Ṙ/K, so the slip rate is the
//! velocity's component along the force less the circle's own growth, and the force turns
//! with the velocity's component across it. Events: yield when |F| reaches R (elastic →
//! plastic: the force grows, or the circle shrinks onto it), unloading when λ reaches 0
//! (plastic → elastic). After each plastic step p is put back on the circle,
//! p = u − R·n/K (the exact flow keeps |F| = R; this removes the integrator's drift of
//! |F|, which is O(h⁵) a step).
//!
//! The normal force ([`Normal`]): M·g without a vertical component; with one, a rigid
//! vertical contact N = M·(g + a_v(t)) (`normal_force = "quasi-static"`), or the contact's
//! vertical stiffness Kz (`"dynamic"`): M·δ'' + Kz·δ = M·(g + a_v), N = Kz·δ from static
//! rest δ = M·g/Kz, integrated with the rest — the physics of the planar vertical
//! reference (`crate::vertical`). The contact is compression-only there; here a normal
//! force that reaches 0 (lift-off) stops the reference with an error.

use super::block::{SLIP_EPISODES_RESPONSE, peak_resultant, plan_channels, write_plan};
use super::drive::PlanDrive;
use super::integrate::{Sample, dot, grid, hermite, hermite_at, locate, march, norm, rk4};
use crate::ExactSolution;
use rockslide_core::case::{NormalForce, Oscillator};
use rockslide_core::trace::{Quantity, Trace};

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
    normal: Normal,
}

/// How the normal force N, and the yield circle's radius R = μ·N, follow the vertical
/// motion. The state is (u, u̇, p, δ, δ̇), the last two the vertical compression and its
/// rate (used by [`Normal::Dynamic`] only).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Normal {
    /// No vertical component: R = μ·M·g.
    Constant(f64),
    /// A rigid vertical contact: N = M·(g + a_v(t)).
    Rigid { mu: f64, mass: f64, gravity: f64 },
    /// The vertical stiffness Kz: δ'' = g + a_v − ωz²·δ, N = Kz·δ.
    Dynamic {
        mu: f64,
        kz: f64,
        wz2: f64,
        gravity: f64,
    },
}

/// The state's length: u, u̇, p (two each), δ, δ̇.
const STATE: usize = 8;

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
        let mu = osc.contact.mu;
        let normal = match (drive.has_vertical(), drive.normal_force()) {
            (false, _) => Normal::Constant(osc.friction_limit()),
            (true, NormalForce::QuasiStatic) => Normal::Rigid {
                mu,
                mass: osc.mass,
                gravity: osc.gravity,
            },
            (true, NormalForce::Dynamic) => {
                let wz = (osc.contact.kz / osc.mass).sqrt();
                Normal::Dynamic {
                    mu,
                    kz: osc.contact.kz,
                    wz2: wz * wz,
                    gravity: osc.gravity,
                }
            }
        };
        let mut e = PlanEpo {
            samples: Vec::new(),
            slips: Vec::new(),
            step,
            law: EpoLaw {
                drive: drive.clone(),
                mass: osc.mass,
                k: osc.contact.kx,
                c: osc.damping(),
                normal,
            },
        };
        e.integrate(duration)?;
        Ok(e)
    }

    /// Record the state at `t`, its rates taken on the piece of the drive that holds
    /// `inside` (the step that ended there).
    fn push(
        samples: &mut Vec<Sample>,
        law: &EpoLaw,
        (t, inside): (f64, f64),
        y: &[f64; STATE],
        phase: PlanEpoPhase,
    ) {
        let r = law.rhs(phase, inside)(t, y);
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
        let mut y = self.law.rest();
        let mut phase = PlanEpoPhase::Elastic;
        let first = nodes.get(1).map_or(0.0, |t1| 0.5 * t1);
        Self::push(&mut self.samples, &self.law, (0.0, first), &y, phase);
        march(&nodes, &mut y, &mut phase, |t, t1, y, phase| {
            let next = self.advance(t, t1, y, phase);
            self.law.check_contact(*t, y)?;
            Ok(next)
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
        y: &mut [f64; STATE],
        phase: PlanEpoPhase,
    ) -> PlanEpoPhase {
        let t0 = *t;
        let h = t1 - t0;
        let inside = t0 + 0.5 * h;
        let law = &self.law;
        let f = law.rhs(phase, inside);
        // the event function at τ into the step: > 0 while the phase holds
        let g = |tau: f64, z: &[f64; STATE]| match phase {
            PlanEpoPhase::Elastic => law.radius(t0 + tau, z) - norm(law.force(z)),
            PlanEpoPhase::Plastic => law.lambda(t0 + tau, z, inside),
        };
        let end = rk4(&f, t0, y, h);
        let (tau, next) = if g(h, &end) > 0.0 {
            (h, phase)
        } else {
            let tau = locate(h, |tau| g(tau, &rk4(&f, t0, y, tau)));
            let next = match phase {
                PlanEpoPhase::Elastic => PlanEpoPhase::Plastic,
                PlanEpoPhase::Plastic => PlanEpoPhase::Elastic,
            };
            (tau, next)
        };
        let mut z = if tau == h { end } else { rk4(&f, t0, y, tau) };
        if phase == PlanEpoPhase::Plastic || next == PlanEpoPhase::Plastic {
            law.onto_circle(t0 + tau, &mut z);
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
        Self::push(&mut self.samples, &self.law, (*t, inside), y, next);
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
    /// At rest, the vertical contact compressed by its static load.
    fn rest(&self) -> [f64; STATE] {
        let mut y = [0.0; STATE];
        if let Normal::Dynamic { wz2, gravity, .. } = self.normal {
            y[6] = gravity / wz2;
        }
        y
    }

    /// The state's rate in `phase`, a_v's rate taken on the piece that holds `inside`.
    fn rhs(
        &self,
        phase: PlanEpoPhase,
        inside: f64,
    ) -> impl Fn(f64, &[f64; STATE]) -> [f64; STATE] + '_ {
        let drive = self.drive.remembered();
        move |t, y| {
            let d = drive.at(t);
            let f = [self.k * (y[0] - y[4]), self.k * (y[1] - y[5])];
            let pdot = match phase {
                PlanEpoPhase::Elastic => [0.0, 0.0],
                PlanEpoPhase::Plastic => {
                    let n = norm(f);
                    let e = [f[0] / n, f[1] / n];
                    let lambda = dot(e, [y[2], y[3]]) - self.radius_rate(t, y, inside) / self.k;
                    [lambda * e[0], lambda * e[1]]
                }
            };
            let (dz, vz) = match self.normal {
                Normal::Dynamic { wz2, gravity, .. } => {
                    (y[7], gravity + self.drive.vertical(t) - wz2 * y[6])
                }
                _ => (0.0, 0.0),
            };
            [
                y[2],
                y[3],
                d[0] - (self.c * y[2] + f[0]) / self.mass,
                d[1] - (self.c * y[3] + f[1]) / self.mass,
                pdot[0],
                pdot[1],
                dz,
                vz,
            ]
        }
    }

    fn force(&self, y: &[f64; STATE]) -> [f64; 2] {
        [self.k * (y[0] - y[4]), self.k * (y[1] - y[5])]
    }

    /// The normal force N at `t` in state `y`, N (M·g without a vertical component).
    fn normal_force(&self, t: f64, y: &[f64; STATE]) -> f64 {
        match self.normal {
            Normal::Constant(_) => f64::INFINITY,
            Normal::Rigid { mass, gravity, .. } => mass * (gravity + self.drive.vertical(t)),
            Normal::Dynamic { kz, .. } => kz * y[6],
        }
    }

    /// The yield circle's radius R = μ·N, N.
    fn radius(&self, t: f64, y: &[f64; STATE]) -> f64 {
        match self.normal {
            Normal::Constant(r) => r,
            Normal::Rigid { mu, .. } | Normal::Dynamic { mu, .. } => mu * self.normal_force(t, y),
        }
    }

    /// Ṙ = μ·Ṅ, N/s (a_v's rate on the piece that holds `inside`).
    fn radius_rate(&self, t: f64, y: &[f64; STATE], inside: f64) -> f64 {
        match self.normal {
            Normal::Constant(_) => 0.0,
            Normal::Rigid { mu, mass, .. } => mu * (mass * self.drive.vertical_rate(t, inside)),
            Normal::Dynamic { mu, kz, .. } => mu * (kz * y[7]),
        }
    }

    /// λ = n·u̇ − Ṙ/K (the yield rate along the force).
    fn lambda(&self, t: f64, y: &[f64; STATE], inside: f64) -> f64 {
        let f = self.force(y);
        dot(f, [y[2], y[3]]) / norm(f) - self.radius_rate(t, y, inside) / self.k
    }

    /// Put p back on the yield circle: p = u − R·n/K.
    fn onto_circle(&self, t: f64, y: &mut [f64; STATE]) {
        let f = self.force(y);
        let n = norm(f);
        let r = self.radius(t, y);
        y[4] = y[0] - r * f[0] / n / self.k;
        y[5] = y[1] - r * f[1] / n / self.k;
    }

    /// An error once the normal force has fallen to zero (the mass would lift off).
    fn check_contact(&self, t: f64, y: &[f64; STATE]) -> Result<(), String> {
        let n = self.normal_force(t, y);
        if n > 0.0 {
            Ok(())
        } else {
            Err(format!(
                "the normal force falls to {n:.6e} N at t = {t:.6} s: the mass would lift off, which the plan-motion oscillator reference does not model"
            ))
        }
    }

    /// The normal-force model in words, for the method note.
    fn describe(&self) -> &'static str {
        match self.normal {
            Normal::Constant(_) => "ṗ = (n·u̇)·n on |K(u − p)| = μ·M·g",
            Normal::Rigid { .. } => {
                "ṗ = (n·u̇ − Ṙ/K)·n on |K(u − p)| = R = μ·N(t), N = M·(g + a_v(t)), a rigid vertical contact"
            }
            Normal::Dynamic { .. } => {
                "ṗ = (n·u̇ − Ṙ/K)·n on |K(u − p)| = R = μ·N(t), N = Kz·δ with M·δ'' + Kz·δ = M·(g + a_v) integrated with the rest, lift-off not modelled"
            }
        }
    }
}

impl ExactSolution for PlanEpo {
    fn name(&self) -> &'static str {
        "plan EPO (RK4, events)"
    }

    fn method(&self) -> String {
        format!(
            "elastic-perfectly-plastic oscillator with a circular yield surface ({}): classical RK4, steps ≤ {} s with a node at every kink of the drive, yield and unloading located by bisection; {} plastic phases (slip episodes of the plan slip: yield to unloading). {SLIP_EPISODES_RESPONSE}",
            self.law.describe(),
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

    fn sample_into(&self, times: &[f64], trace: &mut Trace) {
        let samples = &self.samples;
        crate::each_row_by_piece(
            trace,
            times,
            samples,
            |s, t| s.t <= t,
            |i, t, out| {
                let (u, v, p) = hermite_at(samples, i, t);
                write_plan(out, u, p, v);
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

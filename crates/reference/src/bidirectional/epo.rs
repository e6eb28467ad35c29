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
//! reference (`crate::vertical`).
//!
//! Lift-off and landing (Kz only): the contact is compression-only. When δ reaches 0 the
//! contact opens ([`PlanEpoPhase::Open`]): free flight, ü = d(t) in plan (no spring, no
//! dashpot: they are the contact's), δ'' = g + a_v, and the tangential spring's origin
//! follows the mass (p = u, the slip takes the flight's plan path), so the contact
//! closes again with no tangential force. It closes when δ returns to 0 — the impact
//! rule is the spring Kz itself, nothing lost: a linear spring while closed, integrated
//! with the rest — elastic when the circle grows faster than the tangential force
//! (μ·Kz·δ̇ ≥ K·|u̇|), plastic along u̇ otherwise. Both events are located by bisection
//! like yield and unloading. A rigid vertical contact (`"quasi-static"`) whose
//! N = M·(g + a_v) reaches 0 stops the reference with an error (a rigid contact needs
//! an impact rule of its own, not modelled).

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
    /// The contact open (δ < 0, Kz only): free flight, the slip following the mass.
    Open,
}

/// The oscillator's history, integrated.
#[derive(Debug, Clone)]
pub struct PlanEpo {
    /// Every grid node and event, in time order.
    pub samples: Vec<Sample>,
    /// The plastic (slip) episodes: start and end times.
    pub slips: Vec<(f64, f64)>,
    /// The flights (the contact open, Kz only): lift-off and landing times.
    pub flights: Vec<(f64, f64)>,
    /// The largest integration step, s.
    pub step: f64,
    /// The vertical compression δ, its rate and acceleration at every sample (zeros
    /// unless N comes from Kz): δ < 0 is a gap, the mass's uplift above the ground.
    heights: Vec<[f64; 3]>,
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
            flights: Vec::new(),
            step,
            heights: Vec::new(),
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
        (samples, heights): (&mut Vec<Sample>, &mut Vec<[f64; 3]>),
        law: &EpoLaw,
        (t, inside): (f64, f64),
        y: &[f64; STATE],
        phase: PlanEpoPhase,
    ) {
        let r = law.rhs(phase, inside)(t, y);
        heights.push([y[6], y[7], r[7]]);
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
        Self::push(
            (&mut self.samples, &mut self.heights),
            &self.law,
            (0.0, first),
            &y,
            phase,
        );
        march(&nodes, &mut y, &mut phase, |t, t1, y, phase| {
            let next = self.advance(t, t1, y, phase);
            self.law.check_contact(*t, y)?;
            Ok(next)
        })?;
        let open_at_end = match phase {
            PlanEpoPhase::Plastic => self.slips.last_mut(),
            PlanEpoPhase::Open => self.flights.last_mut(),
            PlanEpoPhase::Elastic => None,
        };
        if let Some(last) = open_at_end {
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
        let g = |tau: f64, z: &[f64; STATE]| law.event(phase, (t0 + tau, inside), z);
        let end = rk4(&f, t0, y, h);
        let (tau, next) = if g(h, &end) > 0.0 {
            (h, phase)
        } else {
            let tau = locate(h, |tau| g(tau, &rk4(&f, t0, y, tau)));
            let at = rk4(&f, t0, y, tau);
            (tau, law.next_phase(phase, &at))
        };
        let mut z = if tau == h { end } else { rk4(&f, t0, y, tau) };
        match next {
            PlanEpoPhase::Open => {
                z[4] = z[0];
                z[5] = z[1];
            }
            PlanEpoPhase::Plastic => law.onto_circle(t0 + tau, &mut z),
            PlanEpoPhase::Elastic if phase == PlanEpoPhase::Plastic => {
                law.onto_circle(t0 + tau, &mut z)
            }
            PlanEpoPhase::Elastic => {}
        }
        *t = t0 + tau;
        *y = z;
        mark((&mut self.slips, &mut self.flights), (phase, next), *t);
        Self::push(
            (&mut self.samples, &mut self.heights),
            &self.law,
            (*t, inside),
            y,
            next,
        );
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

    /// The vertical compression δ at `t`, m (negative: the gap of a flight), by cubic
    /// Hermite interpolation of δ and δ̇ between samples; 0 unless N comes from Kz.
    pub fn compression(&self, t: f64) -> f64 {
        let i = self.samples.partition_point(|s| s.t <= t);
        if i == 0 || i == self.samples.len() {
            return self.heights[i.saturating_sub(1)][0];
        }
        let (a, b) = (self.heights[i - 1], self.heights[i]);
        let (ta, tb) = (self.samples[i - 1].t, self.samples[i].t);
        let h = tb - ta;
        if h <= 0.0 {
            return b[0];
        }
        let x = (t - ta) / h;
        (1.0 + 2.0 * x) * (1.0 - x) * (1.0 - x) * a[0]
            + h * x * (1.0 - x) * (1.0 - x) * a[1]
            + x * x * (3.0 - 2.0 * x) * b[0]
            + h * x * x * (x - 1.0) * b[1]
    }

    /// The largest gap −δ of the flights, m (0 without one): the samples' largest, and at
    /// each apex inside a step (δ̇ from negative to positive) δ − δ̇²/(2·δ̈) from the
    /// sample before it (δ̈ = g + a_v there: exact to O(h³·ȧ_v)).
    pub fn peak_uplift(&self) -> f64 {
        let mut peak: f64 = 0.0;
        for w in self.heights.windows(2) {
            let [a, b] = [w[0], w[1]];
            peak = peak.max(-a[0]).max(-b[0]);
            if a[0] < 0.0 && a[1] < 0.0 && b[1] > 0.0 && a[2] > 0.0 {
                peak = peak.max(-(a[0] - a[1] * a[1] / (2.0 * a[2])));
            }
        }
        peak
    }
}

/// Start and end times of a phase's spans (slip episodes, flights).
type Spans = Vec<(f64, f64)>;

/// Open or close a slip episode or a flight at a phase change at `t`.
fn mark(
    (slips, flights): (&mut Spans, &mut Spans),
    (from, to): (PlanEpoPhase, PlanEpoPhase),
    t: f64,
) {
    use PlanEpoPhase::{Open, Plastic};
    if from == to {
        return;
    }
    for (list, phase) in [(slips, Plastic), (flights, Open)] {
        if from == phase
            && let Some(last) = list.last_mut()
        {
            last.1 = t;
        }
        if to == phase {
            list.push((t, f64::NAN));
        }
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
            let open = phase == PlanEpoPhase::Open;
            // the contact's forces on the mass: none while open
            let (f, c) = if open {
                ([0.0, 0.0], 0.0)
            } else {
                (self.force(y), self.c)
            };
            let pdot = match phase {
                PlanEpoPhase::Elastic => [0.0, 0.0],
                PlanEpoPhase::Plastic => {
                    let e = self.direction(y);
                    let lambda = dot(e, [y[2], y[3]]) - self.radius_rate(t, y, inside) / self.k;
                    [lambda * e[0], lambda * e[1]]
                }
                PlanEpoPhase::Open => [y[2], y[3]],
            };
            let (dz, vz) = match self.normal {
                Normal::Dynamic { wz2, gravity, .. } => {
                    let spring = if open { 0.0 } else { wz2 * y[6] };
                    (y[7], gravity + self.drive.vertical(t) - spring)
                }
                _ => (0.0, 0.0),
            };
            [
                y[2],
                y[3],
                d[0] - (c * y[2] + f[0]) / self.mass,
                d[1] - (c * y[3] + f[1]) / self.mass,
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

    /// The unit direction of the force, or of the velocity when the force is zero (a
    /// plastic phase that starts at a landing, F = 0 = R), or +x.
    fn direction(&self, y: &[f64; STATE]) -> [f64; 2] {
        let f = self.force(y);
        let v = [y[2], y[3]];
        let (nf, nv) = (norm(f), norm(v));
        if nf > 0.0 {
            [f[0] / nf, f[1] / nf]
        } else if nv > 0.0 {
            [v[0] / nv, v[1] / nv]
        } else {
            [1.0, 0.0]
        }
    }

    /// The event function of `phase` at `t` (`inside`: a time inside the step): > 0
    /// while the phase holds. Closed phases under Kz also end when δ reaches 0.
    fn event(&self, phase: PlanEpoPhase, (t, inside): (f64, f64), z: &[f64; STATE]) -> f64 {
        let kz = matches!(self.normal, Normal::Dynamic { .. });
        match phase {
            PlanEpoPhase::Open => -z[6],
            PlanEpoPhase::Elastic => {
                let yield_gap = self.radius(t, z) - norm(self.force(z));
                if kz { yield_gap.min(z[6]) } else { yield_gap }
            }
            PlanEpoPhase::Plastic => {
                let lambda = self.lambda(t, z, inside);
                if kz { lambda.min(z[6]) } else { lambda }
            }
        }
    }

    /// The phase after an event of `phase` found in state `z`: a lift-off (δ ≤ 0 under
    /// Kz), a landing (elastic when μ·Kz·δ̇ ≥ K·|u̇|, else plastic), yield or unloading.
    fn next_phase(&self, phase: PlanEpoPhase, z: &[f64; STATE]) -> PlanEpoPhase {
        let kz = matches!(self.normal, Normal::Dynamic { .. });
        match phase {
            PlanEpoPhase::Open => match self.normal {
                Normal::Dynamic { mu, kz, .. } if mu * kz * z[7] < self.k * norm([z[2], z[3]]) => {
                    PlanEpoPhase::Plastic
                }
                _ => PlanEpoPhase::Elastic,
            },
            _ if kz && z[6] <= 0.0 => PlanEpoPhase::Open,
            PlanEpoPhase::Elastic => PlanEpoPhase::Plastic,
            PlanEpoPhase::Plastic => PlanEpoPhase::Elastic,
        }
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
        let along = match norm(f) {
            n if n > 0.0 => dot(f, [y[2], y[3]]) / n,
            _ => dot(self.direction(y), [y[2], y[3]]),
        };
        along - self.radius_rate(t, y, inside) / self.k
    }

    /// Put p back on the yield circle: p = u − R·n/K (R ≥ 0).
    fn onto_circle(&self, t: f64, y: &mut [f64; STATE]) {
        let f = self.force(y);
        let r = self.radius(t, y).max(0.0);
        let n = norm(f);
        let back = if n > 0.0 {
            [r * f[0] / n / self.k, r * f[1] / n / self.k]
        } else {
            self.direction(y).map(|e| r * e / self.k)
        };
        y[4] = y[0] - back[0];
        y[5] = y[1] - back[1];
    }

    /// An error once the rigid vertical contact's normal force has fallen to zero (the
    /// mass would lift off, with no impact rule for its landing); under Kz the contact
    /// opens instead.
    fn check_contact(&self, t: f64, y: &[f64; STATE]) -> Result<(), String> {
        let n = self.normal_force(t, y);
        if n > 0.0 || matches!(self.normal, Normal::Dynamic { .. }) {
            Ok(())
        } else {
            Err(format!(
                "the normal force falls to {n:.6e} N at t = {t:.6} s: the mass would lift off its rigid vertical contact, whose landing the plan-motion oscillator reference does not model (the contact's Kz, normal_force = \"dynamic\", opens and closes)"
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
                "ṗ = (n·u̇ − Ṙ/K)·n on |K(u − p)| = R = μ·N(t), N = Kz·δ with M·δ'' + Kz·δ = M·(g + a_v) integrated with the rest; compression only: free flight with the slip following the mass while δ < 0, landing on Kz"
            }
        }
    }
}

impl PlanEpo {
    /// The flights in words for the method note (empty without one).
    fn flight_note(&self) -> String {
        match self.flights.len() {
            0 => String::new(),
            n => format!(
                "; {n} flight{} (the contact open, first lift-off at {:.4} s), peak uplift {:.4} mm",
                if n == 1 { "" } else { "s" },
                self.flights[0].0,
                1e3 * self.peak_uplift()
            ),
        }
    }
}

impl ExactSolution for PlanEpo {
    fn name(&self) -> &'static str {
        "plan EPO (RK4, events)"
    }

    fn method(&self) -> String {
        format!(
            "elastic-perfectly-plastic oscillator with a circular yield surface ({}): classical RK4, steps ≤ {} s with a node at every kink of the drive, yield and unloading{} located by bisection; {} plastic phases (slip episodes of the plan slip: yield to unloading){}. {SLIP_EPISODES_RESPONSE}",
            self.law.describe(),
            self.step,
            if matches!(self.law.normal, Normal::Dynamic { .. }) {
                ", lift-off and landing"
            } else {
                ""
            },
            self.slips.len(),
            self.flight_note(),
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
        let mut q = vec![
            ("peak_resultant_sliding", peak),
            ("residual_resultant_sliding", norm(self.residual())),
        ];
        // the flights' largest gap, when the contact opened
        if !self.flights.is_empty() {
            q.push(("peak_uplift", self.peak_uplift()));
        }
        q
    }
}

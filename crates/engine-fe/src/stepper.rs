//! The time loop: static preload under gravity, then Newmark average acceleration or
//! HHT-α with Newton–Raphson equilibrium iterations on the consistent tangent.
//!
//! Newmark (Newmark 1959), with q the body's degrees of freedom:
//!   a₊ = (q₊ − qₙ − Δt·vₙ)/(βΔt²) − (1/(2β) − 1)·aₙ,   v₊ = vₙ + Δt·((1 − γ)aₙ + γa₊)
//! HHT-α (Hilber, Hughes & Taylor 1977), equilibrium at t_{n+1+α}:
//!   M·a₊ + (1 + α)(p₊ + C·v₊ − f₊) − α(pₙ + C·vₙ − fₙ) = 0
//! Massless nodes carry no inertia: their rows are (1 + α)·p₊ − α·pₙ = 0.
//! Nothing is allocated inside the loop: every vector lives in a [`Workspace`].

mod slider;

use nalgebra::{SVector, Vector2, Vector3};

use super::model::{Assembly, Model, System, solve};
use super::options::FeOptions;
use rockslide_core::case::{Excitation, Signal};
use rockslide_engine_api::RunStatus;

/// How the excitation drives the model.
#[derive(Debug, Clone, Copy)]
pub struct Drive<'a> {
    excitation: &'a Excitation,
    mass: f64,
    /// The vertical ground acceleration a_v(t), if any (`vertical`).
    vertical: Option<&'a Signal>,
}

impl<'a> Drive<'a> {
    /// The drive of an excitation on a body of mass `mass`.
    pub fn new(excitation: &'a Excitation, mass: f64) -> Self {
        Self {
            excitation,
            mass,
            vertical: None,
        }
    }
    /// The same drive with a vertical ground acceleration a_v(t) (positive upward).
    pub fn with_vertical(self, vertical: Option<&'a Signal>) -> Self {
        Self { vertical, ..self }
    }
    /// Vertical force on the body at `t` beyond the preload, N: −M·a_v(t) (`vertical`).
    pub fn vertical_force(&self, t: f64) -> f64 {
        super::vertical::load(self.vertical, self.mass, t)
    }
    /// Horizontal force applied to the body at `t`, N. A ground acceleration record is
    /// run in relative coordinates (force −M·ag, ground fixed).
    pub fn force(&self, t: f64) -> f64 {
        match self.excitation {
            Excitation::MassAcceleration(s) => self.mass * s.value(t),
            Excitation::GroundAcceleration(s) => -self.mass * s.value(t),
            _ => 0.0,
        }
    }
    /// Prescribed ground (displacement, velocity, acceleration) at `t`, in the model.
    pub fn ground(&self, t: f64) -> (f64, f64, f64) {
        match self.excitation {
            Excitation::GroundDisplacement(s) => {
                (s.value(t), s.derivative(t), s.second_derivative(t))
            }
            _ => (0.0, 0.0, 0.0),
        }
    }
    /// The horizontal force on the mass in relative coordinates (output channel `force`).
    /// `force` is `self.force(t)`, as a snapshot holds it (no second evaluation).
    pub fn equivalent_force(&self, t: f64, force: f64) -> f64 {
        match self.excitation {
            Excitation::GroundDisplacement(s) => -self.mass * s.second_derivative(t),
            _ => force,
        }
    }
}

/// The model's state at one output instant.
#[derive(Debug, Clone, Copy)]
pub struct Snapshot<'a> {
    /// Time, s.
    pub t: f64,
    /// Body displacement (X, Z, θ) from the unloaded position.
    pub q: Vector3<f64>,
    /// Body velocity.
    pub v: Vector3<f64>,
    /// Body acceleration.
    pub a: Vector3<f64>,
    /// Node displacements.
    pub un: &'a [Vector2<f64>],
    /// Ground (displacement, velocity, acceleration).
    pub ground: (f64, f64, f64),
    /// Body displacement at static equilibrium.
    pub q_static: Vector3<f64>,
    /// Applied horizontal force at `t` (`Drive::force`), N.
    pub force: f64,
    /// Vertical load at `t` beyond the preload (`Drive::vertical_force`), N.
    pub vertical_force: f64,
    /// (cos θ, sin θ) of `q` as the model's kinematics use them (`Assembly::rotation`).
    pub rotation: (f64, f64),
}

/// Deterministic counters of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Time steps taken.
    pub steps: u64,
    /// Equilibrium (Newton) iterations over all steps.
    pub iterations: u64,
    /// Most iterations in one step.
    pub max_step_iterations: u64,
    /// Iterations of the static preload.
    pub static_iterations: u64,
    /// Step attempts that failed and were retried as two halves (step cutting).
    pub step_cuts: u64,
    /// Steps accepted at the round-off floor (residual within tolerance and no longer
    /// falling, correction still above the displacement criterion).
    pub roundoff_accepted: u64,
}

/// The Newmark/HHT-α coefficients of one step of length `h` (the 2D and 3D steppers').
#[derive(Debug, Clone, Copy)]
pub(crate) struct Newmark {
    /// HHT's α (0 for Newmark).
    pub alpha: f64,
    /// Newmark's γ (β enters through `c0`, `c1` and the weight of aₙ).
    pub gamma: f64,
    /// 1 + α, the weight of the end-of-step forces.
    pub s: f64,
    /// ∂a/∂q = 1/(β·h²) and ∂v/∂q = γ/(β·h).
    pub c0: f64,
    pub c1: f64,
    /// Step, s.
    pub h: f64,
    /// 1/(2β) − 1 and 1 − γ, the weights of aₙ in `kinematics` (computed once).
    a_weight: f64,
    v_weight: f64,
}

impl Newmark {
    pub(crate) fn new(opts: &FeOptions, h: f64) -> Self {
        let (alpha, beta, gamma) = opts.integrator.parameters();
        Self {
            alpha,
            gamma,
            s: 1.0 + alpha,
            c0: 1.0 / (beta * h * h),
            c1: gamma / (beta * h),
            h,
            a_weight: 0.5 / beta - 1.0,
            v_weight: 1.0 - gamma,
        }
    }

    /// Acceleration and velocity at the end of the step from the displacement increment
    /// `dq` = q − qₙ and the start's velocity and acceleration (Newmark's relations).
    #[inline]
    pub(crate) fn kinematics<const D: usize>(
        &self,
        dq: SVector<f64, D>,
        vn: &SVector<f64, D>,
        an: &SVector<f64, D>,
    ) -> (SVector<f64, D>, SVector<f64, D>) {
        let a = (dq - vn * self.h) * self.c0 - an * self.a_weight;
        let v = vn + (an * self.v_weight + a * self.gamma) * self.h;
        (a, v)
    }
}

/// Every vector the loop needs, allocated once.
struct Workspace {
    asm: Assembly,
    un: Vec<Vector2<f64>>,
    un_n: Vec<Vector2<f64>>,
    pn_n: Vec<Vector2<f64>>,
    rn: Vec<Vector2<f64>>,
    dun: Vec<Vector2<f64>>,
    /// Line search: the last accepted iterate and its Newton direction.
    un_prev: Vec<Vector2<f64>>,
    dun_prev: Vec<Vector2<f64>>,
    /// The sliding oscillator's cached 2×2 factors (`slider`).
    slider_factors: Option<crate::lu::Lu2>,
}

impl Workspace {
    fn new(model: &Model) -> Self {
        let z = vec![Vector2::zeros(); model.nodes];
        Self {
            asm: Assembly::new(model),
            un: z.clone(),
            un_n: z.clone(),
            pn_n: z.clone(),
            rn: z.clone(),
            dun: z.clone(),
            un_prev: z.clone(),
            dun_prev: z,
            slider_factors: None,
        }
    }

    /// Keep the nodes' converged displacements and forces as the next step's start
    /// (nothing to copy without nodes: no call for an empty copy every step). With
    /// condensed supports (`loop_nodes` = 0) the step reads neither `un` nor the node
    /// forces, and `commit_step` writes every node of `un`: the two vectors are swapped,
    /// and the node forces (never assembled) are not copied.
    fn keep_nodes(&mut self, loop_nodes: usize) {
        if self.un.is_empty() {
            return;
        }
        if loop_nodes == 0 {
            std::mem::swap(&mut self.un, &mut self.un_n);
        } else {
            self.un_n.copy_from_slice(&self.un);
            self.pn_n.copy_from_slice(&self.asm.pn);
        }
    }
}

/// Static equilibrium under gravity from the unloaded, just-touching state (Newton,
/// converged to round-off); commits the elements. Returns (q, iterations).
fn static_preload(model: &mut Model, w: &mut Workspace) -> Result<(Vector3<f64>, u64), String> {
    let f = Vector3::new(0.0, -model.weight(), 0.0);
    let sys = System {
        c0: 0.0,
        s: 1.0,
        damp_xx: 0.0,
    };
    let mut q = Vector3::zeros();
    let mut dq = Vector3::zeros();
    for it in 0..100 {
        model.assemble(&q, &mut w.un, 0.0, &mut w.asm);
        let rb = f - w.asm.pb;
        let mut r2 = rb.norm_squared();
        for k in 0..model.loop_nodes() {
            w.rn[k] = -w.asm.pn[k];
            r2 += w.rn[k].norm_squared();
        }
        if !solve(model, &sys, &mut w.asm, &rb, &w.rn, &mut dq, &mut w.dun) {
            return Err("singular stiffness in the static preload".into());
        }
        let mut d2 = dq.norm_squared();
        for k in 0..model.loop_nodes() {
            d2 += w.dun[k].norm_squared();
        }
        if it > 0
            && r2.sqrt() <= 1e-10 * f.norm().max(1.0)
            && d2.sqrt() <= 1e-12 * q.norm().max(1e-9)
        {
            model.commit_step(&w.asm, &mut w.un);
            return Ok((q, it as u64 + 1));
        }
        q += dq;
        for k in 0..model.loop_nodes() {
            w.un[k] += w.dun[k];
        }
    }
    Err("the static preload did not converge in 100 iterations".into())
}

/// The static equilibrium under gravity (body q and node displacements); commits the
/// elements' states.
pub fn preload(model: &mut Model) -> Result<(Vector3<f64>, Vec<Vector2<f64>>), String> {
    let mut w = Workspace::new(model);
    let (q, _) = static_preload(model, &mut w)?;
    Ok((q, w.un))
}

/// Run the model from its static equilibrium for `steps` steps of `dt`, calling
/// `observe` at t = 0 and after every converged step. Non-convergence and divergence
/// end the run with a [`RunStatus`].
pub fn integrate(
    model: &mut Model,
    drive: &Drive,
    opts: &FeOptions,
    dt: f64,
    steps: usize,
    mut observe: impl FnMut(&Model, &Snapshot),
) -> (RunStatus, Counters) {
    let mut w = Workspace::new(model);
    let mut counters = Counters::default();
    let q_static = match static_preload(model, &mut w) {
        Ok((q, it)) => {
            counters.static_iterations = it;
            q
        }
        Err(reason) => return (RunStatus::NotConverged { time: 0.0, reason }, counters),
    };
    let m = model.mass_diag();
    let c = model.body.damping;
    let weight = model.weight();

    // State at n.
    let g0 = drive.ground(0.0);
    let mut n = StepState {
        t: 0.0,
        q: q_static,
        v: Vector3::zeros(),
        a: Vector3::zeros(),
        f: Vector3::new(drive.force(0.0), -weight + drive.vertical_force(0.0), 0.0),
        fz: drive.vertical_force(0.0),
        pb: Vector3::zeros(),
        damp: c * (0.0 - g0.1),
        g: g0,
    };
    model.assemble(&n.q, &mut w.un, g0.0, &mut w.asm);
    n.pb = w.asm.pb;
    w.keep_nodes(model.loop_nodes());
    n.a = (n.f - n.pb - Vector3::new(n.damp, 0.0, 0.0))
        .component_div(&m.map(|x| if x > 0.0 { x } else { f64::INFINITY }));
    if !model.body.rotation {
        n.a.z = 0.0;
    }
    model.restore();
    observe(
        model,
        &Snapshot {
            t: 0.0,
            q: n.q,
            v: n.v,
            a: n.a,
            un: &w.un_n,
            ground: g0,
            q_static,
            force: n.f.x,
            vertical_force: n.fz,
            rotation: w.asm.rotation(),
        },
    );

    // The state at n and the step's result, each written in place (no copy of the
    // accepted state): `cur` is n's, the other is written by the step.
    let mut states = [n, n];
    let mut cur = 0;
    let max_depth = opts.newton.max_step_cuts;
    let units = 1u32 << max_depth;
    // The coefficients of the step size in use (recomputed when a step is cut).
    let mut nm = Newmark::new(opts, dt);
    // A sliding oscillator steps in scalars (`slider`): the same operations, fewer of them.
    let slider = model.is_slider();
    for step in 1..=steps {
        // Step cutting: a step whose Newton iteration fails is retried as two halves,
        // down to Δt/2^max_step_cuts, then the step size grows back when aligned.
        let (mut pos, mut level) = (0u32, 0u32);
        while pos < units {
            let size = units >> level;
            let end = pos + size;
            let t = if end == units {
                step as f64 * dt
            } else {
                let t_start = (step - 1) as f64 * dt;
                t_start + dt * f64::from(end) / f64::from(units)
            };
            // dt/1 is dt: no division for an uncut step.
            let h = if level == 0 {
                dt
            } else {
                dt / f64::from(1u32 << level)
            };
            if nm.h != h {
                nm = Newmark::new(opts, h);
            }
            let [s0, s1] = &mut states;
            let (n, next) = if cur == 0 { (&*s0, s1) } else { (&*s1, s0) };
            let result = if slider {
                slider::step(model, drive, opts, &nm, &mut w, (n, next), t, &mut counters)
            } else {
                newton_step(model, drive, opts, &nm, &mut w, (n, next), t, &mut counters)
            };
            match result {
                Ok(()) => {
                    model.commit_step(&w.asm, &mut w.un);
                    cur = 1 - cur;
                    w.keep_nodes(model.loop_nodes());
                    pos = end;
                    if level > 0 && pos % (2 * size) == 0 {
                        level -= 1;
                    }
                }
                Err(failure) => {
                    model.restore();
                    if failure.diverged || level == max_depth {
                        let cut = if level > 0 {
                            format!(" (after cutting the step to Δt/{})", 1u32 << level)
                        } else {
                            String::new()
                        };
                        let reason = format!("{}{cut}", failure.reason);
                        let status = if failure.diverged {
                            RunStatus::Diverged { time: t, reason }
                        } else {
                            RunStatus::NotConverged { time: t, reason }
                        };
                        return (status, counters);
                    }
                    level += 1;
                    counters.step_cuts += 1;
                }
            }
        }
        counters.steps += 1;
        let n = &states[cur];
        observe(
            model,
            &Snapshot {
                t: n.t,
                q: n.q,
                v: n.v,
                a: n.a,
                un: &w.un_n,
                ground: n.g,
                q_static,
                force: n.f.x,
                vertical_force: n.fz,
                rotation: w.asm.rotation(),
            },
        );
    }
    (RunStatus::Completed, counters)
}

/// The body's state at the end of a (sub)step, what the next step starts from.
#[derive(Debug, Clone, Copy)]
struct StepState {
    t: f64,
    q: Vector3<f64>,
    v: Vector3<f64>,
    a: Vector3<f64>,
    /// External force.
    f: Vector3<f64>,
    /// Vertical load beyond the preload (`Drive::vertical_force`), N.
    fz: f64,
    /// Base reaction on the body.
    pb: Vector3<f64>,
    /// Damping force.
    damp: f64,
    /// Ground (displacement, velocity, acceleration).
    g: (f64, f64, f64),
}

/// What ended a Newton iteration.
enum FailureReason {
    /// Displacement or residual not finite.
    NotFinite,
    /// Singular tangent at this iteration.
    Singular(usize),
    /// Iterations used; the last iteration's norms; the tolerances.
    NotConverged {
        iterations: usize,
        last: LastIteration,
        force_tol: f64,
        displacement_tol: f64,
    },
}

impl std::fmt::Display for FailureReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Self::NotFinite => write!(f, "displacement or residual is not finite"),
            Self::Singular(it) => write!(f, "singular tangent at iteration {it}"),
            Self::NotConverged {
                iterations,
                last,
                force_tol,
                displacement_tol,
            } => write!(
                f,
                "{} iterations: relative residual {:.3e} (limit {:.1e}), last correction {:.3e} m against a step increment of {:.3e} m (limit {:.1e})",
                iterations,
                last.residual / last.force_scale.max(f64::MIN_POSITIVE),
                force_tol,
                last.correction_squared.sqrt(),
                last.increment_squared.sqrt(),
                displacement_tol
            ),
        }
    }
}

/// The norms of a Newton iteration, kept for the message of a step that fails to
/// converge (the square roots and the ratio are taken only then).
#[derive(Debug, Clone, Copy, Default)]
struct LastIteration {
    /// Residual norm and the force scale it is measured against, N.
    residual: f64,
    force_scale: f64,
    /// Squared norms of the correction and of the step's increment with it, m².
    correction_squared: f64,
    increment_squared: f64,
}

/// Why a step failed.
struct StepFailure {
    /// Why, in numbers: formatted only if the run ends on it (a step that is cut and
    /// retried allocates nothing).
    reason: FailureReason,
    /// Not finite: cutting the step is not tried.
    diverged: bool,
}

/// One step of length `nm.h` from `n` to time `t`: Newton–Raphson with a backtracking
/// line search on the consistent tangent. On success `next`, the elements' trial states
/// and `w.un`, `w.asm` hold the new state (not yet committed).
#[allow(clippy::too_many_arguments)]
fn newton_step(
    model: &mut Model,
    drive: &Drive,
    opts: &FeOptions,
    nm: &Newmark,
    w: &mut Workspace,
    (n, next): (&StepState, &mut StepState),
    t: f64,
    counters: &mut Counters,
) -> Result<(), StepFailure> {
    let m = model.mass_diag();
    let c = model.body.damping;
    let Newmark {
        alpha,
        s,
        c0,
        c1,
        h,
        ..
    } = *nm;
    let sys = System {
        c0,
        s,
        damp_xx: s * c * c1,
    };
    let newton = opts.newton;
    let g = drive.ground(t);
    let fz = drive.vertical_force(t);
    let f = Vector3::new(drive.force(t), -model.weight() + fz, 0.0);
    let f_norm = f.norm();
    let mut dq = Vector3::zeros();
    // Predictor: constant acceleration over the step.
    let mut q = n.q + n.v * h + n.a * (0.5 * h * h);
    let nodes = model.loop_nodes();
    // Condensed supports: `un` is not read before `commit_step` writes it.
    if nodes > 0 {
        w.un.copy_from_slice(&w.un_n);
    }
    // Predictor: nodes on the ground move with it (element 1 is the stiff one); a
    // node left behind would put element 1 far into slip and let Newton cycle.
    // (Condensed supports have no node unknowns: `relax_nodes` places them.)
    if nodes > 0 {
        for sup in &model.supports {
            if let Some(k) = sup.node {
                w.un[k].x += g.0 - n.g.0;
            }
        }
    }
    let (mut a, mut v);
    let mut last = LastIteration::default();
    let mut it = 0;
    // Backtracking line search (Dennis & Schnabel 1983, §6.3): the friction law is
    // piecewise linear, and a full Newton step can jump between stick and slip of
    // several elements and cycle; halve the step while the residual does not fall.
    let (mut q_prev, mut dq_prev) = (q, Vector3::zeros());
    let (mut r_prev, mut lambda) = (f64::INFINITY, 1.0_f64);
    let done = |it: usize, counters: &mut Counters| {
        counters.iterations += it as u64;
        counters.max_step_iterations = counters.max_step_iterations.max(it as u64);
    };
    while it < newton.max_iterations {
        it += 1;
        (a, v) = nm.kinematics(q - n.q, &n.v, &n.a);
        if !model.body.rotation {
            a.z = 0.0;
            v.z = 0.0;
        }
        model.assemble(&q, &mut w.un, g.0, &mut w.asm);
        let damp = c * (v.x - g.1);
        // HHT residual (α = 0: Newmark), paper Eq 2 generalised.
        let rb = (f - w.asm.pb - Vector3::new(damp, 0.0, 0.0)) * s
            - (n.f - n.pb - Vector3::new(n.damp, 0.0, 0.0)) * alpha
            - m.component_mul(&a);
        let mut r2 = rb.norm_squared();
        for k in 0..nodes {
            w.rn[k] = -w.asm.pn[k] * s + w.pn_n[k] * alpha;
            r2 += w.rn[k].norm_squared();
        }
        let fref = f_norm + w.asm.pb.norm() + m.component_mul(&a).norm();
        if r2.sqrt() > (1.0 - 1e-4 * lambda) * r_prev && lambda > 1.0 / 64.0 {
            lambda *= 0.5;
            q = q_prev + dq_prev * lambda;
            for k in 0..nodes {
                w.un[k] = w.un_prev[k] + w.dun_prev[k] * lambda;
            }
            continue;
        }
        if !(r2.is_finite() && q.iter().all(|x| x.is_finite())) {
            done(it, counters);
            return Err(StepFailure {
                reason: FailureReason::NotFinite,
                diverged: true,
            });
        }
        // A residual at the round-off of the force scale is converged whatever the
        // correction: accepted before solving (the linear sticking step's second
        // iteration costs an assembly, no solve). The same test as below, so the same
        // iterate is accepted.
        if r2.sqrt() <= 1e-11 * fref {
            done(it, counters);
            *next = StepState {
                t,
                q,
                v,
                a,
                f,
                fz,
                pb: w.asm.pb,
                damp,
                g,
            };
            return Ok(());
        }
        if !solve(model, &sys, &mut w.asm, &rb, &w.rn, &mut dq, &mut w.dun) {
            done(it, counters);
            return Err(StepFailure {
                reason: FailureReason::Singular(it),
                diverged: false,
            });
        }
        let (mut d2, mut inc2, mut u2) = (
            dq.norm_squared(),
            (q + dq - n.q).norm_squared(),
            q.norm_squared(),
        );
        for k in 0..nodes {
            d2 += w.dun[k].norm_squared();
            inc2 += (w.un[k] + w.dun[k] - w.un_n[k]).norm_squared();
            u2 += w.un[k].norm_squared();
        }
        let rn = r2.sqrt();
        last = LastIteration {
            residual: rn,
            force_scale: fref,
            correction_squared: d2,
            increment_squared: inc2,
        };
        // Converged at the current iterate: its residual is small and the correction
        // Newton would still make is small against the step's increment.
        // A correction below 1e-12 of the displacement is round-off of the absolute
        // positions: nothing to correct. (A residual below 1e-11 of the force scale was
        // accepted before the solve.) The correction's norms matter only to a residual
        // within the tolerance: their square roots are taken only then.
        let force_ok = rn <= newton.force_tol * fref;
        let disp_ok =
            || d2.sqrt() <= (newton.displacement_tol * inc2.sqrt()).max(1e-12 * u2.sqrt());
        if force_ok && disp_ok() {
            done(it, counters);
            *next = StepState {
                t,
                q,
                v,
                a,
                f,
                fz,
                pb: w.asm.pb,
                damp,
                g,
            };
            return Ok(());
        }
        // Round-off floor: the residual is within the force tolerance, and a full Newton
        // iteration (with its line search) no longer halves it — the iterate is at the
        // round-off level of the load, and the remaining correction is noise.
        if force_ok && r_prev.is_finite() && rn > 0.5 * r_prev {
            counters.roundoff_accepted += 1;
            done(it, counters);
            *next = StepState {
                t,
                q,
                v,
                a,
                f,
                fz,
                pb: w.asm.pb,
                damp,
                g,
            };
            return Ok(());
        }
        (q_prev, dq_prev, r_prev, lambda) = (q, dq, rn, 1.0);
        q += dq;
        for k in 0..nodes {
            w.un_prev[k] = w.un[k];
            w.dun_prev[k] = w.dun[k];
            w.un[k] += w.dun[k];
        }
    }
    done(it, counters);
    Err(StepFailure {
        reason: FailureReason::NotConverged {
            iterations: it,
            last,
            force_tol: newton.force_tol,
            displacement_tol: newton.displacement_tol,
        },
        diverged: false,
    })
}

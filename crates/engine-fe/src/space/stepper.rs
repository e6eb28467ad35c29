//! The 3D time loop: static preload under gravity, then Newmark or HHT-α with Newton on
//! SO(3) — the 2D loop (`stepper.rs`) with the rotation advanced exactly.
//!
//! Formulation (Simo & Vu-Quoc 1988, material form): the angular velocity Ω and
//! acceleration A are body-frame vectors; a step's unknowns are the centre of mass X and
//! the body-frame incremental rotation vector Θ, R₊ = Rₙ·exp(Θ̂), and Newmark acts on Θ
//! as on a displacement increment:
//!   A₊ = (Θ − Δt·Ωₙ)/(βΔt²) − (1/(2β) − 1)·Aₙ,   Ω₊ = Ωₙ + Δt·((1 − γ)Aₙ + γA₊),
//! with Euler's equations J·A + Ω × J·Ω = moment (body frame). The rotation stays exactly
//! orthogonal (a product of exponentials); the Newton tangent is exact (the right Jacobian
//! J_r(Θ) in `model.rs`, the gyroscopic tangent c0·J + c1·(Ω̂J − (JΩ)^)). Why this and
//! not a quaternion or the total rotation vector: the increment Θ is a vector-space
//! unknown, so the 2D Newmark and HHT algebra, its line search and convergence tests
//! apply unchanged, and for a motion in one plane Θ = (0, −Δθ, 0), J_r acts as the
//! identity on it and every formula reduces to the 2D one. HHT-α weights the moments of
//! steps n and n+1 each in its own body frame: exact in plane; for a 3D rotation the two
//! frames differ by the step's rotation Θ = O(Δt), a simplification of the Lie-group
//! HHT/generalised-α (Brüls & Cardona 2010) not analysed further here (the measured
//! self-convergence in `tests/all/fe_space.rs` runs HHT with α = −0.1).
//! Nothing is allocated inside the loop.

use nalgebra::{Matrix3, Vector3, Vector6};

use super::model::{Pose, SpaceAssembly, SpaceModel, SpaceSystem, solve};
use super::rotation::{exp, log, skew};
use crate::options::FeOptions;
use crate::stepper::Newmark;
use rockslide_core::case::{Excitation, Signal};
use rockslide_engine_api::RunStatus;

/// How an excitation drives the 3D model: the scene's signal along the horizontal
/// direction e₁ at `azimuth` (radians from x towards y) and an optional second signal of
/// the same kind along e₂ = (−sin, cos) of the azimuth.
#[derive(Debug, Clone, Copy)]
pub struct SpaceDrive<'a> {
    excitation: &'a Excitation,
    second: Option<&'a Signal>,
    /// The vertical ground acceleration a_v(t), if any (positive upward).
    vertical: Option<&'a Signal>,
    mass: f64,
    first_direction: Vector3<f64>,
    second_direction: Vector3<f64>,
}

impl<'a> SpaceDrive<'a> {
    /// The drive of `excitation` (and `second`) at `azimuth` on a body of mass `mass`.
    pub fn new(
        excitation: &'a Excitation,
        second: Option<&'a Signal>,
        azimuth: f64,
        mass: f64,
    ) -> Self {
        let (s, c) = azimuth.sin_cos();
        Self {
            excitation,
            second,
            vertical: None,
            mass,
            first_direction: Vector3::new(c, s, 0.0),
            second_direction: Vector3::new(-s, c, 0.0),
        }
    }
    /// The same drive with a vertical ground acceleration a_v(t) (positive upward).
    pub fn with_vertical(self, vertical: Option<&'a Signal>) -> Self {
        Self { vertical, ..self }
    }
    /// Vertical force on the body at `t` beyond the preload, N: −M·a_v(t), in relative
    /// coordinates as in 2D (`crate::vertical`).
    pub fn vertical_force(&self, t: f64) -> f64 {
        crate::vertical::load(self.vertical, self.mass, t)
    }
    /// The horizontal vector Σ value(signal)·direction, `value` one of the signal's
    /// derivatives.
    #[inline]
    fn vector(&self, first: &Signal, value: impl Fn(&Signal) -> f64) -> Vector3<f64> {
        let v = self.first_direction * value(first);
        match self.second {
            Some(s) => v + self.second_direction * value(s),
            None => v,
        }
    }
    /// Force on the body at `t` (ground acceleration in relative coordinates), N.
    pub fn force(&self, t: f64) -> Vector3<f64> {
        match self.excitation {
            Excitation::MassAcceleration(s) => self.vector(s, |s| self.mass * s.value(t)),
            Excitation::GroundAcceleration(s) => self.vector(s, |s| -self.mass * s.value(t)),
            _ => Vector3::zeros(),
        }
    }
    /// Prescribed ground (displacement, velocity, acceleration) at `t`.
    pub fn ground(&self, t: f64) -> [Vector3<f64>; 3] {
        match self.excitation {
            Excitation::GroundDisplacement(s) => [
                self.vector(s, |s| s.value(t)),
                self.vector(s, |s| s.derivative(t)),
                self.vector(s, |s| s.second_derivative(t)),
            ],
            _ => [Vector3::zeros(); 3],
        }
    }
    /// The horizontal force on the mass in relative coordinates.
    pub fn equivalent_force(&self, t: f64) -> Vector3<f64> {
        match self.excitation {
            Excitation::GroundDisplacement(s) => {
                self.vector(s, |s| -self.mass * s.second_derivative(t))
            }
            _ => self.force(t),
        }
    }
}

/// The model's state at one output instant.
#[derive(Debug, Clone, Copy)]
pub struct SpaceSnapshot<'a> {
    /// Time, s.
    pub t: f64,
    /// Centre-of-mass displacement from the unloaded position, m.
    pub x: Vector3<f64>,
    /// Rotation of the body.
    pub r: Matrix3<f64>,
    /// Velocity: centre of mass (ground frame) and Ω (body frame).
    pub v: Vector6<f64>,
    /// Acceleration: centre of mass and A (body frame).
    pub a: Vector6<f64>,
    /// Node displacements.
    pub un: &'a [Vector3<f64>],
    /// Ground displacement, velocity, acceleration.
    pub ground: [Vector3<f64>; 3],
    /// Centre of mass at static equilibrium.
    pub x_static: Vector3<f64>,
}

/// Deterministic counters of a run: the 2D ones.
pub use crate::stepper::Counters as SpaceCounters;

/// Every vector the loop needs, allocated once.
struct Workspace {
    asm: SpaceAssembly,
    un: Vec<Vector3<f64>>,
    un_n: Vec<Vector3<f64>>,
    pn_n: Vec<Vector3<f64>>,
    rn: Vec<Vector3<f64>>,
    dun: Vec<Vector3<f64>>,
    un_prev: Vec<Vector3<f64>>,
    dun_prev: Vec<Vector3<f64>>,
}

impl Workspace {
    fn new(model: &SpaceModel) -> Self {
        let z = vec![Vector3::zeros(); model.nodes];
        Self {
            asm: SpaceAssembly::new(model),
            un: z.clone(),
            un_n: z.clone(),
            pn_n: z.clone(),
            rn: z.clone(),
            dun: z.clone(),
            un_prev: z.clone(),
            dun_prev: z,
        }
    }
}

/// The pose of unknowns q = (X, Θ) from the rotation `rn` of the last step.
#[inline]
fn pose(q: &Vector6<f64>, rn: &Matrix3<f64>) -> Pose {
    let theta = q.fixed_rows::<3>(3).into_owned();
    Pose {
        x: q.fixed_rows::<3>(0).into_owned(),
        r: if theta == Vector3::zeros() {
            *rn
        } else {
            rn * exp(&theta)
        },
        theta,
    }
}

/// Static equilibrium under gravity from the unloaded, just-touching state; commits the
/// elements. Returns (X, R, iterations).
fn static_preload(
    model: &mut SpaceModel,
    w: &mut Workspace,
) -> Result<(Vector3<f64>, Matrix3<f64>, u64), String> {
    let f = Vector6::new(0.0, 0.0, -model.weight(), 0.0, 0.0, 0.0);
    let sys = SpaceSystem {
        c0: 0.0,
        s: 1.0,
        damp: 0.0,
        inertial: Matrix3::zeros(),
    };
    let ground = Vector3::zeros();
    let r0 = Matrix3::identity();
    let mut q = Vector6::zeros();
    let mut dq = Vector6::zeros();
    for it in 0..100 {
        let p = pose(&q, &r0);
        model.assemble(&p, &mut w.un, &ground, &mut w.asm);
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
            model.commit_step(&mut w.un, &ground);
            return Ok((p.x, p.r, it as u64 + 1));
        }
        q += dq;
        for k in 0..model.loop_nodes() {
            w.un[k] += w.dun[k];
        }
    }
    Err("the static preload did not converge in 100 iterations".into())
}

/// The state at the end of a (sub)step.
#[derive(Debug, Clone, Copy)]
struct StepState {
    t: f64,
    x: Vector3<f64>,
    r: Matrix3<f64>,
    /// Rotation vector of `r` (a displacement scale for the convergence test only).
    psi: Vector3<f64>,
    v: Vector6<f64>,
    a: Vector6<f64>,
    /// External force and moment.
    f: Vector6<f64>,
    /// Internal force and moment.
    pb: Vector6<f64>,
    /// Damping force (x, y).
    damp: Vector6<f64>,
    g: [Vector3<f64>; 3],
}

struct StepFailure {
    reason: String,
    diverged: bool,
}

/// Run the model from its static equilibrium for `steps` steps of `dt`, calling
/// `observe` at t = 0 and after every converged step.
pub fn integrate(
    model: &mut SpaceModel,
    drive: &SpaceDrive,
    opts: &FeOptions,
    dt: f64,
    steps: usize,
    mut observe: impl FnMut(&SpaceModel, &SpaceSnapshot),
) -> (RunStatus, SpaceCounters) {
    let mut w = Workspace::new(model);
    let mut counters = SpaceCounters::default();
    let (x_static, r_static) = match static_preload(model, &mut w) {
        Ok((x, r, it)) => {
            counters.static_iterations = it;
            (x, r)
        }
        Err(reason) => return (RunStatus::NotConverged { time: 0.0, reason }, counters),
    };
    let weight = model.weight();
    let c = model.body.damping;
    let g0 = drive.ground(0.0);
    let f0 = drive.force(0.0);
    let mut n = StepState {
        t: 0.0,
        x: x_static,
        r: r_static,
        psi: log(&r_static),
        v: Vector6::zeros(),
        a: Vector6::zeros(),
        f: Vector6::new(f0.x, f0.y, -weight, 0.0, 0.0, 0.0),
        pb: Vector6::zeros(),
        damp: damping(c, &Vector6::zeros(), &g0[1]),
        g: g0,
    };
    let p = Pose {
        x: n.x,
        r: n.r,
        theta: Vector3::zeros(),
    };
    model.assemble(&p, &mut w.un, &g0[0], &mut w.asm);
    n.pb = w.asm.pb;
    w.un_n.copy_from_slice(&w.un);
    w.pn_n.copy_from_slice(&w.asm.pn);
    let out = n.f - n.pb - n.damp;
    let m = model.body.mass;
    n.a = Vector6::new(out[0] / m, out[1] / m, out[2] / m, 0.0, 0.0, 0.0);
    if model.body.rotation {
        if let Some(a_rot) = model.body.inertia.lu().solve(&out.fixed_rows::<3>(3)) {
            n.a.fixed_rows_mut::<3>(3).copy_from(&a_rot);
        }
    }
    model.restore();
    observe(
        model,
        &SpaceSnapshot {
            t: 0.0,
            x: n.x,
            r: n.r,
            v: n.v,
            a: n.a,
            un: &w.un_n,
            ground: g0,
            x_static,
        },
    );
    let max_depth = opts.newton.max_step_cuts;
    let units = 1u32 << max_depth;
    for step in 1..=steps {
        let t_start = (step - 1) as f64 * dt;
        let (mut pos, mut level) = (0u32, 0u32);
        while pos < units {
            let size = units >> level;
            let end = pos + size;
            let t = if end == units {
                step as f64 * dt
            } else {
                t_start + dt * f64::from(end) / f64::from(units)
            };
            let h = dt / f64::from(1u32 << level);
            match newton_step(model, drive, opts, &mut w, &n, t, h, &mut counters) {
                Ok(next) => {
                    model.commit_step(&mut w.un, &next.g[0]);
                    n = next;
                    w.un_n.copy_from_slice(&w.un);
                    w.pn_n.copy_from_slice(&w.asm.pn);
                    pos = end;
                    if level > 0 && pos % (2 * size) == 0 {
                        level -= 1;
                    }
                }
                Err(failure) => {
                    model.restore();
                    if failure.diverged || level == max_depth {
                        let reason = failure.reason;
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
        observe(
            model,
            &SpaceSnapshot {
                t: n.t,
                x: n.x,
                r: n.r,
                v: n.v,
                a: n.a,
                un: &w.un_n,
                ground: n.g,
                x_static,
            },
        );
    }
    (RunStatus::Completed, counters)
}

/// Horizontal viscous damping force C·(v − v_ground) on x and y.
#[inline]
fn damping(c: f64, v: &Vector6<f64>, vg: &Vector3<f64>) -> Vector6<f64> {
    Vector6::new(c * (v[0] - vg.x), c * (v[1] - vg.y), 0.0, 0.0, 0.0, 0.0)
}

/// Inertial force (M·a, J·A + Ω × J·Ω).
#[inline]
fn inertia_force(model: &SpaceModel, a: &Vector6<f64>, v: &Vector6<f64>) -> Vector6<f64> {
    let m = model.body.mass;
    let mut out = Vector6::new(m * a[0], m * a[1], m * a[2], 0.0, 0.0, 0.0);
    if model.body.rotation {
        let j = &model.body.inertia;
        let om = v.fixed_rows::<3>(3).into_owned();
        let rot = j * a.fixed_rows::<3>(3) + om.cross(&(j * om));
        out.fixed_rows_mut::<3>(3).copy_from(&rot);
    }
    out
}

/// One step of length `h` from `n` to `t`: Newton with a backtracking line search, as
/// in 2D. On success the elements' trial states and `w` hold the new state.
#[allow(clippy::too_many_arguments)]
fn newton_step(
    model: &mut SpaceModel,
    drive: &SpaceDrive,
    opts: &FeOptions,
    w: &mut Workspace,
    n: &StepState,
    t: f64,
    h: f64,
    counters: &mut SpaceCounters,
) -> Result<StepState, StepFailure> {
    let c = model.body.damping;
    let nm = Newmark::new(opts, h);
    let Newmark {
        alpha, s, c0, c1, ..
    } = nm;
    let newton = opts.newton;
    let g = drive.ground(t);
    let fd = drive.force(t);
    let fz = drive.vertical_force(t) - model.weight();
    let f = Vector6::new(fd.x, fd.y, fz, 0.0, 0.0, 0.0);
    let rotation = model.body.rotation;
    let nodes = model.loop_nodes();
    let j = model.body.inertia;
    let mut dq = Vector6::zeros();
    // Unknowns q = (X, Θ): predictor with constant acceleration over the step.
    let mut q = Vector6::zeros();
    q.fixed_rows_mut::<3>(0)
        .copy_from(&(n.x + n.v.fixed_rows::<3>(0) * h + n.a.fixed_rows::<3>(0) * (0.5 * h * h)));
    if rotation {
        q.fixed_rows_mut::<3>(3)
            .copy_from(&(n.v.fixed_rows::<3>(3) * h + n.a.fixed_rows::<3>(3) * (0.5 * h * h)));
    }
    let q_n = {
        let mut v = Vector6::zeros();
        v.fixed_rows_mut::<3>(0).copy_from(&n.x);
        v
    };
    w.un.copy_from_slice(&w.un_n);
    for k in 0..nodes {
        w.un[k] += g[0] - n.g[0];
    }
    let (mut a, mut v);
    let mut last = (0.0, 0.0, 0.0);
    let mut it = 0;
    let (mut q_prev, mut dq_prev) = (q, Vector6::zeros());
    let (mut r_prev, mut lambda) = (f64::INFINITY, 1.0_f64);
    let done = |it: usize, counters: &mut SpaceCounters| {
        counters.iterations += it as u64;
        counters.max_step_iterations = counters.max_step_iterations.max(it as u64);
    };
    let step_state = |p: &Pose, v, a, pb, damp| StepState {
        t,
        x: p.x,
        r: p.r,
        psi: log(&p.r),
        v,
        a,
        f,
        pb,
        damp,
        g,
    };
    while it < newton.max_iterations {
        it += 1;
        (a, v) = nm.kinematics(q - q_n, &n.v, &n.a);
        if !rotation {
            a.fixed_rows_mut::<3>(3).fill(0.0);
            v.fixed_rows_mut::<3>(3).fill(0.0);
        }
        let p = pose(&q, &n.r);
        model.assemble(&p, &mut w.un, &g[0], &mut w.asm);
        let damp = damping(c, &v, &g[1]);
        let inertial = inertia_force(model, &a, &v);
        let rb = (f - w.asm.pb - damp) * s - (n.f - n.pb - n.damp) * alpha - inertial;
        let mut r2 = rb.norm_squared();
        for k in 0..nodes {
            w.rn[k] = -w.asm.pn[k] * s + w.pn_n[k] * alpha;
            r2 += w.rn[k].norm_squared();
        }
        let fref = f.norm() + w.asm.pb.norm() + inertial.norm();
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
                reason: "displacement or residual is not finite".into(),
                diverged: true,
            });
        }
        if r2.sqrt() <= 1e-11 * fref {
            done(it, counters);
            return Ok(step_state(&p, v, a, w.asm.pb, damp));
        }
        let om = v.fixed_rows::<3>(3).into_owned();
        let sys = SpaceSystem {
            c0,
            s,
            damp: s * c * c1,
            inertial: if rotation {
                j * c0 + (skew(&om) * j - skew(&(j * om))) * c1
            } else {
                Matrix3::zeros()
            },
        };
        if !solve(model, &sys, &mut w.asm, &rb, &w.rn, &mut dq, &mut w.dun) {
            done(it, counters);
            return Err(StepFailure {
                reason: format!("singular tangent at iteration {it}"),
                diverged: false,
            });
        }
        let (mut d2, mut inc2, mut u2) = (
            dq.norm_squared(),
            (q + dq - q_n).norm_squared(),
            p.x.norm_squared() + (n.psi + p.theta).norm_squared(),
        );
        for k in 0..nodes {
            d2 += w.dun[k].norm_squared();
            inc2 += (w.un[k] + w.dun[k] - w.un_n[k]).norm_squared();
            u2 += w.un[k].norm_squared();
        }
        let (rn, dn, incn) = (r2.sqrt(), d2.sqrt(), inc2.sqrt());
        last = (rn / fref.max(f64::MIN_POSITIVE), dn, incn);
        let force_ok = rn <= newton.force_tol * fref;
        let disp_ok = dn <= (newton.displacement_tol * incn).max(1e-12 * u2.sqrt());
        if (force_ok && disp_ok) || rn <= 1e-11 * fref {
            done(it, counters);
            return Ok(step_state(&p, v, a, w.asm.pb, damp));
        }
        if force_ok && r_prev.is_finite() && rn > 0.5 * r_prev {
            counters.roundoff_accepted += 1;
            done(it, counters);
            return Ok(step_state(&p, v, a, w.asm.pb, damp));
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
        reason: format!(
            "{} iterations: relative residual {:.3e} (limit {:.1e}), last correction {:.3e} against a step increment of {:.3e} (limit {:.1e})",
            it, last.0, newton.force_tol, last.1, last.2, newton.displacement_tol
        ),
        diverged: false,
    })
}

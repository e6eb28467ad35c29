//! One time step, for either model: Newton–Raphson on the consistent tangent with a
//! backtracking line search, the convergence tests (residual against the force scale,
//! correction against the step's increment), acceptance at the round-off floor.

use nalgebra::SVector;

use super::failure::{Counters, FailureReason, LastIteration, StepFailure};
use super::mechanics::{Mechanics, State, StepState};
use super::newmark::Newmark;
use super::time_loop::Workspace;
use crate::options::FeOptions;

/// One step of length `nm.h` from `n` to time `t`: Newton–Raphson with a backtracking
/// line search on the consistent tangent. On success `next`, the elements' trial states
/// and `w.un`, `w.asm` hold the new state (not yet committed).
#[allow(clippy::too_many_arguments)]
pub(crate) fn step<const Q: usize, const N: usize, M: Mechanics<Q, N>>(
    model: &mut M,
    drive: &M::Drive<'_>,
    opts: &FeOptions,
    nm: &Newmark,
    w: &mut Workspace<Q, N, M>,
    (n, next): (&State<Q, N, M>, &mut State<Q, N, M>),
    t: f64,
    counters: &mut Counters,
) -> Result<(), StepFailure> {
    let Newmark { alpha, s, h, .. } = *nm;
    let newton = opts.newton;
    let (f, fz, g) = model.load(drive, t);
    let f_norm = f.norm();
    let mut dq = SVector::<f64, Q>::zeros();
    // Predictor: constant acceleration over the step.
    let mut q = model.predict(n, h);
    let q_n = M::reference(&n.pose);
    let nodes = model.loop_nodes();
    // Condensed supports: `un` is not read before `commit_step` writes it.
    if nodes > 0 {
        w.un.copy_from_slice(&w.un_n);
        // Predictor: nodes on the ground move with it (element 1 is the stiff one); a
        // node left behind would put element 1 far into slip and let Newton cycle.
        model.predict_nodes(&mut w.un, &g, &n.g);
    }
    let rotates = model.rotates();
    let mut last = LastIteration::default();
    let mut it = 0;
    // Backtracking line search (Dennis & Schnabel 1983, §6.3): the friction law is
    // piecewise linear, and a full Newton step can jump between stick and slip of
    // several elements and cycle; halve the step while the residual does not fall.
    let (mut q_prev, mut dq_prev) = (q, SVector::<f64, Q>::zeros());
    let (mut r_prev, mut lambda) = (f64::INFINITY, 1.0_f64);
    while it < newton.max_iterations {
        it += 1;
        let (mut a, mut v) = nm.kinematics(q - q_n, &n.v, &n.a);
        if !rotates {
            M::lock_rotation(&mut a);
            M::lock_rotation(&mut v);
        }
        let at = model.assemble(&q, &n.pose, &mut w.un, &g, &mut w.asm);
        let pb = *M::body_force(&w.asm);
        let damp = model.damping(&v, &g);
        let inertial = model.inertia(&a, &v);
        // HHT residual (α = 0: Newmark), paper Eq 2 generalised.
        let rb = (f - pb - damp) * s - (n.f - n.pb - n.damp) * alpha - inertial;
        let mut r2 = rb.norm_squared();
        for ((r, p), p_n) in
            w.rn.iter_mut()
                .zip(M::node_forces(&w.asm))
                .zip(&w.pn_n)
                .take(nodes)
        {
            *r = -p * s + p_n * alpha;
            r2 += r.norm_squared();
        }
        let fref = f_norm + pb.norm() + inertial.norm();
        if r2.sqrt() > (1.0 - 1e-4 * lambda) * r_prev && lambda > 1.0 / 64.0 {
            lambda *= 0.5;
            q = q_prev + dq_prev * lambda;
            for k in 0..nodes {
                w.un[k] = w.un_prev[k] + w.dun_prev[k] * lambda;
            }
            continue;
        }
        let accept = || StepState {
            t,
            pose: M::pose(&q, &at),
            v,
            a,
            f,
            fz,
            pb,
            damp,
            g,
        };
        if !(r2.is_finite() && q.iter().all(|x| x.is_finite())) {
            counters.add_step_iterations(it);
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
            counters.add_step_iterations(it);
            *next = accept();
            return Ok(());
        }
        if !model.solve_step(nm, &v, &mut w.asm, &rb, &w.rn, &mut dq, &mut w.dun) {
            counters.add_step_iterations(it);
            return Err(StepFailure {
                reason: FailureReason::Singular(it),
                diverged: false,
            });
        }
        let (mut d2, mut inc2, mut u2) = (
            dq.norm_squared(),
            (q + dq - q_n).norm_squared(),
            M::displacement_squared(&q, &at, &n.pose),
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
            counters.add_step_iterations(it);
            *next = accept();
            return Ok(());
        }
        // Round-off floor: the residual is within the force tolerance, and a full Newton
        // iteration (with its line search) no longer halves it — the iterate is at the
        // round-off level of the load, and the remaining correction is noise.
        if force_ok && r_prev.is_finite() && rn > 0.5 * r_prev {
            counters.roundoff_accepted += 1;
            counters.add_step_iterations(it);
            *next = accept();
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
    counters.add_step_iterations(it);
    Err(StepFailure {
        reason: FailureReason::NotConverged {
            iterations: it,
            last,
            force_tol: newton.force_tol,
            displacement_tol: newton.displacement_tol,
            unit: M::CORRECTION_UNIT,
        },
        diverged: false,
    })
}

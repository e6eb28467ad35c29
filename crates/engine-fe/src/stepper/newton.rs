//! One time step, for either model: Newton–Raphson on the consistent tangent with a
//! backtracking line search, the convergence tests (residual against the force scale,
//! correction against the step's increment), acceptance at the round-off floor.

use nalgebra::SVector;

use super::failure::{Counters, FailureReason, LastIteration, StepFailure};
use super::mechanics::{Mechanics, State, StepState, Workspace};
use super::newmark::Newmark;
use crate::options::{FeOptions, Newton};

/// Backtracking line search (Dennis & Schnabel 1983, §6.3): the friction law is piecewise
/// linear, and a full Newton step can jump between stick and slip of several elements and
/// cycle; the step is halved while the residual does not fall.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LineSearch<const D: usize> {
    /// The last iterate a full Newton step left from, and that step.
    q_prev: SVector<f64, D>,
    dq_prev: SVector<f64, D>,
    /// Its residual norm (∞ before the first solve).
    pub r_prev: f64,
    /// The fraction of the step taken.
    pub lambda: f64,
}

impl<const D: usize> LineSearch<D> {
    /// A search starting at the predictor `q`.
    pub(crate) fn new(q: SVector<f64, D>) -> Self {
        Self {
            q_prev: q,
            dq_prev: SVector::zeros(),
            r_prev: f64::INFINITY,
            lambda: 1.0,
        }
    }

    /// Whether the residual `r` of the iterate is to be backtracked from (it did not fall
    /// enough, and the step may still be halved); if so `q` is moved back to half the
    /// last step's fraction, and `lambda` is that fraction.
    #[inline]
    pub(crate) fn backtrack(&mut self, r: f64, q: &mut SVector<f64, D>) -> bool {
        if r > (1.0 - 1e-4 * self.lambda) * self.r_prev && self.lambda > 1.0 / 64.0 {
            self.lambda *= 0.5;
            *q = self.q_prev + self.dq_prev * self.lambda;
            return true;
        }
        false
    }

    /// A full Newton step `dq` from `q`, whose residual norm is `r`.
    #[inline]
    pub(crate) fn advance(&mut self, q: &mut SVector<f64, D>, dq: SVector<f64, D>, r: f64) {
        (self.q_prev, self.dq_prev, self.r_prev, self.lambda) = (*q, dq, r, 1.0);
        *q += dq;
    }
}

/// What a solved iteration's norms decide.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Verdict {
    /// Converged at the current iterate.
    Converged,
    /// Accepted at the round-off floor.
    RoundOff,
    /// Not yet: take the Newton step.
    Continue,
}

/// The convergence tests of an iteration whose residual norm is `rn` against the force
/// scale `fref`, correction and step increment (with it) of squared norms `d2` and `inc2`,
/// displacement of squared norm `u2`, after an iteration of residual `r_prev`.
///
/// Converged at the current iterate: its residual is small and the correction Newton
/// would still make is small against the step's increment. A correction below 1e-12 of
/// the displacement is round-off of the absolute positions: nothing to correct. (A
/// residual below 1e-11 of the force scale is accepted before the solve.) The correction's
/// norms matter only to a residual within the tolerance: their square roots are taken
/// only then. Round-off floor: the residual is within the force tolerance, and a full
/// Newton iteration (with its line search) no longer halves it — the iterate is at the
/// round-off level of the load, and the remaining correction is noise.
#[inline]
pub(crate) fn verdict(
    newton: &Newton,
    (rn, fref): (f64, f64),
    (d2, inc2, u2): (f64, f64, f64),
    r_prev: f64,
) -> Verdict {
    let force_ok = rn <= newton.force_tol * fref;
    let disp_ok = || d2.sqrt() <= (newton.displacement_tol * inc2.sqrt()).max(1e-12 * u2.sqrt());
    if force_ok && disp_ok() {
        Verdict::Converged
    } else if force_ok && r_prev.is_finite() && rn > 0.5 * r_prev {
        Verdict::RoundOff
    } else {
        Verdict::Continue
    }
}

/// One iteration's measures kept in `last` (what a step that fails reports) and judged by
/// [`verdict`]; when the step ends here (converged, or accepted at the round-off floor)
/// its `it` iterations are counted. True when the step ends.
#[inline]
pub(crate) fn judge(
    newton: &Newton,
    (rn, fref): (f64, f64),
    (d2, inc2, u2): (f64, f64, f64),
    r_prev: f64,
    last: &mut LastIteration,
    counters: &mut Counters,
    it: usize,
) -> bool {
    *last = LastIteration {
        residual: rn,
        force_scale: fref,
        correction_squared: d2,
        increment_squared: inc2,
    };
    let verdict = verdict(newton, (rn, fref), (d2, inc2, u2), r_prev);
    if verdict == Verdict::Continue {
        return false;
    }
    counters.roundoff_accepted += u64::from(verdict == Verdict::RoundOff);
    counters.add_step_iterations(it);
    true
}

/// A failed step after `it` iterations (counted).
#[inline]
pub(crate) fn failed(
    counters: &mut Counters,
    it: usize,
    reason: FailureReason,
    diverged: bool,
) -> Result<(), StepFailure> {
    counters.add_step_iterations(it);
    Err(StepFailure { reason, diverged })
}

/// The step did not converge in `it` = `newton.max_iterations` iterations.
pub(crate) fn not_converged(
    counters: &mut Counters,
    it: usize,
    last: LastIteration,
    newton: &Newton,
    unit: &'static str,
) -> Result<(), StepFailure> {
    let reason = FailureReason::NotConverged {
        iterations: it,
        last,
        force_tol: newton.force_tol,
        displacement_tol: newton.displacement_tol,
        unit,
    };
    failed(counters, it, reason, false)
}

/// The nodes' rows of the HHT residual, −(1 + α)·p₊ + α·pₙ (massless: no inertia),
/// written into `w.rn`; returns the body's squared residual norm `r2` with theirs added
/// in node order.
#[inline]
fn with_node_residuals<const Q: usize, const N: usize, M: Mechanics<Q, N>>(
    mut r2: f64,
    w: &mut Workspace<Q, N, M>,
    nodes: usize,
    s: f64,
    alpha: f64,
) -> f64 {
    let node_forces = M::node_forces(&w.asm).iter().zip(&w.pn_n);
    for (r, (p, p_n)) in w.rn.iter_mut().zip(node_forces).take(nodes) {
        *r = -p * s + p_n * alpha;
        r2 += r.norm_squared();
    }
    r2
}

/// The squared norms of the correction, the step's increment with it and the
/// displacement, the body's `(d2, inc2, u2)` with every node's added in node order.
#[inline]
fn with_nodes<const Q: usize, const N: usize, M: Mechanics<Q, N>>(
    (mut d2, mut inc2, mut u2): (f64, f64, f64),
    w: &Workspace<Q, N, M>,
    nodes: usize,
) -> (f64, f64, f64) {
    for k in 0..nodes {
        d2 += w.dun[k].norm_squared();
        inc2 += (w.un[k] + w.dun[k] - w.un_n[k]).norm_squared();
        u2 += w.un[k].norm_squared();
    }
    (d2, inc2, u2)
}

/// One step of length `nm.h` from `n` to time `t`: Newton–Raphson with a backtracking
/// line search on the consistent tangent. On success `next`, the elements' trial states
/// and `w.un`, `w.asm` hold the new state (not yet committed).
///
/// A residual at the round-off of the force scale (≤ 1e-11 of it) is converged whatever
/// the correction: accepted before solving (the linear sticking step's second iteration
/// costs an assembly, no solve), by the same test as [`verdict`]'s, so the same iterate
/// is accepted.
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
        model.predict_nodes(&mut w.un, &g, &n.g);
    }
    let rotates = model.rotates();
    let (mut last, mut it) = (LastIteration::default(), 0);
    let mut search = LineSearch::new(q);
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
        let r2 = with_node_residuals(rb.norm_squared(), w, nodes, s, alpha);
        let fref = f_norm + pb.norm() + inertial.norm();
        if search.backtrack(r2.sqrt(), &mut q) {
            for k in 0..nodes {
                w.un[k] = w.un_prev[k] + w.dun_prev[k] * search.lambda;
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
            return failed(counters, it, FailureReason::NotFinite, true);
        }
        if r2.sqrt() <= 1e-11 * fref {
            counters.add_step_iterations(it);
            *next = accept();
            return Ok(());
        }
        if !model.solve_step(nm, &v, &mut w.asm, &rb, &w.rn, &mut dq, &mut w.dun) {
            return failed(counters, it, FailureReason::Singular(it), false);
        }
        let body = (
            dq.norm_squared(),
            (q + dq - q_n).norm_squared(),
            M::displacement_squared(&q, &at, &n.pose),
        );
        let (d2, inc2, u2) = with_nodes(body, w, nodes);
        let rn = r2.sqrt();
        let (measures, r_prev) = ((d2, inc2, u2), search.r_prev);
        if judge(
            &newton,
            (rn, fref),
            measures,
            r_prev,
            &mut last,
            counters,
            it,
        ) {
            *next = accept();
            return Ok(());
        }
        search.advance(&mut q, dq, rn);
        for k in 0..nodes {
            w.un_prev[k] = w.un[k];
            w.dun_prev[k] = w.dun[k];
            w.un[k] += w.dun[k];
        }
    }
    not_converged(counters, it, last, &newton, M::CORRECTION_UNIT)
}

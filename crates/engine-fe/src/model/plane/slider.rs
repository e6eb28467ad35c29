//! The sliding oscillator's step in scalars (the PEPO, single or condensed double): the
//! body's X and Z with θ locked, one element from the ground to the centre of mass.
//!
//! The same Newton–Raphson with line search as the general step (`stepper::newton`), the same operations in the
//! same order on the two live components, so the same bits: the general step's θ row
//! carries exact zeros there (a locked θ, an attachment at the centre of mass), and the
//! 3×3 LU of a matrix whose θ row and column are (0, 0, 1) is this 2×2 LU step for step
//! (`Lu2`). What goes is the general step's dispatch, its 3-vectors and 3×3 matrices, and
//! the 9-entry comparison of the cached factors.

use nalgebra::{Vector2, Vector3};

use super::Plane;
use crate::lu::Lu2;
use crate::model::{Drive, Model};
use crate::options::FeOptions;
use crate::stepper::{
    Counters, FailureReason, LastIteration, LineSearch, Newmark, State, StepFailure, StepState,
    Workspace, failed, judge, not_converged,
};

/// The factors of `m`, cached in `cache` (new ones unless `m` is the cached matrix).
fn factors(cache: &mut Option<Lu2>, m: [f64; 4]) -> &Lu2 {
    if !matches!(cache, Some(lu) if lu.same_matrix(&m)) {
        *cache = Some(Lu2::new(m));
    }
    cache.as_ref().expect("just set")
}

/// The step's element evaluation: internal force (X, Z) on the body and its tangent
/// [[k00, k01], [k10, k11]] at body position `q`, ground at `xg`.
#[inline(always)]
fn assemble(model: &mut Model<Plane>, q: &Vector2<f64>, xg: f64) -> ((f64, f64), [f64; 4]) {
    let e = model.slider_element();
    // The attachment is the centre of mass: its displacement is q (`point_kin` adds
    // −θ·0 = −0 to X, which leaves every value's bits as they are).
    let (f, d) = e.trial_contact(Vector2::new(q.x - xg, q.y));
    // `PlaneSums`' sums from zero (0 + x is x but for the sign of a zero).
    (
        (0.0 + f.x, 0.0 + f.y),
        [
            0.0 + d[(0, 0)],
            0.0 + d[(0, 1)],
            0.0 + d[(1, 0)],
            0.0 + d[(1, 1)],
        ],
    )
}

/// The Newton correction for the residual (rx, rz): the live block of the Newton matrix
/// S = M·c0 + s·K (+ the damping's γ/(βΔt)·C·s on X) with tangent `k`, solved with the
/// factors cached in `cache` (`None`: singular). `solve`'s matrix entry for entry (each
/// off-diagonal from +0, as its sum).
#[inline]
fn correction(
    cache: &mut Option<Lu2>,
    k: &[f64; 4],
    (mass_c0, s, damp_xx): (f64, f64, f64),
    (rx, rz): (f64, f64),
) -> Option<(f64, f64)> {
    let matrix = [
        (mass_c0 + k[0] * s) + damp_xx,
        0.0 + k[1] * s,
        0.0 + k[2] * s,
        mass_c0 + k[3] * s,
    ];
    factors(cache, matrix).solve(rx, rz)
}

/// One step of length `nm.h` from `n` to time `t` (`stepper::newton::step` for a slider
/// model).
#[allow(clippy::too_many_arguments)]
pub(crate) fn step(
    model: &mut Model<Plane>,
    drive: &Drive<'_>,
    opts: &FeOptions,
    nm: &Newmark,
    w: &mut Workspace<3, 2, Model<Plane>>,
    (n, next): (&State<3, 2, Model<Plane>>, &mut State<3, 2, Model<Plane>>),
    t: f64,
    counters: &mut Counters,
) -> Result<(), StepFailure> {
    let (mass, c) = (model.body.mass, model.body.damping);
    let (alpha, s, c0, c1, h) = (nm.alpha, nm.s, nm.c0, nm.c1, nm.h);
    let damp_xx = s * c * c1;
    let newton = opts.newton;
    let g = drive.ground::<Plane>(t);
    let fz = drive.vertical_force(t);
    let f = Vector2::new(drive.force::<Plane>(t), -model.weight() + fz);
    let f_norm = f.norm();
    let (nq, nv, na) = (n.pose.xy(), n.v.xy(), n.a.xy());
    // The start's share of the HHT residual, (fₙ − pₙ − damping)·α.
    let start_x = ((n.f.x - n.pb.x) - n.damp.x) * alpha;
    let start_z = (n.f.y - n.pb.y) * alpha;
    let mass_c0 = mass * c0;
    let mut q = nq + nv * h + na * (0.5 * h * h);
    let (mut last, mut it) = (LastIteration::default(), 0);
    let mut search = LineSearch::new(q);
    // The tangent of the iterate a full Newton step left (`linear_step`).
    let mut stepped_from: Option<[f64; 4]> = None;
    let accept =
        |q: Vector2<f64>, v: Vector2<f64>, a: Vector2<f64>, pb: (f64, f64), damp| StepState {
            t,
            pose: Vector3::new(q.x, q.y, n.pose.z),
            v: Vector3::new(v.x, v.y, 0.0),
            a: Vector3::new(a.x, a.y, 0.0),
            f: Vector3::new(f.x, f.y, 0.0),
            fz,
            pb: Vector3::new(pb.0, pb.1, 0.0),
            damp: Vector3::new(damp, 0.0, 0.0),
            g,
        };
    while it < newton.max_iterations {
        it += 1;
        let (a, v) = nm.kinematics(q - nq, &nv, &na);
        let (pb, k) = assemble(model, &q, g.0);
        let damp = c * (v.x - g.1);
        if linear_step(stepped_from, &k, &q) {
            counters.add_step_iterations(it);
            *next = accept(q, v, a, pb, damp);
            return Ok(());
        }
        let rx = ((f.x - pb.0) - damp) * s - start_x - mass * a.x;
        let rz = (f.y - pb.1) * s - start_z - mass * a.y;
        let r2 = rx * rx + rz * rz;
        let fref = f_norm
            + (pb.0 * pb.0 + pb.1 * pb.1).sqrt()
            + ((mass * a.x) * (mass * a.x) + (mass * a.y) * (mass * a.y)).sqrt();
        if search.backtrack(r2.sqrt(), &mut q) {
            stepped_from = None;
            continue;
        }
        if !(r2.is_finite() && q.iter().all(|x| x.is_finite())) {
            return failed(counters, it, FailureReason::NotFinite, true);
        }
        if r2.sqrt() <= 1e-11 * fref {
            counters.add_step_iterations(it);
            *next = accept(q, v, a, pb, damp);
            return Ok(());
        }
        let cached = &mut w.asm.extra;
        let Some((dx, dz)) = correction(cached, &k, (mass_c0, s, damp_xx), (rx, rz)) else {
            return failed(counters, it, FailureReason::Singular(it), false);
        };
        let dq = Vector2::new(dx, dz);
        let (d2, inc2, u2) = (
            dq.norm_squared(),
            (q + dq - nq).norm_squared(),
            // q's θ is +0 or −0 (locked): its square adds nothing.
            q.norm_squared(),
        );
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
            *next = accept(q, v, a, pb, damp);
            return Ok(());
        }
        search.advance(&mut q, dq, rn);
        stepped_from = Some(k);
    }
    not_converged(counters, it, last, &newton, " m")
}

/// Whether the iterate `q`, reached by a full Newton step from an iterate whose tangent was
/// `from`, is converged without forming its residual: the same tangent bit for bit is
/// the same contact state (stick, slip in the same direction, or open), in which the
/// element's force is affine in q — and so are Newmark's a and v and the damping — so the
/// residual, affine too, is zero at the Newton step's end up to the round-off of the
/// solve. The general step forms that residual and accepts it at the round-off test
/// (≤ 1e-11 of the force scale); accepting here gives the same iterate, the same
/// iteration count, and the same bits whenever that test would pass.
#[inline]
fn linear_step(from: Option<[f64; 4]>, k: &[f64; 4], q: &Vector2<f64>) -> bool {
    from.is_some_and(|from| {
        from.iter().zip(k).all(|(x, y)| x.to_bits() == y.to_bits())
            && q.x.is_finite()
            && q.y.is_finite()
    })
}

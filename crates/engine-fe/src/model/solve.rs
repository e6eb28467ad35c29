//! The Newton system of either dimension, S·Δq = rhs on the body's unknowns with the
//! massless nodes condensed out (their series tangents in the assembly, their residuals
//! here), solved by LU with partial pivoting whose factors are reused while the matrix is
//! bit for bit the same.

use super::assembly::Assembly;
use super::dimension::{Dimension, Model, System, Vector};

/// Solve the Newton system of `sys`: writes the body's correction `dq` and the nodes'
/// `dun`; false if singular. Each node's residual rn enters the right-hand side as the
/// generalized force Gᵀ·v of v = D2·(D1 + D2)⁻¹·rn and its correction is recovered after
/// the body's, Δun = (D1 + D2)⁻¹·(rn/s + D2·G·Δq). A tangent the assembly deferred is
/// summed first.
pub(crate) fn solve<D: Dimension>(
    model: &Model<D>,
    sys: &System<D::Unknowns>,
    a: &mut Assembly<D>,
    rb: &D::Unknowns,
    rn: &[Vector<D>],
    dq: &mut D::Unknowns,
    dun: &mut [Vector<D>],
) -> bool {
    if a.singular {
        return false;
    }
    model.finish_tangent(a);
    let nodes = model.loop_nodes();
    let mut s_mat = D::newton_matrix(&model.body, sys, &a.kbb);
    let mut rhs = *rb;
    for (k, r) in rn.iter().enumerate().take(nodes) {
        let v = a.d2[k] * (a.knn_inv[k] * *r);
        rhs += D::generalized_force(&a.points[k], &a.at, &v);
    }
    if !model.body.rotation {
        D::lock_rotation_rows(&mut s_mat, &mut rhs);
    }
    if model.body.rotation && !D::ROTATING_MATRIX_REPEATS {
        // The matrix moves with the pose at every iteration: nothing to look up (a
        // matrix factored again gives the same factors).
        D::factor(&s_mat, &mut a.lu);
    } else if !matches!(&a.factored, Some(m) if D::same_bits(m, &s_mat)) {
        D::factor(&s_mat, &mut a.lu);
        a.factored = Some(s_mat);
    }
    let Some(x) = D::solve(&a.lu, &rhs) else {
        return false;
    };
    *dq = x;
    for k in 0..nodes {
        let motion = D::point_motion(&a.points[k], &a.at, model.body.rotation, &x);
        dun[k] = a.knn_inv[k] * (rn[k] / sys.s + a.d2[k] * motion);
    }
    true
}

//! The plane model's Newton system: S·Δq = rhs on the body's (X, Z, θ) with the nodes
//! condensed out (Schur complement of their 2×2 blocks), solved by LU with partial
//! pivoting whose factors are reused while the matrix is bit for bit the same.

use nalgebra::{Matrix3, Vector2, Vector3};

use super::assembly::{Assembly, Factors};
use super::body::Model;
use crate::lu::Lu3;

/// Scaling of the Newton system: S·Δq = rhs with S = diag(M)·c0 + s·(Kbb − Σ Kbn Knn⁻¹ Knb)
/// (+ c_damp on XX), rhs = rb − Σ Kbn Knn⁻¹ rn; nodes Δun = Knn⁻¹(rn/s − Knb Δq).
pub struct System {
    /// Coefficient of the mass matrix, 1/(β·Δt²) (0 for statics).
    pub c0: f64,
    /// Scale of the stiffness, 1 + α.
    pub s: f64,
    /// Extra XX stiffness (damping γ/(βΔt)·C·(1+α)).
    pub damp_xx: f64,
}

/// Solve the Newton system; writes Δq and Δun. Returns false if a block is singular.
pub fn solve(
    model: &Model,
    sys: &System,
    a: &mut Assembly,
    rb: &Vector3<f64>,
    rn: &[Vector2<f64>],
    dq: &mut Vector3<f64>,
    dun: &mut [Vector2<f64>],
) -> bool {
    let m = model.mass_diag();
    let mut s_mat = Matrix3::from_diagonal(&(m * sys.c0)) + a.kbb * sys.s;
    s_mat[(0, 0)] += sys.damp_xx;
    let mut rhs = *rb;
    for (k, r) in rn.iter().enumerate().take(model.loop_nodes()) {
        let Some(inv) = a.knn[k].try_inverse() else {
            return false;
        };
        a.knn_inv[k] = inv;
        let kbn_inv = a.kbn[k] * inv;
        s_mat -= kbn_inv * a.knb[k] * sys.s;
        rhs -= kbn_inv * r;
    }
    if !model.body.rotation {
        for j in 0..3 {
            s_mat[(2, j)] = 0.0;
            s_mat[(j, 2)] = 0.0;
        }
        s_mat[(2, 2)] = 1.0;
        rhs.z = 0.0;
    }
    // LU with partial pivoting (`Lu3`): the closed-form 3×3 inverse is a little cheaper but
    // loses digits, and the tight preset then needs more iterations. The factors are
    // reused while the matrix is unchanged (the same bits, so the same solution).
    let Some(x) = factors_of(&mut a.factors, &s_mat).and_then(|lu| lu.solve(&rhs)) else {
        return false;
    };
    *dq = x;
    for k in 0..model.loop_nodes() {
        dun[k] = a.knn_inv[k] * (rn[k] / sys.s - a.knb[k] * x);
    }
    true
}

/// The LU factors of `s_mat`: the cached ones when `s_mat` is bit for bit the matrix they
/// factor, else new ones (cached). On the stack: no allocation.
fn factors_of<'a>(cache: &'a mut Option<Factors>, s_mat: &Matrix3<f64>) -> Option<&'a Lu3> {
    let same = |m: &Matrix3<f64>| {
        m.iter()
            .zip(s_mat.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    };
    if !matches!(cache, Some((m, _)) if same(m)) {
        *cache = Some((*s_mat, Lu3::new(s_mat)));
    }
    cache.as_ref().map(|(_, lu)| lu)
}

/// The tangent stiffness condensed onto the body's (X, Z, θ) at the current element
/// states (Schur complement of the node blocks); `None` if a node block is singular.
pub fn condensed_tangent(model: &Model, a: &Assembly) -> Option<Matrix3<f64>> {
    let mut k = a.kbb;
    for n in 0..model.loop_nodes() {
        let inv = a.knn[n].try_inverse()?;
        k -= a.kbn[n] * inv * a.knb[n];
    }
    Some(k)
}

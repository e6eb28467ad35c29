//! Kinematics of a body point: its displacement u at body-frame offset d from the centre
//! of mass for the body's q = (X, Z, θ), the θ column g of its Jacobian G = ∂u/∂q =
//! [I₂ | g], and h = ∂²u/∂θ² — exact rotations, small rotations, or small rotations with
//! the second-order (P-Delta) terms.

use nalgebra::{Vector2, Vector3};

use crate::options::Kinematics;

/// Displacement of a body point, the θ column g of its Jacobian G = ∂u/∂q = [I₂ | g],
/// and h = ∂²u/∂θ².
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct PointKin {
    pub u: Vector2<f64>,
    pub g: Vector2<f64>,
    pub h: Vector2<f64>,
}

/// Kinematics of a body point at body-frame offset `d` from the centre of mass.
#[inline]
pub(crate) fn point_kin(
    kin: Kinematics,
    p_delta: bool,
    q: &Vector3<f64>,
    cs: (f64, f64),
    d: &Vector2<f64>,
) -> PointKin {
    let (dx, dz) = (d.x, d.y);
    let th = q.z;
    let (ux, uz, gx, gz, hx, hz) = match (kin, p_delta) {
        (Kinematics::Exact, _) => {
            // r = R(θ)·d, R = [[c, −s], [s, c]]: u = (R − I)·d
            let (c, s) = cs;
            (
                (c - 1.0) * dx - s * dz,
                s * dx + (c - 1.0) * dz,
                -s * dx - c * dz,
                c * dx - s * dz,
                -c * dx + s * dz,
                -s * dx - c * dz,
            )
        }
        (Kinematics::SmallRotation, false) => (-th * dz, th * dx, -dz, dx, 0.0, 0.0),
        // Second order in θ: cos θ ≈ 1 − θ²/2, sin θ ≈ θ.
        (Kinematics::SmallRotation, true) => (
            -th * dz - 0.5 * th * th * dx,
            th * dx - 0.5 * th * th * dz,
            -dz - th * dx,
            dx - th * dz,
            -dx,
            -dz,
        ),
    };
    PointKin {
        u: Vector2::new(q.x + ux, q.y + uz),
        g: Vector2::new(gx, gz),
        h: Vector2::new(hx, hz),
    }
}

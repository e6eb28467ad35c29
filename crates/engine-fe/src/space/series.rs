//! Condensed double supports in 3D: two cone contacts in series through a massless node,
//! element 2 bonded with μ2 = ∞, are one cone contact with the series stiffnesses and
//! element 1's friction and slip (`series_equivalent`, derived there); after a converged
//! step the two elements' states and the node are set from it (`split_equivalent`).

use nalgebra::Vector3;

use super::contact::{ConeContact, ConeState};
use crate::element::Status;

/// The exact single cone contact of two in series through a massless node: element 1
/// (ground side, compression-only, friction μ1 on the circular cone) and element 2
/// (bonded, μ2 = ∞); `None` for any other pair.
///
/// Derivation (the 2D one, `crate::model::series_equivalent`, with the tangential pair as
/// a vector). The node carries no load, so both elements transmit the same force f.
/// Normal: element 1 closed (δtz ≤ 0) gives N = kzs·(−δtz), kzs = kz1·kz2/(kz1 + kz2);
/// δtz > 0 opens element 1 and nothing is transmitted. Tangential, with element 1's slip
/// s1: sticking, T = kt1·(δ1 − s1) = kt2·(δt − δ1) gives T = kts·(δt − s1),
/// kts = kt1·kt2/(kt1 + kt2), and the pair sticks while |T| ≤ μ1·N — the same test on the
/// same numbers. Slipping, element 1's radial return puts T = μ1·N·m with m the direction
/// of its trial δ1 − s1 = (δt − s1) − T/kt2, so m is the direction of δt − s1 (the
/// equivalent's trial direction), and s1 ← δ1 − T/kt1 = δt − T/kts: the radial return of
/// one element (kts, kzs, μ1) with slip s1. Open: δ1 = δt and the origin follows the point,
/// s1 = δt, again the same. The consistent tangent, the derivative of the same function,
/// is the node's Schur complement D2 − D2·(D1 + D2)⁻¹·D2. Only round-off differs.
pub fn series_equivalent(lower: &ConeContact, upper: &ConeContact) -> Option<ConeContact> {
    if lower.bonded || !upper.bonded || upper.mu.is_finite() {
        return None;
    }
    let series = |a: f64, b: f64| a * b / (a + b);
    let mut eq = ConeContact::new(
        series(lower.kt, upper.kt),
        series(lower.kz, upper.kz),
        lower.mu,
        false,
    );
    eq.set_committed(*lower.state());
    Some(eq)
}

/// Set the committed states of a condensed support's element 1 (`lower`) and element 2
/// (`upper`) from the last trial of their series equivalent `eq`; returns the node's
/// position relative to the ground, δ1. Both elements carry the equivalent's force f;
/// element 2 sticks, so its deflection is δ2 = (fx/kt2, fy/kt2, fz/kz2) and δ1 = δt − δ2
/// (δ1 = δt, δ2 = 0 when element 1 is open); element 1 has the equivalent's slip and
/// status.
pub(crate) fn split_equivalent(
    eq: &ConeContact,
    lower: &mut ConeContact,
    upper: &mut ConeContact,
) -> Vector3<f64> {
    let st = *eq.trial_state();
    let d2 = if st.status == Status::Open {
        Vector3::zeros()
    } else {
        Vector3::new(
            st.force.x / upper.kt,
            st.force.y / upper.kt,
            st.force.z / upper.kz,
        )
    };
    let d1 = st.delta - d2;
    lower.set_committed(ConeState { delta: d1, ..st });
    upper.set_committed(ConeState {
        slip: upper.state().slip,
        delta: d2,
        force: st.force,
        status: Status::Stick,
    });
    d1
}

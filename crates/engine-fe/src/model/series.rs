//! Condensed supports: when element 2 of the double arrangement is bonded with μ2 = ∞
//! (every shipped case), the pair in series *is* one CONTA178-like element with the
//! series stiffnesses and element 1's friction and slip (`series_equivalent`, derived
//! there); after a converged step the two elements' states and the node are rebuilt from
//! it (`split_equivalent`).

use nalgebra::Vector2;

use crate::element::{Contact178, ContactState, Status};

/// The exact single element of two CONTA178-like elements in series through a massless
/// node, element 1 (ground side: compression-only, friction μ1) and element 2 (bonded,
/// μ2 = ∞); `None` for any other pair.
///
/// Derivation. The node carries no load, so both elements transmit the same force f.
/// Normal: element 1 closed (δtz ≤ 0) gives N = kz1·(−δ1z) = kz2·(δ1z − δtz), so
/// N = kzs·(−δtz) with kzs = kz1·kz2/(kz1 + kz2); δtz > 0 opens element 1 and nothing is
/// transmitted (element 2 is bonded, so it only follows). Tangential, with element 1's
/// slip s1: sticking, T = kx1·(δ1x − s1) = kx2·(δtx − δ1x) gives T = ks·(δtx − s1),
/// ks = kx1·kx2/(kx1 + kx2), and the pair sticks while |T| ≤ μ1·N — the same test on the
/// same numbers; slipping, T = ±μ1·N and s1 = δ1x − T/kx1 = δtx − T/kx2 − T/kx1 = δtx − T/ks,
/// the return mapping of an element (ks, kzs, μ1) whose slip is s1. Open: δ1 = δt, and
/// CONTA178 moves the tangential origin with the point, s1 = δtx, again the same. The
/// consistent tangents agree too: the Schur complement D2·(D1 + D2)⁻¹·D1 of the node is
/// diag(ks, kzs) sticking and [[0, −sg·μ1·kzs], [0, kzs]] slipping. So the equivalent is
/// exact in every state; only round-off differs (kzs·δtz against kz1·(kz2·δtz/(kz1 + kz2))).
pub fn series_equivalent(lower: &Contact178, upper: &Contact178) -> Option<Contact178> {
    if lower.bonded || !upper.bonded || upper.mu.is_finite() {
        return None;
    }
    let series = |a: f64, b: f64| a * b / (a + b);
    let mut eq = Contact178::new(
        series(lower.kx, upper.kx),
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
/// element 2 sticks, so its deflection is δ2 = (fx/kx2, fz/kz2) and δ1 = δt − δ2
/// (δ1 = δt, δ2 = 0 when element 1 is open); element 1 has the equivalent's slip and
/// status (`series_equivalent`).
pub(crate) fn split_equivalent(
    eq: &Contact178,
    lower: &mut Contact178,
    upper: &mut Contact178,
) -> Vector2<f64> {
    let st = *eq.trial_state();
    let d2 = if st.status == Status::Open {
        Vector2::zeros()
    } else {
        Vector2::new(st.force.x / upper.kx, st.force.y / upper.kz)
    };
    let d1 = st.delta - d2;
    // Only the committed states: a condensed support's elements are never trialled.
    lower.set_state(ContactState { delta: d1, ..st });
    upper.set_state(ContactState {
        slip: upper.state().slip,
        delta: d2,
        force: st.force,
        status: Status::Stick,
    });
    d1
}

//! Condensed double supports, in either dimension: when element 2 of the double
//! arrangement is bonded with μ2 = ∞ (every shipped case), the pair in series through a
//! massless node *is* one contact element with the series stiffnesses and element 1's
//! friction and slip (`series_equivalent`, derived there); after a converged step the two
//! elements' states and the node are rebuilt from it (`split_equivalent`). The node's
//! exact equilibrium for the uncondensed model is `node_equilibrium`.

use crate::element::{Contact, ContactState, Status, Tangential};

/// The exact single element of two contact elements in series through a massless node,
/// element 1 (ground side: compression-only, friction μ1) and element 2 (bonded, μ2 = ∞);
/// `None` for any other pair.
///
/// Derivation. The node carries no load, so both elements transmit the same force f.
/// Normal: element 1 closed (δtz ≤ 0) gives N = kz1·(−δ1z) = kz2·(δ1z − δtz), so
/// N = kzs·(−δtz) with kzs = kz1·kz2/(kz1 + kz2); δtz > 0 opens element 1 and nothing is
/// transmitted (element 2 is bonded, so it only follows). Tangential, with element 1's
/// slip s1: sticking, T = kt1·(δ1t − s1) = kt2·(δtt − δ1t) gives T = kts·(δtt − s1),
/// kts = kt1·kt2/(kt1 + kt2), and the pair sticks while |T| ≤ μ1·N — the same test on the
/// same numbers. Slipping, element 1's return mapping puts T = μ1·N·n with n the direction
/// of its trial δ1t − s1 = (δtt − s1) − T/kt2, so n is the direction of δtt − s1 (the
/// equivalent's trial direction), and s1 ← δ1t − T/kt1 = δtt − T/kts: the return mapping of
/// one element (kts, kzs, μ1) whose slip is s1. Open: δ1 = δt, and CONTA178 moves the
/// tangential origin with the point, s1 = δtt, again the same. The consistent tangents
/// agree too: the node's Schur complement D2·(D1 + D2)⁻¹·D1 is diag(kts, kzs) sticking and
/// the slipping element's tangent slipping. So the equivalent is exact in every state;
/// only round-off differs (kzs·δtz against kz1·(kz2·δtz/(kz1 + kz2))).
pub fn series_equivalent<T: Tangential>(
    lower: &Contact<T>,
    upper: &Contact<T>,
) -> Option<Contact<T>> {
    if lower.bonded || !upper.bonded || upper.mu.is_finite() {
        return None;
    }
    let series = |a: f64, b: f64| a * b / (a + b);
    let mut eq = Contact::new(
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
/// element 2 sticks, so its deflection is δ2 = (ft/kt2, fz/kz2) and δ1 = δt − δ2
/// (δ1 = δt, δ2 = 0 when element 1 is open); element 1 has the equivalent's slip and
/// status (`series_equivalent`).
pub(crate) fn split_equivalent<T: Tangential>(
    eq: &Contact<T>,
    lower: &mut Contact<T>,
    upper: &mut Contact<T>,
) -> T::Vector {
    let st = *eq.trial_state();
    let d2 = if st.status == Status::Open {
        T::zero().join(0.0)
    } else {
        let (ft, fz) = T::split(&st.force);
        ft.over(upper.kt).join(fz / upper.kz)
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

/// The exact equilibrium of a massless node between element 1 (`e1`: compression-only,
/// friction μ1 from the ground) and the bonded element 2 (`e2`: μ2 = ∞), for the body
/// point at `dt` relative to the ground: the node's position relative to the ground, δ1.
///
/// The node's equations f1(δ1) = f2(δt − δ1) are piecewise linear; Newton on them cycles
/// between stick and slip (a saturating force plus a soft spring behaves like arctan), so
/// they are solved in closed form (the return mapping of the series spring):
///   closed (δtz ≤ 0): δ1z = kz2·δtz/(kz1 + kz2);  open: δ1 = δt (no force);
///   stick: δ1t = (kt1·s1 + kt2·δtt)/(kt1 + kt2);  slip (|T| > μ1·N, T = kts·(δtt − s1)):
///   δ1t = δtt − μ1·N·n/kt2, n the direction of T.
#[inline]
pub(crate) fn node_equilibrium<T: Tangential>(
    e1: &Contact<T>,
    e2: &Contact<T>,
    dt: T::Vector,
) -> T::Vector {
    let (dtt, dtz) = T::split(&dt);
    if dtz > 0.0 {
        return dt;
    }
    let z1 = e2.kz * dtz / (e1.kz + e2.kz);
    let n = -e1.kz * z1;
    let s1 = e1.state().slip;
    let ks = e1.kt * e2.kt / (e1.kt + e2.kt);
    let t = (dtt - s1) * ks;
    let cap = e1.mu * n;
    let size = t.size();
    let x1 = if e1.mu.is_infinite() || size <= cap {
        (s1 * e1.kt + dtt * e2.kt).over(e1.kt + e2.kt)
    } else {
        dtt - (t.direction(size) * cap).over(e2.kt)
    };
    x1.join(z1)
}

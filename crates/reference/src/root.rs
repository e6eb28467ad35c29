//! Root finding for event location: bracket by scanning, refine by bisection to the last
//! representable time. Plain and robust: event functions here are smooth closed forms.

/// The halvings every bisection of the references may take: enough to bring any finite
/// bracket of doubles to two adjacent floats (the doubles span 2¹⁰²⁴ down to 2⁻¹⁰⁷⁴, so
/// 2098 halvings shrink the widest bracket below the smallest spacing), so the loop ends
/// on "the bracket cannot shrink" and the cap only guards against a NaN bracket.
pub const BISECTION_LIMIT: usize = 2100;

/// A root of `f` in `[a, b]` where `f(a) ≤ 0 < f(b)` (or the reverse), by bisection until
/// the bracket cannot shrink.
pub fn bisect(mut a: f64, mut b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let fa_neg = f(a) <= 0.0;
    for _ in 0..BISECTION_LIMIT {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if (f(m) <= 0.0) == fa_neg {
            a = m;
        } else {
            b = m;
        }
    }
    // the first time past the event
    b
}

#[cfg(test)]
mod tests {
    #[test]
    fn finds_pi() {
        let r = super::bisect(3.0, 3.5, |x| -x.sin());
        assert!((r - std::f64::consts::PI).abs() < 1e-15);
    }
}

//! The first rise of a smooth closed form above zero, found with a bound on its curvature:
//! on a piece [a, b] a function with f'' ≥ −L cannot exceed max(f(a), f(b)) + L·(b − a)²/8,
//! so a piece whose bound stays ≤ 0 has no crossing and is skipped, the others are halved.
//! The first piece whose right end is above zero brackets the event, refined by bisection
//! to the last float ([`crate::root::bisect`]). Every loop is bounded: a graze narrower
//! than the halving depth (≈ 1e-15 of the span) is taken as no crossing. A search that
//! cannot be bounded — a curvature bound or a value of `f` that is not a number (a scene
//! whose scales overflow double precision, such as Kx = 1e-300 N/m) — is an error at
//! once, never tens of thousands of halvings per interval.

use crate::root::bisect;

/// Halvings of one piece before a graze is declared no crossing.
const MAX_DEPTH: u32 = 52;
/// Function evaluations allowed in one search (pieces and halvings together).
const MAX_EVALUATIONS: usize = 20_000;
/// Most pieces a span is first cut into.
const MAX_PIECES: usize = 4096;

/// First τ in (0, span] at which `f(τ) > 0`, if any, for `f(0) ≤ 0` (a positive value at
/// 0, a rounding residue after an event, is read as 0). `curvature` is L with f'' ≥ −L on
/// [0, span] (kinks that point down are allowed); `frequency` (rad/s) is the fastest
/// oscillation in f, which sets how finely the span is first cut. `Err` when the search
/// cannot be bounded: the curvature bound is not finite, or `f` is NaN at a sample.
pub fn first_rise(
    f: impl Fn(f64) -> f64,
    span: f64,
    curvature: f64,
    frequency: f64,
) -> Result<Option<f64>, String> {
    if span.is_nan() || span <= 0.0 {
        return Ok(None);
    }
    if !curvature.is_finite() {
        return Err(format!(
            "the event search's curvature bound is {curvature}: the scene's scales overflow double precision"
        ));
    }
    let pieces =
        ((span * frequency * 2.0 / std::f64::consts::PI).ceil() as usize + 1).min(MAX_PIECES);
    let mut search = Search {
        f: &f,
        curvature: curvature.abs(),
        budget: MAX_EVALUATIONS,
    };
    let mut a = 0.0;
    let mut fa = f(0.0).min(0.0);
    for i in 1..=pieces {
        let b = span * i as f64 / pieces as f64;
        let fb = f(b);
        if fa.is_nan() || fb.is_nan() {
            return Err(format!(
                "the event function is not a number at τ = {b:e} s: the scene's scales overflow double precision"
            ));
        }
        if let Some(t) = search.piece(a, fa, b, fb, MAX_DEPTH) {
            return Ok(Some(t));
        }
        a = b;
        fa = fb;
    }
    Ok(None)
}

struct Search<'a, F: Fn(f64) -> f64> {
    f: &'a F,
    curvature: f64,
    budget: usize,
}

impl<F: Fn(f64) -> f64> Search<'_, F> {
    fn piece(&mut self, a: f64, fa: f64, b: f64, fb: f64, depth: u32) -> Option<f64> {
        if fb > 0.0 {
            let f = self.f;
            return Some(bisect(a, b, |t| if t <= a { fa } else { f(t) }));
        }
        let w = b - a;
        if fa.max(fb) + self.curvature * w * w / 8.0 <= 0.0 || depth == 0 || self.budget == 0 {
            return None;
        }
        self.budget -= 1;
        let m = 0.5 * (a + b);
        let fm = (self.f)(m);
        self.piece(a, fa, m, fm, depth - 1)
            .or_else(|| self.piece(m, fm, b, fb, depth - 1))
    }
}

#[cfg(test)]
mod tests {
    use super::first_rise;

    #[test]
    fn finds_a_hump_between_samples() {
        // f = 1e-6 − (τ − 0.5)²: above zero only on 0.5 ± 1e-3, between coarse samples.
        let t = first_rise(|t| 1e-6 - (t - 0.5) * (t - 0.5), 1.0, 2.0, 1.0)
            .unwrap()
            .unwrap();
        assert!((t - 0.499).abs() < 1e-12, "{t}");
    }

    #[test]
    fn none_when_it_stays_below() {
        assert_eq!(first_rise(|t| -1e-9 - t * t, 1.0, 0.0, 1.0), Ok(None));
        assert_eq!(
            first_rise(|t| (10.0 * t).sin() - 1.5, 3.0, 100.0, 10.0),
            Ok(None)
        );
    }

    /// Kx = 1e-300 N/m under a vertical pulse made the slip-stop search's curvature bound
    /// infinite, and every grid interval spent its 20,000 halvings: a search that cannot
    /// be bounded is an error at its first evaluation.
    #[test]
    fn an_unbounded_search_is_refused_at_once() {
        let calls = std::cell::Cell::new(0);
        let f = |t: f64| {
            calls.set(calls.get() + 1);
            -1.0 - t
        };
        assert!(first_rise(f, 1.0, f64::INFINITY, 1.0).is_err());
        assert_eq!(calls.get(), 0);
        let e = first_rise(|_| f64::NAN, 1.0, 1.0, 1.0).unwrap_err();
        assert!(e.contains("not a number"), "{e}");
    }
}

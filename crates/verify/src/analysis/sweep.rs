//! Error against time step: the Δt ladder, the error of one rung against a basis (the
//! exact reference, or the engine's own finest rung where no reference exists), the
//! observed order of accuracy, and Richardson extrapolation. Pure arithmetic on traces:
//! running the engines is the `sweep` command's job (`crate::sweep`).
//!
//! Conventions (FIELD-NOTES, "Verification conventions"): errors are whole-history
//! differences normalised by the basis's peak; the observed order between two rungs is
//! p = ln(e₁/e₂)/ln(Δt₁/Δt₂); from three solutions at a constant refinement ratio r,
//! p = ln((f₃ − f₂)/(f₂ − f₁))/ln r and the Richardson estimate is
//! f ≈ f₁ + (f₁ − f₂)/(r^p − 1), with the Grid Convergence Index GCI = 1.25·|f₁ − f₂|/|f₁|/(r^p − 1)
//! (Roache 1994).

use rockslide_core::trace::{Quantity, Trace, q};
use rockslide_reference::ExactSolution;

use super::metrics::{Responses, history_difference};

/// Event-time quantities compared between a rung and its basis (slip and lift-off).
pub const EVENT_KEYS: &[&str] = &["slip_start", "slip_end", "first_liftoff"];

/// A Δt ladder: `rungs` steps from `coarsest` down, each `ratio` times smaller.
pub fn ladder(coarsest: f64, ratio: f64, rungs: usize) -> Vec<f64> {
    (0..rungs)
        .map(|k| coarsest / ratio.powi(k as i32))
        .collect()
}

/// The error of one rung against its basis.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RungError {
    /// max |Δx| / peak |x_basis| of the primary displacement (`rel_disp`).
    #[serde(with = "crate::json::real")]
    pub max: f64,
    /// RMS Δx / peak |x_basis|.
    #[serde(with = "crate::json::real")]
    pub rms: f64,
    /// |residual sliding − basis|, m (when both have a `slide` channel).
    #[serde(with = "crate::json::real_opt")]
    pub residual_sliding: Option<f64>,
    /// Largest |event time − basis| over slip start, slip end and first lift-off, s
    /// (events both have).
    #[serde(with = "crate::json::real_opt")]
    pub event_time: Option<f64>,
    /// Events the basis has and the rung lacks (or the other way round).
    pub events_missing: usize,
}

/// Error of a run against a basis. `basis_at_run` is the basis sampled at the run's row
/// times; `run_resp` and `basis_resp` are both sides' response quantities.
pub fn rung_error(
    run: &Trace,
    run_resp: &Responses,
    basis_at_run: &Trace,
    basis_resp: &Responses,
) -> Option<RungError> {
    let (max, rms) = history_difference(run, basis_at_run, q::REL_DISP.key)?;
    let residual_sliding = match (
        run_resp.get("residual_sliding"),
        basis_resp.get("residual_sliding"),
    ) {
        (Some(a), Some(b)) => Some((a - b).abs()),
        _ => None,
    };
    let mut event_time: Option<f64> = None;
    let mut events_missing = 0;
    for key in EVENT_KEYS {
        match (run_resp.get(key), basis_resp.get(key)) {
            (Some(a), Some(b)) => {
                let d = (a - b).abs();
                event_time = Some(event_time.map_or(d, |e| e.max(d)));
            }
            (None, None) => {}
            _ => events_missing += 1,
        }
    }
    Some(RungError {
        max,
        rms,
        residual_sliding,
        event_time,
        events_missing,
    })
}

/// `trace` linearly interpolated at `times`, every channel (a fine solution used as the
/// basis of coarser ones).
pub fn resample(trace: &Trace, times: &[f64]) -> Trace {
    let mut out = Trace::with_channels(&trace.channels, times.len());
    let mut row = vec![0.0; trace.channels.len()];
    for &t in times {
        for (j, c) in trace.channels.iter().enumerate() {
            row[j] = trace.sample(c.key, t).unwrap_or(f64::NAN);
        }
        out.push(t, &row);
    }
    out
}

/// One channel of `trace`, linearly interpolated at `times`, as a one-column trace: the
/// column [`resample`] would give for `key`, bit for bit (the same [`Trace::sample`]),
/// without sampling the channels a comparison does not read. `None` when `trace` lacks
/// the channel.
pub fn resample_channel(trace: &Trace, key: &str, times: &[f64]) -> Option<Trace> {
    let channel = *trace.channels.iter().find(|c| c.key == key)?;
    let column = times
        .iter()
        .map(|&t| trace.sample(key, t))
        .collect::<Option<_>>()?;
    Some(one_column(channel, times, column))
}

/// One channel of an exact solution evaluated at `times`, as a one-column trace: the
/// column `rockslide_reference::sample` would give for `key`, bit for bit (the same
/// `eval`), without keeping the channels a comparison does not read. `None` when the
/// solution lacks the channel.
pub fn exact_channel(solution: &dyn ExactSolution, key: &str, times: &[f64]) -> Option<Trace> {
    let channels = solution.channels();
    let j = channels.iter().position(|c| c.key == key)?;
    let mut row = vec![0.0; channels.len()];
    let column = times
        .iter()
        .map(|&t| {
            solution.eval(t, &mut row);
            row[j]
        })
        .collect();
    Some(one_column(channels[j], times, column))
}

/// [`exact_channel`] through a cache of one: the runs of every engine variant at one
/// rung usually share their row times, so the solution is evaluated once a rung, not once
/// a run. The cached trace is reused when it holds `key` at the same times bit for bit,
/// else replaced. `None` when the solution lacks the channel.
pub fn exact_channel_cached<'c>(
    cache: &'c mut Option<Trace>,
    solution: &dyn ExactSolution,
    key: &str,
    times: &[f64],
) -> Option<&'c Trace> {
    let hit = cache
        .as_ref()
        .is_some_and(|c| c.channels[0].key == key && same_bits(&c.time, times));
    if !hit {
        *cache = Some(exact_channel(solution, key, times)?);
    }
    cache.as_ref()
}

/// Whether two series of times are the same, bit for bit.
fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// A trace of one channel at `times`.
fn one_column(channel: &'static Quantity, times: &[f64], column: Vec<f64>) -> Trace {
    Trace {
        channels: vec![channel],
        time: times.to_vec(),
        columns: vec![column],
        ..Trace::default()
    }
}

/// Observed order between consecutive rungs: p = ln(e₁/e₂)/ln(Δt₁/Δt₂), one per pair
/// (`None` where either error is zero or not finite).
pub fn local_orders(points: &[(f64, f64)]) -> Vec<Option<f64>> {
    points
        .windows(2)
        .map(|w| {
            let ((h1, e1), (h2, e2)) = (w[0], w[1]);
            let ok = e1 > 0.0 && e2 > 0.0 && e1.is_finite() && e2.is_finite() && h1 != h2;
            ok.then(|| (e1 / e2).ln() / (h1 / h2).ln())
        })
        .collect()
}

/// Observed order as the least-squares slope of ln e against ln Δt over the points with a
/// positive finite error (`None` with fewer than two).
pub fn fitted_order(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(h, e)| *h > 0.0 && *e > 0.0 && e.is_finite())
        .map(|(h, e)| (h.ln(), e.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (sx / n, sy / n);
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (x, y) in &pts {
        sxy += (x - mx) * (y - my);
        sxx += (x - mx) * (x - mx);
    }
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Rungs the one observed order of a series is fitted over: the finest ones, the ladder's
/// asymptotic range (the coarse rungs of a friction scene step over slip events).
pub const ASYMPTOTIC_RUNGS: usize = 4;

/// How the one observed order shown for a series is computed, in words: every page, table
/// header, figure legend and console line that shows an order shows this one.
pub const ORDER_METHOD: &str =
    "least-squares slope of ln(max error) against ln Δt over the 4 finest rungs";

/// The one observed order of a ladder: [`fitted_order`] over its [`ASYMPTOTIC_RUNGS`]
/// finest points.
pub fn asymptotic_order(points: &[(f64, f64)]) -> Option<f64> {
    fitted_order(&points[points.len().saturating_sub(ASYMPTOTIC_RUNGS)..])
}

/// Richardson extrapolation of the two finest solutions with a given order p (the series'
/// one observed order): f ≈ f₁ + (f₁ − f₂)/(r^p − 1), GCI = 1.25·|f₁ − f₂|/|f₁|/(r^p − 1)
/// (Roache 1994). `None` without a positive finite order or a ratio above 1.
pub fn richardson_at_order(fine: f64, mid: f64, r: f64, order: f64) -> Option<Richardson> {
    if !(order.is_finite() && order > 0.0 && r > 1.0) {
        return None;
    }
    Some(Richardson::at_order(fine, mid, r, order))
}

/// Richardson extrapolation from three solutions at a constant refinement ratio.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Richardson {
    /// Observed order p = ln((f₃ − f₂)/(f₂ − f₁))/ln r.
    #[serde(with = "crate::json::real")]
    pub order: f64,
    /// Extrapolated value f₁ + (f₁ − f₂)/(r^p − 1).
    #[serde(with = "crate::json::real")]
    pub extrapolated: f64,
    /// Grid Convergence Index of the finest solution, 1.25·|f₁ − f₂|/|f₁|/(r^p − 1).
    #[serde(with = "crate::json::real")]
    pub gci: f64,
}

/// Richardson from `fine` (f₁), `mid` (f₂), `coarse` (f₃) at ratio `r`; `None` when the
/// differences do not shrink monotonically (no asymptotic range).
pub fn richardson(fine: f64, mid: f64, coarse: f64, r: f64) -> Option<Richardson> {
    let (d21, d32) = (mid - fine, coarse - mid);
    if d21 == 0.0 || d32 == 0.0 || d32 / d21 <= 1.0 || r <= 1.0 {
        return None;
    }
    let order = (d32 / d21).ln() / r.ln();
    Some(Richardson::at_order(fine, mid, r, order))
}

impl Richardson {
    /// The extrapolation and GCI of `fine` and `mid` at ratio `r` for a given order,
    /// unchecked (the callers check the order and the ratio).
    fn at_order(fine: f64, mid: f64, r: f64, order: f64) -> Richardson {
        let denom = r.powf(order) - 1.0;
        let gci = if fine != 0.0 {
            1.25 * (fine - mid).abs() / fine.abs() / denom
        } else {
            f64::NAN
        };
        Richardson {
            order,
            extrapolated: fine + (fine - mid) / denom,
            gci,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x = sin t, v = cos t: an exact solution of two channels.
    struct Sine;

    impl ExactSolution for Sine {
        fn name(&self) -> &'static str {
            "sine"
        }
        fn method(&self) -> String {
            "sin t".into()
        }
        fn channels(&self) -> Vec<&'static Quantity> {
            vec![&q::VEL, &q::REL_DISP]
        }
        fn eval(&self, t: f64, out: &mut [f64]) {
            out[0] = t.cos();
            out[1] = t.sin();
        }
    }

    /// One channel sampled alone is the column every channel sampled together gives, bit
    /// for bit; the cache of one answers the same times from memory and other times anew.
    #[test]
    fn one_channel_is_the_column_of_all_channels() {
        let bits = |t: &Trace| -> Vec<u64> {
            t.column(q::REL_DISP.key)
                .unwrap()
                .iter()
                .map(|v| v.to_bits())
                .collect()
        };
        let fine: Vec<f64> = (0..=100).map(|i| 0.013 * i as f64).collect();
        let coarse: Vec<f64> = (0..=40).map(|i| 0.0331 * i as f64).collect();
        let key = q::REL_DISP.key;
        let all = rockslide_reference::sample(&Sine, &fine);
        let one = exact_channel(&Sine, key, &fine).unwrap();
        assert_eq!((one.channels.len(), &one.time), (1, &fine));
        assert_eq!(bits(&one), bits(&all));
        assert_eq!(
            bits(&resample_channel(&all, key, &coarse).unwrap()),
            bits(&resample(&all, &coarse))
        );
        assert!(exact_channel(&Sine, q::SLIDE.key, &fine).is_none());
        assert!(resample_channel(&all, q::SLIDE.key, &coarse).is_none());
        let mut cache = None;
        let first = exact_channel_cached(&mut cache, &Sine, key, &fine)
            .unwrap()
            .clone();
        assert_eq!(bits(&first), bits(&all));
        let other = exact_channel_cached(&mut cache, &Sine, key, &coarse).unwrap();
        assert_eq!(other.time, coarse);
        assert_eq!(
            bits(other),
            bits(&rockslide_reference::sample(&Sine, &coarse))
        );
    }

    #[test]
    fn ladder_halves() {
        let l = ladder(0.02, 2.0, 4);
        assert_eq!(l, vec![0.02, 0.01, 0.005, 0.0025]);
    }

    #[test]
    fn orders_of_a_second_order_error() {
        let pts: Vec<(f64, f64)> = [0.1, 0.05, 0.025]
            .iter()
            .map(|&h| (h, 3.0 * h * h))
            .collect();
        for p in local_orders(&pts) {
            assert!((p.unwrap() - 2.0).abs() < 1e-12);
        }
        assert!((fitted_order(&pts).unwrap() - 2.0).abs() < 1e-12);
    }

    /// f(h) = 1 + h² with the order given (p = 2): the two finest solutions give f(0) = 1;
    /// the asymptotic order ignores the coarse rungs (here a plateau before the range).
    #[test]
    fn richardson_at_a_given_order_and_the_asymptotic_fit() {
        let f = |h: f64| 1.0 + h * h;
        let r = richardson_at_order(f(0.1), f(0.2), 2.0, 2.0).unwrap();
        assert!((r.extrapolated - 1.0).abs() < 1e-12);
        assert!((r.gci - 1.25 * 0.03 / 1.01 / 3.0).abs() < 1e-15);
        assert!(richardson_at_order(1.0, 1.1, 2.0, f64::NAN).is_none());
        let pts: Vec<(f64, f64)> = [0.8, 0.4, 0.2, 0.1, 0.05, 0.025]
            .iter()
            .map(|&h| (h, if h > 0.3 { 0.05 } else { h * h }))
            .collect();
        assert!((asymptotic_order(&pts).unwrap() - 2.0).abs() < 1e-12);
        assert!(
            fitted_order(&pts).unwrap() < 1.9,
            "the whole ladder is pulled down"
        );
    }

    /// f(h) = 1 + h²: from h = 0.1, 0.2, 0.4 Richardson recovers p = 2 and f(0) = 1.
    #[test]
    fn richardson_recovers_the_limit() {
        let f = |h: f64| 1.0 + h * h;
        let r = richardson(f(0.1), f(0.2), f(0.4), 2.0).unwrap();
        assert!((r.order - 2.0).abs() < 1e-12);
        assert!((r.extrapolated - 1.0).abs() < 1e-12);
        assert!(richardson(1.0, 1.0, 2.0, 2.0).is_none());
    }
}

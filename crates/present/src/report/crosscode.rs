//! The cross-code matrix: how far each participant (the reference and every completed
//! engine run) is from each other one, as the paper compares ANSYS with SAP2000 — on the
//! response quantities (peaks in %, event times in ms) and on the whole history of the
//! relative displacement (normalised RMS difference). For scenes that lift off, the history
//! difference is also given up to the first full lift-off, since the airborne phase and the
//! landing amplify small differences (the paper's RPEPO, docs/findings.md).

use rockslide_core::trace::Trace;
use rockslide_verify::analysis::{QUANTITY_KEYS, Responses, discrepancy_percent, quantity_def};
use rockslide_verify::suite::CaseResult;

/// The channel whose whole history is compared.
pub(crate) const HISTORY_KEY: &str = "rel_disp";
/// The quantity of the peak matrix.
pub(crate) const PEAK_KEY: &str = "peak_relative_displacement";
/// The quantity that marks the first full lift-off.
pub(crate) const LIFTOFF_KEY: &str = "first_liftoff";

/// One side of a comparison.
pub(crate) struct Participant<'a> {
    /// Column label (`reference (exact)`, `engine/variant`).
    pub label: String,
    /// Its time histories.
    pub trace: &'a Trace,
    /// Its response quantities.
    pub responses: &'a Responses,
}

/// The reference (first, when there is one) and every run that completed.
pub(crate) fn participants(r: &CaseResult) -> Vec<Participant<'_>> {
    let mut out = Vec::new();
    if let Ok(reference) = &r.reference {
        out.push(Participant {
            label: format!("reference ({})", reference.solution.name()),
            trace: &reference.trace,
            responses: &reference.responses,
        });
    }
    for (run, resp) in r.runs.iter().zip(&r.run_responses) {
        if run.status.completed() {
            out.push(Participant {
                label: run.label(),
                trace: &run.trace,
                responses: resp,
            });
        }
    }
    out
}

/// Pairwise differences of two participants `a` (the basis) and `b`.
#[derive(Debug, Clone)]
pub(crate) struct Pair {
    /// Index of the basis participant.
    pub a: usize,
    /// Index of the compared participant.
    pub b: usize,
    /// Per `CrossCode::keys`: 100·(b/a − 1) for values, (b − a) in ms for event times.
    pub entries: Vec<Option<f64>>,
    /// Normalised RMS difference of the whole relative-displacement history.
    pub nrms: Option<f64>,
    /// The same up to the first full lift-off of either (scenes that lift off).
    pub nrms_to_liftoff: Option<f64>,
}

/// The cross-code comparison of one case.
#[derive(Debug, Clone)]
pub(crate) struct CrossCode {
    /// Participant labels, matrix order.
    pub labels: Vec<String>,
    /// Quantity keys of the pair entries.
    pub keys: Vec<&'static str>,
    /// `nrms[i][j]`: RMS of (x_i − x_j) / peak |x_j| (diagonal `None`).
    pub nrms: Vec<Vec<Option<f64>>>,
    /// `peak[i][j]`: 100·(peak_i / peak_j − 1) of the peak relative displacement.
    pub peak: Vec<Vec<Option<f64>>>,
    /// Every unordered pair, basis first.
    pub pairs: Vec<Pair>,
    /// Whether any participant lifts off.
    pub lifts_off: bool,
}

/// RMS of (a − b) over the times of the coarser of the two traces, the finer one linearly
/// interpolated there, up to `until`; normalised by the peak |b| over the same window.
pub(crate) fn normalised_rms(a: &Trace, b: &Trace, key: &str, until: f64) -> Option<f64> {
    let (coarse, fine, coarse_is_a) = if a.len() <= b.len() {
        (a, b, true)
    } else {
        (b, a, false)
    };
    let col = coarse.column(key)?;
    let fine_col = fine.column(key)?;
    let (ft, m) = (&fine.time, fine.time.len());
    if m == 0 {
        return None;
    }
    let (mut sum, mut n, mut peak_b) = (0.0, 0usize, 0.0_f64);
    // `fine` linearly interpolated at each coarse time, as `Trace::sample` does, with one
    // cursor walking both time axes (they ascend) instead of a search per row
    let mut j = 0;
    for (i, &t) in coarse.time.iter().enumerate() {
        if t > until {
            break;
        }
        while j < m && ft[j] <= t {
            j += 1;
        }
        let other = match j {
            0 => fine_col[0],
            j if j >= m => fine_col[m - 1],
            j => {
                let (t0, t1) = (ft[j - 1], ft[j]);
                let f = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
                fine_col[j - 1] + f * (fine_col[j] - fine_col[j - 1])
            }
        };
        let (va, vb) = if coarse_is_a {
            (col[i], other)
        } else {
            (other, col[i])
        };
        sum += (va - vb) * (va - vb);
        peak_b = peak_b.max(vb.abs());
        n += 1;
    }
    (n > 0 && peak_b > 0.0).then(|| (sum / n as f64).sqrt() / peak_b)
}

/// Compare every participant with every other one.
pub(crate) fn cross_code(r: &CaseResult) -> CrossCode {
    let ps = participants(r);
    let n = ps.len();
    let keys: Vec<&'static str> = QUANTITY_KEYS
        .iter()
        .copied()
        .filter(|k| ps.iter().filter(|p| p.responses.contains_key(k)).count() >= 2)
        .collect();
    let lifts_off = ps.iter().any(|p| p.responses.contains_key(LIFTOFF_KEY));
    let mut nrms = vec![vec![None; n]; n];
    let mut peak = vec![vec![None; n]; n];
    for i in 0..n {
        for j in 0..n {
            if i == j {
                continue;
            }
            nrms[i][j] = normalised_rms(ps[i].trace, ps[j].trace, HISTORY_KEY, f64::INFINITY);
            peak[i][j] = ps[i]
                .responses
                .get(PEAK_KEY)
                .zip(ps[j].responses.get(PEAK_KEY))
                .and_then(|(v, b)| discrepancy_percent(*v, *b));
        }
    }
    let mut pairs = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            let entries = keys
                .iter()
                .map(|k| {
                    let (va, vb) = (ps[a].responses.get(k)?, ps[b].responses.get(k)?);
                    if quantity_def(k).is_some_and(|d| d.is_time()) {
                        Some((vb - va) * 1e3)
                    } else {
                        discrepancy_percent(*vb, *va)
                    }
                })
                .collect();
            let liftoff = [a, b]
                .iter()
                .filter_map(|&i| ps[i].responses.get(LIFTOFF_KEY).copied())
                .fold(f64::INFINITY, f64::min);
            pairs.push(Pair {
                a,
                b,
                entries,
                nrms: nrms[b][a],
                nrms_to_liftoff: (lifts_off && liftoff.is_finite())
                    .then(|| normalised_rms(ps[b].trace, ps[a].trace, HISTORY_KEY, liftoff))
                    .flatten(),
            });
        }
    }
    CrossCode {
        labels: ps.into_iter().map(|p| p.label).collect(),
        keys,
        nrms,
        peak,
        pairs,
        lifts_off,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::trace::q;

    fn line(times: &[f64], f: impl Fn(f64) -> f64) -> Trace {
        let mut t = Trace::with_channels(&[&q::REL_DISP], times.len());
        for &x in times {
            t.push(x, &[f(x)]);
        }
        t
    }

    #[test]
    fn rms_of_a_constant_offset_is_the_offset_over_the_peak() {
        // b = 2 + t on [0, 1] (peak 3), a = b + 0.3 sampled coarsely: RMS Δ = 0.3 exactly,
        // because the fine trace is linear and interpolates without error.
        let fine: Vec<f64> = (0..=100).map(|i| i as f64 / 100.0).collect();
        let coarse: Vec<f64> = (0..=10).map(|i| i as f64 / 10.0).collect();
        let b = line(&fine, |t| 2.0 + t);
        let a = line(&coarse, |t| 2.3 + t);
        let r = normalised_rms(&a, &b, "rel_disp", f64::INFINITY).unwrap();
        assert!((r - 0.1).abs() < 1e-12, "{r}");
        // Windowed to t ≤ 0.5: peak |b| = 2.5.
        let r = normalised_rms(&a, &b, "rel_disp", 0.5).unwrap();
        assert!((r - 0.3 / 2.5).abs() < 1e-12, "{r}");
    }

    #[test]
    fn the_cursor_interpolates_as_trace_sample_does_bit_for_bit() {
        // irregular fine times (a repeated time, coarse times before, between and after
        // them): the RMS from the cursor equals the one from `Trace::sample` per row
        let fine = line(&[0.1, 0.2, 0.25, 0.25, 0.4, 0.6, 0.77, 0.8, 0.9], |t| {
            (7.0 * t).sin()
        });
        let coarse = line(&[0.0, 0.1, 0.25, 0.3, 0.95, 1.2], |t| t * t);
        let mut sum = 0.0;
        for (i, &t) in coarse.time.iter().enumerate() {
            let d = coarse.columns[0][i] - fine.sample("rel_disp", t).unwrap();
            sum += d * d;
        }
        let peak = fine.columns[0].iter().fold(0.0_f64, |p, v| p.max(v.abs()));
        let sample_peak = coarse
            .time
            .iter()
            .map(|&t| fine.sample("rel_disp", t).unwrap().abs())
            .fold(0.0, f64::max);
        assert!(sample_peak <= peak);
        let expected = (sum / 6.0).sqrt() / sample_peak;
        let r = normalised_rms(&coarse, &fine, "rel_disp", f64::INFINITY).unwrap();
        assert_eq!(r.to_bits(), expected.to_bits());
    }
}

//! Response quantities in the paper's style — peak relative displacement, peak, minimum
//! and residual sliding, slip start and end, peak resistance, and for rocking bodies peak
//! rotation, uplift and centre-of-mass motion — read off any trace.

use std::collections::BTreeMap;

use rockslide_core::response::{DEFS, Reading};
use rockslide_core::trace::Trace;

/// Response quantities of one trace, by key (only those its channels allow).
pub type Responses = BTreeMap<&'static str, f64>;

/// Read every applicable response quantity off `trace`: one pass of the slide rates per
/// slide column and one search of sign changes per column, whatever number of quantities
/// read them ([`Passes`]).
pub fn responses(trace: &Trace) -> Responses {
    let mut out = Responses::new();
    let mut passes = Passes::default();
    for d in DEFS {
        let Some(col) = trace.column(d.channel.key) else {
            continue;
        };
        if col.is_empty() {
            continue;
        }
        let value = match d.reading {
            Reading::PeakAbs => Some(passes.extremes(d.channel.key, col).peak_abs),
            Reading::SignedPeak => Some(passes.extremes(d.channel.key, col).signed_peak),
            Reading::Max => Some(passes.extremes(d.channel.key, col).max),
            Reading::Min => Some(passes.extremes(d.channel.key, col).min),
            Reading::Last => col.last().copied(),
            Reading::SlipStart => passes
                .slip_window(&trace.time, d.channel.key, col)
                .map(|w| w.0),
            Reading::SlipEnd => passes
                .slip_window(&trace.time, d.channel.key, col)
                .map(|w| w.1),
            Reading::TotalVariation => Some(total_variation(col)),
            Reading::SlipEpisodes => {
                let y = d.plan_partner().and_then(|y| trace.column(y.key));
                let slipping = passes.slipping(&trace.time, d.channel.key, col, y);
                Some(episodes(slipping, col, y) as f64)
            }
            Reading::FirstZero => col.iter().position(|&c| c <= 0.0).map(|i| trace.time[i]),
            Reading::FirstCrossing => passes
                .sign_changes(&trace.time, d.channel.key, col)
                .first()
                .copied(),
            Reading::SecondCrossing => passes
                .sign_changes(&trace.time, d.channel.key, col)
                .get(1)
                .copied(),
            Reading::PeakAbsAfterFirstCrossing => {
                let c = passes.sign_changes(&trace.time, d.channel.key, col);
                c.first().map(|&t0| {
                    let t1 = c.get(1).copied().unwrap_or(f64::INFINITY);
                    trace
                        .time
                        .iter()
                        .zip(col)
                        .filter(|(t, _)| **t > t0 && **t < t1)
                        .fold(0.0_f64, |m, (_, x)| m.max(x.abs()))
                })
            }
        };
        if let Some(v) = value {
            out.insert(d.key, v);
        }
    }
    out
}

/// The passes over a column that several response quantities read, each made once per
/// column: its extremes ([`Extremes`], one loop for the four), the slipping steps (slip episodes, and the slip window, which is the first and
/// last of the slipping steps of the slide alone) and the sign changes (first and second
/// crossings, the peak between them). The same numbers as a pass per quantity, bit for
/// bit (the direct definitions `slip_episodes` and `slip_window` are kept for the tests
/// below that pin them).
#[derive(Default)]
struct Passes {
    /// (column key, planar), the slipping steps.
    slipping: Vec<((&'static str, bool), Vec<bool>)>,
    /// Column key, its sign changes.
    crossings: Vec<(&'static str, Vec<f64>)>,
    /// Column key, its extremes.
    extremes: Vec<(&'static str, Extremes)>,
}

/// A column's smallest and largest value, largest magnitude, and the value of largest
/// magnitude with its sign (the first one on a tie; 0 for an all-zero or empty column):
/// four folds in one loop, each the fold a pass of its own would make, in the same order.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Extremes {
    min: f64,
    max: f64,
    peak_abs: f64,
    signed_peak: f64,
}

impl Extremes {
    fn of(col: &[f64]) -> Self {
        let mut e = Extremes {
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            peak_abs: 0.0,
            signed_peak: 0.0,
        };
        for &x in col {
            e.min = e.min.min(x);
            e.max = e.max.max(x);
            e.peak_abs = e.peak_abs.max(x.abs());
            if x.abs() > e.signed_peak.abs() {
                e.signed_peak = x;
            }
        }
        e
    }
}

impl Passes {
    /// [`Extremes`] of column `key`, computed once.
    fn extremes(&mut self, key: &'static str, col: &[f64]) -> Extremes {
        *once(&mut self.extremes, key, || Extremes::of(col))
    }

    /// [`slipping_steps`] of column `key` (planar with `slide_y`), computed once.
    fn slipping(
        &mut self,
        time: &[f64],
        key: &'static str,
        slide: &[f64],
        slide_y: Option<&[f64]>,
    ) -> &[bool] {
        once(&mut self.slipping, (key, slide_y.is_some()), || {
            slipping_steps(time, slide, slide_y)
        })
        .as_slice()
    }

    /// The slip window of column `key` ([`window`]), off its (non-planar) slipping steps.
    fn slip_window(
        &mut self,
        time: &[f64],
        key: &'static str,
        slide: &[f64],
    ) -> Option<(f64, f64)> {
        window(time, self.slipping(time, key, slide, None))
    }

    /// [`sign_changes`] of column `key`, computed once.
    fn sign_changes(&mut self, time: &[f64], key: &'static str, col: &[f64]) -> &[f64] {
        once(&mut self.crossings, key, || sign_changes(time, col)).as_slice()
    }
}

/// The value `kept` holds for `key`, made by `make` and kept the first time it is asked.
fn once<K: PartialEq, V>(kept: &mut Vec<(K, V)>, key: K, make: impl FnOnce() -> V) -> &V {
    let at = match kept.iter().position(|(k, _)| *k == key) {
        Some(at) => at,
        None => {
            kept.push((key, make()));
            kept.len() - 1
        }
    };
    &kept[at].1
}

/// First and last instants of slipping, detected from the slip *rate* (never from
/// |R| = Ru: an undamped oscillator that stopped sliding touches the limit every half
/// period), off the slipping steps of the slide alone ([`slipping_steps`] without
/// `slide_y`): the start of the first slipping step, the end of the last.
fn window(time: &[f64], slipping: &[bool]) -> Option<(f64, f64)> {
    let first = slipping.iter().position(|&s| s)?;
    let last = slipping.iter().rposition(|&s| s)?;
    Some((time[first], time[last + 1]))
}

/// Least slide of a slip episode, m: a run of slipping steps counts as an episode when
/// the distance slid in it (Σ|Δslide|, or Σ|(Δslide, Δslide_y)| along the slip path)
/// exceeds 1 µm. Below it a contact is in its pre-sliding range — the elastic
/// deformation of the asperities before gross slip, micrometres for engineering surfaces
/// (Courtney-Pratt & Eisner 1957; Rabinowicz's critical slip distance) — so no physical
/// slip is resolved, while a discrete model's grazes of the friction limit (slips of
/// 0.1 µm and less where the exact solution touches the limit without slipping) stay out.
/// Every engine's trace and the exact reference's are counted with it.
pub const EPISODE_MIN_SLIP: f64 = 1e-6;

/// Slide of one step: |Δslide|, or |(Δslide, Δslide_y)| on a plan trace.
pub(super) fn step_slide(dx: f64, dy: Option<f64>) -> f64 {
    match dy {
        None => dx.abs(),
        Some(dy) => dx.hypot(dy),
    }
}

/// Number of slip episodes: maximal runs of slipping steps ([`slipping_steps`]; on a plan
/// trace the planar rate along the slip path, so an episode whose slip turns across x is
/// one episode) in which the body slides more than [`EPISODE_MIN_SLIP`]. Read the same way
/// off every engine's trace; a stick shorter than one output step joins its neighbours.
fn episodes(slipping: &[bool], slide: &[f64], slide_y: Option<&[f64]>) -> usize {
    let mut count = 0;
    let mut slid: Option<f64> = None;
    for (i, &s) in slipping.iter().enumerate() {
        if s {
            let dy = slide_y.map(|y| y[i + 1] - y[i]);
            *slid.get_or_insert(0.0) += step_slide(slide[i + 1] - slide[i], dy);
        } else if let Some(d) = slid.take() {
            count += usize::from(d > EPISODE_MIN_SLIP);
        }
    }
    count + slid.map_or(0, |d| usize::from(d > EPISODE_MIN_SLIP))
}

/// The value with the largest magnitude, with its sign (the first one on a tie; 0 for an
/// all-zero or empty column).
#[cfg(test)]
fn signed_peak(col: &[f64]) -> f64 {
    col.iter()
        .copied()
        .fold(0.0_f64, |m, x| if x.abs() > m.abs() { x } else { m })
}

/// The slip window ([`window`]) read directly: a step slips when its slide increment
/// exceeds 1e-3 of the largest increment of the run; the start is the beginning of the
/// first slipping step, the end the end of the last.
#[cfg(test)]
fn slip_window(time: &[f64], slide: &[f64]) -> Option<(f64, f64)> {
    let rate = |i: usize| ((slide[i] - slide[i - 1]) / (time[i] - time[i - 1])).abs();
    let peak = (1..slide.len()).map(rate).fold(0.0_f64, f64::max);
    if peak.is_nan() || peak <= 0.0 {
        return None;
    }
    let threshold = 1e-3 * peak;
    let first = (1..slide.len()).find(|&i| rate(i) > threshold)?;
    let last = (1..slide.len()).rev().find(|&i| rate(i) > threshold)?;
    Some((time[first - 1], time[last]))
}

/// Slide rate of one step of length `dt` whose slide changed by `dx` (and by `dy` along y
/// on a plan trace): |Δx|/Δt, or the planar rate |(Δx, Δy)|/Δt along the slip path.
/// With Δy = 0 the two are the same number bit for bit (`hypot(Δx, 0)` is |Δx| exactly).
pub(super) fn slide_rate(dt: f64, dx: f64, dy: Option<f64>) -> f64 {
    match dy {
        None => (dx / dt).abs(),
        Some(dy) => dx.hypot(dy) / dt,
    }
}

/// Whether each step `i` (from sample i − 1 to i, `i ≥ 1`) slips: its slide rate
/// ([`slide_rate`], planar when `slide_y` is given) exceeds 1e-3 of the run's largest, the
/// threshold of the slip window ([`window`]). Empty when the slide never changes.
fn slipping_steps(time: &[f64], slide: &[f64], slide_y: Option<&[f64]>) -> Vec<bool> {
    let rate = |i: usize| {
        let dy = slide_y.map(|y| y[i] - y[i - 1]);
        slide_rate(time[i] - time[i - 1], slide[i] - slide[i - 1], dy)
    };
    // each step's rate once: the peak and the comparisons read the same numbers
    let rates: Vec<f64> = (1..slide.len()).map(rate).collect();
    let peak = rates.iter().copied().fold(0.0_f64, f64::max);
    if peak.is_nan() || peak <= 0.0 {
        return Vec::new();
    }
    let threshold = 1e-3 * peak;
    rates.iter().map(|&r| r > threshold).collect()
}

/// Number of slip episodes read off a slide history: maximal runs of slipping steps
/// (rate above 1e-3 of the largest, as for the slip window). On a plan trace (`slide_y` given)
/// the rate is the planar one along the slip path, so an episode whose slip turns across
/// x is one episode. Read the same way off every engine's trace; a stick shorter than one
/// output step joins its neighbours.
#[cfg(test)]
fn slip_episodes(time: &[f64], slide: &[f64], slide_y: Option<&[f64]>) -> usize {
    episodes(&slipping_steps(time, slide, slide_y), slide, slide_y)
}

/// Sum of |increments| of a channel: on the slide, the total distance slid both ways.
pub fn total_variation(col: &[f64]) -> f64 {
    col.windows(2).map(|w| (w[1] - w[0]).abs()).sum()
}

/// Times at which a channel changes sign, linearly interpolated. Samples smaller than
/// 1e-3 of the channel's peak are ignored (a block resting flat has rotation noise).
pub fn sign_changes(time: &[f64], col: &[f64]) -> Vec<f64> {
    let peak = col.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let floor = 1e-3 * peak;
    let mut out = Vec::new();
    let mut last: Option<(usize, f64)> = None;
    for (i, &x) in col.iter().enumerate() {
        if x.abs() <= floor {
            continue;
        }
        if let Some((j, s)) = last {
            if x.signum() != s {
                // the change lies between samples j and i: find the raw crossing
                let k = (j..i)
                    .find(|&k| col[k + 1].signum() != s || col[k + 1] == 0.0)
                    .unwrap_or(i - 1);
                let (x0, x1) = (col[k], col[k + 1]);
                let f = if x1 != x0 { x0 / (x0 - x1) } else { 0.0 };
                out.push(time[k] + f * (time[k + 1] - time[k]));
            }
        }
        last = Some((i, x.signum()));
    }
    out
}

/// Discrepancy in percent, 100·(value/basis − 1) (the SAP2000 verification convention);
/// `None` when the basis is zero.
pub fn discrepancy_percent(value: f64, basis: f64) -> Option<f64> {
    (basis != 0.0).then(|| 100.0 * (value / basis - 1.0))
}

/// Whole-history difference of channel `key` between a run and a basis sampled at the
/// same times: (max |Δ|, RMS Δ), both normalised by the basis's peak |value|.
pub fn history_difference(run: &Trace, basis: &Trace, key: &str) -> Option<(f64, f64)> {
    let a = run.column(key)?;
    let peak = basis
        .column(key)?
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    if peak == 0.0 || run.is_empty() {
        return None;
    }
    let column = basis.column(key)?;
    let mut basis_at = Interpolator::new(&basis.time, column)?;
    let (mut max, mut sum) = (0.0_f64, 0.0);
    for (i, &t) in run.time.iter().enumerate() {
        let b = basis_at.value(t);
        let d = a[i] - b;
        max = max.max(d.abs());
        sum += d * d;
    }
    Some((max / peak, (sum / run.len() as f64).sqrt() / peak))
}

/// [`Trace::sample`] of one column at ascending times, without the search per call: it
/// keeps the row it found last and walks forward from it (a time earlier than the last one
/// searches again), so sampling n times costs O(n + rows) instead of O(n log rows).
/// Values are those of [`Trace::sample`] bit for bit: the same row, the same formula.
struct Interpolator<'a> {
    time: &'a [f64],
    column: &'a [f64],
    /// First row whose time is after the last time asked (`partition_point(x ≤ t)`).
    after: usize,
}

impl<'a> Interpolator<'a> {
    /// `None` when there is no row.
    fn new(time: &'a [f64], column: &'a [f64]) -> Option<Self> {
        (!time.is_empty()).then_some(Self {
            time,
            column,
            after: 0,
        })
    }

    fn value(&mut self, t: f64) -> f64 {
        let (time, col) = (self.time, self.column);
        let n = time.len();
        if self.after > 0 && (time[self.after - 1] > t || t.is_nan()) {
            self.after = time.partition_point(|&x| x <= t);
        } else {
            while self.after < n && time[self.after] <= t {
                self.after += 1;
            }
        }
        match self.after {
            0 => col[0],
            i if i >= n => col[n - 1],
            i => {
                let (t0, t1) = (time[i - 1], time[i]);
                let f = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
                col[i - 1] + f * (col[i] - col[i - 1])
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slip_window_ignores_a_constant_slide() {
        let t = [0.0, 0.1, 0.2, 0.3, 0.4];
        assert_eq!(slip_window(&t, &[0.0; 5]), None);
        let w = slip_window(&t, &[0.0, 0.0, 1.0, 2.0, 2.0]).unwrap();
        assert_eq!(w, (0.1, 0.3));
    }

    #[test]
    fn slip_episodes_count_runs_of_slipping_steps() {
        let t = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
        assert_eq!(slip_episodes(&t, &[0.0; 7], None), 0);
        // slide up, stick, slide back: two episodes, 1 + 0.5 m slid, 0.5 m net
        let s = [0.0, 0.5, 1.0, 1.0, 1.0, 0.5, 0.5];
        assert_eq!(slip_episodes(&t, &s, None), 2);
        assert!((total_variation(&s) - 1.5).abs() < 1e-15);
        // a step below 1e-3 of the peak rate is stuck (creep), not an episode
        let creep = [0.0, 1.0, 1.0, 1.0 + 1e-4, 1.0 + 1e-4, 2.0, 2.0];
        assert_eq!(slip_episodes(&t, &creep, None), 2);
        // a run that slides no more than EPISODE_MIN_SLIP (1 µm) in all is a graze of the
        // friction limit, not an episode: 0.6 + 0.4 µm is not counted, 0.6 + 0.6 µm is
        let graze = [0.0, 0.6e-6, 1.0e-6, 1.0e-6, 1.0e-6, 1.0e-6, 1.0e-6];
        assert_eq!(slip_episodes(&t, &graze, None), 0);
        let slip = [0.0, 0.6e-6, 1.2e-6, 1.2e-6, 1.2e-6, 1.2e-6, 1.2e-6];
        assert_eq!(slip_episodes(&t, &slip, None), 1);
        // … between two slides (0.1 mm each way; the graze's rate is above 1e-3 of theirs)
        let s = [0.0, 1e-4, 1e-4, 1e-4 + 5e-7, 1e-4 + 5e-7, 0.0, 0.0];
        assert_eq!(slip_episodes(&t, &s, None), 2);
    }

    /// Slip around a regular octagon at constant speed (a circle sampled at 8 points a
    /// turn, vertices at 22.5° + k·45°): every step slides one chord, so the planar rate is
    /// constant and two turns are one episode; the x component's rate is exactly zero on
    /// the two steps a turn that cross x (from −22.5° to 22.5° and from 157.5° to 202.5°:
    /// the same x at both ends), so x alone counts two runs a turn. Then a stick (two
    /// steps) and half a turn more: one episode along the path, one more run of x (its
    /// steps 0→1, 1→2, 2→3 slide, 3→4 crosses x).
    #[test]
    fn slip_episodes_count_along_the_slip_path_on_a_plan_trace() {
        let (c, s) = (
            std::f64::consts::FRAC_PI_8.cos(),
            std::f64::consts::FRAC_PI_8.sin(),
        );
        let vertex_x = [c, s, -s, -c, -c, -s, s, c];
        let vertex_y = [s, c, c, s, -s, -c, -c, -s];
        // two turns (vertices 0..=16), a stick of two steps, then vertices 1..=4
        let mut path: Vec<usize> = (0..=16).map(|k| k % 8).collect();
        path.extend([0, 0, 1, 2, 3, 4]);
        let x: Vec<f64> = path.iter().map(|&k| vertex_x[k] - c).collect();
        let y: Vec<f64> = path.iter().map(|&k| vertex_y[k] - s).collect();
        let t: Vec<f64> = (0..path.len()).map(|i| 0.1 * i as f64).collect();
        assert_eq!(slip_episodes(&t, &x, Some(&y)), 2);
        assert_eq!(slip_episodes(&t, &x, None), 5, "2 runs a turn, then 1");
        // the planar rate of a step along x alone is |Δx|/Δt bit for bit
        for (dx, dt) in [(0.3, 0.1), (-1e-9, 7e-4), (2.5e3, 3.0)] {
            assert_eq!(
                slide_rate(dt, dx, Some(0.0)).to_bits(),
                slide_rate(dt, dx, None).to_bits()
            );
        }
    }

    /// The slip window off the slipping steps equals [`slip_window`]'s own passes, bit for
    /// bit, on slides that stick, creep, slip once or twice, and never move.
    #[test]
    fn the_window_off_the_slipping_steps_is_slip_window() {
        let t: Vec<f64> = (0..9)
            .map(|i| 0.1 * f64::from(i) + 1e-3 * f64::from(i * i))
            .collect();
        let slides: [[f64; 9]; 5] = [
            [0.0; 9],
            [0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0],
            [0.0, 0.5, 1.0, 1.0, 1.0, 0.5, 0.5, 0.5, 0.25],
            [0.0, 1.0, 1.0, 1.0 + 1e-4, 1.0 + 1e-4, 2.0, 2.0, 2.0, 2.0],
            [3.0, 3.0, 3.0, 3.0, 3.0, 3.0, 3.0, 3.0, 3.5],
        ];
        for s in slides {
            let mut passes = Passes::default();
            let w = passes.slip_window(&t, "slide", &s);
            assert_eq!(w, slip_window(&t, &s), "{s:?}");
            let bits = |w: Option<(f64, f64)>| w.map(|(a, b)| (a.to_bits(), b.to_bits()));
            assert_eq!(bits(w), bits(slip_window(&t, &s)));
            // the same pass read again, and the episodes off it
            assert_eq!(passes.slip_window(&t, "slide", &s), w);
            assert_eq!(
                episodes(passes.slipping(&t, "slide", &s, None), &s, None),
                slip_episodes(&t, &s, None)
            );
        }
    }

    /// The four extremes of one loop are the folds of a pass each, bit for bit, with
    /// ties, signed zeros, a NaN and infinities among the values.
    #[test]
    fn the_extremes_of_one_loop_are_the_four_folds() {
        let columns: [&[f64]; 6] = [
            &[],
            &[0.0, -0.0, 0.0],
            &[1.0, -3.0, 3.0, 2.5, -3.0],
            &[-1e-300, 5e-324, -7.25, 7.0],
            &[1.0, f64::NAN, -2.0, 0.5],
            &[f64::NEG_INFINITY, 4.0, f64::INFINITY],
        ];
        for col in columns {
            let e = Extremes::of(col);
            let bits = |x: f64| x.to_bits();
            let peak = col.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            let max = col.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let min = col.iter().copied().fold(f64::INFINITY, f64::min);
            assert_eq!(bits(e.peak_abs), bits(peak), "{col:?}");
            assert_eq!(bits(e.max), bits(max), "{col:?}");
            assert_eq!(bits(e.min), bits(min), "{col:?}");
            assert_eq!(bits(e.signed_peak), bits(signed_peak(col)), "{col:?}");
        }
    }

    #[test]
    fn the_interpolator_gives_trace_sample_bit_for_bit() {
        let mut basis = Trace::with_channels(&[&rockslide_core::trace::q::REL_DISP], 50);
        for i in 0..50 {
            let t = 0.013 * i as f64;
            basis.push(t, &[(7.0 * t).sin()]);
        }
        let col = basis.column("rel_disp").unwrap();
        let mut at = Interpolator::new(&basis.time, col).unwrap();
        // ascending, repeated, before the start, past the end, then back in time
        let times = [
            -1.0, 0.0, 0.0, 0.0065, 0.013, 0.2, 0.2001, 0.637, 0.7, 9.0, 0.1, 0.3,
        ];
        for t in times {
            assert_eq!(
                at.value(t).to_bits(),
                basis.sample("rel_disp", t).unwrap().to_bits(),
                "t = {t}"
            );
        }
    }

    #[test]
    fn discrepancy_follows_the_sap2000_convention() {
        assert!((discrepancy_percent(1.05, 1.0).unwrap() - 5.0).abs() < 1e-12);
        assert_eq!(discrepancy_percent(1.0, 0.0), None);
    }
}

//! The reference of a case: its exact or closed-form solution sampled on a fine uniform
//! grid ([`fine_grid`]) for the response quantities, and again where it is compared (every
//! run's output times and the solution's exact instants) for the files and figures.

use crate::analysis::{Responses, quantity_def, responses};
use rockslide_core::case::Case;
use rockslide_core::trace::{Quantity, Trace};
use rockslide_engine_api::Run;
use rockslide_reference::ExactSolution;

/// The reference of a case, sampled, with its response quantities.
pub struct ReferenceResult {
    /// The solution, for sampling at other times.
    pub solution: Box<dyn ExactSolution>,
    /// Sampled on a fine uniform grid, in memory only: response quantities, the energy
    /// audit and history differences read it.
    pub trace: Trace,
    /// Sampled where it is compared — every run's output times and the exact event times —
    /// for the files and figures ([`ReferenceResult::at_compared_times`]); until then, no
    /// rows (the solution's channels).
    pub output: Trace,
    /// Response quantities (exact event times where the solution knows them).
    pub responses: Responses,
    /// The exact instants the solution knows (slip start and end, lift-off, impacts),
    /// read once off [`ExactSolution::exact_quantities`].
    event_times: Vec<f64>,
}

impl ReferenceResult {
    /// A reference from its solution, fine trace and the response quantities read off
    /// that trace, with no output rows yet: the solution's exact quantities, read once,
    /// replace the readings they also give (the slip episodes too: counted from the
    /// solution's own located slips, so two slips parted by a stick shorter than the fine
    /// trace's step stay two), and its exact instants are kept as the event times.
    pub(crate) fn from_parts(
        solution: Box<dyn ExactSolution>,
        trace: Trace,
        mut responses: Responses,
    ) -> Self {
        let mut event_times = Vec::new();
        for (k, v) in solution.exact_quantities() {
            if quantity_def(k).is_some_and(|d| d.is_time()) {
                event_times.push(v);
            }
            responses.insert(k, v);
        }
        ReferenceResult {
            solution,
            output: Trace::with_channels(&trace.channels, 0),
            trace,
            responses,
            event_times,
        }
    }

    /// Sample the output trace at the union of the runs' output times and the exact
    /// event times (what the CSV, the MCAP file and the figures show): no fixed fine grid.
    /// A time that is also a row of the fine trace (the same bits) takes that row — the
    /// solution is evaluated pointwise, so the same values — and only the others are
    /// evaluated. Without any such time (no run), the fine trace.
    pub fn at_compared_times(&mut self, runs: &[Run]) {
        let mut times: Vec<f64> = runs
            .iter()
            .flat_map(|r| r.trace.time.iter().copied())
            .chain(self.event_times.iter().copied())
            .filter(|t| t.is_finite())
            .collect();
        if times.is_empty() {
            self.output = self.trace.clone();
            return;
        }
        times.sort_by(f64::total_cmp);
        times.dedup();
        self.output = self.sampled_reusing_fine_rows(&times);
    }

    /// The solution at `times` (ascending): the fine trace's row where a time is one of
    /// its rows bit for bit, the solution evaluated at the others.
    fn sampled_reusing_fine_rows(&self, times: &[f64]) -> Trace {
        let fine = &self.trace;
        let rows = rows_of(&fine.time, times);
        let missing: Vec<f64> = times
            .iter()
            .zip(&rows)
            .filter(|(_, row)| row.is_none())
            .map(|(&t, _)| t)
            .collect();
        // (a solution samples the same channels at any time: the fine trace's)
        let fresh = rockslide_reference::sample(self.solution.as_ref(), &missing);
        let mut out = Trace::with_channels(&fine.channels, times.len());
        out.time.extend_from_slice(times);
        let mut next_fresh = 0;
        for row in rows {
            let (source, i) = match row {
                Some(i) => (fine, i),
                None => {
                    next_fresh += 1;
                    (&fresh, next_fresh - 1)
                }
            };
            for (column, from) in out.columns.iter_mut().zip(&source.columns) {
                column.push(from[i]);
            }
        }
        out
    }

    /// The reference at `times` (a run's output times): the rows of the output trace,
    /// which was sampled at every run's times, when each time is there (the same values:
    /// the solution is evaluated pointwise); sampled anew otherwise.
    pub fn at_times(&self, times: &[f64]) -> Trace {
        self.at_times_of(times, &self.output.channels)
    }

    /// [`Self::at_times`] of only the `channels` asked (those the output trace has): what a
    /// history difference reads, without copying every other column of every row.
    pub fn at_times_of(&self, times: &[f64], channels: &[&'static Quantity]) -> Trace {
        rows_at(&self.output, times, channels).unwrap_or_else(|| {
            let all = rockslide_reference::sample(self.solution.as_ref(), times);
            rows_at(&all, times, channels).unwrap_or(all)
        })
    }
}

/// For each of `times` (ascending), the index of the row of `rows` (ascending) with the
/// same bits, if any: one walk over both.
fn rows_of(rows: &[f64], times: &[f64]) -> Vec<Option<usize>> {
    let mut at = 0;
    times
        .iter()
        .map(|&t| {
            while rows.get(at).is_some_and(|&x| x < t) {
                at += 1;
            }
            rows.get(at)
                .filter(|x| x.to_bits() == t.to_bits())
                .map(|_| at)
        })
        .collect()
}

/// The rows of `trace` at `times` (ascending) in its columns of `channels` (those it has,
/// in `channels`' order), or `None` when some time is not one of its rows, bit for bit.
fn rows_at(trace: &Trace, times: &[f64], channels: &[&'static Quantity]) -> Option<Trace> {
    let kept: Vec<(&'static Quantity, &[f64])> = channels
        .iter()
        .filter_map(|&c| Some((c, trace.column(c.key)?)))
        .collect();
    let kept_channels: Vec<&'static Quantity> = kept.iter().map(|(c, _)| *c).collect();
    let mut out = Trace::with_channels(&kept_channels, times.len());
    let mut row = vec![0.0; kept.len()];
    // times ascend: one walk over both (O(rows + times) in all)
    for (&t, at) in times.iter().zip(rows_of(&trace.time, times)) {
        let at = at?;
        for (v, (_, column)) in row.iter_mut().zip(&kept) {
            *v = column[at];
        }
        out.push(t, &row);
    }
    Some(out)
}

/// Solve and sample the reference of a case.
pub fn solve_reference(case: &Case) -> Result<ReferenceResult, String> {
    let solution = rockslide_reference::for_case(case)?;
    let n = fine_grid(case.run.duration);
    let trace = rockslide_reference::sample_uniform(solution.as_ref(), case.run.duration, n);
    let resp = responses(&trace);
    Ok(ReferenceResult::from_parts(solution, trace, resp))
}

/// Intervals of the fine uniform grid a reference is sampled on over a scene's duration:
/// one per 10 µs, within 1,000 … 200,000 (the grid of [`solve_reference`], so
/// that peaks, event times and energy audits read off it — and every error they normalise
/// — are the ones the case reports measure).
pub fn fine_grid(duration: f64) -> usize {
    ((duration / 1e-5).ceil() as usize).clamp(1000, 200_000)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::trace::q;

    fn trace(times: &[f64]) -> Trace {
        let mut t = Trace::with_channels(&[&q::REL_DISP, &q::VEL], times.len());
        for &x in times {
            t.push(x, &[10.0 * x, -x]);
        }
        t
    }

    #[test]
    fn rows_at_takes_the_rows_of_the_times_asked_and_nothing_else() {
        let full = trace(&[0.0, 0.25, 0.5, 0.75, 1.0]);
        let both = [&q::REL_DISP, &q::VEL];
        let rows = rows_at(&full, &[0.25, 1.0], &both).expect("both times are rows");
        assert_eq!(rows, trace(&[0.25, 1.0]));
        assert_eq!(rows_at(&full, &[], &both), Some(trace(&[])));
        // a time between rows, past the end, or out of order: sampled anew by the caller
        assert_eq!(rows_at(&full, &[0.3], &both), None);
        assert_eq!(rows_at(&full, &[2.0], &both), None);
        assert_eq!(rows_at(&full, &[0.5, 0.25], &both), None);
        assert_eq!(rows_at(&full, &[f64::NAN], &both), None);
    }

    #[test]
    fn rows_of_finds_each_time_s_row_by_its_bits_and_nothing_else() {
        let rows = [0.0, 0.25, 0.5, 0.75, 1.0];
        let times = [-0.0, 0.0, 0.1, 0.25, 0.5 + f64::EPSILON, 1.0, 2.0];
        let found = rows_of(&rows, &times);
        // −0.0 is not the row 0.0 (another bit pattern): sampled anew, as are the times
        // between rows or past the end
        assert_eq!(found, [None, Some(0), None, Some(1), None, Some(4), None]);
        assert_eq!(rows_of(&[], &[0.0]), [None]);
    }

    #[test]
    fn rows_at_keeps_only_the_channels_asked_bit_for_bit() {
        let full = trace(&[0.0, 0.25, 0.5]);
        let one = rows_at(&full, &[0.25, 0.5], &[&q::VEL, &q::SLIDE]).expect("rows");
        // the channel the trace lacks is left out; the one kept is the same column
        assert_eq!(one.channels, vec![&q::VEL]);
        assert_eq!(one.time, [0.25, 0.5]);
        assert_eq!(one.columns, vec![vec![-0.25, -0.5]]);
    }
}

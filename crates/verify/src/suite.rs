//! Running a case: plan the engine runs it asks for (or say why an engine does not apply),
//! run them in parallel through the one guarded run ([`crate::run::guarded`]: an engine
//! that panics is a diverged run carrying the panic's message, never an aborted `check`),
//! solve the reference, read the response quantities off every trace and apply the case's
//! tolerances. The result feeds reports, traces and the gate.

use rayon::prelude::*;

use crate::analysis::streamed::{Peaks, StreamedSummary, Summaries};
use crate::analysis::{
    Check, Responses, evaluate_tolerances, history_difference, quantity_def, responses,
};
use crate::registry;
use crate::timings;
use rockslide_core::case::Case;
use rockslide_core::error::{InputError, InputErrors};
use rockslide_core::trace::{Quantity, Trace, q};
use rockslide_engine_api::{Engine, Run};
use rockslide_reference::ExactSolution;

/// One planned run.
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedRun {
    /// Engine id.
    pub engine: &'static str,
    /// Variant.
    pub variant: String,
    /// Time step, s.
    pub dt: f64,
    /// Values one row records (time, channels, contact fields), when the engine declares
    /// it ([`Engine::recorded_values`]); `None`: priced as every quantity of the catalogue.
    pub values: Option<usize>,
    /// Whether the engine streams natively ([`Engine::streams_natively`]): a streamed run
    /// then holds only its kept rows.
    pub native_streaming: bool,
}

/// The runs a case asks for, and the engines that do not apply (with why).
#[derive(Debug, Clone, Default)]
pub struct Plan {
    /// Runs to make.
    pub runs: Vec<PlannedRun>,
    /// (engine id, reason) for each engine that cannot represent the scene.
    pub not_applicable: Vec<(&'static str, String)>,
}

/// Plan a case: every engine it names (all engines if it names none) with every variant
/// it asks for (all that apply by default). Unknown variants are input errors, and so is a
/// plan whose traces would exceed the memory or disk limit ([`crate::footprint`]).
pub fn plan(case: &Case, engines: &[Box<dyn Engine>]) -> Result<Plan, InputErrors> {
    let mut plan = Plan::default();
    let mut errors: Vec<InputError> = Vec::new();
    for e in engines {
        let request = case.engine(e.id());
        if !case.engines.is_empty() && request.is_none() {
            continue;
        }
        errors.extend(e.check_options(case));
        let available = match e.variants(&case.scene) {
            Ok(v) => v,
            Err(na) => {
                plan.not_applicable.push((e.id(), na.0));
                continue;
            }
        };
        let wanted: Vec<String> = match request.and_then(|r| r.variants.clone()) {
            Some(v) => v,
            None => available.iter().map(|v| v.name.to_string()).collect(),
        };
        for (i, v) in wanted.iter().enumerate() {
            if !available.iter().any(|a| a.name == v.as_str()) {
                errors.push(case.field_error(
                    &format!("engines.{}.variants[{i}]", e.id()),
                    format!(
                        "\"{v}\" is not a variant of {} for this scene; available: {}",
                        e.id(),
                        available
                            .iter()
                            .map(|a| a.name)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
                continue;
            }
            plan.runs.push(PlannedRun {
                engine: e.id(),
                variant: v.clone(),
                dt: case.dt_for(e.id()),
                values: e.recorded_values(case, v),
                native_streaming: e.streams_natively(),
            });
        }
    }
    if errors.is_empty() {
        // refused before any work when its traces would not fit (crate::footprint)
        crate::footprint::check(case, &plan)?;
        Ok(plan)
    } else {
        Err(InputErrors(errors))
    }
}

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
    /// replace the readings they also give, and its exact instants are kept as the event
    /// times.
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

/// Whole-history difference of one run from the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryError {
    /// max |Δ| / peak of the primary displacement.
    pub max: f64,
    /// RMS Δ / peak of the primary displacement.
    pub rms: f64,
}

/// Everything known about one case after running it.
pub struct CaseResult {
    /// The case.
    pub case: Case,
    /// The runs, in plan order.
    pub runs: Vec<Run>,
    /// Response quantities of each run.
    pub run_responses: Vec<Responses>,
    /// Relative-displacement history error of each run against the reference.
    pub history_errors: Vec<Option<HistoryError>>,
    /// Engines that do not apply, and why.
    pub not_applicable: Vec<(&'static str, String)>,
    /// The reference, or why there is none.
    pub reference: Result<ReferenceResult, String>,
    /// Tolerance checks.
    pub checks: Vec<Check>,
    /// Physical invariants of every completed run ([`crate::invariants`]).
    pub invariants: Vec<crate::invariants::InvariantCheck>,
    /// Per run (in run order; missing or `None`: draw the trace), the per-slice extremes
    /// of every channel over every step of a streamed run, which the figures draw instead
    /// of its kept rows ([`crate::analysis::envelope`]).
    pub envelopes: Vec<Option<crate::analysis::envelope::Envelope>>,
}

impl CaseResult {
    /// The envelope of run `i`, when it was streamed.
    pub fn envelope(&self, i: usize) -> Option<&crate::analysis::envelope::Envelope> {
        self.envelopes.get(i).and_then(Option::as_ref)
    }

    /// Release the time histories once the case's own files are written: every run's
    /// trace and per-contact block, the reference's sampled traces and the streamed runs'
    /// envelopes, down to each trace's last row (its end time and final values). What the
    /// suite's pages, the gate and the JUnit XML read — checks, responses, invariants,
    /// statuses, solver statistics — stays. A run of many cases then holds the histories
    /// of the cases in flight, not of every case at once.
    pub fn release_histories(&mut self) {
        for run in &mut self.runs {
            keep_last_row(&mut run.trace);
        }
        if let Ok(reference) = &mut self.reference {
            keep_last_row(&mut reference.trace);
            keep_last_row(&mut reference.output);
        }
        self.envelopes.clear();
    }

    /// Whether the case passes the gate (as `rockslide check` decides it).
    pub fn gate_passed(&self) -> bool {
        // one truth with `check`: failed gated checks and gated tolerances that check nothing
        crate::verdict::failures(std::slice::from_ref(self)).is_empty()
    }
}

/// Cut a trace to its last row (none when it has none), its memory returned.
fn keep_last_row(trace: &mut Trace) {
    let n = trace.time.len();
    let keep = |v: &mut Vec<f64>, from: usize| {
        let tail = v.get(from..).map(<[f64]>::to_vec).unwrap_or_default();
        *v = tail;
    };
    let from = n.saturating_sub(1);
    keep(&mut trace.time, from);
    for column in &mut trace.columns {
        keep(column, from);
    }
    let contacts = &mut trace.contacts;
    let rows = contacts.time.len();
    if let Some(width) = contacts.values.len().checked_div(rows) {
        keep(&mut contacts.time, rows - 1);
        keep(&mut contacts.values, (rows - 1) * width);
    }
}

/// Run one planned run, guarded and timed: a panic inside the engine becomes a run that
/// diverged at an unknown time with the panic's message ([`crate::run::Timed::into_run`]).
pub fn execute(
    case: &Case,
    engines: &[Box<dyn Engine>],
    p: &PlannedRun,
) -> Result<Run, InputError> {
    let e = engines
        .iter()
        .find(|e| e.id() == p.engine)
        .expect("planned engines exist");
    let timed = crate::run::guarded(e.as_ref(), case, &p.variant, p.dt, 1)?;
    Ok(timed.into_run(e.id(), &p.variant, p.dt))
}

/// Steps above which a run is streamed ([`crate::analysis::streamed`]): its rows go to
/// the analysis as they are computed and only those at the case's output step are kept,
/// so its memory follows its output rows, not its steps. Every shipped case runs below
/// it (the longest: 2·10⁵ steps), so their figures keep every step; a streamed run's
/// responses, invariants and history errors are those of a whole run bit for bit
/// (tests/all/streaming.rs), and its figures draw every channel's per-slice extremes over
/// every step ([`crate::analysis::envelope`]), not the kept rows.
pub const STREAMING_STEPS: u64 = 500_000;

/// Whether planned run `p` of `case` is streamed: more than [`STREAMING_STEPS`] steps of
/// an engine that streams natively, keeping at most half its rows (`[run] output_dt` at
/// least 2 Δt); every registered engine streams natively (the predictor-corrector, fe,
/// rapier). An engine that does not stream natively would run whole anyway and
/// forward its rows — holding its whole trace, and run twice by the two passes — so its
/// long runs are analysed whole, once; a run that keeps every row (no `output_dt`) holds
/// its whole trace either way, so streaming would only cost the second pass.
pub fn streams(case: &Case, p: &PlannedRun) -> bool {
    p.native_streaming && streams_above(case, p, STREAMING_STEPS) && keeps_few_rows(case, p)
}

/// Whether run `p` keeps at most half its rows: the case's output step at least twice
/// the run's Δt (to a relative 10⁻⁹, so 0.002 s over 0.001 s counts whatever its bits).
fn keeps_few_rows(case: &Case, p: &PlannedRun) -> bool {
    case.run
        .output_dt
        .is_some_and(|o| o >= 2.0 * p.dt * (1.0 - 1e-9))
}

/// Whether planned run `p` of `case` takes more than `steps` steps.
fn streams_above(case: &Case, p: &PlannedRun, steps: u64) -> bool {
    crate::footprint::rows_of(case.run.duration, p.dt) > steps.saturating_add(1)
}

/// Expected rows kept at the case's output step (every row without one), for sizing.
fn kept_rows(case: &Case, dt: f64) -> usize {
    let kept = case.run.output_dt.map_or(dt, |o| o.max(dt));
    crate::footprint::rows_of(case.run.duration, kept).saturating_add(1) as usize
}

/// Run one planned run streamed, guarded: a first pass reads the run-wide scales, the
/// second the summaries at every step and the rows at the output step
/// ([`crate::analysis::streamed`]); the reference's history error is evaluated at every
/// step when `solution` is given. A panic is a diverged run with its message (no summary);
/// two passes that disagree (a non-deterministic engine) are refused as an error finding.
pub fn execute_streamed(
    case: &Case,
    engines: &[Box<dyn Engine>],
    p: &PlannedRun,
    solution: Option<&dyn ExactSolution>,
) -> Result<(Run, Option<StreamedSummary>), InputError> {
    let e = engines
        .iter()
        .find(|e| e.id() == p.engine)
        .expect("planned engines exist");
    let start = std::time::Instant::now();
    let outcome = crate::run::guard(|| -> Result<(Run, StreamedSummary), InputError> {
        let mut peaks = Peaks::default();
        e.run_streaming(case, &p.variant, p.dt, &mut peaks)?;
        let capacity = kept_rows(case, p.dt);
        let mut sink = Summaries::new(case, &peaks, solution, case.run.output_dt, capacity);
        let mut run = e.run_streaming(case, &p.variant, p.dt, &mut sink)?;
        let summary = sink.finish(&mut run);
        let same = summary.rows == peaks.rows
            && run.trace.end_time().to_bits() == peaks.last_time.to_bits();
        if !same {
            run.findings.push(format!(
                "the two passes of this streamed run differ ({} and {} rows): the engine is not deterministic",
                peaks.rows, summary.rows
            ));
        }
        Ok((run, summary))
    });
    let seconds = start.elapsed().as_secs_f64();
    match outcome {
        Ok(Ok((mut run, summary))) => {
            run.wall_seconds = seconds;
            Ok((run, Some(summary)))
        }
        Ok(Err(e)) => Err(e),
        Err(message) => {
            let timed = crate::run::Timed {
                run: Err(message),
                seconds: vec![seconds],
                deterministic: true,
            };
            Ok((timed.into_run(e.id(), &p.variant, p.dt), None))
        }
    }
}

/// Solve and sample the reference of a case.
pub fn solve_reference(case: &Case) -> Result<ReferenceResult, String> {
    let solution = rockslide_reference::for_case(case)?;
    let n = crate::sweep::plan::fine_grid(case.run.duration);
    let trace = rockslide_reference::sample_uniform(solution.as_ref(), case.run.duration, n);
    let resp = responses(&trace);
    Ok(ReferenceResult::from_parts(solution, trace, resp))
}

/// Run a whole case: plan, run engines in parallel, reference, responses, checks.
pub fn run_case(case: Case) -> Result<CaseResult, InputErrors> {
    run_case_with(case, &registry::all())
}

/// [`run_case`] with the given engines instead of the registry's.
pub fn run_case_with(case: Case, engines: &[Box<dyn Engine>]) -> Result<CaseResult, InputErrors> {
    run_case_streaming_where(case, engines, streams)
}

/// [`run_case_with`], streaming every run of more than `streaming_steps` steps, whether
/// its engine streams natively or not (0: every run; `u64::MAX`: none), for comparing a
/// streamed run with a whole one.
pub fn run_case_streaming_above(
    case: Case,
    engines: &[Box<dyn Engine>],
    streaming_steps: u64,
) -> Result<CaseResult, InputErrors> {
    run_case_streaming_where(case, engines, |case: &Case, p: &PlannedRun| {
        streams_above(case, p, streaming_steps)
    })
}

/// [`run_case_with`], streaming the planned runs `streams` selects.
fn run_case_streaming_where(
    case: Case,
    engines: &[Box<dyn Engine>],
    streams: impl Fn(&Case, &PlannedRun) -> bool + Sync,
) -> Result<CaseResult, InputErrors> {
    let plan = plan(&case, engines)?;
    let opensees = crate::opensees::prepare(&case)?;
    let name = case.name.clone();
    let run_all = |solution: Option<&dyn ExactSolution>| {
        timings::time("engines", &name, || {
            plan.runs
                .par_iter()
                .map(|p| match streams(&case, p) {
                    true => execute_streamed(&case, engines, p, solution),
                    false => execute(&case, engines, p).map(|r| (r, None)),
                })
                .collect::<Vec<_>>()
        })
    };
    let ((runs, live), reference) = if plan.runs.iter().any(|p| streams(&case, p)) {
        // a streamed run compares with the reference at every step as it runs: solved first
        let reference = timings::time("reference", &name, || solve_reference(&case));
        let solution = reference.as_ref().ok().map(|r| r.solution.as_ref());
        let both = rayon::join(
            || run_all(solution),
            || crate::opensees::live(&case, opensees.as_ref()),
        );
        (both, reference)
    } else {
        rayon::join(
            || {
                rayon::join(
                    || run_all(None),
                    || crate::opensees::live(&case, opensees.as_ref()),
                )
            },
            || timings::time("reference", &name, || solve_reference(&case)),
        )
    };
    timings::time("analysis", &name, || {
        analyse(case, plan.not_applicable, runs, live, reference)
    })
}

/// The runs and the reference of a case judged: external participants joined, the
/// reference sampled where it is compared, responses, history errors, checks, invariants.
fn analyse(
    case: Case,
    not_applicable: Vec<(&'static str, String)>,
    runs: Vec<Result<(Run, Option<StreamedSummary>), InputError>>,
    live: crate::opensees::Live,
    reference: Result<ReferenceResult, String>,
) -> Result<CaseResult, InputErrors> {
    let (mut case, mut not_applicable) = (case, not_applicable);
    let mut reference = reference;
    let (runs, mut streamed): (Vec<Run>, Vec<Option<StreamedSummary>>) = runs
        .into_iter()
        .collect::<Result<Vec<_>, _>>()
        .map_err(InputErrors::from)?
        .into_iter()
        .unzip();
    let mut runs = runs;
    match live {
        crate::opensees::Live::NotAsked => {}
        crate::opensees::Live::NotApplicable(why) => {
            not_applicable.push((crate::opensees::LABEL, why))
        }
        crate::opensees::Live::Participant(e) => case.add_external(*e),
        crate::opensees::Live::Failed(run) => runs.push(*run),
    }
    let runs = crate::external::with_external_runs(&case, runs);
    streamed.resize(runs.len(), None);
    // the reference sampled at the compared times with the history errors, beside the
    // responses and the invariants (independent readings of every run): on both cores
    let (history_errors, (run_responses, invariants)): (_, (Vec<Responses>, _)) = rayon::join(
        || {
            if let Ok(r) = &mut reference {
                r.at_compared_times(&runs);
            }
            let reference = &reference;
            runs.iter()
                .zip(&streamed)
                .map(|(r, s)| {
                    if let Some(s) = s {
                        return s.history.map(|(max, rms)| HistoryError { max, rms });
                    }
                    let sampled = reference
                        .as_ref()
                        .ok()?
                        .at_times_of(&r.trace.time, &[&q::REL_DISP]);
                    history_difference(&r.trace, &sampled, q::REL_DISP.key)
                        .map(|(max, rms)| HistoryError { max, rms })
                })
                .collect()
        },
        || {
            rayon::join(
                || {
                    runs.iter()
                        .zip(&streamed)
                        .map(|(r, s)| match s {
                            Some(s) => s.responses.clone(),
                            None => responses(&r.trace),
                        })
                        .collect()
                },
                || {
                    runs.iter()
                        .zip(&streamed)
                        .flat_map(|(r, s)| match s {
                            Some(s) => s.invariants.clone(),
                            None => crate::external::check_invariants(&case, r),
                        })
                        .collect()
                },
            )
        },
    );
    let reference_responses = reference.as_ref().ok().map(|r| &r.responses);
    let checks = evaluate_tolerances(&case.tolerances, &runs, &run_responses, reference_responses);
    let checks =
        crate::external::adjust_checks(&case, &runs, &run_responses, reference_responses, checks);
    let envelopes = streamed
        .iter_mut()
        .map(|s| s.as_mut().and_then(|s| s.envelope.take()))
        .collect();
    Ok(CaseResult {
        envelopes,
        invariants,
        case,
        runs,
        run_responses,
        history_errors,
        not_applicable,
        reference,
        checks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

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

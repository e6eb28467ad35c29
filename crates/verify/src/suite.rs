//! Running a case: plan the engine runs it asks for (or say why an engine does not apply),
//! run them in parallel through the one guarded run ([`crate::run::guarded`]: an engine
//! that panics is a diverged run carrying the panic's message, never an aborted `check`),
//! solve the reference, read the response quantities off every trace and apply the case's
//! tolerances. The result feeds reports, traces and the gate.

use rayon::prelude::*;

use crate::analysis::streamed::{Peaks, StreamedSummary, Summaries};
use crate::analysis::{Responses, evaluate_tolerances, history_difference, responses};
use crate::registry;
use crate::timings;
use rockslide_core::case::Case;
use rockslide_core::error::{InputError, InputErrors};
use rockslide_core::trace::q;
use rockslide_engine_api::{Engine, Run, Variant, declared};
use rockslide_reference::ExactSolution;

pub use crate::plan::{Plan, PlannedRun, STREAMING_STEPS, streams};
use crate::plan::{kept_rows, streams_above};
pub use crate::reference::{ReferenceResult, solve_reference};
pub use crate::result::{CaseResult, HistoryError};

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
        errors.extend(registry::option_problems(case, e.as_ref()));
        let available = match e.variants(&case.scene) {
            Ok(v) => v,
            Err(na) => {
                plan.not_applicable.push((e.id(), na.0));
                continue;
            }
        };
        let wanted = match request.and_then(|r| r.variants.as_deref()) {
            Some(names) => asked_variants(case, e.id(), &available, names, &mut errors),
            None => available,
        };
        plan.runs.extend(wanted.into_iter().map(|v| PlannedRun {
            engine: e.id(),
            variant: v,
            dt: case.dt_for(e.id()),
            values: e.recorded_values(case, v),
            native_streaming: e.streams_natively(),
        }));
    }
    if case.azimuths.is_some() && !case.externals.is_empty() {
        errors.push(case.field_error(
            "excitation.station.x_azimuths_deg",
            "runs the case at each azimuth, but an external participant's results are at one: \
             give x_azimuth_deg (one azimuth) to compare them",
        ));
    }
    if errors.is_empty() {
        // refused before any work when its traces would not fit (crate::footprint)
        crate::footprint::check(case, &plan)?;
        Ok(plan)
    } else {
        Err(InputErrors(errors))
    }
}

/// The variants of engine `id` a case asks for by name, each resolved to the one the
/// engine declared; a name it did not declare for the scene is a located error.
fn asked_variants(
    case: &Case,
    id: &str,
    available: &[Variant],
    names: &[String],
    errors: &mut Vec<InputError>,
) -> Vec<Variant> {
    let mut wanted = Vec::with_capacity(names.len());
    for (i, name) in names.iter().enumerate() {
        match declared(available, name) {
            Some(v) => wanted.push(v),
            None => errors.push(case.field_error(
                &format!("engines.{id}.variants[{i}]"),
                format!(
                    "\"{name}\" is not a variant of {id} for this scene; available: {}",
                    available
                        .iter()
                        .map(|a| a.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )),
        }
    }
    wanted
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
    let timed = crate::run::guarded(e.as_ref(), case, p.variant, p.dt, 1)?;
    Ok(timed.into_run(e.id(), p.variant.name, p.dt))
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
        e.run_streaming(case, p.variant, p.dt, &mut peaks)?;
        let capacity = kept_rows(case, p.dt);
        let mut sink = Summaries::new(case, &peaks, solution, case.run.output_dt, capacity);
        let mut run = e.run_streaming(case, p.variant, p.dt, &mut sink)?;
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
            Ok((timed.into_run(e.id(), p.variant.name, p.dt), None))
        }
    }
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

/// [`run_case_with`], streaming the planned runs `streams` selects; a case with a set of
/// azimuths run at each ([`crate::azimuths`]).
pub(crate) fn run_case_streaming_where(
    case: Case,
    engines: &[Box<dyn Engine>],
    streams: impl Fn(&Case, &PlannedRun) -> bool + Sync,
) -> Result<CaseResult, InputErrors> {
    let plan = plan(&case, engines)?;
    if case.azimuths.is_some() {
        // one instance for every azimuth: the selection passed on as a trait object
        let streams: &(dyn Fn(&Case, &PlannedRun) -> bool + Sync) = &streams;
        return crate::azimuths::run_sweep(case, |at| {
            run_case_streaming_where(at, engines, streams)
        });
    }
    let opensees = crate::opensees::prepare(&case)?;
    let calculix = crate::calculix::prepare(&case)?;
    let name = case.name.clone();
    // the live participants (other programs run on the exported scene), beside the engines
    let live_all = || {
        let (o, c) = rayon::join(
            || crate::opensees::live(&case, opensees.as_ref()),
            || crate::calculix::live(&case, calculix.as_ref()),
        );
        vec![(crate::opensees::LABEL, o), (crate::calculix::LABEL, c)]
    };
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
        let both = rayon::join(|| run_all(solution), live_all);
        (both, reference)
    } else {
        rayon::join(
            || rayon::join(|| run_all(None), live_all),
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
    live: Vec<(&'static str, crate::live::Live)>,
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
    for (label, live) in live {
        match live {
            crate::live::Live::NotAsked => {}
            crate::live::Live::NotApplicable(why) => not_applicable.push((label, why)),
            crate::live::Live::Participant(e) => case.add_external(*e),
            crate::live::Live::Failed(run) => runs.push(*run),
        }
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
        azimuths: None,
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

//! A case with a set of azimuths (`x_azimuths_deg`, [`rockslide_core::case::AzimuthSet`]):
//! the whole case — every engine run and the reference — run at each azimuth, in
//! parallel, each an ordinary case result ([`Case::at_azimuth`]); then, per participant,
//! the sliding and uplift at each azimuth, their maximum over the set and the azimuth
//! that gives it ([`AzimuthSweep`]).
//!
//! The case's own result (its traces, figures, checks and report) is the one at the
//! governing azimuth: the azimuth of the largest peak sliding of the basis (the
//! reference, else the first run). The other azimuths keep their figures, checks and gate
//! failures, not their histories, so the trace files are one set, the governing one's.
//! The gate fails when a check fails at any azimuth, or when a run's maximum over the set
//! is outside the case's tolerance of the reference's maximum.
//!
//! The figures: a scene driven in plan (x and y) is read by its resultant sliding (peak
//! and residual), a scene driven along x alone by its peak |sliding| and its signed
//! residual sliding (the set spans both polarities, so its maximum is the largest residual
//! in either direction); the peak uplift where the station drives z.

use rayon::prelude::*;

use crate::analysis::{Check, Responses, evaluate_tolerances};
use crate::check_record::CheckRecord;
use crate::failure::Failure;
use crate::result::CaseResult;
use crate::verdict;
use rockslide_core::case::{AzimuthSet, Case, Coverage};
use rockslide_core::error::InputErrors;

/// Participant name of the reference in an [`AzimuthSweep`].
pub use rockslide_core::case::REFERENCE_LABEL as REFERENCE;

/// What a check or failure field on the maxima over the set ends with.
const OVER_THE_SET: &str = ", maximum over x_azimuths_deg";

pub use crate::azimuth_record::{AzimuthPoint, AzimuthSweep, Figures, Maximum, ParticipantMaxima};

/// The response keys read at each azimuth: peak sliding, residual sliding, uplift.
fn swept_keys(set: &AzimuthSet, case: &Case) -> (&'static str, &'static str, Option<&'static str>) {
    let uplift = case.scene.vertical.is_some().then_some("peak_uplift");
    match set.coverage {
        Coverage::Plan => (
            "peak_resultant_sliding",
            "residual_resultant_sliding",
            uplift,
        ),
        Coverage::Axis => ("peak_abs_sliding", "residual_sliding", uplift),
    }
}

/// Run `case` (which has a set) at every azimuth of its set, in parallel, each as a whole
/// case by `run_case` (the suite's run of a case without a set), and gather the sweep;
/// the result returned is the governing azimuth's, carrying the sweep and the case with
/// its set.
pub(crate) fn run_sweep(
    case: Case,
    run_case: impl Fn(Case) -> Result<CaseResult, InputErrors> + Sync,
) -> Result<CaseResult, InputErrors> {
    let set = case
        .azimuths
        .clone()
        .expect("run_sweep is given a case with a set");
    let results: Vec<CaseResult> = set
        .degrees
        .par_iter()
        .map(|&a| run_case(case.at_azimuth(a).expect("a case with a set")))
        .collect::<Result<_, _>>()?;
    Ok(gather(case, &set, results))
}

/// The sweep of per-azimuth `results` (in the set's order), returned in the governing
/// azimuth's result; the others are dropped with their histories.
fn gather(case: Case, set: &AzimuthSet, results: Vec<CaseResult>) -> CaseResult {
    let keys = swept_keys(set, &case);
    let participants = participants(&results[0]);
    let stale: Vec<Vec<Failure>> = results
        .iter()
        .map(verdict::stale_declaration_failures)
        .collect();
    let points: Vec<AzimuthPoint> = set
        .degrees
        .iter()
        .zip(&results)
        .map(|(&a, r)| point(a, r, &participants, keys))
        .collect();
    // no participant reads an uplift (the planar oscillator's): no uplift column
    let no_uplift = points
        .iter()
        .all(|p| p.figures.iter().all(|f| f.peak_uplift.is_none()));
    let keys = (keys.0, keys.1, keys.2.filter(|_| !no_uplift));
    let maxima: Vec<ParticipantMaxima> = participants
        .iter()
        .enumerate()
        .map(|(i, p)| maxima(p, i, &points))
        .collect();
    let basis = participants
        .iter()
        .zip(&maxima)
        .find(|(_, m)| m.peak_sliding.is_some())
        .map_or_else(|| participants[0].clone(), |(p, _)| p.clone());
    let governing = maxima
        .iter()
        .find(|m| m.participant == basis)
        .and_then(|m| m.peak_sliding)
        .and_then(|m| points.iter().position(|p| p.azimuth_deg == m.azimuth_deg))
        .unwrap_or(0);
    let mut main = results
        .into_iter()
        .nth(governing)
        .expect("one result per azimuth");
    let max_checks = max_checks(&main, &case, &participants, &maxima, keys);
    let to_failure = |gated: bool| -> Vec<Failure> {
        max_checks
            .iter()
            .filter(|c| c.gated == gated && c.verdict != crate::analysis::Verdict::Pass)
            .map(|c| {
                let mut f = verdict::failed_check(&main, c);
                f.field = format!("{}{OVER_THE_SET}", f.field);
                f
            })
            .collect()
    };
    let (mut set_failures, max_informative) = (to_failure(true), to_failure(false));
    set_failures.extend(stale_everywhere(&stale));
    let sweep = AzimuthSweep {
        span_deg: set.coverage.span_deg(),
        span_reason: set.coverage.reason().to_string(),
        peak_key: keys.0.to_string(),
        residual_key: keys.1.to_string(),
        uplift_key: keys.2.map(str::to_string),
        participants,
        basis,
        governing,
        points,
        maxima,
        max_checks: max_checks
            .iter()
            .map(|c| {
                let mut record = CheckRecord::of(c);
                record.limit = verdict::limit_text(&main, c);
                record.field = format!("{}{OVER_THE_SET}", record.field);
                record
            })
            .collect(),
        set_failures,
        max_informative,
    };
    main.case.azimuths = case.azimuths;
    main.azimuths = Some(Box::new(sweep));
    main
}

/// The participants of a result: the reference (when solved) and every run, by label.
fn participants(r: &CaseResult) -> Vec<String> {
    let reference = r.reference.is_ok().then(|| REFERENCE.to_string());
    reference
        .into_iter()
        .chain(r.runs.iter().map(|run| run.label()))
        .collect()
}

/// The responses of `participant` in `r`, when it completed.
fn responses_of<'a>(r: &'a CaseResult, participant: &str) -> Option<&'a Responses> {
    if participant == REFERENCE {
        return r.reference.as_ref().ok().map(|x| &x.responses);
    }
    let i = r.runs.iter().position(|run| run.label() == participant)?;
    r.runs[i].status.completed().then(|| &r.run_responses[i])
}

/// The case at azimuth `a`: each participant's figures, its checks and gate lines.
fn point(
    a: f64,
    r: &CaseResult,
    participants: &[String],
    (peak, residual, uplift): (&str, &str, Option<&str>),
) -> AzimuthPoint {
    let figures = participants
        .iter()
        .map(|p| {
            let resp = responses_of(r, p);
            let read = |key: &str| resp.and_then(|x| x.get(key).copied());
            Figures {
                participant: p.clone(),
                peak_sliding: read(peak),
                residual_sliding: read(residual),
                peak_uplift: uplift.and_then(read),
            }
        })
        .collect();
    let one = std::slice::from_ref(r);
    let here = |list: Vec<Failure>| -> Vec<Failure> {
        list.into_iter()
            .map(|mut f| {
                f.field = format!("{}, at x_azimuth_deg = {a}", f.field);
                f
            })
            .collect()
    };
    AzimuthPoint {
        azimuth_deg: a,
        figures,
        checks: r
            .checks
            .iter()
            .map(|c| CheckRecord {
                limit: verdict::limit_text(r, c),
                ..CheckRecord::of(c)
            })
            .collect(),
        failures: here(verdict::case_failures(r, false)),
        informative: here(verdict::informative(one)),
        notes: here(verdict::informative_notes(one)),
    }
}

/// The declared disagreements stale at every azimuth (one that happens at some azimuth
/// is still needed there), each once, as the first azimuth words it.
fn stale_everywhere(stale: &[Vec<Failure>]) -> Vec<Failure> {
    let Some((first, rest)) = stale.split_first() else {
        return Vec::new();
    };
    first
        .iter()
        .filter(|f| rest.iter().all(|s| s.iter().any(|g| g.field == f.field)))
        .map(|f| {
            let mut f = f.clone();
            f.field = format!("{}, at every azimuth of x_azimuths_deg", f.field);
            f
        })
        .collect()
}

/// The maxima over the set of participant `i` (`None` where it misses any azimuth).
fn maxima(participant: &str, i: usize, points: &[AzimuthPoint]) -> ParticipantMaxima {
    let largest = |read: &dyn Fn(&Figures) -> Option<f64>| -> Option<Maximum> {
        let mut best: Option<Maximum> = None;
        for p in points {
            let value = read(&p.figures[i])?;
            if best.is_none_or(|b| value > b.value) {
                best = Some(Maximum {
                    value,
                    azimuth_deg: p.azimuth_deg,
                });
            }
        }
        best
    };
    ParticipantMaxima {
        participant: participant.to_string(),
        peak_sliding: largest(&|f| f.peak_sliding),
        residual_sliding: largest(&|f| f.residual_sliding),
        peak_uplift: largest(&|f| f.peak_uplift),
    }
}

/// The case's tolerances on the swept quantities applied to each run's maxima over the
/// set against the reference's (or the basis run's) maxima: each check's field says so.
fn max_checks(
    main: &CaseResult,
    case: &Case,
    participants: &[String],
    maxima: &[ParticipantMaxima],
    (peak, residual, uplift): (&'static str, &'static str, Option<&'static str>),
) -> Vec<Check> {
    let as_responses = |m: &ParticipantMaxima| -> Responses {
        let mut out = Responses::new();
        for (key, value) in [
            (Some(peak), m.peak_sliding),
            (Some(residual), m.residual_sliding),
            (uplift, m.peak_uplift),
        ] {
            if let (Some(key), Some(value)) = (key, value) {
                out.insert(key, value.value);
            }
        }
        out
    };
    let of = |label: &str| {
        participants
            .iter()
            .position(|p| p == label)
            .map(|i| as_responses(&maxima[i]))
            .unwrap_or_default()
    };
    let reference = main.reference.is_ok().then(|| of(REFERENCE));
    let run_maxima: Vec<Responses> = main.runs.iter().map(|r| of(&r.label())).collect();
    let swept = [Some(peak), Some(residual), uplift];
    let tolerances: Vec<_> = case
        .tolerances
        .iter()
        .filter(|t| swept.contains(&Some(t.quantity.as_str())))
        .cloned()
        .collect();
    evaluate_tolerances(&tolerances, &main.runs, &run_maxima, reference.as_ref())
}

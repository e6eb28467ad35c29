//! External participants: results another program produced (ANSYS, SAP2000, OpenSees, a
//! rockslide trace of another build), declared in a case (`[[external]]`) or on the
//! command line (`--external LABEL=PATH`), taking part in a case like an engine run.
//!
//! Each becomes a [`Run`] (engine = its label, variant [`EXTERNAL_VARIANT`], status
//! completed, settings naming the program, element and file), so it appears wherever a run
//! does: the response table, the cross-code matrix, the plots, the MCAP log, JUnit and the
//! gate. Its response quantities are read off the file's own samples (no resampling, so
//! that its peaks are the program's); whole histories are compared by linear
//! interpolation (the reference sampled at the file's times, run against run on the
//! coarser grid). A quantity the file lacks is "not provided", never zero.
//!
//! Gating: tolerances that name the label (`engine = "<label>"`) apply as written; the
//! case's tolerances that name no engine were written for the engines and do not apply.
//! An external that no tolerance names is gated against the reference (or, without one,
//! against the fe engine) at the SAP2000 verification manual's "Acceptable" limit:
//! [`ACCEPTABLE_PERCENT`] on displacements, rotations and forces, one output step of the
//! file on event times. Physical invariants are measured on the channels the file
//! provides, with [`INVARIANT_LIMIT`].

use rockslide_core::case::REFERENCE_LABEL;
use std::collections::BTreeSet;
use std::path::PathBuf;
use std::sync::Mutex;

use rockslide_core::case::{Case, EXTERNAL_VARIANT, External, Model};
use rockslide_core::error::{InputError, InputErrors};
use rockslide_core::response::quantity_def;
use rockslide_core::trace::Trace;
use rockslide_engine_api::{Arrangement, Run, RunStatus, Setting, SolverStats};
use rockslide_formats::read_external_participant;

use crate::analysis::{Check, QUANTITY_KEYS, Responses, Verdict, discrepancy_percent};
use crate::invariants::InvariantCheck;
use crate::result::CaseResult;

/// The SAP2000 verification manual's "Acceptable" difference, % (displacements, forces).
pub const ACCEPTABLE_PERCENT: f64 = 5.0;

/// Limit on an external run's physical invariants: the same 5 %, since another program's
/// output is rounded and sampled more coarsely than an engine's state.
pub const INVARIANT_LIMIT: f64 = 0.05;

/// How an external run's histories meet the others', for the report.
pub const INTERPOLATION: &str = "response quantities read off the file's own samples; \
     whole histories compared by linear interpolation (the reference sampled at the file's \
     times, run against run on the coarser of the two grids)";

/// Add the participants named on the command line (`LABEL=PATH`, each) to a case.
pub fn add_from_command_line(case: &mut Case, specs: &[String]) -> Result<(), InputErrors> {
    let mut errors = Vec::new();
    for spec in specs {
        let Some((label, path)) = spec.split_once('=') else {
            errors.push(InputError::new(
                &PathBuf::from(spec),
                "--external",
                "must be LABEL=PATH (e.g. --external sap2000=results/sap2000.csv, or \
                 run.mcap#/fe/single/state for one topic of an MCAP file)",
            ));
            continue;
        };
        // `trace.mcap#/fe/single/state`: one state topic of an MCAP file
        let (path, topic) = match path.split_once(".mcap#") {
            Some((stem, topic)) => (format!("{stem}.mcap"), Some(topic)),
            None => (path.to_string(), None),
        };
        let engine_ids = crate::registry::ENGINE_IDS;
        match read_external_participant(case, label, &PathBuf::from(path), topic, engine_ids) {
            Ok(e) => case.add_external(e),
            Err(e) => errors.extend(e.0),
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(InputErrors(errors))
    }
}

/// The engine runs followed by one run per external participant of the case.
pub fn with_external_runs(case: &Case, mut runs: Vec<Run>) -> Vec<Run> {
    runs.extend(case.externals.iter().map(|e| external_run(case, e)));
    runs
}

/// Whether a run is an external participant's.
pub fn is_external(run: &Run) -> bool {
    run.variant == EXTERNAL_VARIANT
}

/// A label as the `'static` engine id a [`Run`] carries: each distinct label is stored
/// once for the life of the process (a handful of short strings).
fn intern(label: &str) -> &'static str {
    static LABELS: Mutex<BTreeSet<&'static str>> = Mutex::new(BTreeSet::new());
    let mut labels = LABELS.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(l) = labels.get(label) {
        return l;
    }
    let leaked: &'static str = Box::leak(label.to_string().into_boxed_str());
    labels.insert(leaked);
    leaked
}

/// Largest interval between two output times (0 for a single row), s, to 12 significant
/// digits (so that a 1 ms grid written as decimals gives 0.001 s, not 0.0010000000000000009).
fn output_step(time: &[f64]) -> f64 {
    let step = time.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    format!("{step:.11e}").parse().unwrap_or(step)
}

/// The run of one external participant.
fn external_run(case: &Case, e: &External) -> Run {
    let trace = e.read.trace.clone();
    let step = output_step(&trace.time);
    let (t0, t1) = (trace.time[0], trace.end_time());
    let channels: Vec<&str> = trace.channels.iter().map(|c| c.key).collect();
    let mut findings = e.read.notes.clone();
    findings.extend(invariant_coverage(case, &trace));
    if t1 < case.run.duration * (1.0 - 1e-9) {
        findings.push(format!(
            "the file ends at t = {t1} s, before the case's duration {} s",
            case.run.duration
        ));
    }
    Run {
        engine: intern(&e.label),
        variant: EXTERNAL_VARIANT.to_string(),
        arrangement: Arrangement::Single,
        dt: step,
        settings: vec![
            Setting::text("program", e.program.clone()),
            Setting::text("element", e.element.clone()),
            Setting::text("file", e.file.display().to_string()),
            Setting::text(
                "time grid",
                format!(
                    "{} samples from {t0} s to {t1} s, largest output step {step} s",
                    trace.len()
                ),
            ),
            Setting::text("channels", channels.join(", ")),
            Setting::text("comparison", INTERPOLATION),
            Setting::text("solver statistics", "not known (steps: output intervals)"),
        ],
        stats: SolverStats::steps(trace.len().saturating_sub(1) as u64),
        findings,
        trace,
        status: RunStatus::Completed,
        wall_seconds: 0.0,
    }
}

/// Whether some tolerance of the case names this run by its label.
fn named(case: &Case, run: &Run) -> bool {
    case.tolerances
        .iter()
        .any(|t| t.runs.is_some() && t.applies_to(run.engine, &run.variant))
}

/// The checks of a case with external participants: the engine checks as evaluated, the
/// external runs' checks from tolerances that name them, and the default "Acceptable"
/// checks of each external run that no tolerance names.
pub fn adjust_checks(
    case: &Case,
    runs: &[Run],
    run_responses: &[Responses],
    reference: Option<&Responses>,
    checks: Vec<Check>,
) -> Vec<Check> {
    let unnamed_tolerance = |c: &Check| {
        case.tolerances
            .iter()
            .any(|t| t.field == c.field && t.runs.is_none())
    };
    let mut out: Vec<Check> = checks
        .into_iter()
        .filter(|c| {
            let external = runs.iter().any(|r| is_external(r) && r.label() == c.run);
            !(external && unnamed_tolerance(c))
        })
        .collect();
    let Some((basis_name, basis)) = default_basis(runs, run_responses, reference) else {
        return out;
    };
    for (run, resp) in runs.iter().zip(run_responses) {
        if is_external(run) && !named(case, run) {
            let field = case
                .externals
                .iter()
                .find(|e| e.label == run.engine)
                .map_or_else(String::new, |e| e.field.clone());
            out.extend(default_checks(run, resp, &basis_name, basis, &field));
        }
    }
    out
}

/// The reference's responses, or else the first completed fe run's.
fn default_basis<'a>(
    runs: &[Run],
    run_responses: &'a [Responses],
    reference: Option<&'a Responses>,
) -> Option<(String, &'a Responses)> {
    if let Some(r) = reference {
        return Some((REFERENCE_LABEL.into(), r));
    }
    runs.iter()
        .zip(run_responses)
        .find(|(r, _)| r.engine == crate::registry::EXTERNAL_BASIS_ENGINE && r.status.completed())
        .map(|(r, resp)| (r.label(), resp))
}

/// The "Acceptable" checks of one external run against `basis`, on every quantity both
/// have: 5 % on displacements, rotations and forces (skipped where the basis is zero, as
/// a percentage of zero is undefined), one output step on event times.
fn default_checks(
    run: &Run,
    resp: &Responses,
    basis_name: &str,
    basis: &Responses,
    field: &str,
) -> Vec<Check> {
    let mut out = Vec::new();
    for key in QUANTITY_KEYS {
        let (Some(&v), Some(&b), Some(def)) = (resp.get(*key), basis.get(*key), quantity_def(key))
        else {
            continue;
        };
        let (percent, limit, pass) = if def.is_time() {
            let limit = format!(
                "≤ {} s (default: one output step, SAP2000 \"Acceptable\")",
                run.dt
            );
            (discrepancy_percent(v, b), limit, (v - b).abs() <= run.dt)
        } else if matches!(def.unit(), "m" | "N" | "rad") && b != 0.0 {
            let p = discrepancy_percent(v, b);
            let limit = format!("≤ {ACCEPTABLE_PERCENT} % (default: SAP2000 \"Acceptable\")");
            (p, limit, p.is_some_and(|p| p.abs() <= ACCEPTABLE_PERCENT))
        } else {
            continue;
        };
        out.push(Check {
            quantity: key.to_string(),
            run: run.label(),
            basis: basis_name.to_string(),
            value: Some(v),
            basis_value: Some(b),
            percent,
            limit,
            gated: true,
            verdict: if pass { Verdict::Pass } else { Verdict::Fail },
            field: field.to_string(),
        });
    }
    out
}

/// The physical invariants of a run: an engine's with its own limits, an external run's
/// on the channels its file provides, with [`INVARIANT_LIMIT`].
pub fn check_invariants(case: &Case, run: &Run) -> Vec<InvariantCheck> {
    if !is_external(run) {
        return crate::invariants::check_run(case, run);
    }
    let mut checks = crate::invariants::check_external_run(case, run);
    for c in &mut checks {
        c.limit = INVARIANT_LIMIT;
    }
    checks
}

/// What an external trace lets the invariants measure, in words for the run's findings:
/// each invariant its file cannot support is "not provided" (with the channels it lacks),
/// never a zero that passes; a normal force the file does not give but the scene fixes
/// (M·g on a horizontally shaken oscillator) is said to be the scene's.
fn invariant_coverage(case: &Case, trace: &Trace) -> Vec<String> {
    let has = |k: &str| trace.has(k);
    let tangential = has("resistance") || has("base_shear");
    let scene_normal =
        matches!(case.scene.model, Model::Oscillator(_)) && case.scene.vertical().is_none();
    let normal = has("normal") || scene_normal;
    let one_contact = matches!(case.scene.model, Model::Oscillator(_));
    let mut missing: Vec<String> = Vec::new();
    let lack = |missing: &mut Vec<String>, invariant: &str, needs: &[(&str, bool)]| {
        let absent: Vec<&str> = needs.iter().filter(|n| !n.1).map(|n| n.0).collect();
        if !absent.is_empty() {
            missing.push(format!("{invariant} (no {})", absent.join(", no ")));
        }
    };
    let tangential_force = ("resistance or base_shear", tangential);
    lack(
        &mut missing,
        "friction_bound",
        &[tangential_force, ("normal", normal)],
    );
    lack(&mut missing, "compression", &[("normal", has("normal"))]);
    let slip = [
        tangential_force,
        ("normal", normal),
        ("slide", has("slide")),
    ];
    if one_contact {
        lack(&mut missing, "stick_slip", &slip);
        lack(&mut missing, "dissipation", &slip);
    } else {
        missing.push("stick_slip, dissipation (need each support's own forces and slip)".into());
    }
    missing.push("penetration (no per-contact gaps)".into());
    let energy = [
        ("energy_input", has("energy_input")),
        ("energy_error", has("energy_error")),
    ];
    lack(&mut missing, "energy_balance", &energy);
    let mut notes = vec![format!(
        "invariants not provided by the file: {}",
        missing.join("; ")
    )];
    if !has("normal") && scene_normal && tangential {
        notes.push(
            "friction_bound measured against the scene's normal force M·g (the file gives \
             no normal force)"
                .into(),
        );
    }
    notes
}

/// What a response table shows for a run without a value of quantity `key`: "not
/// provided" when the run is external and its file lacks the channel, else "—".
pub fn missing_text(run: &Run, key: &str) -> &'static str {
    let lacks = quantity_def(key).is_some_and(|d| !run.trace.has(d.channel.key));
    if is_external(run) && lacks {
        "not provided"
    } else {
        "—"
    }
}

/// One line per external participant for the report, under the response table: who made
/// it, how it is compared and which limit applies to it.
pub fn report_notes(r: &CaseResult) -> Vec<String> {
    let (case, runs) = (&r.case, &r.runs);
    let basis = default_basis(
        runs,
        &r.run_responses,
        r.reference.as_ref().ok().map(|x| &x.responses),
    );
    runs.iter()
        .filter(|r| is_external(r))
        .map(|r| {
            let e = case.externals.iter().find(|e| e.label == r.engine);
            let (program, element) = e.map_or(("?", "?"), |e| (&e.program[..], &e.element[..]));
            let limit = if named(case, r) {
                "the case's tolerances that name it".to_string()
            } else if basis.is_none() {
                "none: no tolerance names it and the case has neither a reference nor an fe \
                 run to apply the default limit against"
                    .to_string()
            } else {
                format!(
                    "no tolerance names it, so the SAP2000 \"Acceptable\" limit applies against \
                     the reference (else fe): {ACCEPTABLE_PERCENT} % on displacements, rotations \
                     and forces, one output step ({} s) on event times",
                    r.dt
                )
            };
            format!(
                "{}: external results of {program} (element: {element}). Comparison: \
                 {INTERPOLATION}; a quantity its file lacks is \"not provided\". Limits: {limit}.",
                r.label()
            )
        })
        .collect()
}

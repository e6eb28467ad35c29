//! The verdict of a case: which checks fail the gate (and which are informative), as values
//! with a one-line rendering for logs. The one pass/fail rule; `rockslide check`, the
//! reports and the JUnit all ask it.

use crate::analysis::{Check, Verdict};
use crate::disagreement::difference_words;
use crate::failure::Failure;
use crate::invariants::InvariantCheck;
use crate::result::CaseResult;
use rockslide_core::case::Tolerance;
use rockslide_core::response::show_value;

/// What a check found, in words: the discrepancy and both values in display units.
pub fn describe(c: &Check) -> String {
    match (c.value, c.basis_value) {
        (Some(v), Some(b)) => difference_words(&c.quantity, v, b),
        (None, _) => {
            "missing: the run has no value (did not complete or lacks the quantity)".to_string()
        }
        (Some(_), None) => "missing: the basis has no value".to_string(),
    }
}

/// The tolerance of a check in words with the quantity's display unit (`≤ 1 %`,
/// `≤ 0.01000 s`), read from the case's tolerance the check came from.
pub fn limit_text(r: &CaseResult, c: &Check) -> String {
    r.case
        .tolerances
        .iter()
        .find(|t| t.field == c.field)
        .map_or_else(|| c.limit.clone(), tolerance_words)
}

/// A tolerance in words, absolute limits in the quantity's display unit.
fn tolerance_words(t: &Tolerance) -> String {
    let is_count =
        rockslide_core::response::quantity_def(&t.quantity).is_some_and(|d| d.is_count());
    let abs = t.absolute.map(|a| {
        if is_count {
            return format!("≤ {a}");
        }
        let (v, unit) = show_value(&t.quantity, a);
        format!("≤ {v} {unit}").trim_end().to_string()
    });
    match (t.percent, abs) {
        (Some(p), Some(a)) => format!("≤ {p} % or {a}"),
        (Some(p), None) => format!("≤ {p} %"),
        (None, Some(a)) => a,
        (None, None) => "—".into(),
    }
}

/// Whether a check fails the gate.
pub fn fails(c: &Check) -> bool {
    c.gated && c.verdict != Verdict::Pass
}

/// The failure line of check `c` of result `r`.
pub(crate) fn failed_check(r: &CaseResult, c: &Check) -> Failure {
    Failure {
        case: r.case.name.clone(),
        quantity: c.quantity.clone(),
        engines: format!("{} vs {}", c.run, c.basis),
        value: describe(c),
        tolerance: limit_text(r, c),
        field: format!("{}: {}", r.case.path.display(), c.field),
        checks_nothing: false,
        gated: c.gated,
    }
}

/// Checks that are not gated and did not pass: findings to report, never gate failures
/// (e.g. the paper's literal Eq 12 route against the exact solution). Lines start `INFO`.
pub fn informative(results: &[CaseResult]) -> Vec<Failure> {
    results
        .iter()
        .flat_map(|r| {
            if let Some(sweep) = &r.azimuths {
                return sweep.informative();
            }
            r.checks
                .iter()
                .filter(|c| !c.gated && c.verdict != Verdict::Pass)
                .map(move |c| failed_check(r, c))
                .collect()
        })
        .collect()
}

/// The informative findings a reader has not been told already: [`informative`] without
/// the checks a declared design disagreement (a `KNOWN` line of [`warnings`]) covers.
pub fn informative_notes(results: &[CaseResult]) -> Vec<Failure> {
    results
        .iter()
        .flat_map(|r| {
            if let Some(sweep) = &r.azimuths {
                return sweep.notes();
            }
            let known = crate::disagreement::design_disagreements(r);
            r.checks
                .iter()
                .filter(|c| !c.gated && c.verdict != Verdict::Pass)
                .filter(move |c| {
                    !known.iter().any(|d| {
                        d.declared.is_some()
                            && d.quantity == c.quantity
                            && d.run == c.run
                            && d.basis == c.basis
                    })
                })
                .map(move |c| failed_check(r, c))
                .collect()
        })
        .collect()
}

/// Every gate failure of the results, in case order: failed gated checks, gated tolerances
/// that match no run, a case whose gate checks nothing, runs that did not end as the case
/// declares (completed unless `[[expected_outcome]]` says otherwise), and physical
/// invariants broken beyond the engine's tolerance and not declared. Lines start `FAIL`.
pub fn failures(results: &[CaseResult]) -> Vec<Failure> {
    let mut out = Vec::new();
    for r in results {
        match &r.azimuths {
            // every azimuth's own failures, the governing one's among them
            Some(sweep) => out.extend(sweep.failures()),
            None => out.extend(case_failures(r, true)),
        }
    }
    out
}

/// The gate failures of one case result, its stale declarations
/// ([`stale_declaration_failures`]) only `with_stale`: a case with a set of azimuths
/// judges those over the whole set.
pub(crate) fn case_failures(r: &CaseResult, with_stale: bool) -> Vec<Failure> {
    let mut out = Vec::new();
    {
        let before = out.len();
        for c in r.checks.iter().filter(|c| fails(c)) {
            out.push(failed_check(r, c));
        }
        out.extend(unmatched_tolerances(r));
        let unmatched = out[before..].iter().any(|f| f.checks_nothing);
        if !unmatched && !checks_something(r) {
            out.push(case_failure(
                r,
                "gate",
                "any run",
                "checks nothing: the case has no gated check (add a gated [[tolerance]] or an [[expected_outcome]])".into(),
                "at least one gated check".into(),
                String::new(),
                true,
            ));
        }
        out.extend(unchecked_externals(r));
        out.extend(outcome_failures(r));
        out.extend(stale_violations(r));
        out.extend(disagreement_failures(r));
        if with_stale {
            out.extend(stale_declaration_failures(r));
        }
        out.extend(
            r.invariants
                .iter()
                .filter(|i| i.fails())
                .map(|i| invariant_failure(r, i)),
        );
    }
    out
}

/// External participants no gated check compares: a program's results brought in and
/// then checked against nothing (no reference and no fe run, or no quantity in common)
/// fail rather than pass silently.
fn unchecked_externals(r: &CaseResult) -> Vec<Failure> {
    r.runs
        .iter()
        .filter(|run| crate::external::is_external(run))
        .filter(|run| {
            let label = run.label();
            !r.checks.iter().any(|c| c.gated && c.run == label)
        })
        .map(|run| {
            case_failure(
                r,
                "gate",
                &run.label(),
                "checks nothing: no gated check compares this external participant (no reference or fe run to compare it with, or no quantity in common)".into(),
                "at least one gated check".into(),
                String::new(),
                true,
            )
        })
        .collect()
}

/// Design-quantity disagreements beyond [`crate::disagreement::DESIGN_PERCENT`] that no
/// gated tolerance judges and the case does not declare.
fn disagreement_failures(r: &CaseResult) -> Vec<Failure> {
    use crate::disagreement::{DESIGN_PERCENT, design_disagreements};
    design_disagreements(r)
        .into_iter()
        .filter(|d| d.declared.is_none())
        .map(|d| {
            case_failure(
                r,
                d.quantity,
                &format!("{} vs {}", d.run, d.basis),
                format!(
                    "undeclared disagreement on a design quantity: {}",
                    difference_words(d.quantity, d.value, d.basis_value)
                ),
                format!(
                    "≤ {DESIGN_PERCENT} %, or a gated [[tolerance]], or an [[expected_disagreement]] with reason and evidence"
                ),
                String::new(),
                false,
            )
        })
        .collect()
}

/// Declarations whose disagreement no longer happens.
pub(crate) fn stale_declaration_failures(r: &CaseResult) -> Vec<Failure> {
    use crate::disagreement::{DESIGN_PERCENT, measured_now, stale_declarations};
    let mut out = Vec::new();
    for d in stale_declarations(r) {
        let now = measured_now(r, d).map_or_else(
            || "no run of this case matches it".to_string(),
            |m| format!("measured {m}"),
        );
        out.push(case_failure(
            r,
            &d.quantity,
            &format!("{} vs {}", d.runs, d.against),
            format!(
                "declared disagreement no longer happens: {now}; remove the declaration or say why it should still happen"
            ),
            format!("beyond {DESIGN_PERCENT} %, declared: {}", d.reason),
            d.field.clone(),
            false,
        ));
    }
    out
}

/// Declared violations that no longer happen: an `[[expected_violation]]` none of whose
/// engine's runs breaks the invariant is a wrong record of the engine's limits and fails
/// like an unexpected pass, with the largest measured value.
fn stale_violations(r: &CaseResult) -> Vec<Failure> {
    r.case
        .expected_violations
        .iter()
        .filter_map(|v| {
            let measured: Vec<&InvariantCheck> = r
                .invariants
                .iter()
                .filter(|i| i.expected.as_ref().is_some_and(|(f, _)| *f == v.field))
                .collect();
            if measured.iter().any(|i| !i.holds()) {
                return None;
            }
            let value = match measured.iter().max_by(|a, b| a.worst.total_cmp(&b.worst)) {
                Some(worst) => format!(
                    "declared violation no longer happens: measured {} on {} (limit {}); remove the declaration or say why it should still happen",
                    show_measure(worst.worst),
                    worst.run,
                    show_measure(worst.limit)
                ),
                None => "checks nothing: no run of this case measures the declared violation".into(),
            };
            Some(case_failure(
                r,
                &v.invariant,
                &v.engine,
                value,
                format!("declared: {}", v.reason),
                v.field.clone(),
                measured.is_empty(),
            ))
        })
        .collect()
}

/// An invariant's dimensionless measure for people: four significant digits, a value
/// below 1e-9 (round-off) as 0.
pub fn show_measure(x: f64) -> String {
    if x.abs() < 1e-9 {
        "0".into()
    } else {
        rockslide_core::response::sig(x)
    }
}

/// Whether the case's gate checks anything: a gated tolerance check or a declared outcome.
fn checks_something(r: &CaseResult) -> bool {
    r.checks.iter().any(|c| c.gated) || !r.case.expected_outcomes.is_empty()
}

fn case_failure(
    r: &CaseResult,
    quantity: &str,
    engines: &str,
    value: String,
    tolerance: String,
    field: String,
    checks_nothing: bool,
) -> Failure {
    let file = r.case.path.display().to_string();
    Failure {
        case: r.case.name.clone(),
        quantity: quantity.into(),
        engines: engines.into(),
        value,
        tolerance,
        field: if field.is_empty() {
            file
        } else {
            format!("{file}: {field}")
        },
        checks_nothing,
        gated: true,
    }
}

fn unmatched_tolerances(r: &CaseResult) -> Vec<Failure> {
    r.case
        .tolerances
        .iter()
        .filter(|t| t.gate && r.checks.iter().all(|c| c.field != t.field))
        .map(|t| {
            case_failure(
                r,
                &t.quantity,
                &t.runs.clone().unwrap_or_else(|| "any run".into()),
                unmatched_reason(r, t.runs.as_deref()),
                tolerance_words(t),
                t.field.clone(),
                true,
            )
        })
        .collect()
}

/// Why a tolerance matched no run, naming the participant that did not run and why when
/// the registry or the live participant said so (`opensees: OpenSeesPy not found …`).
fn unmatched_reason(r: &CaseResult, runs: Option<&str>) -> String {
    let engine = runs.map(|s| s.split('/').next().unwrap_or(s));
    let why = r
        .not_applicable
        .iter()
        .find(|(id, _)| Some(*id) == engine)
        .map(|(id, why)| format!(" ({id} did not run: {why})"))
        .unwrap_or_default();
    format!("checks nothing: no run of this case matches the tolerance{why}")
}

/// Runs that did not end as declared: a run that did not complete without an
/// `[[expected_outcome]]` saying so, a run whose declared outcome did not happen, and a
/// declaration that matches no run.
fn outcome_failures(r: &CaseResult) -> Vec<Failure> {
    let mut out = Vec::new();
    for run in &r.runs {
        let declared = r
            .case
            .expected_outcomes
            .iter()
            .find(|o| o.applies_to(run.engine, &run.variant));
        let (value, field) = match declared {
            None if run.status.completed() => continue,
            None => (
                format!("run did not complete: {}", run.status),
                String::new(),
            ),
            Some(o) if o.status == run.status.label() => continue,
            Some(o) => (
                format!("expected {}, run {}", o.status, run.status),
                o.field.clone(),
            ),
        };
        let expected = declared.map_or("completed", |o| o.status.as_str());
        out.push(case_failure(
            r,
            "run status",
            &run.label(),
            value,
            expected.to_string(),
            field,
            false,
        ));
    }
    for o in &r.case.expected_outcomes {
        if !r
            .runs
            .iter()
            .any(|run| o.applies_to(run.engine, &run.variant))
        {
            out.push(case_failure(
                r,
                "run status",
                &o.engine,
                "checks nothing: no run of this case matches the expected outcome".into(),
                o.status.clone(),
                o.field.clone(),
                true,
            ));
        }
    }
    out
}

fn invariant_failure(r: &CaseResult, i: &InvariantCheck) -> Failure {
    let at =
        i.at.map(|t| format!(" at t = {t:.4} s"))
            .unwrap_or_default();
    case_failure(
        r,
        i.invariant.key(),
        &i.run,
        format!("invariant broken: {:.3e}{at}", i.worst),
        format!(
            "≤ {:.1e} ({})",
            i.limit,
            crate::invariants::meaning(i.invariant)
        ),
        String::new(),
        false,
    )
}

/// Ungated checks outside their limit by at least this much (in per cent) are marked
/// `WARN` among the informative findings, the others `INFO`.
pub const WARN_PERCENT: f64 = 10.0;

/// What must not hide under a green PASS, each said once: the design-quantity
/// disagreements the case declares (`KNOWN`, with reason and evidence) and the invariant
/// violations it declares, one line per declaration with every run's measured size
/// (`KNOWN housner-pulse: rapier breaks stick_slip: kinematic-ground 0.8399, …`).
pub fn warnings(results: &[CaseResult]) -> Vec<String> {
    let mut out = Vec::new();
    for r in results {
        for d in crate::disagreement::design_disagreements(r) {
            if let Some(x) = &d.declared {
                out.push(format!(
                    "KNOWN {}: {}: {} vs {} differ: {} — {}; evidence: {} [{}: {}]",
                    r.case.name,
                    d.quantity,
                    d.run,
                    d.basis,
                    difference_words(d.quantity, d.value, d.basis_value),
                    x.reason,
                    x.evidence,
                    r.case.path.display(),
                    x.field
                ));
            }
        }
        for v in &r.case.expected_violations {
            let broken: Vec<String> = r
                .invariants
                .iter()
                .filter(|i| !i.holds())
                .filter(|i| i.expected.as_ref().is_some_and(|(f, _)| *f == v.field))
                .map(|i| {
                    let variant = i.run.split_once('/').map_or(i.run.as_str(), |x| x.1);
                    format!("{variant} {}", show_measure(i.worst))
                })
                .collect();
            if broken.is_empty() {
                continue; // a stale declaration: a gate failure, not a note
            }
            let limit = r
                .invariants
                .iter()
                .find(|i| i.expected.as_ref().is_some_and(|(f, _)| *f == v.field))
                .map_or(String::new(), |i| {
                    format!(" (limit {})", show_measure(i.limit))
                });
            out.push(format!(
                "KNOWN {}: {} breaks {}: {}{limit} — declared: {} [{}: {}]",
                r.case.name,
                v.engine,
                v.invariant,
                broken.join(", "),
                v.reason,
                r.case.path.display(),
                v.field
            ));
        }
    }
    out
}

impl CaseResult {
    /// Whether the case passes the gate (as `rockslide check` decides it).
    pub fn gate_passed(&self) -> bool {
        // one truth with `check`: failed gated checks and gated tolerances that check nothing
        failures(std::slice::from_ref(self)).is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::invariants::check_run;
    use rockslide_core::case::Invariant;
    use rockslide_core::trace::{Trace, q};
    use rockslide_engine_api::{Run, RunStatus};

    /// A PEPO (M = 1000 kg, g = 10 m/s², μ = 0.5: μ·M·g = 5 kN) with `extra` appended.
    fn case(extra: &str) -> rockslide_core::case::Case {
        let text = format!(
            r#"
[model]
kind = "oscillator"
mass = 1000.0
gravity = 10.0
[model.contact]
kx = 1.0e6
kz = 4.0e6
mu = 0.5
[excitation]
kind = "mass-acceleration"
shape = "sine-pulse"
amplitude = 1.0
omega = 10.0
cycles = 0.5
[run]
duration = 1.0
dt = 0.1
{extra}
"#
        );
        crate::registry::parse_case(std::path::Path::new("t.toml"), &text).expect("valid case")
    }

    /// A run whose contact force and slip are the given rows (t = 0, 0.1, …).
    fn run(engine: &'static str, status: RunStatus, rows: &[(f64, f64)]) -> Run {
        let mut trace = Trace::with_channels(&[&q::RESISTANCE, &q::SLIDE], rows.len());
        for (i, (r, s)) in rows.iter().enumerate() {
            trace.push(i as f64 * 0.1, &[*r, *s]);
        }
        Run {
            engine,
            variant: "v".into(),
            arrangement: Default::default(),
            dt: 0.1,
            settings: Vec::new(),
            stats: rockslide_engine_api::SolverStats::default(),
            findings: Vec::new(),
            trace,
            status,
            wall_seconds: 0.0,
        }
    }

    fn result(case: rockslide_core::case::Case, runs: Vec<Run>) -> CaseResult {
        let invariants = runs.iter().flat_map(|r| check_run(&case, r)).collect();
        CaseResult {
            run_responses: runs.iter().map(|_| Default::default()).collect(),
            history_errors: runs.iter().map(|_| None).collect(),
            case,
            runs,
            not_applicable: Vec::new(),
            reference: Err("none".into()),
            checks: Vec::new(),
            azimuths: None,
            invariants,
            envelopes: Vec::new(),
        }
    }

    fn diverged() -> RunStatus {
        RunStatus::Diverged {
            time: 0.5,
            reason: "NaN".into(),
        }
    }

    const STUCK: &[(f64, f64)] = &[(0.0, 0.0), (1000.0, 0.0), (-1000.0, 0.0)];

    #[test]
    fn a_case_that_checks_nothing_fails_and_a_declared_divergence_passes() {
        let f = failures(&[result(
            case(""),
            vec![run("fe", RunStatus::Completed, STUCK)],
        )]);
        assert_eq!(f.len(), 1, "{f:?}");
        assert!(f[0].checks_nothing && f[0].value.starts_with("checks nothing: the case"));

        let declared = case("[[expected_outcome]]\nengine = \"fe\"\nstatus = \"diverged\"");
        assert!(failures(&[result(declared, vec![run("fe", diverged(), STUCK)])]).is_empty());
    }

    #[test]
    fn an_undeclared_divergence_and_a_declared_one_that_did_not_happen_fail() {
        let outcome = "[[expected_outcome]]\nengine = \"rapier\"\nstatus = \"diverged\"";
        let runs = vec![
            run("fe", diverged(), STUCK),
            run("rapier", RunStatus::Completed, STUCK),
        ];
        let f = failures(&[result(case(outcome), runs)]);
        let values: Vec<&str> = f.iter().map(|f| f.value.as_str()).collect();
        assert_eq!(
            values,
            [
                "run did not complete: diverged at t = 0.500000 s: NaN",
                "expected diverged, run completed"
            ]
        );
        assert_eq!(f[1].field, "t.toml: expected_outcome[0]");
    }

    #[test]
    fn a_force_beyond_mu_n_breaks_the_friction_bound_unless_declared() {
        // |T| = 6 kN against μN = 5 kN: excess (6 − 5)/5 = 0.2 at t = 0.1 s.
        let rows = [(0.0, 0.0), (6000.0, 0.0), (0.0, 0.0)];
        let outcome = "[[expected_outcome]]\nengine = \"fe\"\nstatus = \"diverged\"\n";
        let plain = result(case(outcome), vec![run("fe", RunStatus::Completed, &rows)]);
        let bound = &plain.invariants[0];
        assert_eq!(
            (bound.invariant, bound.worst, bound.at),
            (Invariant::FrictionBound, 0.2, Some(0.1))
        );
        // The declared outcome did not happen (one failure) and the bound is broken (another).
        let f = failures(std::slice::from_ref(&plain));
        assert!(f.iter().any(|f| f.quantity == "friction_bound"), "{f:?}");

        let declared = format!(
            "{outcome}[[expected_violation]]\nengine = \"fe\"\ninvariant = \"friction_bound\"\nreason = \"measured 0.2\""
        );
        let known = result(
            case(&declared),
            vec![run("fe", RunStatus::Completed, &rows)],
        );
        assert!(
            !failures(std::slice::from_ref(&known))
                .iter()
                .any(|f| f.quantity == "friction_bound")
        );
        let w = warnings(std::slice::from_ref(&known));
        assert!(
            w[0].starts_with("KNOWN t: fe breaks friction_bound: v 0.2000 (limit "),
            "{w:?}"
        );
    }

    /// A declared violation the run no longer shows fails the gate with the measured value,
    /// like an unexpected pass: |T| = 1 kN stays under μN = 5 kN, so friction_bound
    /// measures |T|/(μN) − 1 = −0.8 (a case with nothing else gated also checks nothing).
    #[test]
    fn a_declared_violation_that_no_longer_happens_fails() {
        let declared = "[[expected_violation]]\nengine = \"fe\"\ninvariant = \"friction_bound\"\nreason = \"measured 0.2\"";
        let r = result(case(declared), vec![run("fe", RunStatus::Completed, STUCK)]);
        let all = failures(std::slice::from_ref(&r));
        let f: Vec<&Failure> = all.iter().filter(|f| !f.checks_nothing).collect();
        assert_eq!(f.len(), 1, "{all:?}");
        assert_eq!(f[0].quantity, "friction_bound");
        assert_eq!(f[0].field, "t.toml: expected_violation[0]");
        assert!(
            f[0].value
                .starts_with("declared violation no longer happens: measured -0.8000 on fe/v"),
            "{}",
            f[0].value
        );
        assert!(!r.gate_passed());
    }

    #[test]
    fn creep_while_stuck_and_negative_friction_work_are_measured() {
        // Stuck (|T| = 1 kN < μN) while slipping 2 mm: all of the slip path is creep.
        let creep = [(1000.0, 0.0), (1000.0, 0.001), (1000.0, 0.002)];
        let r = result(case(""), vec![run("fe", RunStatus::Completed, &creep)]);
        let stick = r
            .invariants
            .iter()
            .find(|i| i.invariant == "stick_slip")
            .unwrap();
        assert_eq!(stick.worst, 1.0);
        // Slipping at T = +μN towards −x for 2 mm: the friction work is all negative.
        let pumping = [(5000.0, 0.0), (5000.0, -0.001), (5000.0, -0.002)];
        let r = result(case(""), vec![run("fe", RunStatus::Completed, &pumping)]);
        let d = r
            .invariants
            .iter()
            .find(|i| i.invariant == "dissipation")
            .unwrap();
        assert_eq!(d.worst, 1.0);
        let stick = r
            .invariants
            .iter()
            .find(|i| i.invariant == "stick_slip")
            .unwrap();
        assert_eq!(stick.worst, 0.0);
    }

    #[test]
    fn unknown_expected_keys_are_located_errors() {
        let text = "[[expected_violation]]\nengine = \"fe\"\ninvariant = \"wobble\"\nreason = \"x\"\n[[expected_outcome]]\nengine = \"fe\"\nstatus = \"exploded\"";
        let full = format!(
            "[model]\nkind = \"oscillator\"\nmass = 1.0\ngravity = 1.0\n[model.contact]\nkx = 1.0\nkz = 1.0\nmu = 0.5\n[excitation]\nkind = \"none\"\n[run]\nduration = 1.0\ndt = 0.1\n{text}"
        );
        let err = crate::registry::parse_case(std::path::Path::new("t.toml"), &full)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("expected_violation[0].invariant: unknown invariant \"wobble\""),
            "{err}"
        );
        assert!(
            err.contains("expected_outcome[0].status: unknown status \"exploded\""),
            "{err}"
        );
    }
}

//! The verdict of a case: which checks fail the gate (and which are informative), as values
//! with a one-line rendering for logs. The one pass/fail rule; `rockslide check`, the
//! reports and the JUnit all ask it.

use std::fmt;

use crate::analysis::{Check, Verdict};
use crate::invariants::InvariantCheck;
use crate::suite::CaseResult;
use rockslide_core::case::Tolerance;
use rockslide_core::response::show_value;

/// One failed check: a gated one fails the gate; an informative one (`gate = false`) is
/// only reported.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// Case name.
    pub case: String,
    /// Quantity key.
    pub quantity: String,
    /// `run vs basis` (`predictor-corrector/paper vs reference`).
    pub engines: String,
    /// What was found, in words (`Δ -0.65 % (8.699 mm vs 8.756 mm)`).
    pub value: String,
    /// The tolerance in words (`≤ 0.1 %`).
    pub tolerance: String,
    /// Where the tolerance is in the case file (`cases/x.toml: tolerance[2]`).
    pub field: String,
    /// A gated tolerance that matched no run (rather than a check that failed).
    pub checks_nothing: bool,
    /// Whether the check is gated (informative failures come from [`informative`]).
    pub gated: bool,
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {}: {}: {}: {} (tolerance {}) [{}]",
            if self.gated { "FAIL" } else { "INFO" },
            self.case,
            self.quantity,
            self.engines,
            self.value,
            self.tolerance,
            self.field
        )
    }
}

/// What a check found, in words: the discrepancy and both values in display units.
pub fn describe(c: &Check) -> String {
    match (c.value, c.basis_value) {
        (Some(v), Some(b)) => {
            let both = format!(
                "{} vs {} {}",
                show_value(&c.quantity, v).0,
                show_value(&c.quantity, b).0,
                show_value(&c.quantity, b).1
            );
            match c.percent {
                Some(p) => format!("Δ {p:+.3} % ({})", both.trim_end()),
                None => {
                    let (d, unit) = show_value(&c.quantity, v - b);
                    format!("Δ {d} {unit} ({})", both.trim_end())
                }
            }
        }
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
    let abs = t.absolute.map(|a| {
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

fn failed_check(r: &CaseResult, c: &Check) -> Failure {
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
            r.checks
                .iter()
                .filter(|c| !c.gated && c.verdict != Verdict::Pass)
                .map(move |c| failed_check(r, c))
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
        out.extend(outcome_failures(r));
        out.extend(
            r.invariants
                .iter()
                .filter(|i| i.fails())
                .map(|i| invariant_failure(r, i)),
        );
    }
    out
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
                "checks nothing: no run of this case matches the tolerance".into(),
                tolerance_words(t),
                t.field.clone(),
                true,
            )
        })
        .collect()
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
        if !r.runs.iter().any(|run| o.applies_to(run.engine, &run.variant)) {
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
    let at = i.at.map(|t| format!(" at t = {t:.4} s")).unwrap_or_default();
    case_failure(
        r,
        i.invariant,
        &i.run,
        format!("invariant broken: {:.3e}{at}", i.worst),
        format!("≤ {:.1e} ({})", i.limit, crate::invariants::meaning(i.invariant)),
        String::new(),
        false,
    )
}

/// Ungated disagreements at least this large (in per cent) are warnings, shown first.
pub const WARN_PERCENT: f64 = 10.0;

/// What must not hide under a green PASS, one line each starting `WARN`: informative
/// (ungated) checks whose discrepancy is at least [`WARN_PERCENT`], and declared invariant
/// violations with their measured size.
pub fn warnings(results: &[CaseResult]) -> Vec<String> {
    let mut out = Vec::new();
    for r in results {
        for c in r.checks.iter().filter(|c| !c.gated) {
            if let Some(p) = c.percent.filter(|p| p.abs() >= WARN_PERCENT) {
                out.push(format!(
                    "WARN {}: {}: {} vs {}: disagree by {p:+.1} % (not gated) [{}: {}]",
                    r.case.name,
                    c.quantity,
                    c.run,
                    c.basis,
                    r.case.path.display(),
                    c.field
                ));
            }
        }
        for i in r.invariants.iter().filter(|i| !i.holds()) {
            if let Some((field, reason)) = &i.expected {
                out.push(format!(
                    "WARN {}: {}: {}: {} — declared known: {reason} [{}: {field}]",
                    r.case.name,
                    i.invariant,
                    i.run,
                    i.describe(),
                    r.case.path.display()
                ));
            }
        }
    }
    out
}

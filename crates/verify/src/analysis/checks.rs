//! Tolerance checks: each tolerance of a case applied to each run it names, against the
//! reference or another run, giving PASS/FAIL lines for reports and the gate.

use rockslide_core::case::REFERENCE_LABEL;
use rockslide_core::case::{Tolerance, ToleranceBasis};
use rockslide_engine_api::Run;

use super::metrics::{Responses, discrepancy_percent};

/// Outcome of one check.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Within tolerance.
    Pass,
    /// Outside tolerance.
    Fail,
    /// Could not be evaluated (quantity missing on one side, run failed).
    Missing,
}

impl Verdict {
    /// PASS / FAIL / MISSING.
    pub fn label(&self) -> &'static str {
        match self {
            Verdict::Pass => "PASS",
            Verdict::Fail => "FAIL",
            Verdict::Missing => "MISSING",
        }
    }
}

/// One tolerance applied to one run.
#[derive(Debug, Clone)]
pub struct Check {
    /// Quantity key.
    pub quantity: String,
    /// The run checked, `engine/variant`.
    pub run: String,
    /// What it is compared with (`reference` or `engine/variant`).
    pub basis: String,
    /// The run's value, SI.
    pub value: Option<f64>,
    /// The basis value, SI.
    pub basis_value: Option<f64>,
    /// Discrepancy in percent, when defined.
    pub percent: Option<f64>,
    /// The tolerance in words (`≤ 2 %`, `≤ 0.005 s`).
    pub limit: String,
    /// Whether a failure fails the gate.
    pub gated: bool,
    /// The outcome.
    pub verdict: Verdict,
    /// Where the tolerance is in the case file.
    pub field: String,
}

/// Apply the case's tolerances. `reference` holds the reference's quantities, if any;
/// `run_responses[i]` belongs to `runs[i]`.
pub fn evaluate_tolerances(
    tolerances: &[Tolerance],
    runs: &[Run],
    run_responses: &[Responses],
    reference: Option<&Responses>,
) -> Vec<Check> {
    let mut checks = Vec::new();
    for tol in tolerances {
        for (run, resp) in runs.iter().zip(run_responses) {
            if !tol.applies_to(run.engine, &run.variant) {
                continue;
            }
            let (basis_name, basis) = match &tol.basis {
                ToleranceBasis::Reference => (REFERENCE_LABEL.to_string(), reference),
                ToleranceBasis::Run(label) => {
                    if *label == run.label() {
                        continue;
                    }
                    let other = runs.iter().position(|r| r.label() == *label);
                    (label.clone(), other.map(|i| &run_responses[i]))
                }
            };
            let key = tol.quantity.as_str();
            let value = resp.get(key).copied().filter(|_| run.status.completed());
            let basis_value = basis.and_then(|b| b.get(key).copied());
            let (percent, verdict) = match (value, basis_value) {
                (Some(v), Some(b)) => {
                    let pct = discrepancy_percent(v, b);
                    // Either limit suffices (validation guarantees at least one is given).
                    let within_pct = tol
                        .percent
                        .is_some_and(|lim| pct.is_some_and(|p| p.abs() <= lim));
                    let within_abs = tol.absolute.is_some_and(|lim| (v - b).abs() <= lim);
                    let pass = within_pct || within_abs;
                    (pct, if pass { Verdict::Pass } else { Verdict::Fail })
                }
                _ => (None, Verdict::Missing),
            };
            let limit = match (tol.percent, tol.absolute) {
                (Some(p), Some(a)) => format!("≤ {p} % or ≤ {a}"),
                (Some(p), None) => format!("≤ {p} %"),
                (None, Some(a)) => format!("≤ {a}"),
                (None, None) => "—".into(),
            };
            checks.push(Check {
                quantity: key.to_string(),
                run: run.label(),
                basis: basis_name,
                value,
                basis_value,
                percent,
                limit,
                gated: tol.gate,
                verdict,
                field: tol.field.clone(),
            });
        }
    }
    checks
}

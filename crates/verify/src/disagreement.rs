//! Disagreements on the design quantities (peak and residual sliding, uplift, rotation):
//! each participant against the basis (the reference, or the first completed run when
//! there is none). A difference beyond [`DESIGN_PERCENT`] that no gated tolerance judges
//! must be declared (`[[expected_disagreement]]`, with its reason and evidence) or it
//! fails the gate; a declaration whose disagreement no longer happens fails it too.

use rockslide_core::case::REFERENCE_LABEL;
use rockslide_core::case::{DESIGN_QUANTITIES, ExpectedDisagreement};
use rockslide_core::response::show_value;

use crate::analysis::Responses;
use crate::result::CaseResult;

/// A design quantity differing from the basis by more than this (per cent of the scale
/// below) is a disagreement.
pub const DESIGN_PERCENT: f64 = 10.0;

/// Sliding differences are measured against at least this fraction of the basis's peak
/// |sliding|, so that a residual near zero does not turn round-off into a disagreement.
const SLIDING_SCALE_OF_PEAK: f64 = 0.1;

/// One participant against the basis on one design quantity, beyond [`DESIGN_PERCENT`].
#[derive(Debug, Clone, PartialEq)]
pub struct Disagreement {
    /// Design quantity key.
    pub quantity: &'static str,
    /// The run, `engine/variant`.
    pub run: String,
    /// The basis: `reference` or a run label.
    pub basis: String,
    /// The run's value, SI.
    pub value: f64,
    /// The basis's value, SI.
    pub basis_value: f64,
    /// 100·(value/basis − 1), when the basis is not zero.
    pub percent: Option<f64>,
    /// The case's declaration that accepts it, if any.
    pub declared: Option<ExpectedDisagreement>,
}

/// The basis of the design comparison: its label and its responses.
pub fn basis(r: &CaseResult) -> Option<(String, &Responses)> {
    if let Ok(x) = &r.reference {
        return Some((REFERENCE_LABEL.into(), &x.responses));
    }
    r.runs
        .iter()
        .zip(&r.run_responses)
        .find(|(run, _)| run.status.completed())
        .map(|(run, resp)| (run.label(), resp))
}

/// Every disagreement of the case beyond [`DESIGN_PERCENT`] that no gated tolerance
/// judges, declared or not, in run then quantity order.
pub fn design_disagreements(r: &CaseResult) -> Vec<Disagreement> {
    let Some((basis_label, basis)) = basis(r) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for (run, resp) in r.runs.iter().zip(&r.run_responses) {
        let label = run.label();
        if !run.status.completed() || label == basis_label {
            continue;
        }
        for &quantity in DESIGN_QUANTITIES {
            let (Some(&value), Some(&basis_value)) = (resp.get(quantity), basis.get(quantity))
            else {
                continue;
            };
            if judged_by_gated_tolerance(r, quantity, &label, &basis_label)
                || !beyond_limit(quantity, value, basis_value, basis)
            {
                continue;
            }
            out.push(Disagreement {
                quantity,
                declared: r
                    .case
                    .expected_disagreements
                    .iter()
                    .find(|d| d.covers(quantity, &label, &basis_label))
                    .cloned(),
                run: label.clone(),
                basis: basis_label.clone(),
                value,
                basis_value,
                percent: (basis_value != 0.0).then(|| 100.0 * (value / basis_value - 1.0)),
            });
        }
    }
    out
}

/// Declarations no current disagreement matches: the participants now agree (or the run
/// is gone), so the case's record of the engines' limits is wrong.
pub fn stale_declarations(r: &CaseResult) -> Vec<&ExpectedDisagreement> {
    let found = design_disagreements(r);
    r.case
        .expected_disagreements
        .iter()
        .filter(|d| {
            !found
                .iter()
                .any(|x| x.declared.as_ref().is_some_and(|y| y.field == d.field))
        })
        .collect()
}

/// The measured difference of a stale declaration's quantity, in words, if its run and
/// basis both ran (`Δ −2.1 % (3.70 vs 3.78 mm)`).
pub fn measured_now(r: &CaseResult, d: &ExpectedDisagreement) -> Option<String> {
    let (basis_label, basis) = basis(r)?;
    if basis_label != d.against {
        return None;
    }
    let (run, resp) = r
        .runs
        .iter()
        .zip(&r.run_responses)
        .find(|(run, _)| d.covers(&d.quantity, &run.label(), &basis_label))?;
    let (v, b) = (
        *resp.get(d.quantity.as_str())?,
        *basis.get(d.quantity.as_str())?,
    );
    Some(format!(
        "{} {}",
        run.label(),
        difference_words(&d.quantity, v, b)
    ))
}

/// Whether a gated tolerance compares this run with this basis on this quantity: then
/// the tolerance decides, and its failure is a gate failure already.
fn judged_by_gated_tolerance(r: &CaseResult, quantity: &str, run: &str, basis: &str) -> bool {
    r.checks
        .iter()
        .any(|c| c.gated && c.quantity == quantity && c.run == run && c.basis == basis)
}

/// Whether |value − basis| exceeds [`DESIGN_PERCENT`] of the scale: |basis|, and for a
/// sliding quantity at least a tenth of the basis's peak |sliding|.
fn beyond_limit(quantity: &str, value: f64, basis_value: f64, basis: &Responses) -> bool {
    let floor = if quantity.contains("sliding") {
        SLIDING_SCALE_OF_PEAK * basis.get("peak_abs_sliding").copied().unwrap_or(0.0)
    } else {
        0.0
    };
    let scale = basis_value.abs().max(floor);
    scale > 0.0 && (value - basis_value).abs() > DESIGN_PERCENT / 100.0 * scale
}

/// A difference in words with both values in display units: in per cent for a value
/// (`Δ −49.8 % (1.891 vs 3.766 mm)`), as a difference for a count or an event time
/// (`Δ −1 (32 vs 33)`, `Δ +0.0010 s (0.8430 vs 0.8420 s)`): never both in one phrase.
pub fn difference_words(quantity: &str, v: f64, b: f64) -> String {
    let def = rockslide_core::response::quantity_def(quantity);
    let (vs, unit) = show_value(quantity, v);
    let both = format!("{vs} vs {} {unit}", show_value(quantity, b).0);
    let both = both.trim_end();
    if def.is_some_and(|d| d.is_count()) {
        return format!("Δ {:+} ({both})", v - b);
    }
    match crate::analysis::discrepancy_percent(v, b) {
        Some(p) if !def.is_some_and(|d| d.is_time()) => format!("Δ {} % ({both})", percent3(p)),
        _ => {
            let (d, unit) = show_value(quantity, v - b);
            let sign = if v >= b { "+" } else { "" };
            format!("Δ {sign}{d} {unit} ({both})")
        }
    }
}

/// A signed percentage to three significant digits (`-0.617`, `-49.8`, `+12215`).
fn percent3(p: f64) -> String {
    let digits = if p == 0.0 {
        1
    } else {
        (2 - p.abs().log10().floor() as i32).max(0) as usize
    };
    format!("{p:+.digits$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn responses(pairs: &[(&'static str, f64)]) -> Responses {
        pairs.iter().copied().collect()
    }

    #[test]
    fn a_residual_near_zero_is_measured_against_a_tenth_of_the_peak() {
        let basis = responses(&[("peak_abs_sliding", 0.010), ("residual_sliding", 0.0001)]);
        // the scale is max(0.1 mm, a tenth of 10 mm) = 1 mm: 0.9 mm off is beyond 0.1 mm
        assert!(beyond_limit("residual_sliding", 0.001, 0.0001, &basis));
        // 0.05 mm off is under 10 % of 1 mm
        assert!(!beyond_limit("residual_sliding", 0.00015, 0.0001, &basis));
        // a peak: 9.75 % of itself is not beyond, 10.1 % is
        let peak = responses(&[("peak_uplift", 0.004)]);
        assert!(!beyond_limit("peak_uplift", 0.00439, 0.004, &peak));
        assert!(beyond_limit("peak_uplift", 0.004404, 0.004, &peak));
    }

    /// A difference reads in per cent for a value, in seconds for an event time (its
    /// percentage depends on where t = 0 is) and as a difference for a count.
    #[test]
    fn differences_never_mix_percentages_and_counts() {
        assert_eq!(
            difference_words("first_liftoff", 0.75, 0.85),
            "Δ -0.1000 s (0.7500 vs 0.8500 s)"
        );
        assert_eq!(
            difference_words("residual_sliding", 0.001891, 0.003766),
            "Δ -49.8 % (1.891 vs 3.766 mm)"
        );
        assert_eq!(
            difference_words("slip_episodes", 32.0, 33.0),
            "Δ -1 (32 vs 33)"
        );
    }
}

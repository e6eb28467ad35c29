//! `[[tolerance]]` (a response quantity, the runs it applies to, its basis and bounds),
//! `[[expected_outcome]]` (a run expected not to complete) and `[[expected_violation]]`
//! (an invariant violation accepted, with its reason), `[[expected_disagreement]]` (a
//! design-quantity disagreement accepted, with its reason and evidence).

use super::super::raw::{
    RawExpectedDisagreement, RawExpectedOutcome, RawExpectedViolation, RawTolerance,
};
use super::super::scene::{
    DESIGN_QUANTITIES, EXPECTED_STATUSES, ExpectedDisagreement, ExpectedOutcome, ExpectedViolation,
    INVARIANT_KEYS, Tolerance, ToleranceBasis, quoted,
};

use super::validator::{Rule, Validator};

impl Validator<'_> {
    pub(super) fn expected_outcome(&mut self, i: usize, o: &RawExpectedOutcome) -> ExpectedOutcome {
        let field = format!("expected_outcome[{i}]");
        self.engine_id(&format!("{field}.engine"), &o.engine);
        if !EXPECTED_STATUSES.contains(&o.status.as_str()) {
            self.fail(
                &format!("{field}.status"),
                format!(
                    "unknown status \"{}\"; a run expected not to complete is one of: {}",
                    o.status,
                    quoted(EXPECTED_STATUSES)
                ),
            );
        }
        ExpectedOutcome {
            engine: o.engine.clone(),
            variant: o.variant.clone(),
            status: o.status.clone(),
            reason: o.reason.clone(),
            field,
        }
    }

    pub(super) fn expected_violation(
        &mut self,
        i: usize,
        o: &RawExpectedViolation,
    ) -> ExpectedViolation {
        let field = format!("expected_violation[{i}]");
        if !self.external_labels.contains(&o.engine) {
            self.engine_id(&format!("{field}.engine"), &o.engine);
        }
        if !INVARIANT_KEYS.contains(&o.invariant.as_str()) {
            self.fail(
                &format!("{field}.invariant"),
                format!(
                    "unknown invariant \"{}\"; known: {}",
                    o.invariant,
                    quoted(INVARIANT_KEYS)
                ),
            );
        }
        if o.reason.trim().is_empty() {
            self.fail(
                &format!("{field}.reason"),
                "must say why the violation is accepted",
            );
        }
        ExpectedViolation {
            engine: o.engine.clone(),
            invariant: o.invariant.clone(),
            reason: o.reason.clone(),
            field,
        }
    }

    pub(super) fn expected_disagreement(
        &mut self,
        i: usize,
        o: &RawExpectedDisagreement,
    ) -> ExpectedDisagreement {
        let field = format!("expected_disagreement[{i}]");
        let engine = o.engine.split('/').next().unwrap_or_default();
        if !self.external_labels.contains(&o.engine) {
            self.engine_id(&format!("{field}.engine"), engine);
        }
        if !DESIGN_QUANTITIES.contains(&o.quantity.as_str()) {
            self.fail(
                &format!("{field}.quantity"),
                format!(
                    "\"{}\" is not a design quantity; one of: {}",
                    o.quantity,
                    quoted(DESIGN_QUANTITIES)
                ),
            );
        }
        for (key, text) in [("reason", &o.reason), ("evidence", &o.evidence)] {
            if text.trim().is_empty() {
                self.fail(
                    &format!("{field}.{key}"),
                    "must say why the disagreement is accepted and what shows it",
                );
            }
        }
        ExpectedDisagreement {
            quantity: o.quantity.clone(),
            runs: o.engine.clone(),
            against: o
                .against
                .clone()
                .unwrap_or_else(|| crate::case::REFERENCE_LABEL.into()),
            reason: o.reason.clone(),
            evidence: o.evidence.clone(),
            field,
        }
    }

    pub(super) fn tolerance(&mut self, i: usize, t: &RawTolerance) -> Option<Tolerance> {
        let field = format!("tolerance[{i}]");
        if t.percent.is_none() && t.absolute.is_none() {
            self.fail(&field, "needs `percent` or `absolute` (or both)");
        }
        if let Some(p) = t.percent {
            self.number(
                &format!("{field}.percent"),
                Some(p),
                Rule::non_negative("%"),
            );
        }
        if let Some(a) = t.absolute {
            self.number(
                &format!("{field}.absolute"),
                Some(a),
                Rule::non_negative("SI unit of the quantity"),
            );
        }
        if !crate::response::QUANTITY_KEYS.contains(&t.quantity.as_str()) {
            self.fail(
                &format!("{field}.quantity"),
                format!(
                    "unknown quantity \"{}\"; known: {}",
                    t.quantity,
                    quoted(crate::response::QUANTITY_KEYS)
                ),
            );
        }
        let basis = match t.against.as_deref() {
            None | Some(crate::case::REFERENCE_LABEL) => ToleranceBasis::Reference,
            Some(run) => ToleranceBasis::Run(run.to_string()),
        };
        Some(Tolerance {
            quantity: t.quantity.clone(),
            runs: t.engine.clone(),
            basis,
            percent: t.percent,
            absolute: t.absolute,
            gate: t.gate.unwrap_or(true),
            field,
        })
    }
}

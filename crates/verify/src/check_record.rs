//! One tolerance check as the records keep it ([`CheckRecord`]): a case's
//! (`result.json`, [`crate::record`]) and each azimuth's of a set ([`crate::azimuth_record`]).

use serde::{Deserialize, Serialize};

use crate::analysis::Check;

/// One tolerance applied to one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckRecord {
    /// Quantity key.
    pub quantity: String,
    /// The run checked, `engine/variant`.
    pub run: String,
    /// What it is compared with (`reference` or `engine/variant`).
    pub basis: String,
    /// The run's value, SI.
    #[serde(with = "crate::json::real_opt")]
    pub value: Option<f64>,
    /// The basis value, SI.
    #[serde(with = "crate::json::real_opt")]
    pub basis_value: Option<f64>,
    /// Discrepancy, %.
    #[serde(with = "crate::json::real_opt")]
    pub percent: Option<f64>,
    /// The tolerance in words.
    pub limit: String,
    /// Whether a failure fails the gate.
    pub gated: bool,
    /// `PASS`, `FAIL`, `MISSING`.
    pub verdict: String,
    /// Where the tolerance is in the case file.
    pub field: String,
}

impl CheckRecord {
    /// The record of a check.
    pub fn of(c: &Check) -> Self {
        CheckRecord {
            quantity: c.quantity.clone(),
            run: c.run.clone(),
            basis: c.basis.clone(),
            value: c.value,
            basis_value: c.basis_value,
            percent: c.percent,
            limit: c.limit.clone(),
            gated: c.gated,
            verdict: c.verdict.label().to_string(),
            field: c.field.clone(),
        }
    }
}

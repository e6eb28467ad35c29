//! One failed check as the gate reports it and the records keep it ([`Failure`]): which
//! checks fail is the verdict's ([`crate::verdict`]).

use std::fmt;

/// One failed check: a gated one fails the gate; an informative one (`gate = false`) is
/// only reported.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
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
    /// Whether the check is gated (informative failures come from [`crate::verdict::informative`]).
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

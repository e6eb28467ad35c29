//! The validator's state (the case's locator, the engines a case may name, the errors
//! found so far) and the checks every section uses: a number against its [`Rule`] (the
//! accepted range and unit, said in words), a key that does not apply to a model kind.

use super::super::external::ReadExternal;
use super::super::locate::Locator;
use super::super::raw::{RawExcitation, RawSecond, RawVertical};
use crate::error::InputError;

pub(super) struct Validator<'a> {
    pub(super) loc: &'a Locator,
    pub(super) engine_ids: &'a [&'a str],
    /// Labels of the case's `[[external]]` participants (an expected violation may name one).
    pub(super) external_labels: Vec<String>,
    pub(super) errors: Vec<InputError>,
    /// Reads an `[[external]]` results file (the file formats are not core's).
    pub(super) read_external: ReadExternal,
}

impl Validator<'_> {
    pub(super) fn fail(&mut self, field: &str, reason: impl Into<String>) {
        self.errors.push(self.loc.error(field, reason));
    }

    /// A required number in `(lo, hi)` or `[lo, hi)` (open at hi), with its unit in the message.
    pub(super) fn number(&mut self, field: &str, value: Option<f64>, rule: Rule) -> f64 {
        let Some(x) = value else {
            self.fail(field, format!("is required ({})", rule.describe()));
            return f64::NAN;
        };
        if !rule.accepts(x) {
            self.fail(field, format!("is {x}, but must be {}", rule.describe()));
        }
        x
    }

    pub(super) fn forbid(&mut self, field: &str, present: bool, kind: &str) {
        if present {
            self.fail(
                field,
                format!("does not apply to a model of kind \"{kind}\""),
            );
        }
    }
}

/// An accepted range for a number, with its unit, able to say itself in words.
pub(super) struct Rule {
    lo: f64,
    lo_open: bool,
    hi: f64,
    allow_inf: bool,
    unit: &'static str,
}

impl Rule {
    pub(super) fn positive(unit: &'static str) -> Self {
        Rule {
            lo: 0.0,
            lo_open: true,
            hi: f64::INFINITY,
            allow_inf: false,
            unit,
        }
    }
    pub(super) fn non_negative(unit: &'static str) -> Self {
        Rule {
            lo: 0.0,
            lo_open: false,
            hi: f64::INFINITY,
            allow_inf: false,
            unit,
        }
    }
    pub(super) fn friction() -> Self {
        Rule {
            lo: 0.0,
            lo_open: false,
            hi: f64::INFINITY,
            allow_inf: true,
            unit: "",
        }
    }
    pub(super) fn fraction() -> Self {
        Rule {
            lo: 0.0,
            lo_open: false,
            hi: 1.0,
            allow_inf: false,
            unit: "",
        }
    }
    pub(super) fn finite() -> Self {
        Rule {
            lo: f64::NEG_INFINITY,
            lo_open: true,
            hi: f64::INFINITY,
            allow_inf: false,
            unit: "",
        }
    }
    /// A body's geometric extent (a half size or a height): positive and at most
    /// [`MAX_EXTENT`](crate::case::limits::MAX_EXTENT) metres.
    pub(super) fn extent(unit: &'static str) -> Self {
        Rule {
            lo: 0.0,
            lo_open: true,
            hi: crate::case::limits::MAX_EXTENT,
            allow_inf: false,
            unit,
        }
    }
    pub(super) fn range(lo: f64, hi: f64, unit: &'static str) -> Self {
        Rule {
            lo,
            lo_open: false,
            hi,
            allow_inf: false,
            unit,
        }
    }

    pub(super) fn accepts(&self, x: f64) -> bool {
        if x.is_nan() {
            return false;
        }
        if x.is_infinite() {
            return self.allow_inf && x > 0.0;
        }
        let above = if self.lo_open {
            x > self.lo
        } else {
            x >= self.lo
        };
        above && x <= self.hi
    }

    pub(super) fn describe(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(", in {}", self.unit)
        };
        let body = match (self.lo, self.hi.is_infinite()) {
            (lo, true) if lo == f64::NEG_INFINITY => "a finite number".to_string(),
            (lo, true) if lo == 0.0 && self.lo_open => "positive and finite".to_string(),
            (0.0, true) => {
                if self.allow_inf {
                    "zero or positive (`inf` for no slip)".to_string()
                } else {
                    "zero or positive and finite".to_string()
                }
            }
            (lo, _) if lo == 0.0 && self.lo_open => {
                format!("positive and at most {}", self.hi)
            }
            (lo, _) => format!("between {lo} and {}", self.hi),
        };
        format!("{body}{unit}")
    }
}

/// The signal keys of an excitation table, horizontal or vertical, borrowed.
pub(super) struct SignalKeys<'a> {
    pub(super) shape: Option<&'a str>,
    pub(super) amplitude: Option<f64>,
    pub(super) omega: Option<f64>,
    pub(super) cycles: Option<f64>,
    pub(super) record: Option<&'a str>,
    pub(super) record_unit: Option<&'a str>,
    pub(super) record_column: Option<i64>,
    pub(super) scale_to_pga_g: Option<f64>,
    pub(super) polarity: Option<f64>,
}

/// [`SignalKeys`] borrowed from each raw excitation table: `RawExcitation`, `RawVertical` and
/// `RawSecond` spell the signal keys alike (serde's `deny_unknown_fields` does not combine
/// with `flatten`, so the raw tables cannot share one struct).
macro_rules! signal_keys_from {
    ($($raw:ty),*) => {$(
        impl<'a> From<&'a $raw> for SignalKeys<'a> {
            fn from(e: &'a $raw) -> Self {
                SignalKeys {
                    shape: e.shape.as_deref(),
                    amplitude: e.amplitude,
                    omega: e.omega,
                    cycles: e.cycles,
                    record: e.record.as_deref(),
                    record_unit: e.record_unit.as_deref(),
                    record_column: e.record_column,
                    scale_to_pga_g: e.scale_to_pga_g,
                    polarity: e.polarity,
                }
            }
        }
    )*};
}

signal_keys_from!(RawExcitation, RawVertical, RawSecond);

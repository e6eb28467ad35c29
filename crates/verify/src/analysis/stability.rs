//! Stability classes of a run: accurate, inaccurate, diverged (NaN/Inf or energy growth,
//! with the time it happened) or not converged (an iterative solver gave up, with time
//! and residual). The classification reads the engine's own [`RunStatus`], then checks
//! the trace itself — an engine that fails to notice its own blow-up is still caught —
//! then the energy audit, then the error against the basis.

use rockslide_core::trace::Trace;
use rockslide_engine_api::RunStatus;

use super::energy::EnergyHistory;

/// What the classification demands.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Criteria {
    /// Largest max-error of the primary displacement, normalised by its peak, that still
    /// counts as accurate (default 0.05: the SAP2000 verification manual's "Acceptable",
    /// ≤ 5 % on displacements).
    pub accuracy: f64,
    /// Energy growth: a run whose stored plus dissipated energy exceeds `1 + growth_factor`
    /// times the most energy ever supplied to it has created energy (default 1.0: twice
    /// the most it was given).
    pub growth_factor: f64,
    /// Absolute energy ceiling, J: a run whose stored plus dissipated energy exceeds it
    /// has diverged whatever its trace says it was given (the `stability` command uses
    /// 100 times the most energy the exact reference was ever given; 0: none).
    pub energy_ceiling: f64,
}

impl Default for Criteria {
    fn default() -> Self {
        Criteria {
            accuracy: 0.05,
            growth_factor: 1.0,
            energy_ceiling: 0.0,
        }
    }
}

/// The class of one run.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "class", rename_all = "snake_case")]
pub enum Class {
    /// Completed, error within the accuracy criterion.
    Accurate,
    /// Completed and stable, error above the accuracy criterion (or no basis to judge).
    Inaccurate,
    /// NaN/Inf, energy growth or an engine panic.
    Diverged {
        /// When, s (`None` when unknown, e.g. a panic).
        #[serde(with = "crate::json::real_opt")]
        time: Option<f64>,
        /// What was seen.
        reason: String,
    },
    /// An iterative solver did not converge.
    NotConverged {
        /// When, s.
        #[serde(with = "crate::json::real")]
        time: f64,
        /// Residual and iterations, in words.
        reason: String,
    },
}

impl Class {
    /// One-word label.
    pub fn label(&self) -> &'static str {
        match self {
            Class::Accurate => "accurate",
            Class::Inaccurate => "inaccurate",
            Class::Diverged { .. } => "diverged",
            Class::NotConverged { .. } => "not converged",
        }
    }

    /// Whether the run blew up.
    pub fn diverged(&self) -> bool {
        matches!(self, Class::Diverged { .. })
    }

    /// Time of the failure, if any.
    pub fn time(&self) -> Option<f64> {
        match self {
            Class::Diverged { time, .. } => *time,
            Class::NotConverged { time, .. } => Some(*time),
            _ => None,
        }
    }

    /// Reason in words ("" for the good classes).
    pub fn reason(&self) -> &str {
        match self {
            Class::Diverged { reason, .. } | Class::NotConverged { reason, .. } => reason,
            _ => "",
        }
    }
}

/// Time and channel of the first non-finite value in a trace: the earliest row holding
/// one, and the first channel in column order at that row. Read column by column, each
/// column only up to the earliest such row found so far.
pub fn first_non_finite(trace: &Trace) -> Option<(f64, &'static str)> {
    let rows = trace.len();
    let mut first: Option<(usize, &'static str)> = None;
    for (c, col) in trace.channels.iter().zip(&trace.columns) {
        let end = first.map_or(rows, |(i, _)| i);
        if let Some(i) = col[..end].iter().position(|v| !v.is_finite()) {
            first = Some((i, c.key));
        }
    }
    first.map(|(i, key)| (trace.time[i], key))
}

/// Classify a run. `status` is the engine's outcome, or the message of a panic caught
/// around it; `energy` its audit when one exists; `error` its max normalised error of
/// the primary displacement against the basis, when there is a basis.
pub fn classify(
    status: Result<&RunStatus, &str>,
    trace: &Trace,
    energy: Option<&EnergyHistory>,
    error: Option<f64>,
    criteria: &Criteria,
) -> Class {
    match status {
        Err(panic) => {
            return Class::Diverged {
                time: None,
                reason: format!("the engine panicked: {panic}"),
            };
        }
        Ok(RunStatus::Diverged { time, reason }) => {
            return Class::Diverged {
                time: Some(*time),
                reason: reason.clone(),
            };
        }
        Ok(RunStatus::NotConverged { time, reason }) => {
            return Class::NotConverged {
                time: *time,
                reason: reason.clone(),
            };
        }
        Ok(RunStatus::Completed) => {}
    }
    if let Some((t, key)) = first_non_finite(trace) {
        return Class::Diverged {
            time: Some(t),
            reason: format!("{key} is not finite"),
        };
    }
    if let Some((t, ratio)) =
        energy.and_then(|h| h.growth_time_above(criteria.growth_factor, criteria.energy_ceiling))
    {
        return Class::Diverged {
            time: Some(t),
            reason: format!(
                "energy growth: stored + dissipated energy is {ratio:.3} times the most energy ever supplied (to the run, or to the exact solution when the run's trace shows less)"
            ),
        };
    }
    match error {
        Some(e) if e.is_finite() && e <= criteria.accuracy => Class::Accurate,
        _ => Class::Inaccurate,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::trace::q;

    fn trace(values: &[f64]) -> Trace {
        let mut t = Trace::with_channels(&[&q::REL_DISP], values.len());
        for (i, v) in values.iter().enumerate() {
            t.push(i as f64 * 0.5, &[*v]);
        }
        t
    }

    #[test]
    fn nan_in_the_trace_is_divergence_at_its_time() {
        let c = classify(
            Ok(&RunStatus::Completed),
            &trace(&[0.0, 1.0, f64::NAN]),
            None,
            Some(0.0),
            &Criteria::default(),
        );
        assert_eq!(c.label(), "diverged");
        assert_eq!(c.time(), Some(1.0));
    }

    /// The earliest row wins whatever its column; on one row, the first column.
    #[test]
    fn first_non_finite_is_the_earliest_row_then_the_first_column() {
        let mut t = Trace::with_channels(&[&q::REL_DISP, &q::VEL], 4);
        t.push(0.0, &[0.0, 0.0]);
        t.push(0.5, &[0.0, f64::INFINITY]);
        t.push(1.0, &[f64::NAN, f64::NAN]);
        t.push(1.5, &[1.0, 1.0]);
        assert_eq!(first_non_finite(&t), Some((0.5, q::VEL.key)));
        t.columns[0][1] = f64::NEG_INFINITY;
        assert_eq!(first_non_finite(&t), Some((0.5, q::REL_DISP.key)));
        assert_eq!(first_non_finite(&trace(&[0.0, 1.0])), None);
    }

    #[test]
    fn error_decides_between_accurate_and_inaccurate() {
        let t = trace(&[0.0, 1.0]);
        let cr = Criteria::default();
        let s = Ok(&RunStatus::Completed);
        assert_eq!(classify(s, &t, None, Some(0.05), &cr), Class::Accurate);
        assert_eq!(classify(s, &t, None, Some(0.0501), &cr), Class::Inaccurate);
        assert_eq!(classify(s, &t, None, None, &cr), Class::Inaccurate);
        let p = classify(Err("boom"), &t, None, Some(0.0), &cr);
        assert!(p.diverged() && p.reason().contains("boom"));
    }
}

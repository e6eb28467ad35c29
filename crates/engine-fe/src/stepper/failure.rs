//! The time loop's deterministic counters and why a step failed (values, formatted only
//! if the run ends on them).

/// Deterministic counters of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Time steps taken.
    pub steps: u64,
    /// Equilibrium (Newton) iterations over all steps.
    pub iterations: u64,
    /// Most iterations in one step.
    pub max_step_iterations: u64,
    /// Iterations of the static preload.
    pub static_iterations: u64,
    /// Step attempts that failed and were retried as two halves (step cutting).
    pub step_cuts: u64,
    /// Steps accepted at the round-off floor (residual within tolerance and no longer
    /// falling, correction still above the displacement criterion).
    pub roundoff_accepted: u64,
}

impl Counters {
    /// Count a step's `it` Newton iterations.
    #[inline]
    pub(crate) fn add_step_iterations(&mut self, it: usize) {
        self.iterations += it as u64;
        self.max_step_iterations = self.max_step_iterations.max(it as u64);
    }
}

/// What ended a Newton iteration.
pub(crate) enum FailureReason {
    /// Displacement or residual not finite.
    NotFinite,
    /// Singular tangent at this iteration.
    Singular(usize),
    /// Iterations used; the last iteration's norms; the tolerances; the unit of the
    /// correction and increment (`Mechanics::CORRECTION_UNIT`).
    NotConverged {
        iterations: usize,
        last: LastIteration,
        force_tol: f64,
        displacement_tol: f64,
        unit: &'static str,
    },
}

impl std::fmt::Display for FailureReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Self::NotFinite => write!(f, "displacement or residual is not finite"),
            Self::Singular(it) => write!(f, "singular tangent at iteration {it}"),
            Self::NotConverged {
                iterations,
                last,
                force_tol,
                displacement_tol,
                unit,
            } => write!(
                f,
                "{} iterations: relative residual {:.3e} (limit {:.1e}), last correction {:.3e}{unit} against a step increment of {:.3e}{unit} (limit {:.1e})",
                iterations,
                last.residual / last.force_scale.max(f64::MIN_POSITIVE),
                force_tol,
                last.correction_squared.sqrt(),
                last.increment_squared.sqrt(),
                displacement_tol
            ),
        }
    }
}

/// The norms of a Newton iteration, kept for the message of a step that fails to
/// converge (the square roots and the ratio are taken only then).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct LastIteration {
    /// Residual norm and the force scale it is measured against, N.
    pub residual: f64,
    pub force_scale: f64,
    /// Squared norms of the correction and of the step's increment with it.
    pub correction_squared: f64,
    pub increment_squared: f64,
}

/// Why a step failed.
pub(crate) struct StepFailure {
    /// Why, in numbers: formatted only if the run ends on it (a step that is cut and
    /// retried allocates nothing).
    pub reason: FailureReason,
    /// Not finite: cutting the step is not tried.
    pub diverged: bool,
}

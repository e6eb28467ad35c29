//! What a run states alike in either dimension: the arrangement its variant names, the
//! located errors of a scene fe does not run, its solver statistics and the integrator's
//! settings.

use super::options::FeOptions;
use super::stepper::Counters;
use super::variant;
use rockslide_core::case::Case;
use rockslide_core::error::InputError;
use rockslide_engine_api::{Setting, SolverStats};

/// Whether `variant` is the double arrangement, or the located error of a name fe does
/// not declare.
pub(crate) fn is_double(case: &Case, variant: &str) -> Result<bool, InputError> {
    match variant {
        variant::SINGLE => Ok(false),
        variant::DOUBLE => Ok(true),
        other => Err(case.field_error(
            "engines.fe.variants",
            format!("\"{other}\" is not a variant of fe; variants: single, double"),
        )),
    }
}

/// The error of the double variant on a scene without double elements.
pub(crate) fn no_double(case: &Case) -> InputError {
    case.field_error(
        "model.double",
        "is required for the fe engine's \"double\" variant",
    )
}

/// The error of a rigid block (no contact stiffness).
pub(crate) fn rigid_block(case: &Case) -> InputError {
    case.field_error(
        "model.kind",
        "the fe engine does not run rigid blocks (no contact stiffness)",
    )
}

/// The solver statistics of a run's counters.
pub(crate) fn solver_stats(counters: &Counters) -> SolverStats {
    SolverStats {
        steps: counters.steps,
        substeps_per_step: None,
        newton_iterations: Some(counters.iterations),
        max_step_iterations: Some(counters.max_step_iterations),
        static_iterations: Some(counters.static_iterations),
        step_cuts: Some(counters.step_cuts),
        roundoff_accepted: Some(counters.roundoff_accepted),
    }
}

/// The settings every run states first: Δt, the integrator and its (α, β, γ).
pub(crate) fn integrator_settings(dt: f64, opts: &FeOptions) -> Vec<Setting> {
    let (alpha, beta, gamma) = opts.integrator.parameters();
    vec![
        Setting::number("dt", "s", dt),
        Setting::choice("integrator", opts.integrator.label()),
        Setting::text("α, β, γ", format!("{alpha}, {beta:.6}, {gamma:.6}")),
    ]
}

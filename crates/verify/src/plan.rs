//! A case's plan: the engine runs it asks for ([`Plan`], [`PlannedRun`]), and what each
//! run will hold — its rows, and whether it is streamed ([`streams`]). Made by
//! [`crate::suite::plan`], priced by [`crate::footprint`] and run by [`crate::suite`].

use rockslide_core::case::Case;
use rockslide_engine_api::Variant;

/// One planned run.
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedRun {
    /// Engine id.
    pub engine: &'static str,
    /// Variant, as the engine declared it.
    pub variant: Variant,
    /// Time step, s.
    pub dt: f64,
    /// Values one row records (time, channels, contact fields), when the engine declares
    /// it ([`Engine::recorded_values`](rockslide_engine_api::Engine::recorded_values)); `None`: priced as every quantity of the catalogue.
    pub values: Option<usize>,
    /// Whether the engine streams natively ([`Engine::streams_natively`](rockslide_engine_api::Engine::streams_natively)): a streamed run
    /// then holds only its kept rows.
    pub native_streaming: bool,
}

/// The runs a case asks for, and the engines that do not apply (with why).
#[derive(Debug, Clone, Default)]
pub struct Plan {
    /// Runs to make.
    pub runs: Vec<PlannedRun>,
    /// (engine id, reason) for each engine that cannot represent the scene.
    pub not_applicable: Vec<(&'static str, String)>,
}

/// Steps above which a run is streamed ([`crate::analysis::streamed`]): its rows go to
/// the analysis as they are computed and only those at the case's output step are kept,
/// so its memory follows its output rows, not its steps. Every shipped case runs below
/// it (the longest: 2·10⁵ steps), so their figures keep every step; a streamed run's
/// responses, invariants and history errors are those of a whole run bit for bit
/// (tests/all/streaming.rs), and its figures draw every channel's per-slice extremes over
/// every step ([`crate::analysis::envelope`]), not the kept rows.
pub const STREAMING_STEPS: u64 = 500_000;

/// Whether planned run `p` of `case` is streamed: more than [`STREAMING_STEPS`] steps of
/// an engine that streams natively, keeping at most half its rows (`[run] output_dt` at
/// least 2 Δt); every registered engine streams natively (the predictor-corrector, fe,
/// rapier). An engine that does not stream natively would run whole anyway and
/// forward its rows — holding its whole trace, and run twice by the two passes — so its
/// long runs are analysed whole, once; a run that keeps every row (no `output_dt`) holds
/// its whole trace either way, so streaming would only cost the second pass.
pub fn streams(case: &Case, p: &PlannedRun) -> bool {
    p.native_streaming && streams_above(case, p, STREAMING_STEPS) && keeps_few_rows(case, p)
}

/// Whether run `p` keeps at most half its rows: the case's output step at least twice
/// the run's Δt (to a relative 10⁻⁹, so 0.002 s over 0.001 s counts whatever its bits).
fn keeps_few_rows(case: &Case, p: &PlannedRun) -> bool {
    case.run
        .output_dt
        .is_some_and(|o| o >= 2.0 * p.dt * (1.0 - 1e-9))
}

/// Whether planned run `p` of `case` takes more than `steps` steps.
pub(crate) fn streams_above(case: &Case, p: &PlannedRun, steps: u64) -> bool {
    rows_of(case.run.duration, p.dt) > steps.saturating_add(1)
}

/// Expected rows kept at the case's output step (every row without one), for sizing.
pub(crate) fn kept_rows(case: &Case, dt: f64) -> usize {
    let kept = case.run.output_dt.map_or(dt, |o| o.max(dt));
    rows_of(case.run.duration, kept).saturating_add(1) as usize
}

/// Rows a run of `duration` at `dt` records (one per step, plus the initial state).
pub(crate) fn rows_of(duration: f64, dt: f64) -> u64 {
    let steps = (duration / dt).ceil();
    if steps.is_finite() && steps >= 0.0 {
        (steps as u64).saturating_add(1)
    } else {
        u64::MAX
    }
}

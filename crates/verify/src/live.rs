//! What the live participants ([`crate::opensees`], [`crate::calculix`]) share: what
//! became of one, and the run of a program that failed.

use rockslide_core::case::{EXTERNAL_VARIANT, External};
use rockslide_core::trace::Trace;
use rockslide_engine_api::{Arrangement, Run, RunStatus, Setting, SolverStats};

/// What became of the live participant of a case.
pub enum Live {
    /// The case does not ask for it.
    NotAsked,
    /// Asked, but its program is not available: the reason.
    NotApplicable(String),
    /// Ran and was read back: add it to the case.
    Participant(Box<External>),
    /// Ran and failed (or timed out): a run that did not converge.
    Failed(Box<Run>),
}

/// A live run that failed, as a run that did not converge: `program` names it in the
/// settings and the findings, each line of `output` prefixed with `source`.
pub fn failed_run(
    label: &'static str,
    program: &str,
    dt: f64,
    reason: String,
    source: &str,
    output: Vec<String>,
) -> Run {
    let mut findings = vec![format!("{program} live run failed: {reason}")];
    findings.extend(output.into_iter().map(|l| format!("{source}: {l}")));
    Run {
        engine: label,
        variant: EXTERNAL_VARIANT.to_string(),
        arrangement: Arrangement::Single,
        dt,
        settings: vec![Setting::text("program", format!("{program} (live)"))],
        stats: SolverStats::default(),
        findings,
        trace: Trace::default(),
        status: RunStatus::NotConverged {
            time: f64::NAN,
            reason,
        },
        wall_seconds: 0.0,
    }
}

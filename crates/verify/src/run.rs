//! The one way an engine is run: timed, repeated when a timing is wanted, and guarded. An
//! engine reports divergence as a `RunStatus`; a panic is a bug, but it is still caught
//! here and becomes a result carrying its message, so one bad run never loses the others
//! — under `check`, `sweep`, `stability` and `study` alike, which all run engines through
//! [`guarded`].

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use rockslide_core::case::Case;
use rockslide_core::error::InputError;
use rockslide_core::trace::Trace;
use rockslide_engine_api::{Arrangement, Engine, Run, RunStatus, SolverStats, Variant};

/// Run `f`, catching a panic as its message.
pub fn guard<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|payload| panic_message(payload.as_ref()))
}

/// The text of a panic payload.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "panic with a non-text payload".into()
    }
}

/// One run, repeated and timed.
#[derive(Debug, Clone)]
pub struct Timed {
    /// The first repeat's run (its `wall_seconds` set), or the message of a panic caught
    /// around the engine.
    pub run: Result<Run, String>,
    /// Wall time of each repeat, s (a panicking repeat included: it is the last).
    pub seconds: Vec<f64>,
    /// Whether every repeat gave a bit-identical trace.
    pub deterministic: bool,
}

/// Median, min and max of repeated wall times, s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TimeStats {
    /// Median, s.
    pub median: f64,
    /// Fastest, s.
    pub min: f64,
    /// Slowest, s.
    pub max: f64,
}

impl Timed {
    /// Median, min and max of the wall times (`None` when nothing was timed).
    pub fn time_stats(&self) -> Option<TimeStats> {
        let mut s = self.seconds.clone();
        if s.is_empty() {
            return None;
        }
        s.sort_by(f64::total_cmp);
        let n = s.len();
        let median = if n % 2 == 1 {
            s[n / 2]
        } else {
            0.5 * (s[n / 2 - 1] + s[n / 2])
        };
        Some(TimeStats {
            median,
            min: s[0],
            max: s[n - 1],
        })
    }

    /// The run as a [`Run`] whatever happened: a panic becomes a run with an empty trace
    /// whose status is `Diverged` at an unknown time (NaN) with the panic's message, so
    /// that a case result, its report and its gate carry it like any failed run.
    pub fn into_run(self, engine: &'static str, variant: &str, dt: f64) -> Run {
        match self.run {
            Ok(run) => run,
            Err(message) => Run {
                engine,
                variant: variant.to_string(),
                arrangement: Arrangement::default(),
                dt,
                settings: Vec::new(),
                stats: SolverStats::default(),
                findings: Vec::new(),
                trace: Trace::default(),
                status: RunStatus::Diverged {
                    time: f64::NAN,
                    reason: format!("the engine panicked (time unknown): {message}"),
                },
                wall_seconds: self.seconds.first().copied().unwrap_or(0.0),
            },
        }
    }
}

/// Run `engine` on `case` at `dt`, `repeats` times (at least once), timing each repeat. A
/// panic inside the engine is caught and returned as the run's outcome with its message;
/// an input error stops the command (it is the case file's fault, not the engine's).
pub fn guarded(
    engine: &dyn Engine,
    case: &Case,
    variant: Variant,
    dt: f64,
    repeats: usize,
) -> Result<Timed, InputError> {
    let mut seconds = Vec::with_capacity(repeats.max(1));
    let mut first: Option<Run> = None;
    let mut deterministic = true;
    for _ in 0..repeats.max(1) {
        let start = Instant::now();
        let outcome = guard(|| engine.run(case, variant, dt));
        let elapsed = start.elapsed().as_secs_f64();
        match outcome {
            Err(message) => {
                seconds.push(elapsed);
                return Ok(Timed {
                    run: Err(message),
                    seconds,
                    deterministic,
                });
            }
            Ok(Err(e)) => return Err(e),
            Ok(Ok(mut run)) => {
                seconds.push(elapsed);
                match &first {
                    Some(f) => deterministic &= same_bits(&f.trace, &run.trace),
                    None => {
                        run.wall_seconds = elapsed;
                        first = Some(run);
                    }
                }
            }
        }
    }
    Ok(Timed {
        run: Ok(first.expect("at least one repeat")),
        seconds,
        deterministic,
    })
}

/// Whether two traces are bit-identical (NaN equals NaN of the same bits).
fn same_bits(a: &Trace, b: &Trace) -> bool {
    let eq = |x: &[f64], y: &[f64]| {
        x.len() == y.len() && x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits())
    };
    a.channels == b.channels
        && eq(&a.time, &b.time)
        && a.columns.len() == b.columns.len()
        && a.columns.iter().zip(&b.columns).all(|(x, y)| eq(x, y))
}

/// How a run ended, as recorded in the typed results (`sweep.json`, `stability.json`):
/// the engine's [`RunStatus`], or the panic the guard caught.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "outcome", rename_all = "snake_case")]
pub enum Outcome {
    /// Ran to the end.
    Completed,
    /// Blew up at `time`.
    Diverged {
        /// Simulation time, s.
        #[serde(with = "crate::json::real")]
        time: f64,
        /// What was seen.
        reason: String,
    },
    /// An iterative solver gave up at `time`.
    NotConverged {
        /// Simulation time, s.
        #[serde(with = "crate::json::real")]
        time: f64,
        /// Residual and iterations, in words.
        reason: String,
    },
    /// The engine panicked (caught by [`guarded`]).
    Panicked {
        /// The panic's message.
        message: String,
    },
}

impl Outcome {
    /// The outcome of a guarded run.
    pub fn of(run: &Result<Run, String>) -> Outcome {
        match run {
            Err(message) => Outcome::Panicked {
                message: message.clone(),
            },
            Ok(r) => Outcome::from(&r.status),
        }
    }

    /// Whether the run reached the end.
    pub fn completed(&self) -> bool {
        matches!(self, Outcome::Completed)
    }

    /// One-word label: `completed`, `diverged`, `not converged`, `panicked`.
    pub fn label(&self) -> &'static str {
        match self {
            Outcome::Completed => "completed",
            Outcome::Diverged { .. } => "diverged",
            Outcome::NotConverged { .. } => "not converged",
            Outcome::Panicked { .. } => "panicked",
        }
    }
}

impl From<&RunStatus> for Outcome {
    fn from(status: &RunStatus) -> Self {
        match status {
            RunStatus::Completed => Outcome::Completed,
            RunStatus::Diverged { time, reason } => Outcome::Diverged {
                time: *time,
                reason: reason.clone(),
            },
            RunStatus::NotConverged { time, reason } => Outcome::NotConverged {
                time: *time,
                reason: reason.clone(),
            },
        }
    }
}

impl std::fmt::Display for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Outcome::Completed => write!(f, "completed"),
            Outcome::Diverged { time, reason } => {
                write!(f, "diverged at t = {time:.6} s: {reason}")
            }
            Outcome::NotConverged { time, reason } => {
                write!(f, "not converged at t = {time:.6} s: {reason}")
            }
            Outcome::Panicked { message } => write!(f, "panicked: {message}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_guard_turns_a_panic_into_its_message() {
        assert_eq!(guard(|| 7), Ok(7));
        let text = guard(|| -> u8 { panic!("stiffness matrix singular at step {}", 12) });
        assert_eq!(
            text,
            Err("stiffness matrix singular at step 12".to_string())
        );
        let literal = guard(|| -> u8 { panic!("plain text") });
        assert_eq!(literal, Err("plain text".to_string()));
        let other = guard(|| std::panic::panic_any(42_u32));
        assert_eq!(other, Err("panic with a non-text payload".to_string()));
    }

    #[test]
    fn time_stats_are_median_min_max() {
        let t = |seconds: Vec<f64>| Timed {
            run: Err(String::new()),
            seconds,
            deterministic: true,
        };
        let s = t(vec![3.0, 1.0, 2.0]).time_stats().unwrap();
        assert_eq!((s.median, s.min, s.max), (2.0, 1.0, 3.0));
        let s = t(vec![4.0, 1.0]).time_stats().unwrap();
        assert_eq!((s.median, s.min, s.max), (2.5, 1.0, 4.0));
        assert_eq!(t(vec![]).time_stats(), None);
    }

    #[test]
    fn a_panic_becomes_a_diverged_run_with_its_message() {
        let t = Timed {
            run: Err("boom".into()),
            seconds: vec![],
            deterministic: true,
        };
        let run = t.into_run("fe", "single", 0.01);
        assert_eq!(run.label(), "fe/single");
        match &run.status {
            RunStatus::Diverged { time, reason } => {
                assert!(time.is_nan());
                assert!(
                    reason.ends_with("panicked (time unknown): boom"),
                    "{reason}"
                );
            }
            s => panic!("{s:?}"),
        }
        assert_eq!(
            Outcome::of(&Err("boom".into())).to_string(),
            "panicked: boom"
        );
    }
}

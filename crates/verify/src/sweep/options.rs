//! Settings of the `sweep` and `stability` commands, with their ranges checked before any
//! work (the message names the command-line option), and the worker pool they run on.

use rockslide_core::error::Error;

/// Most timed repeats of one run: the median of a hundred is as steady as a timing gets,
/// and a million repeats of a second-long run would take eleven days.
pub const MAX_REPEATS: usize = 100;

/// Settings shared by both commands.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Number of rungs of the sweep's Δt ladder (≥ 3), from T/10 down.
    pub rungs: usize,
    /// Refinement ratio between rungs (> 1).
    pub ratio: f64,
    /// Timed repeats of each run (≥ 1); the median, min and max are reported.
    pub repeats: usize,
    /// Worker threads (`None`: all cores).
    pub jobs: Option<usize>,
    /// No progress bar.
    pub quiet: bool,
    /// Sweep only: wall-time budget per engine variant, s (all repeats of all its rungs).
    /// Rungs are run coarse to fine; a rung whose projected cost (the previous rung's
    /// time scaled by its step count) would overrun the budget is run once instead of
    /// `repeats` times, and skipped — with every finer rung — when even one run would.
    /// The first three rungs always run (an order needs three). `None`: no budget.
    pub budget: Option<f64>,
}

/// Default wall-time budget of one engine variant in a sweep, s: rapier at 16 substeps
/// costs about 0.1–0.2 ms per step, so its finest PEPO rungs (T/1280: 6400 steps) take
/// about a second each; a rocking body's cost ten times that.
pub const DEFAULT_BUDGET: f64 = 20.0;

impl Default for Options {
    fn default() -> Self {
        Options {
            rungs: 8,
            ratio: 2.0,
            repeats: 3,
            jobs: None,
            quiet: false,
            budget: Some(DEFAULT_BUDGET),
        }
    }
}

impl Options {
    /// Check the ranges; the message names the option.
    pub fn validate(&self) -> Result<(), Error> {
        if self.rungs < 3 {
            return Err(Error::Other(format!(
                "--rungs is {}, but must be at least 3 (an order needs three solutions)",
                self.rungs
            )));
        }
        if !(self.ratio > 1.0 && self.ratio.is_finite()) {
            return Err(Error::Other(format!(
                "--ratio is {}, but must be a finite number above 1",
                self.ratio
            )));
        }
        if self.repeats == 0 || self.repeats > MAX_REPEATS {
            return Err(Error::Other(format!(
                "--repeats is {}, but must be from 1 to {MAX_REPEATS}",
                self.repeats
            )));
        }
        if let Some(b) = self.budget
            && (b.is_nan() || b <= 0.0)
        {
            return Err(Error::Other(format!(
                "--budget is {b} s, but must be a positive number of seconds"
            )));
        }
        if self.jobs == Some(0) {
            return Err(Error::Other("--jobs must be at least 1".into()));
        }
        Ok(())
    }

    /// Run `f`, which has `work` independent items, on a pool of `jobs` threads — never
    /// more than the work nor [`MAX_JOBS`](rockslide_core::case::limits::MAX_JOBS) — or on
    /// rayon's global pool on all cores.
    pub fn install<T: Send>(&self, work: usize, f: impl FnOnce() -> T + Send) -> Result<T, Error> {
        match self.jobs {
            None => Ok(f()),
            Some(n) => {
                let n = rockslide_core::case::limits::clamp_jobs(Some(n), work);
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .map(|p| p.install(f))
                    .map_err(|e| Error::Other(format!("cannot start {n} worker threads: {e}")))
            }
        }
    }
}

//! Resource bounds, checked before any work starts: the number of time steps of a run, of
//! output samples, of rungs and runs, and of worker threads. A request above a limit is a
//! located error that names the field, the estimate and the limit — never an allocation
//! that aborts the process or a loop that runs for hours.
//!
//! The step limit ([`DEFAULT_MAX_STEPS`]) can be raised for one invocation with the
//! environment variable `ROCKSLIDE_MAX_STEPS`.

/// Default largest number of time steps (or output samples) of one run: 10 million, i.e.
/// about 80 MB per output channel.
pub const DEFAULT_MAX_STEPS: u64 = 10_000_000;

/// Environment variable that raises (or lowers) [`DEFAULT_MAX_STEPS`].
pub const MAX_STEPS_VARIABLE: &str = "ROCKSLIDE_MAX_STEPS";

/// Largest number of worker threads: more than this never helps on one machine.
pub const MAX_JOBS: usize = 256;

/// The step limit in force: `ROCKSLIDE_MAX_STEPS` when set to a positive integer, else
/// [`DEFAULT_MAX_STEPS`].
pub fn max_steps() -> u64 {
    std::env::var(MAX_STEPS_VARIABLE)
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .filter(|&n| n > 0)
        .unwrap_or(DEFAULT_MAX_STEPS)
}

/// Estimated number of steps of length `dt` covering `duration` (infinite when the ratio
/// is not finite); both are assumed positive.
pub fn estimated_steps(duration: f64, dt: f64) -> f64 {
    let n = (duration / dt).ceil();
    if n.is_finite() {
        n.max(1.0)
    } else {
        f64::INFINITY
    }
}

/// `Err(reason)` when covering `duration` with steps of `dt` takes more than
/// [`max_steps`] steps; the reason says how many and how to raise the limit.
pub fn check_steps(duration: f64, dt: f64) -> Result<(), String> {
    let n = estimated_steps(duration, dt);
    let limit = max_steps();
    if n > limit as f64 {
        return Err(format!(
            "is {dt:e} s, which needs {n:.3e} steps to cover {duration} s; the limit is \
             {limit} (set {MAX_STEPS_VARIABLE} to raise it)"
        ));
    }
    Ok(())
}

/// `Err(reason)` when `count` items (samples, runs, rungs) exceed `limit`.
pub fn check_count(count: f64, limit: u64, what: &str) -> Result<(), String> {
    if count.is_nan() || count > limit as f64 {
        return Err(format!("asks for {count:.3e} {what}; the limit is {limit}"));
    }
    Ok(())
}

/// Worker threads for `work` independent items: the request (default: the machine's
/// cores), never more than the work, never more than [`MAX_JOBS`], at least 1.
pub fn clamp_jobs(requested: Option<usize>, work: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    requested.unwrap_or(cores).min(work).clamp(1, MAX_JOBS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_above_the_limit_are_refused_before_work() {
        assert_eq!(estimated_steps(1.0, 1e-3), 1000.0);
        assert!(check_steps(1.0, 1e-3).is_ok());
        assert!(check_steps(1.0, 1.0 / DEFAULT_MAX_STEPS as f64).is_ok());
        let e = check_steps(1.0, 1e-12).unwrap_err();
        assert!(e.contains("1.000e12 steps"), "{e}");
        assert!(check_steps(1.0, 1e-320).is_err());
        assert!(check_steps(f64::MAX, 1.0).is_err());
    }

    #[test]
    fn counts_and_jobs_are_bounded() {
        assert!(check_count(64.0, 30, "rungs").is_err());
        assert!(check_count(f64::NAN, 30, "rungs").is_err());
        assert!(check_count(8.0, 30, "rungs").is_ok());
        assert_eq!(clamp_jobs(Some(100_000), 12), 12);
        assert_eq!(clamp_jobs(Some(100_000), 100_000), MAX_JOBS);
        assert_eq!(clamp_jobs(Some(0), 5), 1);
        assert_eq!(clamp_jobs(Some(2), 0), 1);
    }
}

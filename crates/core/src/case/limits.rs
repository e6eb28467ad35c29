//! Resource bounds, checked before any work starts: the number of time steps of a run, of
//! output samples, of rungs and runs, of worker threads, of a body's supports and the size
//! of a body (every size an allocation follows). A request above a limit is a
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

/// Most supports across a rocking body's base (`model.supports`): each is a contact that
/// every engine models and records at every step (a force column per support in the
/// per-contact block), so the count multiplies the memory of a run.
pub const MAX_SUPPORTS: u64 = 1_000;

/// Most rows of supports along y of a 3D base (`model.support_rows`).
pub const MAX_SUPPORT_ROWS: u64 = 1_000;

/// Most supports of a 3D base in all (`model.supports` × `model.support_rows`).
pub const MAX_SUPPORT_GRID: u64 = 10_000;

/// Most azimuths of a station case's set (`x_azimuths_deg`): every one is a whole run of
/// every participant, and a step of 1° over 360° (both polarities along one axis) is the
/// finest a sliding maximum needs.
pub const MAX_AZIMUTHS: usize = 360;

/// Largest extent of a body, m: every half size (`half_width`, `half_height`,
/// `half_depth`) and the centre-of-mass height. rapier's broad phase sizes its regions
/// from the colliders' extents: a 3D block of half-depth 10⁴ m took 0.67 GB and 15 s
/// for a 1.5 s pulse, 10⁶ m aborted after 11.9 GB, 10³ m runs in 90 MB; the ground slab a
/// body stands on in rapier is 2 × 10⁴ m across.
pub const MAX_EXTENT: f64 = 1.0e3;

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

/// How many times [`max_steps`] a run with an output step coarser than its time step may
/// take: such a run longer than the analysis's streaming threshold is streamed (its memory
/// follows the rows it keeps, one per output step), so its rows kept are held to
/// [`max_steps`] and its steps only to this multiple (10⁹ by default: about a minute of the
/// predictor-corrector), which still bounds the time a mistyped Δt can cost.
pub const STREAMED_STEPS_FACTOR: u64 = 100;

/// [`check_steps`] for a run that keeps one row per `output_dt` (when given and coarser
/// than `dt`): the rows kept within [`max_steps`], the steps within
/// [`STREAMED_STEPS_FACTOR`] × [`max_steps`]; without an output step, [`check_steps`].
pub fn check_kept_steps(duration: f64, dt: f64, output_dt: Option<f64>) -> Result<(), String> {
    let Some(out) = output_dt else {
        return check_steps(duration, dt);
    };
    check_steps(duration, out)
        .map_err(|why| format!("{why} (rows kept at run.output_dt = {out} s)"))?;
    let n = estimated_steps(duration, dt);
    let limit = max_steps().saturating_mul(STREAMED_STEPS_FACTOR);
    if n > limit as f64 {
        return Err(format!(
            "is {dt:e} s, which needs {n:.3e} steps to cover {duration} s; the limit of a \
             run kept at run.output_dt is {limit} ({STREAMED_STEPS_FACTOR} × {MAX_STEPS_VARIABLE}, \
             set it to raise the limit)"
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
    fn a_run_kept_at_an_output_step_may_take_more_steps() {
        let limit = DEFAULT_MAX_STEPS as f64;
        // 10⁸ steps kept every 1000: allowed; without the output step: refused
        assert!(check_kept_steps(1e5, 1e-3, Some(1.0)).is_ok());
        assert!(check_kept_steps(1e5, 1e-3, None).is_err());
        // the rows kept are held to the limit, the steps to 100 times it
        let e = check_kept_steps(limit * 2.0, 1e-3, Some(1e-3 * 1.0001)).unwrap_err();
        assert!(e.contains("rows kept at run.output_dt"), "{e}");
        let e = check_kept_steps(1e6 + 1.0, 1e-3, Some(1.0)).unwrap_err();
        assert!(
            e.contains("1.000e9 steps") && e.contains("100 × ROCKSLIDE_MAX_STEPS"),
            "{e}"
        );
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

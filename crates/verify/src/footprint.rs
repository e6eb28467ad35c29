//! The memory and disk a case's runs will need, estimated before any work from the plan
//! (rows = duration / Δt of each run), and refused with a clear error when over a limit.
//!
//! A whole run keeps one row per step in memory for the analysis; a run streamed by an
//! engine that streams natively (`crate::plan::streams`: every engine — the
//! predictor-corrector, fe and rapier — when the case keeps at most half the rows) keeps
//! only the rows at the case's output step, its analysis reading every step as it comes
//! (`crate::analysis::streamed`), the engine itself holding nothing per step. Each row is
//! counted with the values its engine declares (`Engine::recorded_values`: every engine
//! declares its own; one that declared none would be counted with every quantity of the
//! catalogue); the
//! reference is sampled at every run's kept times, once for the files and once per run
//! for its history error. A plan over a limit is refused here, naming the case file and
//! the field, instead of exhausting the machine part-way through.
//! The limits are overridden by the environment variables [`MEMORY_LIMIT_VAR`] and
//! [`DISK_LIMIT_VAR`] (bytes).

use rockslide_core::case::Case;
use rockslide_core::error::InputError;
use rockslide_core::trace::q;

use crate::plan::{Plan, PlannedRun, rows_of, streams};

/// Default limit of the estimated memory of one case's traces: 8 GiB (a third of the
/// machines this runs on). The estimate is about three times the measured peak (a
/// predictor-corrector run of 10⁶ steps that keeps every row peaks at 0.2 GB), so runs
/// keeping up to ≈ 10⁷ rows pass; a streamed run is estimated by the rows it keeps.
pub const DEFAULT_MEMORY_LIMIT: u64 = 8 << 30;
/// Default limit of the estimated disk use of one case's trace files: 16 GiB.
pub const DEFAULT_DISK_LIMIT: u64 = 16 << 30;
/// Environment variable overriding [`DEFAULT_MEMORY_LIMIT`], in bytes.
pub const MEMORY_LIMIT_VAR: &str = "ROCKSLIDE_MAX_MEMORY_BYTES";
/// Environment variable overriding [`DEFAULT_DISK_LIMIT`], in bytes.
pub const DISK_LIMIT_VAR: &str = "ROCKSLIDE_MAX_DISK_BYTES";

/// Copies of each run row held in memory: the run's trace, the reference sampled at its
/// times for the history error, and its share of the reference output trace.
const COPIES_IN_MEMORY: u64 = 3;
/// Bytes on disk per value a run records (time, channels, contact fields) and writes,
/// with its share of the reference: measured 31.4 on the PEPO predictor-corrector run
/// every step for 100 s (10⁵ rows of 12 values: its CSV 17.1 bytes a value of its 8, the
/// reference CSV 16.4 a value of its 7, the MCAP file 10.4 a value of the 12 — state with
/// its contact, the reference, zstd-compressed; its contacts CSV is not written, it only
/// repeats the run's columns), 31.3 on 10 s; rounded up. (40 before the contacts joined
/// the state messages and the repeating contacts CSV was dropped.)
pub const DISK_BYTES_PER_VALUE: u64 = 32;

/// Estimated needs of a planned case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Footprint {
    /// Rows over all runs (steps + 1 each).
    pub rows: u64,
    /// Rows held in memory over all runs: every row of a whole run, the kept rows (one per
    /// `[run] output_dt`) of a run streamed by an engine that streams natively.
    pub held_rows: u64,
    /// Rows the trace files keep over all runs: every step, or one per `[run] output_dt`
    /// (plus the first and the last) when the case sets it.
    pub written_rows: u64,
    /// Values (time, channels, contact fields) summed over the rows held.
    pub held_values: u64,
    /// Memory of the traces and their reference samples, bytes (an upper estimate: each
    /// run counted with the values its engine declares, else every quantity of the
    /// catalogue).
    pub memory: u64,
    /// Disk of the CSV and MCAP traces, bytes (upper estimate).
    pub disk: u64,
}

/// Values a row of planned run `p` records: the engine's declaration, else time and
/// every quantity of the catalogue.
fn values_per_row(p: &PlannedRun) -> u64 {
    p.values.map_or(1 + q::ALL.len() as u64, |v| v as u64)
}

/// Rows a run of `case` at `dt` keeps in its files: the first, one per output step, the last.
fn kept_rows(case: &Case, dt: f64) -> u64 {
    let kept = case.run.output_dt.map_or(dt, |o| o.max(dt));
    rows_of(case.run.duration, kept).saturating_add(u64::from(kept > dt))
}

/// The estimate for `plan` on `case`.
pub fn estimate(case: &Case, plan: &Plan) -> Footprint {
    let (mut rows, mut held_rows, mut written_rows) = (0u64, 0u64, 0u64);
    let (mut held_values, mut written_values) = (0u64, 0u64);
    for p in &plan.runs {
        let all = rows_of(case.run.duration, p.dt);
        let written = kept_rows(case, p.dt);
        let held = if streams(case, p) { written } else { all };
        let values = values_per_row(p);
        rows = rows.saturating_add(all);
        held_rows = held_rows.saturating_add(held);
        written_rows = written_rows.saturating_add(written);
        held_values = held_values.saturating_add(held.saturating_mul(values));
        written_values = written_values.saturating_add(written.saturating_mul(values));
    }
    Footprint {
        rows,
        held_rows,
        written_rows,
        held_values,
        // a case with a set of azimuths holds every azimuth's runs until the governing
        // one is known; it writes the governing one's traces only
        memory: held_values
            .saturating_mul(8)
            .saturating_mul(COPIES_IN_MEMORY)
            .saturating_mul(case.azimuth_count() as u64),
        disk: written_values.saturating_mul(DISK_BYTES_PER_VALUE),
    }
}

/// A limit: the environment variable's value in bytes, or `default`; a value that is not
/// a whole number of bytes is an error naming the variable.
fn limit(var: &str, default: u64) -> Result<u64, String> {
    match std::env::var(var) {
        Ok(v) => v.trim().parse::<u64>().map_err(|_| {
            format!("{var} is \"{v}\", but must be a whole number of bytes (e.g. 17179869184)")
        }),
        Err(_) => Ok(default),
    }
}

/// Gigabytes, for messages.
fn gb(bytes: u64) -> String {
    format!("{:.1} GB", bytes as f64 / 1e9)
}

/// What the memory estimate counted, in words.
fn held_rows_text(need: &Footprint) -> String {
    if need.held_rows == need.rows {
        format!(
            "record {} rows in all (duration / dt each; {} values)",
            need.rows, need.held_values
        )
    } else {
        format!(
            "record {} rows in all and hold {} (streamed runs keep one per run.output_dt; {} values)",
            need.rows, need.held_rows, need.held_values
        )
    }
}

/// Refuse a plan whose estimated memory or disk exceeds its limit: one error on the
/// case's `run.duration` field saying how much, why, and how to override.
pub fn check(case: &Case, plan: &Plan) -> Result<(), InputError> {
    let need = estimate(case, plan);
    // `rows`: what the runs do with how many rows, and how they are counted; `remedy`: a
    // way out besides the run's length and step.
    let over = |what: &str,
                var: &str,
                default: u64,
                bytes: u64,
                rows: String,
                remedy: &str|
     -> Result<(), InputError> {
        let max = limit(var, default).map_err(|e| case.field_error("run.duration", e))?;
        if bytes <= max {
            return Ok(());
        }
        Err(case.field_error(
            "run.duration",
            format!(
                "the {} planned run(s) {rows}, whose traces need about {} of {what}, over the \
                 limit of {}: shorten the run, enlarge dt{remedy}, or raise the limit with \
                 {var}=<bytes>",
                plan.runs.len(),
                gb(bytes),
                gb(max),
            ),
        ))
    };
    over(
        "memory",
        MEMORY_LIMIT_VAR,
        DEFAULT_MEMORY_LIMIT,
        need.memory,
        held_rows_text(&need),
        "",
    )?;
    let written = if case.run.output_dt.is_some() {
        "one per run.output_dt"
    } else {
        "duration / dt each"
    };
    over(
        "disk",
        DISK_LIMIT_VAR,
        DEFAULT_DISK_LIMIT,
        need.disk,
        format!("write {} rows in all ({written})", need.written_rows),
        " or set run.output_dt",
    )
}

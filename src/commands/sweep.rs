//! `rockslide sweep <case>…`: error against run time of every applicable engine variant
//! over a Δt ladder, one case after the other (each in parallel inside). Writes
//! `<out>/<case>/sweep.json` (the typed result) and `sweep.{md,html,csv,svg}`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use rockslide_core::error::Error;
use rockslide_present::sweep::write_sweep;
use rockslide_verify::sweep::work_precision::sweep_case;
use rockslide_verify::sweep::{Options, SweepResult};

use crate::args::SweepArgs;
use crate::input::{bounded_jobs, load_all};

/// Largest number of rungs of a sweep's Δt ladder.
const MAX_RUNGS: usize = 30;
/// Largest refinement between the first and the last rung (`ratio^(rungs-1)`).
const MAX_REFINEMENT: f64 = 1e7;

/// `rockslide sweep`: the ladder and the budget checked, then every case swept.
pub fn run(args: &SweepArgs, quiet: bool) -> Result<ExitCode, Error> {
    check_ladder(args.rungs, args.ratio)?;
    check_budget(args.budget)?;
    sweep_all(
        &args.cases,
        &args.out,
        &Options {
            rungs: args.rungs,
            ratio: args.ratio,
            repeats: args.repeats,
            jobs: bounded_jobs(args.jobs),
            quiet,
            budget: (args.budget > 0.0).then_some(args.budget),
        },
    )
}

/// The Δt ladder stays within [`MAX_RUNGS`] and [`MAX_REFINEMENT`] (checked before work).
fn check_ladder(rungs: usize, ratio: f64) -> Result<(), Error> {
    if rungs > MAX_RUNGS {
        return Err(Error::Other(format!(
            "--rungs is {rungs}, but the limit is {MAX_RUNGS}"
        )));
    }
    let refinement = ratio.powf(rungs.saturating_sub(1) as f64);
    if ratio > 1.0 && (refinement.is_nan() || refinement > MAX_REFINEMENT) {
        return Err(Error::Other(format!(
            "--ratio {ratio:e} over {rungs} rungs refines Δt by {refinement:.3e}; the limit is \
             {MAX_REFINEMENT:.0e}"
        )));
    }
    Ok(())
}

/// `--budget`: 0 means none, a positive number is seconds; anything else is an error.
fn check_budget(budget: f64) -> Result<(), Error> {
    if budget >= 0.0 && budget.is_finite() {
        return Ok(());
    }
    Err(Error::Other(format!(
        "--budget is {budget} s, but must be >= 0 (0: no budget)"
    )))
}

/// Sweep every case given.
fn sweep_all(cases: &[PathBuf], out: &Path, opts: &Options) -> Result<ExitCode, Error> {
    if cases.is_empty() {
        return Err(Error::Other(
            "sweep needs at least one case file (e.g. cases/pepo-mass-accel.toml)".into(),
        ));
    }
    for case in &load_all(cases)? {
        let r = sweep_case(case, opts)?;
        write(&r, out, opts.quiet)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// Write a sweep's result and pages into `<out>/<case>/` and say each series' order.
pub fn write(r: &SweepResult, out: &Path, quiet: bool) -> Result<(), Error> {
    let dir = out.join(&r.case);
    r.save(&dir)?;
    write_sweep(r, &dir)?;
    if !quiet {
        for se in &r.series {
            say!(
                "{}: {}: observed order p {} ({}){}",
                r.case,
                se.label,
                se.observed_order()
                    .map_or("—".into(), |p| format!("{p:.2}")),
                rockslide_verify::analysis::sweep::ORDER_METHOD,
                se.skipped.as_ref().map_or(String::new(), |k| format!(
                    "; cost budget: {} of {} rungs, Δt ≤ {:.3e} s skipped",
                    se.rungs.len(),
                    r.planned_rungs,
                    k.from_dt
                ))
            );
        }
        say!("{}: → {}", r.case, dir.join("sweep.md").display());
    }
    Ok(())
}

//! `rockslide sweep <case>…`: error against run time of every applicable engine variant
//! over a Δt ladder, one case after the other (each in parallel inside). Writes
//! `<out>/<case>/sweep.json` (the typed result) and `sweep.{md,html,csv,svg}`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use rockslide_core::error::Error;
use rockslide_present::sweep::write_sweep;
use rockslide_verify::sweep::work_precision::sweep_case;
use rockslide_verify::sweep::{Options, SweepResult};

use crate::cli::load_all;

/// Sweep every case given.
pub fn run(cases: &[PathBuf], out: &Path, opts: &Options) -> Result<ExitCode, Error> {
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

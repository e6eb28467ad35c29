//! `rockslide stability [cases…]`: the stiff and extreme scenes (default
//! `cases/stability/`), every run classified, each engine variant's practical stability
//! limit. Writes `<out>/stability/stability.json` (the typed result) and
//! `stability.{md,html,csv,svg}`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use rockslide_core::error::Error;
use rockslide_present::stability::write_stability;
use rockslide_verify::sweep::Options;
use rockslide_verify::sweep::StabilityResult;
use rockslide_verify::sweep::stability::{DIR, study};

use crate::args::StabilityArgs;
use crate::input::{bounded_jobs, case_paths_or, load_all};

/// `rockslide stability`: classify the given case files or folders.
pub fn run(args: &StabilityArgs, quiet: bool) -> Result<ExitCode, Error> {
    classify(
        &args.cases,
        &args.out,
        &Options {
            jobs: bounded_jobs(args.jobs),
            quiet,
            ..Default::default()
        },
    )
}

/// Classify the given case files or folders (default `cases/stability/`).
fn classify(args: &[PathBuf], out: &Path, opts: &Options) -> Result<ExitCode, Error> {
    let cases = load_all(&case_paths_or(args, "cases/stability")?)?;
    if cases.is_empty() {
        return Err(Error::Other("stability: no case files found".into()));
    }
    let r = study(&cases, opts)?;
    write(&r, out, opts.quiet)?;
    Ok(ExitCode::SUCCESS)
}

/// Write a study's result and pages into `<out>/stability/` and say its limits.
pub fn write(r: &StabilityResult, out: &Path, quiet: bool) -> Result<(), Error> {
    let dir = out.join(DIR);
    r.save(&dir)?;
    write_stability(r, &dir)?;
    if !quiet {
        for l in &r.limits {
            say!(
                "{}: practical stability limit Δt/T = {}",
                l.label,
                l.limit()
                    .map_or("> 1.0 (no divergence found)".into(), |x| format!("{x:.4}"))
            );
        }
        say!("→ {}", dir.join("stability.md").display());
    }
    Ok(())
}

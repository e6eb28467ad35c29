//! `rockslide check [cases…]`: run the cases as `run` does, then gate on their tolerances:
//! exit 0 when every gated check passes, 1 when any fails (one line per failure on
//! stderr) or when there is nothing to check, 2 on bad input. Writes the reports and the
//! JUnit XML (default `<out>/junit.xml`).

use std::process::ExitCode;

use rockslide_core::error::Error;
use rockslide_present::report::OutputSet;

use crate::args::CheckArgs;
use crate::input::DEFAULT_CASE_FOLDERS;
use crate::suite_run::{finish, prepare_cases, run_and_write_all};

/// Run the cases, write every report and the JUnit XML; exit code 1 when the gate fails.
pub fn run(args: &CheckArgs, quiet: bool) -> Result<ExitCode, Error> {
    let junit = args
        .junit
        .clone()
        .unwrap_or_else(|| args.out.join("junit.xml"));
    let cases = prepare_cases(&args.cases, &args.out, &args.external, true)?;
    if cases.is_empty() {
        let shown: Vec<String> = args.cases.iter().map(|a| a.display().to_string()).collect();
        eprintln!(
            "FAIL checks nothing: no case file (*.toml) in {}",
            if shown.is_empty() {
                DEFAULT_CASE_FOLDERS.join(", ")
            } else {
                shown.join(", ")
            }
        );
        return Ok(ExitCode::from(1));
    }
    finish(
        run_and_write_all(cases, &args.out, OutputSet::FULL),
        &args.out,
        quiet,
        Some(&junit),
    )
}

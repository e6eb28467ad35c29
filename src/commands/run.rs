//! `rockslide run [cases…]`: run the cases (default: every case folder) and write their
//! traces, reports and the suite's pages into `<out>/`.

use std::process::ExitCode;

use rockslide_core::error::Error;
use rockslide_present::report::OutputSet;

use crate::args::RunArgs;
use crate::suite_run::{finish, prepare_cases, run_and_write_all};

/// Run the cases and write every report.
pub fn run(args: &RunArgs, quiet: bool) -> Result<ExitCode, Error> {
    let cases = prepare_cases(&args.cases, &args.out, &args.external, false)?;
    finish(
        run_and_write_all(cases, &args.out, OutputSet::FULL),
        &args.out,
        quiet,
        None,
    )
}

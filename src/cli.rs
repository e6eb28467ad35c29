//! The command line's dispatch: the parsed arguments ([`crate::args`]) handed to their
//! command (`commands/`, one file per command), `--timings` around it, and the exit code:
//! 0 success (gate passed), 1 a gated discrepancy is out of tolerance, 2 bad input or an
//! error (one `error:` line per line of its message).

use std::path::Path;
use std::process::ExitCode;

use rockslide_core::error::Error;
use rockslide_core::io::remove_stale_temporaries_under;
use rockslide_present::report::OutputSet;

pub use crate::args::{Cli, Command};
use crate::commands;

/// Run the command line; returns the process exit code.
pub fn main(cli: Cli) -> ExitCode {
    if !cli.timings {
        return dispatch(cli);
    }
    rockslide_verify::timings::enable();
    let folder = cli
        .command
        .as_ref()
        .map_or(Some(Path::new("reports")), Command::timings_folder)
        .map(Path::to_path_buf);
    let code = rockslide_verify::timings::time("total", "all", || dispatch(cli));
    if let Some(folder) = folder
        && let Err(e) = crate::timings::write(&rockslide_verify::timings::take(), &folder)
    {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    code
}

/// Run one command; returns the process exit code.
fn dispatch(cli: Cli) -> ExitCode {
    let set = match cli.full_traces {
        true => OutputSet::FULL,
        false => OutputSet::LEAN,
    };
    if cli.full_traces && cli.command.is_some() {
        eprintln!(
            "error: --full-traces applies to the default command only (run and check write every trace)"
        );
        return ExitCode::from(2);
    }
    let stale = cli
        .command
        .as_ref()
        .and_then(Command::output_folder)
        .map_or(Ok(0), remove_stale_temporaries_under);
    match stale.and_then(|_| execute(cli.command, cli.quiet, set)) {
        Ok(code) => code,
        Err(e) => {
            for line in e.to_string().lines() {
                eprintln!("error: {line}");
            }
            ExitCode::from(2)
        }
    }
}

/// Hand a command to its file (none: the default command, into `reports/`).
fn execute(command: Option<Command>, quiet: bool, set: OutputSet) -> Result<ExitCode, Error> {
    match command {
        None => commands::everything::run(Path::new("reports"), quiet, set),
        Some(Command::Run(args)) => commands::run::run(&args, quiet),
        Some(Command::Check(args)) => commands::check::run(&args, quiet),
        Some(Command::List(args)) => commands::list::run(&args),
        Some(Command::Reference(args)) => commands::reference::run(&args),
        Some(Command::Study(args)) => commands::study::run(&args, quiet),
        Some(Command::StudyMerge(args)) => commands::study_merge::run(&args, quiet),
        Some(Command::Newmark(args)) => commands::newmark::run(args),
        Some(Command::TraceInfo(args)) => commands::trace_info::run(&args),
        Some(Command::Sweep(args)) => commands::sweep::run(&args, quiet),
        Some(Command::Stability(args)) => commands::stability::run(&args, quiet),
        Some(Command::Export(args)) => commands::export::run(&args, quiet),
    }
}

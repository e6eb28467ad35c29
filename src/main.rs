//! The `rockslide` binary: parse the command line and hand over to [`rockslide::cli`].

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    rockslide::cli::main(rockslide::cli::Cli::parse())
}

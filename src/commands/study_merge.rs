//! `rockslide study-merge GRID --from DIR…`: gather the shards' results of a study into
//! `<out>` and write its summary (as `rockslide study --merge`).

use std::process::ExitCode;

use rockslide_core::error::Error;

use crate::args::StudyMergeArgs;
use crate::commands::study::merge_command;

/// Merge the shards.
pub fn run(args: &StudyMergeArgs, quiet: bool) -> Result<ExitCode, Error> {
    merge_command(&args.grid, &args.out, &args.from, quiet)?;
    Ok(ExitCode::SUCCESS)
}

//! `rockslide trace-info FILE.mcap`: check an MCAP trace and print its channels, metadata
//! and attachments.

use std::process::ExitCode;

use rockslide_core::error::Error;

use crate::args::TraceInfoArgs;

/// Print what the file holds.
pub fn run(args: &TraceInfoArgs) -> Result<ExitCode, Error> {
    rockslide_formats::mcap_info(&args.file).map(|s| {
        let _ = std::io::Write::write_all(&mut std::io::stdout().lock(), s.as_bytes());
        ExitCode::SUCCESS
    })
}

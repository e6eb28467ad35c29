//! `rockslide newmark RECORD --ky G…`: Newmark rigid-block sliding on a record, both
//! polarities (SLAMMER's rigid block); sliding in mm, block minus ground. Prints the table
//! (and writes it as CSV with `--csv`).

use std::process::ExitCode;

use rockslide_core::error::Error;
use rockslide_verify::study::newmark_command;

use crate::args::NewmarkArgs;

/// Print the table.
pub fn run(args: NewmarkArgs) -> Result<ExitCode, Error> {
    let NewmarkArgs {
        record,
        ky,
        unit,
        pga,
        two_way,
        csv,
    } = args;
    let text = newmark_command(&rockslide_verify::study::NewmarkArgs {
        record,
        ky,
        unit,
        pga,
        two_way,
        csv,
    })?;
    let _ = std::io::Write::write_all(&mut std::io::stdout().lock(), text.as_bytes());
    Ok(ExitCode::SUCCESS)
}

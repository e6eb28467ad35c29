//! Reports: the paper-style tables of a case (Markdown), the suite summary, and writing
//! every output of a case (CSV and MCAP traces, report) atomically under the output folder.

mod markdown;
mod mcap_log;

pub use markdown::{case_markdown, suite_markdown};
pub use mcap_log::{case_trace_log, git_commit, write_case_mcap};

use std::path::{Path, PathBuf};

use crate::error::Error;
use crate::io::write_atomically;
use crate::suite::CaseResult;
use crate::trace::write_csv;

/// Write a case's CSV traces and Markdown report under `out/<case>/`; returns the folder.
pub fn write_case_outputs(result: &CaseResult, out: &Path) -> Result<PathBuf, Error> {
    let dir = out.join(&result.case.name);
    for run in &result.runs {
        write_csv(
            &run.trace,
            &dir.join(format!("{}-{}.csv", run.engine, run.variant)),
        )?;
    }
    if let Ok(r) = &result.reference {
        write_csv(
            &r.trace,
            &dir.join(format!("reference-{}.csv", r.solution.name())),
        )?;
    }
    write_case_mcap(result, &dir.join(format!("{}.mcap", result.case.name)))?;
    write_atomically(&dir.join("report.md"), case_markdown(result).as_bytes())?;
    Ok(dir)
}

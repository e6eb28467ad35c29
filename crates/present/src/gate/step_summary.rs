//! GitHub Actions shows at most ten annotations per step: when `GITHUB_STEP_SUMMARY` names
//! a file, the full suite summary (verdict per case and every failure line) is appended
//! to it so that the whole table appears on the run's page. Elsewhere this does nothing.

use std::io::Write;

use crate::report::suite_markdown;
use rockslide_verify::suite::CaseResult;

/// Append the suite summary to `$GITHUB_STEP_SUMMARY`, if set; a failure to write is
/// reported on stderr and otherwise ignored (the gate's verdict does not depend on it).
pub fn write_step_summary(results: &[CaseResult]) {
    let Some(path) = std::env::var_os("GITHUB_STEP_SUMMARY") else {
        return;
    };
    let appended = std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(&path)
        .and_then(|mut f| f.write_all(suite_markdown(results).as_bytes()));
    if let Err(e) = appended {
        eprintln!(
            "warning: cannot append to GITHUB_STEP_SUMMARY ({}): {e}",
            std::path::Path::new(&path).display()
        );
    }
}

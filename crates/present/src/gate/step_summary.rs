//! GitHub Actions shows at most ten annotations per step: when `GITHUB_STEP_SUMMARY` names
//! a file, the full suite summary (verdict per case and every failure line) is appended
//! to it so that the whole table appears on the run's page. Elsewhere this does nothing.
//!
//! A step summary is read on the run's page, where a link relative to the output folder
//! leads nowhere. Its links are absolute when `ROCKSLIDE_REPORTS_URL` gives the output
//! folder's URL (`$ROCKSLIDE_REPORTS_URL/<case>/report.html`); otherwise each case and
//! figure is named by its path from the repository root (`reports/<case>/report.html`), the
//! path it has in an uploaded artifact of the output folder, and is not linked.

use std::io::Write;
use std::path::Path;

use crate::report::{Links, suite_markdown_with};
use rockslide_verify::suite::CaseResult;

/// The variable naming the URL the output folder is published at.
pub const REPORTS_URL: &str = "ROCKSLIDE_REPORTS_URL";

/// How the step summary links: absolute from `url` when given (and not empty), else the
/// paths of `out` (as given on the command line, relative to the working directory,
/// which in CI is the repository root).
pub fn step_summary_links(url: Option<&str>, out: &Path) -> Links {
    match url.map(str::trim).filter(|u| !u.is_empty()) {
        Some(u) => Links::Absolute(u.to_string()),
        None => {
            let cwd = std::env::current_dir().ok();
            let shown = cwd
                .as_deref()
                .and_then(|c| out.strip_prefix(c).ok())
                .unwrap_or(out);
            Links::Paths(shown.to_string_lossy().replace('\\', "/"))
        }
    }
}

/// Append the suite summary to `$GITHUB_STEP_SUMMARY`, if set, its links made as
/// [`step_summary_links`] says for the output folder `out`; a failure to write is
/// reported on stderr and otherwise ignored (the gate's verdict does not depend on it).
pub fn write_step_summary(results: &[CaseResult], out: &Path) {
    let Some(path) = std::env::var_os("GITHUB_STEP_SUMMARY") else {
        return;
    };
    let url = std::env::var(REPORTS_URL).ok();
    let links = step_summary_links(url.as_deref(), out);
    let appended = std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(&path)
        .and_then(|mut f| f.write_all(suite_markdown_with(results, &links).as_bytes()));
    if let Err(e) = appended {
        eprintln!(
            "warning: cannot append to GITHUB_STEP_SUMMARY ({}): {e}",
            std::path::Path::new(&path).display()
        );
    }
}

//! The progress bar of the many-run commands (`sweep`, `stability`, `study`): shown on a
//! terminal, hidden when asked, when `CI` is set (to anything but `false`) or when stderr
//! is not a terminal, so that logs hold results, not redraws.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressStyle};

/// A bar over `total` items named `unit` (`runs`, `points`), labelled `what`; hidden
/// unless `shown` and on an interactive terminal outside CI.
pub fn bar(total: usize, shown: bool, unit: &str, what: &str) -> ProgressBar {
    let ci = std::env::var_os("CI").is_some_and(|v| !v.is_empty() && v != "false");
    if !shown || ci || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total as u64);
    let template =
        format!("{{msg:>12}} [{{bar:40}}] {{pos}}/{{len}} {unit} ({{elapsed}}, eta {{eta}})");
    if let Ok(style) = ProgressStyle::with_template(&template) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_string());
    bar
}

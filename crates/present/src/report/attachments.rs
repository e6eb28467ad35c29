//! Results of the slow commands that `run` and `check` pick up instead of recomputing:
//! `rockslide sweep <case>` leaves the typed [`SweepResult`] in `<out>/<case>/sweep.json`
//! and `rockslide stability` the typed [`StabilityResult`] in
//! `<out>/stability/stability.json`. The reports read those structs back — never the
//! Markdown, HTML or CSV beside them — so a report carries the work-precision and
//! stability sections whenever those files exist in the output folder, and says how to
//! make them when they do not. A file that cannot be read becomes a sentence in the
//! report, never a failed run.

use std::path::Path;

use rockslide_verify::sweep::{StabilityResult, SweepResult};

/// Everything picked up from an output folder.
#[derive(Debug, Clone, Default)]
pub(crate) struct Attachments {
    /// `<case>/sweep.json`, or why it could not be read (`None`: absent).
    pub sweep: Option<Result<SweepResult, String>>,
    /// `stability/stability.json` (suite reports only), or why it could not be read.
    pub stability: Option<Result<StabilityResult, String>>,
}

impl Attachments {
    /// What lies in a case's folder `dir` (`<out>/<case>/`).
    pub fn for_case(dir: &Path) -> Self {
        Attachments {
            sweep: SweepResult::load(dir),
            stability: None,
        }
    }

    /// What lies in the suite's output folder `out`.
    pub fn for_suite(out: &Path) -> Self {
        Attachments {
            sweep: None,
            stability: StabilityResult::load(&out.join(rockslide_verify::sweep::stability::DIR)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn absent_results_are_none_and_broken_ones_a_reason() {
        let dir = tempfile::tempdir().unwrap();
        assert!(Attachments::for_case(dir.path()).sweep.is_none());
        assert!(Attachments::for_suite(dir.path()).stability.is_none());
        std::fs::write(dir.path().join("sweep.json"), "{\"case\": \"x\"}").unwrap();
        let why = Attachments::for_case(dir.path())
            .sweep
            .unwrap()
            .unwrap_err();
        assert!(
            why.contains("sweep.json") && why.contains("missing field"),
            "{why}"
        );
    }
}

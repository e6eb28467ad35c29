//! JUnit XML (written by the `quick-junit` crate, not by hand): one test suite per case,
//! one test case per check. Gated checks that fail are failures; checks that are not gated
//! are reported as passing with their outcome in `system-out` when they pass, and as
//! skipped with the outcome when they fail, so CI shows them without turning red.

use std::path::Path;

use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;
use rockslide_verify::analysis::Verdict;
use rockslide_verify::suite::CaseResult;
use rockslide_verify::verdict::{describe, fails, failures, limit_text};

/// The JUnit report of a checked suite.
pub fn junit_report(results: &[CaseResult]) -> Report {
    let mut report = Report::new("rockslide check");
    report.set_timestamp(chrono::Utc::now().fixed_offset());
    let all = failures(results);
    for r in results {
        let mut suite = TestSuite::new(r.case.name.as_str());
        suite.add_property(quick_junit::Property::new(
            "case file",
            r.case.path.display().to_string(),
        ));
        suite.add_property(quick_junit::Property::new(
            "case sha256",
            r.case.sha256.as_str(),
        ));
        let class = format!("rockslide.{}", r.case.name);
        for c in &r.checks {
            let name = format!("{}: {} vs {}", c.quantity, c.run, c.basis);
            let what = format!(
                "{}: {} (tolerance {}) [{}]",
                c.verdict.label(),
                describe(c),
                limit_text(r, c),
                c.field
            );
            let status = if fails(c) {
                let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
                s.set_message(what.as_str()).set_type(c.verdict.label());
                s
            } else if !c.gated && c.verdict != Verdict::Pass {
                let mut s = TestCaseStatus::skipped();
                s.set_message(format!("not gated — {what}"));
                s
            } else {
                TestCaseStatus::success()
            };
            let mut tc = TestCase::new(name, status);
            tc.set_classname(class.as_str());
            if let Some(run) = r.runs.iter().find(|x| x.label() == c.run) {
                tc.set_time(std::time::Duration::from_secs_f64(
                    run.wall_seconds.max(0.0),
                ));
            }
            tc.set_system_out(what);
            suite.add_test_case(tc);
        }
        for i in &r.invariants {
            let what = i.describe();
            let status = match (&i.expected, i.holds()) {
                (_, true) => TestCaseStatus::success(),
                (Some((field, reason)), false) => {
                    let mut s = TestCaseStatus::skipped();
                    s.set_message(format!("declared known [{field}]: {reason} — {what}"));
                    s
                }
                (None, false) => {
                    let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
                    s.set_message(what.as_str()).set_type("INVARIANT");
                    s
                }
            };
            let mut tc = TestCase::new(format!("invariant {}: {}", i.invariant, i.run), status);
            tc.set_classname(class.as_str());
            tc.set_system_out(what);
            suite.add_test_case(tc);
        }
        // Failures that are no tolerance check: gated tolerances that matched no run, a case
        // whose gate checks nothing, runs that did not end as declared.
        for f in all
            .iter()
            .filter(|f| f.case == r.case.name && (f.checks_nothing || f.quantity == "run status"))
        {
            let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
            let kind = if f.checks_nothing {
                "CHECKS NOTHING"
            } else {
                "RUN STATUS"
            };
            s.set_message(f.to_string()).set_type(kind);
            let mut tc = TestCase::new(format!("{}: {}", f.quantity, f.engines), s);
            tc.set_classname(class.as_str());
            suite.add_test_case(tc);
        }
        report.add_test_suite(suite);
    }
    report
}

/// Write the JUnit report atomically to `path`.
pub fn write_junit(results: &[CaseResult], path: &Path) -> Result<(), Error> {
    let xml = junit_report(results)
        .to_string()
        .map_err(|e| Error::Other(format!("JUnit serialisation: {e}")))?;
    write_atomically(path, xml.as_bytes())
}

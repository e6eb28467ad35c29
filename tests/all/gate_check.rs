//! `rockslide check` as CI runs it: exit codes (0 pass, 1 gate failed, 2 bad input), one
//! line per gated failure, and JUnit XML that an independent XML parser reads with the
//! right counts. Requirement: docs/report.md, "the gate".

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use quick_xml::Reader;
use quick_xml::events::Event;

fn check(cases: &[&str], out: &Path, junit: Option<&Path>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_rockslide"));
    cmd.current_dir(env!("CARGO_MANIFEST_DIR"))
        .arg("check")
        .args(cases)
        .arg("--out")
        .arg(out);
    if let Some(j) = junit {
        cmd.arg("--junit").arg(j);
    }
    cmd.output().expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Counts read off JUnit XML by quick-xml, independently of the crate that wrote it:
/// (`tests` attribute of <testsuites>, <testcase> elements, <failure> elements,
/// <skipped> elements).
fn junit_counts(xml: &str) -> (usize, usize, usize, usize) {
    let mut reader = Reader::from_str(xml);
    let (mut declared, mut cases, mut failures, mut skipped) = (0, 0, 0, 0);
    loop {
        match reader.read_event().expect("well-formed XML") {
            Event::Start(e) | Event::Empty(e) => match e.name().as_ref() {
                b"testsuites" => {
                    let a = e
                        .try_get_attribute("tests")
                        .expect("attribute parses")
                        .expect("tests attribute");
                    declared = String::from_utf8_lossy(&a.value).parse().unwrap();
                }
                b"testcase" => cases += 1,
                b"failure" => failures += 1,
                b"skipped" => skipped += 1,
                _ => {}
            },
            Event::Eof => break,
            _ => {}
        }
    }
    (declared, cases, failures, skipped)
}

#[test]
fn a_too_tight_tolerance_fails_the_gate_with_one_line_and_exit_1() {
    let dir = tempfile::tempdir().unwrap();
    let junit = dir.path().join("ci/junit.xml");
    let o = check(&["tests/data/too-tight.toml"], dir.path(), Some(&junit));
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "stderr:\n{err}");
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("FAIL ")).collect();
    // Three tolerances: one gated and too tight, one gated and passing, one failing but
    // not gated — exactly one failure line.
    assert_eq!(lines.len(), 1, "{err}");
    let line = lines[0];
    let head =
        "FAIL too-tight: peak_relative_displacement: predictor-corrector/paper vs reference: Δ ";
    let tail = " (tolerance ≤ 0.1 %) [tests/data/too-tight.toml: tolerance[0]]";
    assert!(line.starts_with(head) && line.ends_with(tail), "{line}");
    // The value: Δ in %, then run and reference values in mm. The exact peak relative
    // displacement is 9.263 mm (exact event-driven reference, 4 digits); the
    // predictor-corrector at dt = 0.01 s was measured 0.617 % below it.
    let value = &line[head.len()..line.len() - tail.len()];
    let pct: f64 = value
        .split(' ')
        .next()
        .unwrap()
        .trim_end_matches('%')
        .parse()
        .unwrap();
    assert!((pct - (-0.617)).abs() <= 0.0005, "{value}");
    assert!(value.ends_with("(9.206 vs 9.263 mm)"), "{value}");

    let xml = std::fs::read_to_string(&junit).expect("JUnit written where asked");
    let (declared, cases, failures, skipped) = junit_counts(&xml);
    // Three tolerance checks plus the run's five invariants (friction bound, stick-slip,
    // dissipation: μ finite; compression and penetration on its recorded contact), which
    // hold for the predictor-corrector.
    assert_eq!((declared, cases, failures, skipped), (8, 8, 1, 1), "{xml}");
}

#[test]
fn a_gated_tolerance_that_checks_nothing_fails() {
    let dir = tempfile::tempdir().unwrap();
    let o = check(&["tests/data/checks-nothing.toml"], dir.path(), None);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("FAIL checks-nothing: peak_relative_displacement: rapier: checks nothing"),
        "{err}"
    );
    // --junit defaults to <out>/junit.xml.
    let xml = std::fs::read_to_string(dir.path().join("junit.xml")).unwrap();
    let (declared, cases, failures, _) = junit_counts(&xml);
    // The failing check plus the predictor-corrector's compression and penetration
    // invariants (μ = ∞: no friction invariants), which hold.
    assert_eq!((declared, cases, failures), (3, 3, 1), "{xml}");
}

#[test]
fn a_bad_case_exits_2_with_located_errors_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out: PathBuf = dir.path().join("out");
    let o = check(&["tests/data/bad-case.toml"], &out, None);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("tests/data/bad-case.toml:29:12: tolerance[0].quantity: unknown quantity \"peak_wobble\""),
        "{err}"
    );
    assert!(
        err.contains("tests/data/bad-case.toml:30:11: tolerance[0].percent:"),
        "{err}"
    );
    assert!(!out.exists(), "no output on bad input");
}

#[test]
fn a_missing_case_file_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let o = check(&["tests/data/no-such-case.toml"], dir.path(), None);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn passing_tolerances_exit_0_and_report_zero_failures() {
    // The linear SDOF, predictor-corrector only: three gated checks, all within tolerance.
    let dir = tempfile::tempdir().unwrap();
    let o = check(&["tests/data/within-tolerance.toml"], dir.path(), None);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!stderr(&o).contains("FAIL"));
    let xml = std::fs::read_to_string(dir.path().join("junit.xml")).unwrap();
    let (declared, cases, failures, _) = junit_counts(&xml);
    // Plus the run's compression and penetration invariants (μ = ∞), which hold.
    assert_eq!((declared, cases, failures), (5, 5, 0), "{xml}");
}

#[test]
fn the_suite_summary_is_appended_to_the_github_step_summary() {
    let dir = tempfile::tempdir().unwrap();
    let summary = dir.path().join("step-summary.md");
    std::fs::write(&summary, "earlier step\n").unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("GITHUB_STEP_SUMMARY", &summary)
        .args(["check", "tests/data/too-tight.toml", "--quiet", "--out"])
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let text = std::fs::read_to_string(&summary).unwrap();
    assert!(text.starts_with("earlier step\n"), "appended, not replaced");
    assert!(text.contains("**Gate: FAIL**"), "{text}");
    assert!(
        text.contains("- FAIL too-tight: peak_relative_displacement:"),
        "{text}"
    );
}

/// `check` in a GitHub-like environment: the step summary, summary path `summary` and
/// reports in `<dir>/out`, run from `dir` (the repository root in CI) with `env` set.
fn check_in_ci(dir: &Path, env: &[(&str, &str)]) -> (Output, String) {
    let summary = dir.join("step-summary.md");
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/too-tight.toml");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_rockslide"));
    cmd.current_dir(dir)
        .env_remove("GITHUB_ACTIONS")
        .env_remove("ROCKSLIDE_REPORTS_URL")
        .env("GITHUB_STEP_SUMMARY", &summary)
        .envs(env.iter().copied())
        .arg("check")
        .arg(&case)
        .args(["--out", "out"]);
    let o = cmd.output().unwrap();
    (o, std::fs::read_to_string(&summary).unwrap())
}

/// rockslide shall make the step summary's links work away from the output folder:
/// absolute from `ROCKSLIDE_REPORTS_URL`, else the path from the repository root (as in
/// an uploaded artifact), never a link relative to the output folder.
#[test]
fn step_summary_links_are_absolute_or_paths_from_the_repository_root() {
    let dir = tempfile::tempdir().unwrap();
    let (o, text) = check_in_ci(
        dir.path(),
        &[("ROCKSLIDE_REPORTS_URL", "https://ci.example/run/7/reports/")],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(
        text.contains("[too-tight](https://ci.example/run/7/reports/too-tight/report.html)"),
        "{text}"
    );
    assert!(!text.contains("](too-tight/"), "{text}");
    let dir = tempfile::tempdir().unwrap();
    let (o, text) = check_in_ci(dir.path(), &[]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        text.contains("too-tight (`out/too-tight/report.html`)"),
        "{text}"
    );
    assert!(!text.contains("](too-tight/"), "{text}");
}

/// rockslide shall annotate each gate failure for GitHub (`::error file=…,title=…::…` on
/// stdout) when `GITHUB_ACTIONS=true`, and only then; a passing gate annotates nothing.
#[test]
fn failing_checks_emit_github_annotations_only_under_github_actions() {
    let dir = tempfile::tempdir().unwrap();
    let (o, _) = check_in_ci(dir.path(), &[("GITHUB_ACTIONS", "true")]);
    assert_eq!(o.status.code(), Some(1));
    let out = String::from_utf8_lossy(&o.stdout);
    let notes: Vec<&str> = out.lines().filter(|l| l.starts_with("::error ")).collect();
    assert_eq!(notes.len(), 1, "{out}");
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/too-tight.toml");
    let file = case.display().to_string().replace(':', "%3A");
    assert!(
        notes[0].starts_with(&format!(
            "::error file={file},title=rockslide too-tight::FAIL too-tight: peak_relative_displacement: predictor-corrector/paper vs reference: Δ "
        )),
        "{}",
        notes[0]
    );
    for env in [&[][..], &[("GITHUB_ACTIONS", "false")][..]] {
        let dir = tempfile::tempdir().unwrap();
        let (o, _) = check_in_ci(dir.path(), env);
        assert_eq!(o.status.code(), Some(1));
        assert!(!String::from_utf8_lossy(&o.stdout).contains("::error"));
    }
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("GITHUB_ACTIONS", "true")
        .args(["check", "tests/data/within-tolerance.toml", "--out"])
        .arg(dir.path().join("pass"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!String::from_utf8_lossy(&o.stdout).contains("::error"));
}

#[test]
fn a_case_whose_gate_checks_nothing_fails() {
    let dir = tempfile::tempdir().unwrap();
    let o = check(&["tests/data/no-gated-check.toml"], dir.path(), None);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains(
            "FAIL no-gated-check: gate: any run: checks nothing: the case has no gated check"
        ),
        "{err}"
    );
    let xml = std::fs::read_to_string(dir.path().join("junit.xml")).unwrap();
    let (_, _, failures, _) = junit_counts(&xml);
    assert_eq!(failures, 1, "{xml}");
}

#[test]
fn check_on_an_empty_selection_fails() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("no-cases");
    std::fs::create_dir(&empty).unwrap();
    let o = check(&[empty.to_str().unwrap()], &dir.path().join("out"), None);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("FAIL checks nothing: no case file (*.toml) in"),
        "{err}"
    );
}

#[test]
fn a_closed_pipe_is_not_a_panic() {
    // The reading end closed before `list` has loaded its cases: every write meets a
    // closed pipe (`rockslide list | head -0`).
    let o = crate::common::into_closed_pipe(&["list"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// `rockslide check | head -1`: the reader goes away after the first line; the gate still
/// answers with its exit code (here 1: the case fails), never a panic (101).
#[test]
fn check_into_a_closed_pipe_is_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let o = crate::common::into_closed_pipe(&["check", "tests/data/too-tight.toml", "--out", out]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn error_lines_carry_the_error_prefix() {
    let dir = tempfile::tempdir().unwrap();
    let o = check(&["tests/data/bad-case.toml"], &dir.path().join("out"), None);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.lines().count() >= 2, "{err}");
    assert!(err.lines().all(|l| l.starts_with("error: ")), "{err}");
}

/// The stability scenes carry gated tolerances against their exact references too (a user
/// may `check` them: they are out of the default folders because `rockslide stability`
/// classifies them at other steps). Their tolerances were measured at rapier's 16 substeps
/// and went stale, unnoticed, when rapier moved to its step rule: this holds them. Every
/// scene passes, nothing is skipped, and JUnit judges at least one check per
/// `[[tolerance]]` table of the files (counted here from their text), besides the runs'
/// invariants.
#[test]
fn the_stability_scenes_pass_their_own_gate() {
    let dir = tempfile::tempdir().unwrap();
    let junit = dir.path().join("junit.xml");
    let o = check(&["cases/stability"], &dir.path().join("out"), Some(&junit));
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/stability");
    let tolerances: usize = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| {
            std::fs::read_to_string(p)
                .unwrap()
                .matches("[[tolerance]]")
                .count()
        })
        .sum();
    assert!(tolerances >= 13, "every scene gated: {tolerances}");
    let xml = std::fs::read_to_string(&junit).unwrap();
    let (declared, cases, failures, skipped) = junit_counts(&xml);
    assert_eq!((failures, declared), (0, cases), "{xml}");
    assert!(
        cases > tolerances,
        "{cases} judged for {tolerances} tolerances"
    );
    // skipped: only the invariant breaks rocking-10g declares (its [[expected_violation]])
    assert_eq!(
        xml.matches("<skipped message=\"declared known [expected_violation[")
            .count(),
        skipped,
        "{xml}"
    );
}

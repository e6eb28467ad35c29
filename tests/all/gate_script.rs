//! The CI gate other repositories adopt: `scripts/gate.sh`, the steps of the composite
//! action (`action.yml`), run here as the action runs them (GitHub's environment variables
//! set to files of a temporary folder).
//!
//! Requirements checked:
//! - `check` gates the cases given (exit 0 pass, 1 gate failed), writes JUnit XML where
//!   asked, appends the step summary, annotates each failure (`::error file=…`) and states
//!   its outputs (`junit=`, `reports=`, `status=`) for the action;
//! - each `LABEL=PATH` line of the external input joins the case as a participant;
//! - `install` reuses an install built from the same sources (the cache) without running
//!   cargo, and puts the binary's folder on the job's PATH;
//! - `action.yml` runs these steps and nothing else, on its own files;
//! - the sample workflows name rockslide's repository in one line.

use std::path::Path;
use std::process::{Command, Output};

use crate::common::repo;

/// `scripts/gate.sh <step>` from the repository's root, the built binary as rockslide,
/// GitHub's files in `dir`, `env` added.
fn gate(step: &str, dir: &Path, env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new("bash");
    cmd.arg(repo("scripts/gate.sh"))
        .arg(step)
        .current_dir(repo("."))
        .env("ROCKSLIDE_BIN", env!("CARGO_BIN_EXE_rockslide"))
        .env("ROCKSLIDE_OUT", dir.join("out"))
        .env("GITHUB_ACTIONS", "true")
        .env("GITHUB_STEP_SUMMARY", dir.join("summary.md"))
        .env("GITHUB_OUTPUT", dir.join("output"))
        .env("GITHUB_PATH", dir.join("path"))
        .env_remove("ROCKSLIDE_EXTERNAL")
        .env_remove("ROCKSLIDE_JUNIT");
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.output().expect("bash runs")
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn check_passes_a_passing_case_with_junit_summary_and_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let o = gate(
        "check",
        dir.path(),
        &[("ROCKSLIDE_CASES", "tests/data/within-tolerance.toml")],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let junit = dir.path().join("out/junit.xml");
    assert!(read(&junit).contains("<testcase"), "JUnit has test cases");
    assert!(!read(&dir.path().join("summary.md")).is_empty());
    let outputs = read(&dir.path().join("output"));
    assert!(
        outputs.contains(&format!("junit={}", junit.display())),
        "{outputs}"
    );
    assert!(outputs.contains("status=0"), "{outputs}");
    assert!(!String::from_utf8_lossy(&o.stdout).contains("::error"));
}

#[test]
fn check_fails_a_too_tight_case_with_exit_1_and_an_annotation() {
    let dir = tempfile::tempdir().unwrap();
    let o = gate(
        "check",
        dir.path(),
        &[("ROCKSLIDE_CASES", "tests/data/too-tight.toml")],
    );
    assert_eq!(o.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("::error file=tests/data/too-tight.toml"),
        "{stdout}"
    );
    assert!(read(&dir.path().join("output")).contains("status=1"));
    assert!(dir.path().join("out/junit.xml").is_file());
}

#[test]
fn each_external_line_joins_the_case_as_a_participant() {
    let dir = tempfile::tempdir().unwrap();
    // a result file of "another program": the predictor-corrector's own trace CSV
    let first = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(repo("."))
        .args([
            "run",
            "tests/data/within-tolerance.toml",
            "--quiet",
            "--out",
        ])
        .arg(dir.path().join("mine"))
        .output()
        .unwrap();
    assert!(first.status.success());
    let csv = dir
        .path()
        .join("mine/within-tolerance/predictor-corrector-paper.csv");
    let external = format!("mine={}\n", csv.display());
    let o = gate(
        "check",
        dir.path(),
        &[
            ("ROCKSLIDE_CASES", "tests/data/within-tolerance.toml"),
            ("ROCKSLIDE_EXTERNAL", &external),
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let record = read(&dir.path().join("out/within-tolerance/result.json"));
    assert!(
        record.contains("\"engine\": \"mine\""),
        "the external run is recorded"
    );
}

#[test]
fn install_reuses_an_install_of_the_same_sources_and_puts_it_on_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path().join("root");
    std::fs::create_dir_all(root.join("bin")).unwrap();
    let fingerprint = gate("fingerprint", dir.path(), &[]);
    assert!(fingerprint.status.success());
    let key = String::from_utf8_lossy(&fingerprint.stdout)
        .trim()
        .to_string();
    assert_eq!(key.len(), 16, "{key}");
    std::fs::write(root.join("rockslide.fingerprint"), format!("{key}\n")).unwrap();
    let bin = root.join("bin/rockslide");
    std::fs::copy(env!("CARGO_BIN_EXE_rockslide"), &bin).unwrap();
    let o = gate(
        "install",
        dir.path(),
        &[
            ("ROCKSLIDE_ROOT", root.to_str().unwrap()),
            ("ROCKSLIDE_BIN", bin.to_str().unwrap()),
            // no cargo on the PATH: a cached install must not need it
            ("PATH", "/usr/bin:/bin"),
        ],
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(stdout.contains("(cached)"), "{stdout}");
    assert_eq!(
        read(&dir.path().join("path")).trim(),
        root.join("bin").display().to_string()
    );
}

#[test]
fn the_action_runs_the_scripts_steps() {
    let action = read(&repo("action.yml"));
    for step in [
        "gate.sh\" fingerprint",
        "gate.sh\" install",
        "gate.sh\" check",
    ] {
        assert!(action.contains(step), "action.yml runs {step}");
    }
    assert!(action.contains("actions/upload-artifact@"));
    assert!(action.contains("actions/cache@"));
    // it builds from its own files: the fingerprint and the install read the action's path
    assert_eq!(
        action
            .matches("ROCKSLIDE_SOURCE: ${{ github.action_path }}")
            .count(),
        2
    );
}

/// The samples name rockslide's repository once: the GitHub workflow on its `uses:` line
/// only, the GitLab job in one variable.
#[test]
fn the_sample_workflows_name_the_repository_once() {
    let github = read(&repo("examples/ci/github-workflow.yml"));
    let named: Vec<&str> = github
        .lines()
        .filter(|l| l.contains("OWNER/rockslide"))
        .collect();
    assert_eq!(named.len(), 1, "{named:?}");
    assert!(
        named[0]
            .trim_start()
            .starts_with("- uses: OWNER/rockslide@")
    );
    let gitlab = read(&repo("examples/ci/gitlab-ci.yml"));
    let named: Vec<&str> = gitlab
        .lines()
        .filter(|l| l.contains("OWNER/rockslide"))
        .collect();
    assert_eq!(named.len(), 1, "{named:?}");
    assert!(named[0].trim_start().starts_with("ROCKSLIDE_REPO: "));
}

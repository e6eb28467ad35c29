//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use rockslide::case::{Case, load_case, parse_case};
use rockslide::engine::{Engine, Run};

/// Path of a file in the repository.
pub fn repo(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

/// Load a shipped case.
pub fn case(name: &str) -> Case {
    load_case(&repo(&format!("cases/{name}.toml"))).expect("shipped case loads")
}

/// A shipped case with text replaced (`from` must occur).
pub fn case_with(name: &str, from: &str, to: &str) -> Case {
    case_edited(name, &[(from, to)])
}

/// A shipped case with each `(from, to)` replaced in turn (each `from` must occur).
pub fn case_edited(name: &str, edits: &[(&str, &str)]) -> Case {
    let path = repo(&format!("cases/{name}.toml"));
    let mut text = std::fs::read_to_string(&path).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from:?} not in {name}");
        text = text.replace(from, to);
    }
    parse_case(&path, &text).expect("modified case loads")
}

/// The value of the first of a run's stated settings whose name starts with `key`.
pub fn setting(run: &Run, key: &str) -> Option<String> {
    run.settings
        .iter()
        .find(|s| s.label().starts_with(key))
        .map(|s| s.value_text())
}

/// A case read as the loader reads it before the engines check their options: for tests of
/// an engine's own option checks. Asserts that the checked load refuses it with the same
/// first error the engine gives, so that a bad option never gets past loading.
pub fn parse_with_bad_options(path: &Path, text: &str) -> Case {
    let c = rockslide::formats::parse_case(path, text, rockslide::registry::CASE_SECTION_IDS)
        .expect("the case parses before the engines' option checks");
    let refused = parse_case(path, text).expect_err("a bad option is refused at load");
    let first = rockslide::registry::all()
        .iter()
        .flat_map(|e| e.parse_options(&c).err().unwrap_or_default())
        .next()
        .expect("an engine finds the bad option");
    assert_eq!(refused.0[0].to_string(), first.to_string());
    c
}

/// Observed order of accuracy between two errors at steps dt1 > dt2.
pub fn order(e1: f64, e2: f64, dt1: f64, dt2: f64) -> f64 {
    (e1 / e2).ln() / (dt1 / dt2).ln()
}

/// `rockslide args` run from the repository's root; its exit code and output.
pub fn rockslide(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .unwrap()
}

/// `rockslide args | head -0` from the repository's root: the reading end of standard
/// output closed before the command writes; its exit code and standard error.
pub fn into_closed_pipe(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait_with_output().unwrap()
}

/// Whether the outside program a test needs (OpenSeesPy, CalculiX, Chromium) is here.
/// Such a test is compiled as ignored, with the reason, when the build script (`build.rs`)
/// did not find the program and nothing requires it, so `cargo test` lists it as ignored.
/// This is the check when it runs anyway: where the program is required — `CI=true`, or
/// its own `require_var` (`ROCKSLIDE_REQUIRE_*`, as `.ci/run` sets) — its absence fails
/// the test; elsewhere (run with `--include-ignored`, or the program removed since the
/// build) the test prints SKIPPED with the reason and returns early.
pub fn present_or_skip(test: &str, found: bool, require_var: &str, missing: &str) -> bool {
    if !found {
        let required = std::env::var_os(require_var).is_some()
            || std::env::var("CI").is_ok_and(|v| v == "true");
        assert!(
            !required,
            "{test}: required here ({require_var} or CI=true) — {missing}"
        );
        eprintln!("{test}: SKIPPED, not passed — {missing}");
    }
    found
}

/// The registry's entry for `engine`, found by the engine type's own id: a test that runs
/// an engine "through the registry" names the type, never its id.
pub fn registered(engine: &dyn Engine) -> Box<dyn Engine> {
    rockslide::engine::all()
        .into_iter()
        .find(|e| e.id() == engine.id())
        .unwrap_or_else(|| panic!("{} is not in the registry", engine.id()))
}

//! Bad case files: rockslide shall reject every malformed case with one clear line per
//! problem — file, line and column, field, reason — never a panic, never partial output.

use std::path::Path;
use std::process::Command;

use rockslide::case::parse_case;

const GOOD: &str = include_str!("../../cases/pepo-mass-accel.toml");

/// Errors of `text` (a modified good case) as display lines.
fn errors(text: &str) -> Vec<String> {
    match parse_case(Path::new("bad.toml"), text) {
        Ok(_) => vec![],
        Err(e) => e.0.iter().map(|e| e.to_string()).collect(),
    }
}

fn with(from: &str, to: &str) -> Vec<String> {
    assert!(GOOD.contains(from), "{from}");
    errors(&GOOD.replacen(from, to, 1))
}

fn line_of(needle: &str) -> usize {
    GOOD.lines().position(|l| l.contains(needle)).unwrap() + 1
}

#[test]
fn the_shipped_case_is_good() {
    assert!(errors(GOOD).is_empty());
}

#[test]
fn negative_mass_is_located_and_explained() {
    let e = with("mass = 1.0e6", "mass = -1.0e6");
    let line = line_of("mass = 1.0e6");
    assert_eq!(
        e,
        vec![format!(
            "bad.toml:{line}:8: model.mass: is -1000000, but must be positive and finite, in kg"
        )]
    );
}

#[test]
fn syntax_errors_give_line_and_column() {
    let e = with("kz = 3.94784e9", "kz = 3.94.784e9");
    let line = line_of("kz = 3.94784e9");
    assert_eq!(e.len(), 1);
    assert_eq!(
        e[0],
        format!("bad.toml:{line}:10: model.contact.kz: invalid float, expected nothing")
    );
}

#[test]
fn a_value_of_the_wrong_type_names_its_field() {
    let e = with("mu = 0.5\n", "mu = \"half\"\n");
    let line = GOOD.lines().position(|l| l == "mu = 0.5").unwrap() + 1;
    assert_eq!(
        e,
        vec![format!(
            "bad.toml:{line}:6: model.contact.mu: invalid type: string \"half\", expected f64"
        )]
    );
}

#[test]
fn missing_and_unknown_fields_are_named() {
    let e = with("duration = 1.0\n", "");
    assert!(
        e[0].contains(": run.duration: missing field `duration`"),
        "{e:?}"
    );
    let e = with("gravity = 1.0 ", "gravty = 1.0 ");
    assert!(
        e[0].contains(": model.gravty: unknown field `gravty`"),
        "{e:?}"
    );
    assert!(
        e[0].starts_with(&format!("bad.toml:{}:", line_of("gravity = 1.0 "))),
        "{e:?}"
    );
}

#[test]
fn all_problems_of_a_file_are_reported_together() {
    let text = GOOD
        .replace("mu = 0.5\n\n[model.double]", "mu = -0.5\n\n[model.double]")
        .replacen("dt = 0.001", "dt = 0", 1);
    let e = errors(&text);
    assert_eq!(e.len(), 2, "{e:?}");
    assert!(
        e[0].contains("model.contact.mu: is -0.5, but must be zero or positive"),
        "{}",
        e[0]
    );
    assert!(
        e[1].contains("run.dt: is 0, but must be positive"),
        "{}",
        e[1]
    );
}

#[test]
fn unknown_kinds_list_the_valid_ones() {
    let e = with("kind = \"mass-acceleration\"", "kind = \"mass-accel\"");
    assert!(
        e[0].contains("excitation.kind: is \"mass-accel\", but must be one of"),
        "{e:?}"
    );
    let e = with("[engines.predictor-corrector]", "[engines.ansys]");
    assert!(
        e[0].contains("engines.ansys: unknown engine \"ansys\""),
        "{e:?}"
    );
}

#[test]
fn a_ground_displacement_must_end_at_rest() {
    let text =
        include_str!("../../cases/pepo-ground-disp.toml").replace("cycles = 0.5", "cycles = 0.3");
    let e = errors(&text);
    assert!(
        e[0].contains("excitation.cycles: must be a whole number of half cycles"),
        "{e:?}"
    );
}

#[test]
fn unknown_tolerance_quantity_is_rejected() {
    let text = format!("{GOOD}\n[[tolerance]]\nquantity = \"peak_drift\"\npercent = 1.0\n");
    let e = errors(&text);
    let line = text.lines().count() - 1;
    let index = GOOD.matches("[[tolerance]]").count();
    assert!(
        e[0].starts_with(&format!(
            "bad.toml:{line}:12: tolerance[{index}].quantity: unknown quantity \"peak_drift\""
        )),
        "{e:?}"
    );
}

/// The binary: exit code 2, the error on stderr, nothing written.
#[test]
fn the_cli_rejects_a_bad_case_without_writing_anything() {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("broken.toml");
    std::fs::write(&case, GOOD.replace("mass = 1.0e6", "mass = \"heavy\"")).unwrap();
    let out_dir = dir.path().join("out");
    let out = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args([
            "run",
            case.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let line = line_of("mass = 1.0e6");
    assert!(
        stderr.contains(&format!("broken.toml:{line}:8: ")) && stderr.contains("invalid type"),
        "{stderr}"
    );
    assert!(!out_dir.exists(), "no partial output");
    // a variant the engine does not have
    std::fs::write(
        &case,
        GOOD.replace(
            "dt = 0.01               #",
            "variants = [\"eq13\"]\ndt = 0.01 #",
        ),
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args([
            "run",
            case.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("engines.predictor-corrector.variants[0]: \"eq13\" is not a variant"),
        "{stderr}"
    );
    assert!(!out_dir.exists());
    // a file that does not exist
    let out = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args(["run", "no/such/case.toml"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&out.stderr)
            .contains("no/such/case.toml: cannot read the case file")
    );
}

/// An unknown key no longer hides the file's other errors: two misspelt keys in two
/// tables and a negative friction coefficient give three located lines, in file order of
/// discovery (unknown keys first, then validation).
#[test]
fn unknown_keys_are_reported_with_every_other_error() {
    let text = GOOD
        .replacen("mu = 0.5", "mu = -0.5\nmew = 0.5", 1)
        .replacen("[run]\n", "[run]\nduraton = 2.0\n", 1);
    let e = errors(&text);
    let mu_line = text.lines().position(|l| l == "mu = -0.5").unwrap() + 1;
    let run_line = text.lines().position(|l| l.starts_with("duraton")).unwrap() + 1;
    assert_eq!(e.len(), 3, "{e:#?}");
    assert!(
        e[0].starts_with(&format!(
            "bad.toml:{}:1: model.contact.mew: unknown field `mew`",
            mu_line + 1
        )),
        "{e:#?}"
    );
    assert!(
        e[1].starts_with(&format!(
            "bad.toml:{run_line}:1: run.duraton: unknown field `duraton`"
        )),
        "{e:#?}"
    );
    assert!(
        e[2].starts_with(&format!("bad.toml:{mu_line}:6: model.contact.mu: is -0.5")),
        "{e:#?}"
    );
}

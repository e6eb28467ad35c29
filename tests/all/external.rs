//! External participants (docs/verify-your-own-code.md): another program's results gated like an engine's.
//!
//! Requirements checked:
//! - rockslide shall read its own trace CSV and MCAP back as an external participant with
//!   every response equal to the engine's that wrote it, bit for bit (round trip);
//! - an external that no tolerance names is gated against the reference at the SAP2000
//!   "Acceptable" limit (5 % on displacements and forces, one output step on event times),
//!   and the case's engine-less tolerances do not apply to it; a tolerance naming its
//!   label replaces the default, and `against = "<label>"` compares with it;
//! - a quantity the file lacks is "not provided", never zero;
//! - a malformed file, a bad column map or a label that collides with an engine is an
//!   input error located in the file (line, column) before any work;
//! - the worked example under `examples/external/` passes its gate.

use std::path::Path;

use rockslide::case::parse_case;
use rockslide::external::{ACCEPTABLE_PERCENT, is_external};
use rockslide::report::write_case_outputs;
use rockslide::suite::{CaseResult, run_case};

use crate::common::{repo, rockslide};

/// The paper's PEPO (half-sine mass acceleration) with the fe engine, single contact, and
/// one engine-less tolerance (which must not apply to external runs).
const PEPO: &str = r#"
name = "pepo-byo"
[model]
kind = "oscillator"
mass = 1.0e6
gravity = 1.0
[model.contact]
kx = 9.8696e8
kz = 3.94784e9
mu = 0.5
[excitation]
kind = "mass-acceleration"
shape = "sine-pulse"
amplitude = 1.0
omega = 15.707963267948966
cycles = 0.5
[run]
duration = 1.0
dt = 0.001
[engines.fe]
variants = ["single"]
[[tolerance]]
quantity = "residual_sliding"
percent = 0.02
"#;

fn run_text(dir: &Path, text: &str) -> CaseResult {
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap();
    run_case(parse_case(&path, text).expect("case loads")).expect("case runs")
}

/// The PEPO run once, its outputs written under `dir/out`; returns the fe trace files.
fn fe_outputs(dir: &Path) -> (CaseResult, std::path::PathBuf, std::path::PathBuf) {
    let r = run_text(dir, PEPO);
    let out = write_case_outputs(&r, &dir.join("out")).unwrap();
    (r, out.join("fe-single.csv"), out.join("pepo-byo.mcap"))
}

fn run_index(r: &CaseResult, label: &str) -> usize {
    r.runs.iter().position(|x| x.label() == label).unwrap()
}

#[test]
fn a_trace_fed_back_as_an_external_equals_the_engine_to_the_last_digit() {
    let dir = tempfile::tempdir().unwrap();
    let (_, csv, mcap) = fe_outputs(dir.path());
    let text = format!(
        "{PEPO}\n[[external]]\nlabel = \"copy\"\nfile = {csv:?}\nprogram = \"rockslide fe\"\n\
         [[external]]\nlabel = \"mcap-copy\"\nfile = {mcap:?}\nprogram = \"rockslide fe\"\n\
         topic = \"/fe/single/state\"\n"
    );
    let r = run_text(dir.path(), &text);
    let fe = run_index(&r, "fe/single");
    for label in ["copy/external", "mcap-copy/external"] {
        let i = run_index(&r, label);
        assert!(is_external(&r.runs[i]));
        // the state channels round-trip; an external file carries no per-contact block
        let mut fe_state = r.runs[fe].trace.clone();
        fe_state.contacts = Default::default();
        assert_eq!(r.runs[i].trace, fe_state, "{label}: trace");
        let (mine, theirs) = (&r.run_responses[i], &r.run_responses[fe]);
        assert_eq!(mine.len(), theirs.len(), "{label}: response count");
        for (k, v) in theirs {
            assert_eq!(mine[k].to_bits(), v.to_bits(), "{label}: {k}");
        }
        // Default checks only (the engine-less tolerance[0] is for engines), all passing.
        let checks: Vec<_> = r.checks.iter().filter(|c| c.run == label).collect();
        assert!(
            checks.iter().all(|c| c.field.starts_with("external[")),
            "{checks:?}"
        );
        assert!(checks.iter().all(|c| c.basis == "reference" && c.gated));
        // peak_relative_displacement, peak/residual sliding, slip start/end, peak
        // resistance, peak |sliding| and total slid: the reference and the file both have
        // them, min_sliding is 0.
        let mut keys: Vec<&str> = checks.iter().map(|c| c.quantity.as_str()).collect();
        keys.sort();
        assert_eq!(
            keys,
            [
                "peak_abs_sliding",
                "peak_relative_displacement",
                "peak_resistance",
                "peak_sliding",
                "residual_sliding",
                "slip_end",
                "slip_start",
                "total_slid"
            ]
        );
    }
    assert!(r.gate_passed());
}

#[test]
fn an_external_beyond_five_percent_fails_the_default_gate_and_a_named_tolerance_replaces_it() {
    let dir = tempfile::tempdir().unwrap();
    let (base, _, _) = fe_outputs(dir.path());
    let fe = &base.runs[run_index(&base, "fe/single")].trace;
    // The fe slide history × 1.06, written in mm with foreign headers.
    let mut csv = String::from("t,sliding\n");
    for (t, s) in fe.time.iter().zip(fe.column("slide").unwrap()) {
        csv.push_str(&format!("{t},{}\n", s * 1.06 * 1000.0));
    }
    std::fs::write(dir.path().join("scaled.csv"), csv).unwrap();
    let external = "\n[[external]]\nlabel = \"scaled\"\nfile = \"scaled.csv\"\nprogram = \"test\"\n\
                    columns = { t = \"time [s]\", sliding = \"slide [mm]\" }\n";
    let r = run_text(dir.path(), &format!("{PEPO}{external}"));
    let reference = r.reference.as_ref().unwrap().responses["residual_sliding"];
    let expected = 100.0 * (fe.column("slide").unwrap().last().unwrap() * 1.06 / reference - 1.0);
    let c = r
        .checks
        .iter()
        .find(|c| c.run == "scaled/external" && c.quantity == "residual_sliding")
        .unwrap();
    assert!(
        (c.percent.unwrap() - expected).abs() < 1e-9,
        "{c:?} vs {expected}"
    );
    assert!(expected > ACCEPTABLE_PERCENT);
    assert!(c.limit.contains("SAP2000"), "{}", c.limit);
    assert!(!r.gate_passed());
    // rel_disp is not in the file: no value, shown as "not provided".
    let i = run_index(&r, "scaled/external");
    assert!(!r.run_responses[i].contains_key("peak_relative_displacement"));
    let out = write_case_outputs(&r, &dir.path().join("scaled-out")).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("not provided"));

    // A tolerance naming the label replaces the defaults; `against` a bare label works.
    let named = "[[tolerance]]\nquantity = \"residual_sliding\"\nengine = \"scaled\"\npercent = 7\n\
                 [[tolerance]]\nquantity = \"residual_sliding\"\nengine = \"fe\"\nagainst = \"scaled\"\npercent = 5.7\n";
    let r = run_text(dir.path(), &format!("{PEPO}{external}{named}"));
    let on_scaled: Vec<_> = r
        .checks
        .iter()
        .filter(|c| c.run == "scaled/external")
        .collect();
    assert_eq!(on_scaled.len(), 1, "{on_scaled:?}");
    assert_eq!(on_scaled[0].field, "tolerance[1]");
    let vs = r.checks.iter().find(|c| c.field == "tolerance[2]").unwrap();
    assert_eq!(vs.basis, "scaled/external");
    // fe / (1.06·fe) − 1, exactly the scaling
    assert!(
        (vs.percent.unwrap() - 100.0 * (1.0 / 1.06 - 1.0)).abs() < 1e-9,
        "{vs:?}"
    );
    assert!(r.gate_passed());
}

#[test]
fn bad_external_files_and_labels_are_located_input_errors() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.toml");
    std::fs::write(
        dir.path().join("bad.csv"),
        "time [s],slide [m]\n0,0\n0.1,1e-3x\n",
    )
    .unwrap();
    let load = |external: &str| {
        let text = format!("{PEPO}\n[[external]]\n{external}");
        parse_case(&path, &text).unwrap_err().to_string()
    };
    let e = load("label = \"x\"\nfile = \"bad.csv\"\nprogram = \"p\"\n");
    let bad = dir.path().join("bad.csv");
    // located twice: at the case's `file = ` value (two lines after `[[external]]`,
    // column 8), then in the results file (line 3, column 5)
    let file_line = format!("{PEPO}\n[[external]]\n").matches('\n').count() + 2;
    assert_eq!(
        e,
        format!(
            "{}:{file_line}:8: external[0].file: {}:3:5: column \"slide [m]\": \"1e-3x\" is not a number",
            path.display(),
            bad.display()
        )
    );
    let e = load("label = \"fe\"\nfile = \"bad.csv\"\nprogram = \"p\"\n");
    assert!(
        e.contains("external[0].label: is \"fe\", which is an engine"),
        "{e}"
    );
    // located at the label's value: the line after `[[external]]`, column 9
    let line = format!("{PEPO}\n[[external]]\n").matches('\n').count() + 1;
    assert!(
        e.starts_with(&format!("{}:{line}:9: ", path.display())),
        "{e}"
    );
    let e = load(
        "label = \"x\"\nfile = \"bad.csv\"\nprogram = \"p\"\ncolumns = { a = \"slide [kN]\" }\n",
    );
    assert!(
        e.contains("external[0].columns: \"a\" = \"slide [kN]\": \"slide\" cannot be in [kN]"),
        "{e}"
    );
    let e = load("label = \"x\"\nfile = \"missing.csv\"\nprogram = \"p\"\n");
    assert_eq!(
        e,
        format!(
            "{}:{file_line}:8: external[0].file: {}: cannot read the results file: No such file or directory",
            path.display(),
            dir.path().join("missing.csv").display()
        )
    );
}

#[test]
fn the_command_line_refuses_a_colliding_label_and_several_cases() {
    let e = rockslide(&[
        "run",
        "examples/external/pepo-external.toml",
        "--external",
        "rapier=examples/external/mycode-pepo.csv",
    ]);
    assert_eq!(e.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&e.stderr)
            .contains("--external rapier: label is \"rapier\", which is an engine")
    );
    let e = rockslide(&[
        "run",
        "cases/linear-sdof.toml",
        "cases/pepo-mass-accel.toml",
        "--external",
        "x=examples/external/mycode-pepo.csv",
    ]);
    assert_eq!(e.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&e.stderr).contains("applies to one case, but 2 cases were given")
    );
}

/// The worked example of docs/verify-your-own-code.md: the exact solution at 5 ms rounded
/// to 4 significant digits in mm, so its residual sliding is within half a unit of the
/// 4th digit (0.0005 mm) of the exact one and its slip start within one output step.
#[test]
fn the_worked_example_passes_its_gate_through_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let o = rockslide(&[
        "check",
        "examples/external/pepo-external.toml",
        "--out",
        out,
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let junit = std::fs::read_to_string(dir.path().join("junit.xml")).unwrap();
    assert!(junit.contains("mycode/external"));
    let md = std::fs::read_to_string(dir.path().join("pepo-external/report.md")).unwrap();
    assert!(
        md.contains("| Peak resistance (abs) | kN | 500.0 | 500.0 | +0.00 % | not provided |"),
        "{md}"
    );
    assert!(md.contains("columns ignored: \"Step type\""));

    let case = rockslide::case::load_case(&repo("examples/external/pepo-external.toml")).unwrap();
    let r = run_case(case).unwrap();
    let i = run_index(&r, "mycode/external");
    let exact = &r.reference.as_ref().unwrap().responses;
    let mine = &r.run_responses[i];
    assert!((mine["residual_sliding"] - exact["residual_sliding"]).abs() <= 0.5e-6);
    assert!((mine["slip_start"] - exact["slip_start"]).abs() <= 0.005);
    assert_eq!(r.runs[i].dt, 0.005);
}

/// An external participant that no gated check compares fails the gate ("checks nothing")
/// even when the engines' checks pass: here a file with only the normal force, which no
/// response quantity of the reference or fe is read from.
#[test]
fn an_external_that_nothing_compares_fails_the_gate() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("normal-only.csv");
    let rows: String = (0..=1000)
        .map(|i| format!("{},{}\n", i as f64 * 1e-3, 1.0e6))
        .collect();
    std::fs::write(&file, format!("time [s],normal [N]\n{rows}")).unwrap();
    let text = format!(
        "{PEPO}\n[[external]]\nlabel = \"normal-only\"\nfile = {file:?}\nprogram = \"a spreadsheet\"\n"
    );
    let r = run_text(dir.path(), &text);
    assert!(
        !r.checks
            .iter()
            .any(|c| c.gated && c.run == "normal-only/external"),
        "{:?}",
        r.checks
    );
    let failures = rockslide::verdict::failures(std::slice::from_ref(&r));
    assert_eq!(failures.len(), 1, "{failures:?}");
    assert!(failures[0].checks_nothing);
    assert_eq!(failures[0].engines, "normal-only/external");
    assert!(!r.gate_passed());
}

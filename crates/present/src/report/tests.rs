//! The reports are generic over runs: a synthetic rocking case with two engine runs and no
//! reference (as the RPEPO will be once the FE and rapier engines exist) gets run columns
//! without Δ % against a reference, an n/a reason for the predictor-corrector, a
//! cross-code matrix with event-time differences and the history difference up to the
//! first lift-off, CM and rotation figures, and a run-against-run gate failure. Every
//! expected number is computed here from the synthetic signals.

use std::f64::consts::PI;
use std::path::Path;

use super::crosscode::cross_code;
use super::plots::figures;
use rockslide_core::trace::{Trace, q};
use rockslide_engine_api::{Run, RunStatus, SolverStats};
use rockslide_verify::analysis::{evaluate_tolerances, responses};
use rockslide_verify::registry::parse_case;
use rockslide_verify::suite::CaseResult;

const CASE: &str = r#"
title = "Synthetic rocking case"
source = "rockslide unit test"
requirement = "reports shall be generic over runs"
[model]
kind = "rocking-body"
mass = 1.0e6
gravity = 9.81
cm_height = 0.625
half_width = 0.5
supports = 10
[model.contact]
kx = 2.4e9
kz = 3.94784e8
mu = 0.5
[excitation]
kind = "mass-acceleration"
shape = "sine-pulse"
amplitude = 0.981
omega = 31.41592653589793
cycles = 5
[run]
duration = 1.0
dt = 0.001
[[tolerance]]
quantity = "peak_cm_x"
engine = "rapier"
against = "fe/single"
percent = 1.0
"#;

const N: usize = 1000;

/// cm_x = s·10 mm·sin 2πt, rel_disp = s·1 mm·sin 2πt, rotation = s·1 mrad·sin 2πt,
/// cm_z = 1 mm·t, contacts 10 until `liftoff`, then 0.
fn run(engine: &'static str, variant: &str, s: f64, liftoff: f64) -> Run {
    let ch = [&q::REL_DISP, &q::CM_X, &q::CM_Z, &q::ROTATION, &q::CONTACTS];
    let mut trace = Trace::with_channels(&ch, N + 1);
    for i in 0..=N {
        let t = i as f64 / N as f64;
        let w = (2.0 * PI * t).sin();
        let contacts = if t < liftoff { 10.0 } else { 0.0 };
        trace.push(
            t,
            &[s * 1e-3 * w, s * 1e-2 * w, 1e-3 * t, s * 1e-3 * w, contacts],
        );
    }
    Run {
        engine,
        variant: variant.into(),
        arrangement: Default::default(),
        dt: 1e-3,
        settings: vec![rockslide_engine_api::Setting::number("dt", "s", 0.001)],
        stats: SolverStats::default(),
        findings: vec![],
        trace,
        status: RunStatus::Completed,
        wall_seconds: 0.0,
    }
}

fn result() -> CaseResult {
    result_of(CASE)
}

/// The synthetic runs under the case `text`.
fn result_of(text: &str) -> CaseResult {
    let case = parse_case(Path::new("synthetic-rocking.toml"), text).expect("valid case");
    let runs = vec![
        run("fe", "single", 1.0, 0.6),
        run("rapier", "inertial", 1.03, 0.65),
    ];
    let run_responses: Vec<_> = runs.iter().map(|r| responses(&r.trace)).collect();
    let checks = evaluate_tolerances(&case.tolerances, &runs, &run_responses, None);
    CaseResult {
        case,
        runs,
        run_responses,
        invariants: Vec::new(),
        envelopes: Vec::new(),
        azimuths: None,
        history_errors: vec![None, None],
        not_applicable: vec![(
            "predictor-corrector",
            "the predictor-corrector is a single-degree-of-freedom sliding method".into(),
        )],
        reference: Err("no exact solution exists for the rocking oscillator".into()),
        checks,
    }
}

#[test]
fn cross_code_matrix_of_two_runs_without_reference() {
    let r = result();
    let x = cross_code(&r);
    assert_eq!(x.labels, ["fe/single", "rapier/inertial"]);
    assert!(x.lifts_off);
    // Whole history: RMS over t_i = i/N of 0.03·sin 2πt_i, over fe's peak 1 (at t = 0.25).
    let rms = |upto: usize| {
        let s: f64 = (0..=upto)
            .map(|i| (0.03 * (2.0 * PI * i as f64 / N as f64).sin()).powi(2))
            .sum();
        (s / (upto + 1) as f64).sqrt()
    };
    let whole = x.nrms[1][0].unwrap();
    assert!((whole - rms(N)).abs() < 1e-12, "{whole}");
    // rapier vs fe normalised by fe's peak; fe vs rapier by rapier's (1.03).
    assert!((x.nrms[0][1].unwrap() - rms(N) / 1.03).abs() < 1e-12);
    // Peak relative displacement: +3 % both ways round.
    assert!((x.peak[1][0].unwrap() - 3.0).abs() < 1e-9);
    assert!((x.peak[0][1].unwrap() - 100.0 * (1.0 / 1.03 - 1.0)).abs() < 1e-9);
    // The pair: first lift-off 0.65 s vs 0.60 s → +50 ms; history up to 0.6 s.
    let p = &x.pairs[0];
    let k = x.keys.iter().position(|k| *k == "first_liftoff").unwrap();
    assert!((p.entries[k].unwrap() - 50.0).abs() < 1e-9);
    let to_liftoff = p.nrms_to_liftoff.unwrap();
    assert!((to_liftoff - rms(600)).abs() < 1e-12, "{to_liftoff}");
}

#[test]
fn reports_have_run_columns_na_column_figures_and_the_run_vs_run_failure() {
    let r = result();
    let md = super::case_markdown(&r);
    assert!(
        md.contains("| Quantity | Unit | fe/single | rapier/inertial | Result |"),
        "{md}"
    );
    assert!(
        md.contains("- predictor-corrector: not applicable — the predictor-corrector is a single-degree-of-freedom sliding method"),
        "{md}"
    );
    assert!(md.contains("Reference: none — no exact solution exists for the rocking oscillator."));
    assert!(md.contains(
        "FAIL synthetic-rocking: peak_cm_x: rapier/inertial vs fe/single: Δ +3.00 % (10.30 vs 10.00 mm) (tolerance ≤ 1 %) [synthetic-rocking.toml: tolerance[0]]"
    ), "{md}");
    assert!(md.contains("nRMS to first lift-off"));
    // Without a reference the check marks the value itself.
    let row = md
        .lines()
        .find(|l| l.starts_with("| Peak CM horizontal (abs) |"))
        .unwrap();
    assert!(row.contains("| 10.00 | **10.30 ✗** |"), "{row}");
    let ids: Vec<String> = figures(&r).into_iter().map(|f| f.id).collect();
    assert_eq!(
        ids,
        [
            "record",
            "relative-displacement",
            "cm-horizontal",
            "cm-vertical",
            "rotation"
        ]
    );
    let html = super::case_html(&r);
    assert_eq!(html.matches("<svg").count(), 5);
    assert!(!html.contains("://"));
}

/// A pulse of 4 g (m/s² typed as g: 4 m/s² is 4 / 9.80665 = 0.408 g) is warned about at
/// the top of the case's report and of the summary, once each, before the design
/// quantities; the paper-like case without one has no such section.
#[test]
fn input_warnings_open_the_report_and_the_summary_once() {
    let amplitude = 4.0 * rockslide_core::case::record::STANDARD_GRAVITY;
    let text = CASE.replace("amplitude = 0.981", &format!("amplitude = {amplitude}"));
    let r = result_of(&text);
    let warning = "excitation.amplitude: PGA 4.000 g: was this in m/s²? (4.000 m/s² is 0.408 g)";
    let md = super::case_markdown(&r);
    assert_eq!(md.matches(warning).count(), 1, "{md}");
    let at = md.find("## Input warnings").expect("the section");
    assert!(at < md.find(warning).unwrap());
    assert!(at < md.find("## Design quantities").expect("design quantities"));
    assert!(md.find("**Gate: ").unwrap() < at, "{md}");
    let summary = super::suite_markdown(std::slice::from_ref(&r));
    let named = format!("synthetic-rocking: {warning}");
    assert_eq!(summary.matches(&named).count(), 1, "{summary}");
    assert!(summary.find(&named).unwrap() < summary.find("## Design quantities").unwrap());
    assert!(!super::case_markdown(&result()).contains("Input warnings"));
}

#[test]
fn reference_file_names_are_file_safe() {
    assert_eq!(
        super::file_safe("exact EPO (vertical)"),
        "exact-EPO-vertical"
    );
    assert_eq!(super::file_safe("Newmark (record)"), "Newmark-record");
    assert_eq!(super::file_safe("exact"), "exact");
}

/// A fresh folder under the system's temporary folder, removed by the caller.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rockslide-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The file names in a folder, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn the_lean_set_leaves_traces_to_the_mcap_file_and_links_each_figure_once() {
    let r = result();
    let (full, lean) = (scratch("full"), scratch("lean"));
    let full_case = super::write_case_outputs_with(&r, &full, super::OutputSet::FULL).unwrap();
    let lean_case = super::write_case_outputs_with(&r, &lean, super::OutputSet::LEAN).unwrap();
    let traces = [
        "fe-single.csv",
        "rapier-inertial.csv",
        "synthetic-rocking.mcap",
    ];
    let full_files = names(&full_case.dir);
    assert!(traces.iter().all(|t| full_files.contains(&t.to_string())));
    let lean_files = names(&lean_case.dir);
    // the same files but the CSV traces; the MCAP file holds the full one's rows at the
    // lean file step (the case itself unchanged: every row in memory)
    let without_csv: Vec<&String> = full_files
        .iter()
        .filter(|f| !(f.ends_with(".csv") && *f != "summary.csv"))
        .collect();
    assert_eq!(lean_files.iter().collect::<Vec<_>>(), without_csv);
    let mcap =
        |dir: &Path| rockslide_formats::read_mcap(&dir.join("synthetic-rocking.mcap")).unwrap();
    let (full_mcap, lean_mcap) = (mcap(&full_case.dir), mcap(&lean_case.dir));
    assert_eq!(full_mcap.states.len(), lean_mcap.states.len());
    for ((topic, full), (lean_topic, lean)) in full_mcap.states.iter().zip(&lean_mcap.states) {
        assert_eq!(topic, lean_topic);
        assert!(lean.len() < full.len(), "{topic}: {} rows", lean.len());
        assert_eq!(&full.at_output_step(super::LEAN_FILE_STEP), lean, "{topic}");
    }
    let step = |m: &rockslide_formats::McapContents| m.metadata["rockslide"]["output_dt_s"].clone();
    assert_eq!(step(&full_mcap), "every step");
    assert_eq!(step(&lean_mcap), "0.005");
    assert_eq!(r.case.run.output_dt, None, "the case is not changed");
    // full pages embed the five figures; lean pages link the files beside them
    let page = |dir: &Path| std::fs::read_to_string(dir.join("report.html")).unwrap();
    assert_eq!(page(&full_case.dir).matches("<svg").count(), 5);
    let lean_page = page(&lean_case.dir);
    assert_eq!(lean_page.matches("<svg").count(), 0);
    for f in lean_files.iter().filter(|f| f.starts_with("plot-")) {
        assert_eq!(
            lean_page.matches(&format!("<img src=\"{f}\"")).count(),
            1,
            "{f}"
        );
    }
    // the summary page: the full one as `write_suite_outputs` renders it, byte for byte;
    // the lean one links every case figure by its path from the output folder
    let results = [r];
    let html = super::write_suite_outputs_with(&results, &[full_case], &full).unwrap();
    let once = std::fs::read_to_string(html).unwrap();
    super::write_suite_outputs(&results, &full).unwrap();
    assert_eq!(
        once,
        std::fs::read_to_string(full.join("summary.html")).unwrap()
    );
    let html = super::write_suite_outputs_with(&results, &[lean_case], &lean).unwrap();
    let summary = std::fs::read_to_string(html).unwrap();
    assert_eq!(
        summary
            .matches("<img src=\"synthetic-rocking/plot-")
            .count(),
        5
    );
    assert!(!summary.contains("<svg"));
    for dir in [full, lean] {
        std::fs::remove_dir_all(dir).unwrap();
    }
}

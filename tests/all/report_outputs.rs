//! The reports `check` writes for a case and for the suite: a self-contained HTML page
//! (no URL, no script, the plots inline as SVG), Markdown with the paper-style table and
//! the n/a reasons, SVG plots with the paper's units, a summary CSV whose numbers are
//! consistent, and provenance with the case file's SHA-256. Requirement:
//! docs/report.md.

use std::path::Path;
use std::process::Command;

use sha2::{Digest, Sha256};

/// Run `check` on the too-tight test case into a fresh folder (exit 1 expected).
fn reports() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["check", "tests/data/too-tight.toml", "--quiet", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    dir
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// Assert an HTML page fetches nothing: no URL of any scheme, no script, no external
/// style sheet, image or font; every link an in-page anchor.
fn assert_self_contained(html: &str) {
    for bad in [
        "://", "http:", "https:", "=\"data:", "<script", "<link", "<img", "<iframe", "<object",
        "@import", "url(", "src=",
    ] {
        assert!(!html.contains(bad), "page contains {bad:?}");
    }
    for (i, _) in html.match_indices("href=\"") {
        assert!(
            html[i + 6..].starts_with('#'),
            "non-anchor link at {}",
            &html[i..i + 40]
        );
    }
}

#[test]
fn case_html_is_self_contained_and_embeds_the_plots() {
    let dir = reports();
    let case = dir.path().join("too-tight");
    let html = read(&case.join("report.html"));
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert_self_contained(&html);
    // A sliding oscillator under mass acceleration: the excitation (in g), force &
    // resistance, relative displacement and sliding figures — no CM, rotation (the scene
    // has none).
    let inline = html.matches("<svg").count();
    let files: Vec<_> = std::fs::read_dir(&case)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("plot-") && n.ends_with(".svg"))
        .collect();
    assert_eq!(inline, 4, "inline SVGs");
    assert_eq!(files.len(), 4, "{files:?}");
    for f in &files {
        let svg = read(&case.join(f));
        assert!(svg.contains(" d=\"M"), "{f} has drawn lines");
        assert!(svg.contains("time [s]"), "{f} has a time axis");
    }
    // Axes in the paper's units; the excitation in g.
    let ex = read(&case.join("plot-record.svg"));
    assert!(ex.contains("a [g]"), "mass acceleration in g");
    let fr = read(&case.join("plot-force-resistance.svg"));
    assert!(fr.contains("[kN]"), "force in kN");
    let rd = read(&case.join("plot-relative-displacement.svg"));
    assert!(
        rd.contains("Relative displacement x [mm]"),
        "displacement in mm"
    );
    // The gate verdict and the failure line are on the page.
    assert!(html.contains("Gate: FAIL"));
    assert!(html.contains(
        "FAIL too-tight: peak_relative_displacement: predictor-corrector/paper vs reference"
    ));
}

#[test]
fn suite_html_is_self_contained_and_holds_every_case() {
    let dir = reports();
    let html = read(&dir.path().join("summary.html"));
    assert_self_contained(&html);
    assert!(html.contains("<a href=\"#case-too-tight\">too-tight</a>"));
    assert!(html.contains("<section class=\"case\" id=\"case-too-tight\">"));
    assert_eq!(html.matches("<svg").count(), 4);
    let md = read(&dir.path().join("summary.md"));
    assert!(md.contains("[too-tight](too-tight/report.md)"));
    assert!(md.contains("**Gate: FAIL**"));
}

#[test]
fn markdown_has_the_paper_table_with_na_columns_and_provenance() {
    let dir = reports();
    let md = read(&dir.path().join("too-tight/report.md"));
    assert!(
        md.contains(
            "| Quantity | Unit | Reference (exact) | predictor-corrector/paper | Δ % | Result |"
        ),
        "{md}"
    );
    // Engines that did not run get a reason under the table (no column of "n/a").
    assert!(md.contains("- fe: not applicable — "), "{md}");
    assert!(md.contains("- rapier: not applicable — "), "{md}");
    // The failing row: gated, outside tolerance.
    let row = md
        .lines()
        .find(|l| l.starts_with("| Peak relative displacement (abs) |"))
        .unwrap();
    assert!(row.contains("✗") && row.ends_with("| **FAIL** |"), "{row}");
    // its tolerance: one per check, in the tolerance checks' table
    let check = md
        .lines()
        .find(|l| l.starts_with("| peak_relative_displacement | predictor-corrector/paper |"))
        .unwrap();
    assert!(check.contains("| ≤ 0.1 % |"), "{check}");
    // Provenance: the case file's SHA-256, computed here independently.
    let bytes =
        std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/too-tight.toml"))
            .unwrap();
    let sha = format!("{:x}", Sha256::digest(&bytes));
    assert!(md.contains(&format!("- **case sha256:** {sha}")), "{md}");
    for key in ["tool", "commit", "machine", "date"] {
        assert!(md.contains(&format!("- **{key}:** ")), "provenance {key}");
    }
    // The cross-code matrix.
    assert!(md.contains("### Whole history: normalised RMS difference of rel_disp"));
}

#[test]
fn summary_csv_is_consistent() {
    let dir = reports();
    let mut r = csv::Reader::from_path(dir.path().join("summary.csv")).unwrap();
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(header, rockslide::report::SUMMARY_HEADER);
    let rows: Vec<csv::StringRecord> = r.records().map(|x| x.unwrap()).collect();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let peak = rows
        .iter()
        .find(|x| &x[col("quantity")] == "peak_relative_displacement")
        .unwrap();
    assert_eq!(&peak[col("verdict")], "FAIL");
    assert_eq!(&peak[col("gated")], "true");
    // Δ % = 100·(value/reference − 1), recomputed here from the SI values in the file.
    let v: f64 = peak[col("value")].parse().unwrap();
    let b: f64 = peak[col("reference")].parse().unwrap();
    let d: f64 = peak[col("delta_percent")].parse().unwrap();
    assert!((d - 100.0 * (v / b - 1.0)).abs() < 1e-9, "{d}");
    // Residual sliding has two checks (gated ≤ 1 % passing, informative ≤ 0.01 % failing):
    // one row each.
    let residual: Vec<_> = rows
        .iter()
        .filter(|x| &x[col("quantity")] == "residual_sliding")
        .map(|x| (x[col("gated")].to_string(), x[col("verdict")].to_string()))
        .collect();
    assert_eq!(
        residual,
        [
            ("true".to_string(), "PASS".to_string()),
            ("false".to_string(), "FAIL".to_string())
        ]
    );
    // The per-case summary holds the same rows.
    let case = read(&dir.path().join("too-tight/summary.csv"));
    assert_eq!(case, read(&dir.path().join("summary.csv")));
}

/// A run of many cases releases each case's time histories once its own
/// files are written (`CaseResult::release_histories`), so it holds the histories of the
/// cases in flight, not of every case. What the suite's outputs read stays: the summary
/// CSV, the gate's failures and informative findings, the verdict warnings and the JUnit
/// XML of the released results are those of the whole results, byte for byte — on a case
/// that fails its tolerance, a rocking body with per-contact blocks and a Housner case with
/// an exact reference — and every trace is cut to its last row.
#[test]
fn the_suite_outputs_read_nothing_a_released_case_gave_up() {
    use rockslide::gate;
    use rockslide::report::summary_csv;
    use rockslide::suite::{CaseResult, run_case};
    use rockslide::verdict::warnings;

    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let results: Vec<CaseResult> = [
        "tests/data/too-tight.toml",
        "cases/rpepo-mass-accel.toml",
        "cases/housner-pulse.toml",
    ]
    .iter()
    .map(|p| run_case(rockslide::case::load_case(&root.join(p)).unwrap()).unwrap())
    .collect();
    let outputs = |results: &[CaseResult], junit: &Path| {
        gate::write_junit(results, junit).unwrap();
        (
            summary_csv(results).unwrap(),
            gate::failures(results)
                .iter()
                .map(|f| f.to_string())
                .collect::<Vec<_>>(),
            gate::informative(results)
                .iter()
                .map(|f| f.to_string())
                .collect::<Vec<_>>(),
            warnings(results),
            without_timestamp(&std::fs::read_to_string(junit).unwrap()),
        )
    };
    let dir = tempfile::tempdir().unwrap();
    let whole = outputs(&results, &dir.path().join("whole.xml"));
    assert!(!whole.1.is_empty(), "the too-tight case fails its gate");
    let rows_before: Vec<usize> = results
        .iter()
        .flat_map(|r| r.runs.iter().map(|run| run.trace.len()))
        .collect();
    assert!(rows_before.iter().all(|&n| n > 1), "{rows_before:?}");
    let mut released = results;
    for r in &mut released {
        r.release_histories();
    }
    for r in &released {
        for run in &r.runs {
            assert_eq!(run.trace.len(), 1, "{}: the last row stays", run.label());
            assert!(run.trace.contacts.len() <= 1);
        }
        if let Ok(reference) = &r.reference {
            assert!(reference.trace.len() <= 1 && reference.output.len() <= 1);
        }
    }
    let after = outputs(&released, &dir.path().join("released.xml"));
    assert!(
        after == whole,
        "the suite's outputs changed with the histories released"
    );
}

/// JUnit XML without the `timestamp` attribute of its root (the clock when it was written).
fn without_timestamp(xml: &str) -> String {
    let start = xml
        .find(" timestamp=\"")
        .expect("the root carries a timestamp");
    let end = start + 12 + xml[start + 12..].find('"').unwrap() + 1;
    format!("{}{}", &xml[..start], &xml[end..])
}

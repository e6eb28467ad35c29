//! The report sections, checked with real numbers from small runs: the
//! energy audit of every run and of the reference, the work-precision section picked up
//! from `rockslide sweep`'s typed result `sweep.json` (not recomputed), the stability
//! section of the suite picked up from `rockslide stability`'s `stability.json`, and the
//! RPEPO comparison up to the first full lift-off with the paper's Figs 8–11 overlaid.
//! Requirement: docs/report.md and docs/sweep-and-stability.md (typed results between
//! commands).

use std::path::Path;
use std::process::Command;

use rockslide::sweep::{StabilityResult, SweepResult};

fn rockslide(args: &[&str], out: &Path) {
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .args(["--quiet", "--out"])
        .arg(out)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The Markdown table row starting with `| first |`, split into trimmed cells.
fn row(md: &str, first: &str) -> Vec<String> {
    let line = md
        .lines()
        .find(|l| l.starts_with(&format!("| {first} |")))
        .unwrap_or_else(|| panic!("no row {first:?} in\n{md}"));
    line.trim_matches('|')
        .split('|')
        .map(|c| c.trim().to_string())
        .collect()
}

/// A CSV file as header and numeric rows.
/// A figure written through the reports' compaction (`present::doc::figure::compact_svg`):
/// every line a `<path>` of relative moves (plotters writes `<polyline>`s), the grid lines
/// in groups carrying their attributes.
pub fn compacted(svg: &str) {
    assert!(!svg.contains("<polyline"), "a polyline left");
    assert!(
        svg.contains("<path ") && svg.contains(" d=\"M") && svg.contains("<g "),
        "no path or group"
    );
}

fn csv(p: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(p).unwrap();
    let h = r.headers().unwrap().iter().map(String::from).collect();
    let rows = r
        .records()
        .map(|x| x.unwrap().iter().map(String::from).collect())
        .collect();
    (h, rows)
}

fn column(p: &Path, name: &str) -> Vec<f64> {
    let (h, rows) = csv(p);
    let i = h.iter().position(|x| x.starts_with(name)).unwrap();
    rows.iter().map(|r| r[i].parse().unwrap()).collect()
}

/// PEPO mass acceleration: the energy audit of the exact reference closes, and its
/// friction work equals Ru times the residual sliding (the slip is monotone, one slip
/// phase: paper §PEPO, Ru = μ·M·g = 0.5·1e6 kg·1 m/s² = 500 kN). The sweep written by
/// `rockslide sweep` appears in the report with the observed order recomputed here from
/// its CSV, and its figure is inline in the HTML and linked from the Markdown.
#[test]
fn pepo_report_has_energy_audit_and_the_picked_up_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path();
    rockslide(
        &[
            "sweep",
            "cases/pepo-mass-accel.toml",
            "--rungs",
            "4",
            "--repeats",
            "1",
        ],
        out,
    );
    rockslide(&["run", "cases/pepo-mass-accel.toml"], out);
    let case = out.join("pepo-mass-accel");
    let md = read(&case.join("report.md"));

    // Energy audit of the reference: friction work = Ru · residual sliding of the exact
    // solution's own trace (measured: 4.378 kJ both, agreement 1e-6 relative).
    assert!(md.contains("## Energy audit"), "{md}");
    let slide = column(&case.join("reference-exact.csv"), "slide");
    let ru_xp_kj = 500e3 * slide.last().unwrap() / 1e3;
    let audit = &md[md.find("## Energy audit").unwrap()..];
    let r = row(audit, "reference (exact)");
    let friction: f64 = r[4].parse().unwrap();
    assert!(
        (friction - ru_xp_kj).abs() < 5e-4 * ru_xp_kj,
        "{friction} vs {ru_xp_kj}"
    );
    // Its balance closes to the trapezoidal floor (measured 2.7e-9).
    let rel: f64 = r[7].parse().unwrap();
    assert!(rel < 1e-6, "{rel}");
    // Every run has a row; the FE's implicit Newmark conserves energy to round-off
    // (measured 1e-11), the predictor-corrector at Δt = T/20 does not (measured 2.3e-3).
    let fe: f64 = row(audit, "fe/single")[7].parse().unwrap();
    assert!(fe < 1e-8, "{fe}");
    let pc: f64 = row(audit, "predictor-corrector/paper")[7].parse().unwrap();
    assert!(pc > 1e-4 && pc < 1e-2, "{pc}");

    // The sweep: picked up, order as the least-squares slope of ln e against ln Δt of
    // the CSV's own rows.
    assert!(md.contains("## Error against run time (work-precision)"));
    assert!(md.contains("Picked up from pepo-mass-accel/sweep.json"));
    let (h, rows) = csv(&case.join("sweep.csv"));
    let c = |n: &str| h.iter().position(|x| x == n).unwrap();
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r[c("series")] == "predictor-corrector/paper")
        .map(|r| {
            (
                r[c("dt_s")].parse::<f64>().unwrap().ln(),
                r[c("max_error")].parse::<f64>().unwrap().ln(),
            )
        })
        .collect();
    assert_eq!(pts.len(), 4);
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let slope = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
        / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
    let wp = &md[md.find("## Error against run time").unwrap()..];
    let r = row(wp, "predictor-corrector/paper");
    assert_eq!(r[1], format!("{slope:.2}"), "{r:?}");
    // Average acceleration is second order (measured 2.04 on these four rungs).
    assert!((slope - 2.0).abs() < 0.1, "{slope}");
    // One table row per rung of every series.
    let rung_rows = wp
        .lines()
        .filter(|l| l.starts_with("| fe/double | ") && l.contains("| completed |"))
        .count();
    assert_eq!(rung_rows, 4);
    // The figure: written, linked from the Markdown, inline in the HTML.
    let svg = read(&case.join("plot-work-precision.svg"));
    assert!(svg.contains("median run time [s]") && svg.contains("Δt [s]"));
    compacted(&svg);
    assert!(md.contains("![plot-work-precision.svg](plot-work-precision.svg)"));
    let html = read(&case.join("report.html"));
    assert!(
        html.contains("pepo-mass-accel: work-precision\n</text>"),
        "figure inline"
    );
    assert!(!html.contains("://"));
}

/// Without a sweep the report says how to make one, and `run` does not make it.
#[test]
fn without_a_sweep_the_report_says_how_to_make_one() {
    let dir = tempfile::tempdir().unwrap();
    rockslide(&["run", "cases/linear-sdof.toml"], dir.path());
    let case = dir.path().join("linear-sdof");
    assert!(!case.join("sweep.json").exists());
    let md = read(&case.join("report.md"));
    assert!(md.contains("No sweep in the output folder (linear-sdof/sweep.json): `rockslide sweep cases/linear-sdof.toml"), "{md}");
    let summary = read(&dir.path().join("summary.md"));
    assert!(summary.contains("No stability study in the output folder"));
}

/// The suite report carries the stability study `rockslide stability` left in the output
/// folder: the stated limits exactly as the study's own page shows them and as its typed
/// result holds them, one map row per scene and engine variant of its CSV, with each
/// run's class, and the map figure.
#[test]
fn suite_report_has_the_stability_section() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path();
    rockslide(&["stability"], out);
    rockslide(&["run", "cases/linear-sdof.toml"], out);
    let md = read(&out.join("summary.md"));
    assert!(
        md.contains("## Stability on stiff and extreme scenes"),
        "{md}"
    );
    assert!(md.contains("### Stated stability limits"));
    // The limit of the predictor-corrector as stability.md states it and as
    // stability.json holds it (measured 0.3183: 1/π, tests/all/stability_classify.rs).
    let study = read(&out.join("stability/stability.md"));
    let stated = row(&study, "predictor-corrector/paper");
    let shown = row(&md, "predictor-corrector/paper");
    assert_eq!(shown, stated);
    let typed = StabilityResult::load(&out.join("stability"))
        .unwrap()
        .unwrap();
    let limit = typed
        .limits
        .iter()
        .find(|l| l.label == "predictor-corrector/paper")
        .and_then(|l| l.limit())
        .unwrap();
    assert!((limit - 1.0 / std::f64::consts::PI).abs() < 1e-4, "{limit}");
    assert_eq!(shown[4], format!("**{limit:.4}**"));
    // One map row per scene · series, each class as the CSV says.
    let (h, rows) = csv(&out.join("stability/stability.csv"));
    let c = |n: &str| h.iter().position(|x| x == n).unwrap();
    let mut labels: Vec<String> = rows
        .iter()
        .map(|r| format!("{} · {}", r[c("scene")], r[c("series")]))
        .collect();
    labels.sort();
    labels.dedup();
    for l in &labels {
        let cells = row(&md, l);
        let classes: Vec<&Vec<String>> = rows
            .iter()
            .filter(|r| format!("{} · {}", r[c("scene")], r[c("series")]) == *l)
            .collect();
        let diverged = classes
            .iter()
            .filter(|r| r[c("class")] == "diverged")
            .count();
        let accurate = classes
            .iter()
            .filter(|r| r[c("class")] == "accurate")
            .count();
        // Failures are bold in Markdown: `**✗ t=…**`.
        let count = |m: &str| {
            cells
                .iter()
                .filter(|x| x.trim_start_matches('*').starts_with(m))
                .count()
        };
        assert_eq!(count("✗"), diverged, "{l}");
        assert_eq!(count("✓"), accurate, "{l}");
    }
    let svg = read(&out.join("stability-map.svg"));
    assert!(svg.contains("Δt / T"));
    compacted(&svg);
    assert!(md.contains("![stability-map.svg](stability-map.svg)"));
    let html = read(&out.join("summary.html"));
    assert!(html.contains("\nStability map: class of every run\n</text>"));
}

/// RPEPO: no reference, so the report says the engines are compared with each other and
/// with their own converged solutions; the history is compared up to the first full
/// lift-off *before* the whole history, and that number is recomputed here from the two
/// FE traces; the paper's Figs 8–11 quantities are overlaid for every engine.
#[test]
fn rpepo_report_compares_up_to_first_liftoff_and_draws_figs_8_to_11() {
    let dir = tempfile::tempdir().unwrap();
    rockslide(
        &[
            "sweep",
            "cases/rpepo-mass-accel.toml",
            "--rungs",
            "3",
            "--repeats",
            "1",
        ],
        dir.path(),
    );
    rockslide(&["run", "cases/rpepo-mass-accel.toml"], dir.path());
    let case = dir.path().join("rpepo-mass-accel");
    let md = read(&case.join("report.md"));
    // The sweep against each engine's own finest rung, said so, with the Richardson
    // estimates of sweep.json carried over.
    assert!(md.contains("Without an exact reference these are convergence errors against each engine's own finest solution"));
    let sweep = SweepResult::load(&case).unwrap().unwrap();
    assert!(!sweep.exact_basis);
    // One observed order per engine on the page (the fit over the asymptotic rungs), and
    // the Richardson estimates made with that same order, never a second one.
    let series = sweep.series("fe/single").unwrap();
    let p = series.observed_order().expect("an observed order");
    assert_eq!(
        series.observed_order(),
        rockslide::analysis::sweep::asymptotic_order(
            &series
                .rungs
                .iter()
                .map(|g| (g.dt, g.error.map_or(f64::NAN, |e| e.max)))
                .collect::<Vec<_>>()
        )
    );
    let order_row = format!("| fe/single | {p:.2} | {} |", series.rungs.len());
    assert!(md.contains(&order_row), "{order_row}");
    assert!(md.contains("observed order p (least-squares slope of ln(max error) against ln Δt over the 4 finest rungs)"));
    let (quantity, estimate) = series.extrapolations(sweep.ratio)[0];
    assert_eq!(quantity, "peak relative displacement");
    let e = estimate.expect("two finest rungs and an order");
    assert_eq!(e.order, p, "Richardson uses the one observed order");
    let expected = format!(
        "| fe/single | peak relative displacement | {:.6e} m | {:.3e} |",
        e.extrapolated, e.gci
    );
    assert!(md.contains(&expected), "{expected}");
    assert!(!md.contains("| observed order |"), "no second order column");
    let sweep_md = read(&case.join("sweep.md"));
    assert!(
        sweep_md.contains(expected.trim_start_matches("| fe/single ")),
        "the sweep's own page shows the same row"
    );
    assert!(md.contains("No exact reference exists for this scene. The engines are therefore verified against each other"));
    let lift = md
        .find("### Up to the first full lift-off")
        .expect("lift-off matrix");
    let whole = md.find("### Whole history").unwrap();
    assert!(lift < whole, "lift-off comparison comes first");
    // nRMS of fe/double against fe/single up to the earlier first full lift-off, from the
    // CSV traces (same Δt, same output times): RMS(x_double − x_single) / max|x_single|.
    let lifts = row(&md, "First full lift-off");
    let (ts, td): (f64, f64) = (lifts[2].parse().unwrap(), lifts[3].parse().unwrap());
    let until = ts.min(td);
    let t = column(&case.join("fe-single.csv"), "time");
    let xs = column(&case.join("fe-single.csv"), "rel_disp");
    let xd = column(&case.join("fe-double.csv"), "rel_disp");
    let (mut sum, mut n, mut peak) = (0.0, 0, 0.0_f64);
    for i in 0..t.len() {
        // The table shows lift-off rounded to 0.1 ms; rows are 1 ms apart.
        if t[i] > until + 1e-9 {
            break;
        }
        sum += (xd[i] - xs[i]).powi(2);
        peak = peak.max(xs[i].abs());
        n += 1;
    }
    let expected = (sum / n as f64).sqrt() / peak;
    let pair = row(&md, "nRMS to first lift-off");
    let shown: f64 = pair[1].parse().unwrap();
    assert!(
        (shown - expected).abs() < 1e-3 * expected,
        "{shown} vs {expected}"
    );
    // The lift-off window agrees far better than the whole run (measured 0.034 vs 0.119).
    let whole_nrms: f64 = row(&md, "History nRMS (whole run)")[1].parse().unwrap();
    assert!(shown < 0.5 * whole_nrms, "{shown} vs {whole_nrms}");
    // Figs 8–11, every engine overlaid, legend in its own strip below the plot area.
    for (file, caption) in [
        ("plot-relative-displacement.svg", "paper Fig 8"),
        ("plot-sliding.svg", "paper Fig 9"),
        ("plot-cm-horizontal.svg", "paper Fig 10"),
        ("plot-cm-vertical.svg", "paper Fig 11"),
    ] {
        assert!(md.contains(&format!("— {caption}")), "{caption}");
        let svg = read(&case.join(file));
        for run in ["fe/single", "fe/double", "rapier/applied-force"] {
            assert!(svg.contains(&format!("\n{run}\n</text>")), "{file}: {run}");
        }
        assert!(svg.matches(" d=\"M").count() >= 3, "{file}");
    }
    // Energy audit: the FE runs are audited from the energy channels the engine records
    // (tests/energy_rpepo.rs checks the numbers); rapier's trace has none, and the report
    // says why.
    let audit = &md[md.find("## Energy audit").unwrap()..];
    assert!(audit.contains("| fe/single |") && audit.contains("| fe/double |"));
    assert!(audit.contains(
        "- rapier/applied-force: not audited — energy audit not available for a rocking body"
    ));
    // Engines that did not run get a reason under the table, not an n/a column.
    assert!(
        md.contains("| Quantity | Unit | fe/single | fe/double | rapier/applied-force | Result |"),
        "{md}"
    );
    assert!(md.contains("- predictor-corrector: not applicable — "));
}

/// The document-control block: ID from the case name and the inputs' SHA-256 (computed
/// here from the case file's bytes), revision, date, and the three signature fields.
#[test]
fn case_report_has_a_document_control_block() {
    use sha2::{Digest, Sha256};
    let out = tempfile::tempdir().unwrap();
    rockslide(&["run", "cases/linear-sdof.toml"], out.path());
    let md = read(&out.path().join("linear-sdof/report.md"));
    let text = std::fs::read("cases/linear-sdof.toml").unwrap();
    let hash = format!("{:x}", Sha256::digest(&text));
    let id = format!("**Document ID:** RS-linear-sdof-{}", &hash[..12]);
    assert!(md.contains(&id), "{}", &md[..md.len().min(1500)]);
    for field in [
        "Revision",
        "Date",
        "Prepared by",
        "Checked by",
        "Approved by",
    ] {
        assert!(md.contains(&format!("- **{field}:** ")), "{field}");
    }
}

/// rockslide shall show peaks of signed quantities with their sign: the rigid block of
/// `rigid-sliding-block` slides the negative way only (one slide, Newmark 1965), so its
/// signed peak sliding is its minimum and its residual, −(its absolute peak) — in the
/// response table, in summary.csv and in result.json, for the reference and each run.
/// (Read as the largest value, the peak was 0 beside −281 mm.)
#[test]
fn signed_peaks_keep_their_sign_in_table_csv_and_json() {
    let dir = tempfile::tempdir().unwrap();
    rockslide(&["run", "cases/rigid-sliding-block.toml"], dir.path());
    let case = dir.path().join("rigid-sliding-block");
    let md = read(&case.join("report.md"));
    let signed = row(&md, "Peak sliding (signed)");
    let min = row(&md, "Minimum sliding");
    let residual = row(&md, "Residual sliding");
    let abs = row(&md, "Peak sliding (abs)");
    // Reference, kinematic-ground, inertial-force: columns 2, 3 and 5.
    for i in [2, 3, 5] {
        assert!(signed[i].starts_with("-2"), "{signed:?}");
        assert_eq!(signed[i], min[i]);
        assert_eq!(signed[i], residual[i]);
        assert_eq!(signed[i], format!("-{}", abs[i]));
    }
    let (h, rows) = csv(&case.join("summary.csv"));
    let col = |name: &str| h.iter().position(|x| x == name).unwrap();
    let value = |q: &str, run: &str| -> f64 {
        rows.iter()
            .find(|r| r[col("quantity")] == q && r[col("run")] == run)
            .unwrap()[col("value")]
        .parse()
        .unwrap()
    };
    for run in ["rapier/kinematic-ground", "rapier/inertial-force"] {
        let peak = value("peak_sliding", run);
        assert!(peak < -0.28, "{run}: {peak}");
        assert_eq!(peak, value("min_sliding", run));
        assert_eq!(peak, -value("peak_abs_sliding", run));
    }
    let json = read(&case.join("result.json"));
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    // Every `{"key": "peak_sliding", "value": …}` of the record (reference and runs).
    fn peaks(v: &serde_json::Value, out: &mut Vec<f64>) {
        match v {
            serde_json::Value::Object(m) => {
                if m.get("key").and_then(|k| k.as_str()) == Some("peak_sliding") {
                    out.extend(m.get("value").and_then(|x| x.as_f64()));
                }
                m.values().for_each(|x| peaks(x, out));
            }
            serde_json::Value::Array(a) => a.iter().for_each(|x| peaks(x, out)),
            _ => {}
        }
    }
    let mut found = Vec::new();
    peaks(&v, &mut found);
    assert_eq!(found.len(), 3, "reference and two runs: {found:?}");
    assert!(found.iter().all(|&p| p < -0.28), "{found:?}");
}

/// A 3D scene under a record pair names both records in its report's facts: the first
/// component along e₁ and the second along e₂, each with its PGA as recorded (0.0957 g
/// and 0.1598 g, the figures of cases/records/SOURCES.md).
#[test]
fn a_record_pair_report_names_both_components() {
    let dir = tempfile::tempdir().unwrap();
    rockslide(
        &["run", "cases/spatial/pepo-chino-hills-pair.toml"],
        dir.path(),
    );
    let md = read(&dir.path().join("pepo-chino-hills-pair/report.md"));
    let line = |start: &str| {
        md.lines()
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("no {start} line"))
            .to_string()
    };
    let first = line("- **Record:**");
    assert!(
        first.contains("_090.AT2") && first.contains("(0.0957 g)"),
        "{first}"
    );
    let second = line("- **Record, second component (along e₂):**");
    assert!(
        second.contains("_360.AT2") && second.contains("(0.1598 g)"),
        "{second}"
    );
}

//! Studies over records. Requirements checked:
//! - rockslide shall resume an interrupted study without redoing finished runs (counted
//!   exactly: points executed and skipped, never times);
//! - a study split with `--shard K/N` and merged shall give the same summary, byte for
//!   byte, as the study run in one go;
//! - a changed grid point (different hash) shall be rerun, a missing shard reported.
//!
//! - every engine the base case lists runs at every point, and the engines agree with
//!   each other on the residual sliding (measured tolerances below).
//!
//! Model: the paper's PEPO (cases/records/pepo-northridge.toml, every engine it lists) under
//! the first 8 s of the Northridge record (short, so that the tests stay fast).

use std::path::{Path, PathBuf};

use rockslide::commands::study::{merge_command, study_command};
use rockslide::study::{Study, StudyOptions, load_grid, result_path, run_study};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// The shipped Northridge PEPO case (all its engines) on the record's first 8 s (401
/// samples: the strong motion starts near 3 s), written to `dir`; returns (case, record).
/// `rapier = false` drops the rapier engine (the slow one) from the case.
fn short_base(dir: &Path, rapier: bool) -> (PathBuf, PathBuf) {
    let full =
        std::fs::read_to_string(root().join("cases/records/Northridge_1994_PAC-175.csv")).unwrap();
    let short: Vec<&str> = full
        .lines()
        .filter(|l| {
            l.starts_with('#') || l.split(',').next().unwrap().parse::<f64>().unwrap() <= 8.0
        })
        .collect();
    let rec = dir.join("northridge-8s.csv");
    std::fs::write(&rec, short.join("\n")).unwrap();
    let text = std::fs::read_to_string(root().join("cases/records/pepo-northridge.toml"))
        .unwrap()
        .replace("Northridge_1994_PAC-175.csv", "northridge-8s.csv")
        .replace("duration = 25.0", "duration = 9.0");
    assert!(text.contains("duration = 9.0") && text.contains("[engines.rapier]"));
    let text = if rapier {
        text
    } else {
        text.split("\n[engines.rapier]").next().unwrap().to_string()
    };
    let base = dir.join("pepo-northridge-8s.toml");
    std::fs::write(&base, text).unwrap();
    (base, rec)
}

/// A 2 PGA × 2 polarity × 2 μ grid (8 points) in `dir`.
fn write_grid(dir: &Path, rapier: bool) -> PathBuf {
    let (base, rec) = short_base(dir, rapier);
    let text = format!(
        "title = \"test grid\"\nbase = \"{}\"\nrecords = [{{ path = \"{}\", unit = \"g\" }}]\n\
         pga_g = [0.1, 0.2]\npolarity = [1, -1]\nmu = [0.4, 0.5]\ntail = 1.0\n",
        base.display(),
        rec.display()
    );
    let path = dir.join("grid.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn resume_skips_finished_points() {
    let dir = tempfile::tempdir().unwrap();
    // Without rapier (the slow engine): resuming does not depend on the engines.
    let grid_path = write_grid(dir.path(), false);
    let grid = load_grid(&grid_path).unwrap();
    assert_eq!(grid.points.len(), 8);
    let out = dir.path().join("out");
    let opts = |shard| StudyOptions {
        out: out.clone(),
        shard,
        progress: false,
    };
    // "Interrupted": only shard 0 of 3 (points 0, 3, 6) finished.
    let first = run_study(&grid, &opts(Some((0, 3)))).unwrap();
    assert_eq!((first.assigned, first.executed, first.skipped), (3, 3, 0));
    // Five runs per point: predictor-corrector, fe single and double (every engine of
    // the base case), the exact reference (the study's anchor) and the rigid block.
    assert_eq!(first.runs, 3 * 5);
    // Resume the whole grid: only the other 5 run.
    let second = run_study(&grid, &opts(None)).unwrap();
    assert_eq!((second.executed, second.skipped), (5, 3));
    // Nothing left.
    let third = run_study(&grid, &opts(None)).unwrap();
    assert_eq!((third.executed, third.skipped), (0, 8));
    // A result with a stale hash (grid changed since) is rerun; a deleted one too.
    let p1 = result_path(&out, &grid.points[1]);
    let text = std::fs::read_to_string(&p1).unwrap();
    let hash = grid.point_hash(&grid.points[1]);
    std::fs::write(&p1, text.replace(&hash, "stale")).unwrap();
    std::fs::remove_file(result_path(&out, &grid.points[2])).unwrap();
    let fourth = run_study(&grid, &opts(None)).unwrap();
    assert_eq!((fourth.executed, fourth.skipped), (2, 6));
}

#[test]
fn shards_merged_equal_the_unsharded_summary() {
    let dir = tempfile::tempdir().unwrap();
    let grid_path = write_grid(dir.path(), true);
    let whole = dir.path().join("whole");
    let o = study_command(&grid_path, &whole, None, true).unwrap();
    assert_eq!(o.executed, 8);
    let mut shard_dirs = Vec::new();
    let mut total = 0;
    for k in 0..3 {
        let d = dir.path().join(format!("shard{k}"));
        let o = study_command(&grid_path, &d, Some((k, 3)), true).unwrap();
        total += o.executed;
        assert!(!d.join("summary.csv").exists(), "a shard writes no summary");
        shard_dirs.push(d);
    }
    assert_eq!(total, 8, "every point in exactly one shard");
    let merged = dir.path().join("merged");
    // With a shard missing, merge refuses and names the missing points.
    let err = merge_command(&grid_path, &merged, &shard_dirs[..2], true).unwrap_err();
    assert!(err.to_string().contains("2 of 8 grid points"), "{err}");
    assert!(err.to_string().contains("(p0002, p0005)"), "{err}");
    let c = merge_command(&grid_path, &merged, &shard_dirs, true).unwrap();
    assert_eq!(c.results.len(), 8);
    for f in [
        "summary.csv",
        "summary.md",
        "summary.html",
        "residual-vs-pga.svg",
    ] {
        let a = std::fs::read(whole.join(f)).unwrap();
        let b = std::fs::read(merged.join(f)).unwrap();
        assert!(a == b, "{f} differs between unsharded and merged");
    }
    let figure = std::fs::read_to_string(merged.join("residual-vs-pga.svg")).unwrap();
    crate::report_sections::compacted(&figure);
    // The typed result the summary is rendered from: what merge gathered, read back.
    assert_eq!(Study::load(&merged).unwrap(), c);
    // The summary has one row per point and run, polarity mirroring the sliding exactly
    // (the PEPO is symmetric: inverting the record inverts the response).
    let mut reader = csv::Reader::from_path(merged.join("summary.csv")).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 8 * 7); // five engine runs, the exact reference, the rigid block
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    for f in [
        "residual-vs-pga-predictor-corrector-ground-accel.svg",
        "residual-vs-pga-fe-single.svg",
        "residual-vs-pga-rapier-inertial-force.svg",
    ] {
        assert!(merged.join(f).exists(), "per-engine plot {f}");
    }
    let residual = |point: &str, engine: &str, variant: &str| -> f64 {
        let row = rows
            .iter()
            .find(|r| {
                r[col("point")] == *point
                    && r[col("engine")] == *engine
                    && r[col("variant")].starts_with(variant)
            })
            .unwrap();
        row[col("residual_sliding_m")].parse().unwrap()
    };
    for (a, b) in [("p0000", "p0002"), ("p0001", "p0003")] {
        // Every engine mirrors exactly (measured: bit for bit for all five runs).
        for (e, v) in [
            ("predictor-corrector", ""),
            ("newmark-rigid", ""),
            ("exact", "epo-record"),
            ("fe", "single"),
            ("fe", "double"),
            ("rapier", "kinematic"),
            ("rapier", "inertial"),
        ] {
            assert_eq!(residual(a, e, v), -residual(b, e, v), "{a} {b} {e}/{v}");
        }
    }
    // Engines against the predictor-corrector, residual sliding at all 8 points (1.5 to
    // 16 mm). Measured: FE single and double within 0.29 % (Δt = 5 ms, both time
    // discretisations of the same PEPO); rapier −6.6 % … +2.0 % (its 1 % foot mass rings
    // at 314 rad/s: docs/rapier-engine.md). Tolerances: the largest measured, rounded up.
    for (label, tol) in [
        ("fe/single", 0.3),
        ("fe/double", 0.3),
        ("rapier/kinematic-ground", 7.0),
        ("rapier/inertial-force", 7.0),
    ] {
        let d = rockslide::study::agreement(&c, label, "predictor-corrector/ground-accel");
        assert_eq!(d.len(), 8, "{label}: every point compared");
        let worst = d.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        assert!(worst < tol, "{label}: largest |Δ| {worst:.3} % ≥ {tol} %");
    }
}

#[test]
fn grid_errors_are_located() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    let base = root().join("cases/records/pepo-northridge.toml");
    std::fs::write(
        &path,
        format!(
            "base = \"{}\"\npga_g = [1.0, -2.0]\npolarity = [2]\n",
            base.display()
        ),
    )
    .unwrap();
    let e = load_grid(&path).unwrap_err().to_string();
    assert!(
        e.contains("bad.toml:2:") && e.contains("pga_g[1]: is -2"),
        "{e}"
    );
    assert!(
        e.contains("bad.toml:3:") && e.contains("polarity[0]"),
        "{e}"
    );
}

/// Cross-check of the whole record pipeline (reading, scaling, interpolation, sign
/// conventions) between two independent computations: as the contact stiffness grows the
/// undamped PEPO tends to Newmark's rigid block with ky = μ·g. Kx = 1e4 × the paper's
/// (T = 2 ms), Δt = T/40, Northridge at PGA 0.2 g and 0.3 g; measured differences 0.78 %
/// and 0.06 % (Kx × 100: 5.1 % and 0.9 %; the paper's Kx: 39 % and 15 %).
#[test]
fn stiff_pepo_tends_to_the_rigid_block() {
    let dir = tempfile::tempdir().unwrap();
    // The predictor-corrector only (the engines after it in the file are cut off).
    let base_text = std::fs::read_to_string(root().join("cases/records/pepo-northridge.toml"))
        .unwrap()
        .replace(
            "record = \"Northridge_1994_PAC-175.csv\"",
            &format!(
                "record = \"{}\"",
                root()
                    .join("cases/records/Northridge_1994_PAC-175.csv")
                    .display()
            ),
        )
        .split("\n[engines.fe]")
        .next()
        .unwrap()
        .replace("kx = 9.8696e8 ", "kx = 9.8696e12 ")
        .replace("dt = 0.005 ", "dt = 0.00005 ")
        .replace("dt = 0.001 ", "dt = 0.00005 ");
    assert!(base_text.contains("kx = 9.8696e12") && base_text.contains("dt = 0.00005"));
    assert!(!base_text.contains("dt = 0.001 ") && !base_text.contains("dt = 0.005 "));
    std::fs::write(dir.path().join("stiff.toml"), base_text).unwrap();
    let grid_path = dir.path().join("grid.toml");
    std::fs::write(&grid_path, "base = \"stiff.toml\"\npga_g = [0.2, 0.3]\n").unwrap();
    let grid = load_grid(&grid_path).unwrap();
    let out = dir.path().join("out");
    run_study(
        &grid,
        &StudyOptions {
            out: out.clone(),
            shard: None,
            progress: false,
        },
    )
    .unwrap();
    for (p, tol) in [(&grid.points[0], 0.008), (&grid.points[1], 0.001)] {
        let r = rockslide::study::read_result(&result_path(&out, p)).unwrap();
        let run = |engine: &str| r.runs.iter().find(|x| x.engine == engine).unwrap();
        let pepo = run("predictor-corrector").residual_sliding.unwrap();
        let rigid = run("newmark-rigid").residual_sliding.unwrap();
        let exact = run("exact").residual_sliding.unwrap();
        println!(
            "PGA {}: pc {pepo}, exact PEPO {exact}, rigid {rigid}",
            r.pga
        );
        // The predictor-corrector at Δt = T/40 against the exact PEPO: measured 1.8e-5 and
        // 6.0e-5 relative; the exact PEPO against the rigid block: 0.78 % and 0.05 %.
        assert!(
            (pepo / exact - 1.0).abs() < 1e-4,
            "pc {pepo} vs exact {exact}"
        );
        assert!(rigid < -1e-3, "the block slides (toward −x): {rigid}");
        assert!(
            (pepo / rigid - 1.0).abs() < tol,
            "PGA {}: PEPO {pepo} vs rigid {rigid}",
            r.pga
        );
    }
}

//! The command line as a user meets it: `run` writes CSV traces with units and a
//! paper-style report; `list` shows cases and engines.

use crate::common::{into_closed_pipe, rockslide};

#[test]
fn run_writes_traces_with_units_and_a_report() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let o = rockslide(&["run", "cases/pepo-mass-accel.toml", "--out", out, "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(
        dir.path()
            .join("pepo-mass-accel/predictor-corrector-paper.csv"),
    )
    .unwrap();
    let header = csv.lines().next().unwrap();
    assert_eq!(
        header,
        "time [s],force [N],resistance [N],rel_disp [m],slide [m],vel [m/s],acc [m/s²],pc_change []"
    );
    assert_eq!(
        csv.lines().count(),
        102,
        "header + 101 rows at Δt = 0.01 s over 1 s"
    );
    let report = std::fs::read_to_string(dir.path().join("pepo-mass-accel/report.md")).unwrap();
    assert!(
        report.contains("| Slip start | s | 0.06287 | 0.06000 |"),
        "{report}"
    );
    assert!(
        report.contains("| Peak relative displacement (abs) | mm | 9.263 | 9.206 | -0.62 %"),
        "{report}"
    );
}

#[test]
fn list_shows_engines_and_references() {
    let o = rockslide(&["list", "cases/pepo-ground-disp.toml"]);
    assert!(o.status.success());
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(
        s.contains("predictor-corrector  eq12, eq12-slip-once, ground-accel"),
        "{s}"
    );
    assert!(s.contains("reference            exact"), "{s}");
}

#[test]
fn help_and_version_follow_conventions() {
    let o = rockslide(&["--help"]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("Usage: rockslide"));
    let o = rockslide(&["--version"]);
    assert_eq!(
        String::from_utf8_lossy(&o.stdout).trim(),
        format!("rockslide {}", env!("CARGO_PKG_VERSION"))
    );
    assert_eq!(rockslide(&["frobnicate"]).status.code(), Some(2));
}

/// rockslide shall print `newmark` sliding in the case reports' convention (block minus
/// ground, mm): two-way on the record, PGA and ky of `block-northridge` (ky = μ·g of the
/// case, in g), the "normal" row is the reference's residual sliding in that case's report
/// (+5.380 mm), sign included; the inverted record gives the opposite sign.
#[test]
fn newmark_sliding_has_the_reports_sign_and_unit() {
    let case = rockslide::case::load_case(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/cases/records/block-northridge.toml"
    )))
    .unwrap();
    let solution = rockslide::reference::for_case(&case).unwrap();
    let end = case.run.duration;
    let trace = rockslide::reference::sample(solution.as_ref(), &[0.0, end]);
    let residual_mm = 1e3 * trace.column("slide").unwrap()[1];
    let report = rockslide::response::show("residual_sliding", residual_mm / 1e3);
    assert_eq!(
        report, "5.380",
        "the case report's reference residual sliding"
    );
    let ky_g = 0.185 * 9.81 / rockslide::case::record::STANDARD_GRAVITY;
    let o = rockslide(&[
        "newmark",
        "cases/records/Northridge_1994_PAC-175.csv",
        "--unit",
        "g",
        "--pga",
        "0.3",
        "--two-way",
        "--ky",
        &ky_g.to_string(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("| sliding [mm] |"), "{text}");
    assert!(text.contains("| normal | 5.380 | 3 |"), "{text}");
    assert!(text.contains("| inverse | -5.380 | 3 |"), "{text}");
}

/// rockslide shall take every PGA in g: a case's `scale_to_pga_g` as `newmark --pga`. The
/// old key `scale_to_pga` (m/s²) is refused (exit 2, nothing run) with the new key's name
/// and the value converted; the same case with the new key loads.
#[test]
fn pga_is_in_g_and_the_old_key_names_the_new_one() {
    let dir = tempfile::tempdir().unwrap();
    let shipped = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/cases/records/pepo-northridge.toml"
    ))
    .unwrap();
    let record = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/cases/records/Northridge_1994_PAC-175.csv"
    );
    let new = shipped.replace("\"Northridge_1994_PAC-175.csv\"", &format!("{record:?}"));
    assert!(
        new.contains("\nscale_to_pga_g = 0.1 "),
        "the shipped case uses g"
    );
    let old = new.replace("\nscale_to_pga_g = 0.1 ", "\nscale_to_pga = 0.980665 ");
    let (new_path, old_path) = (dir.path().join("new.toml"), dir.path().join("old.toml"));
    std::fs::write(&new_path, new).unwrap();
    std::fs::write(&old_path, old).unwrap();
    let o = rockslide(&["list", old_path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("old.toml:35:16: excitation.scale_to_pga: is no longer read: the target PGA is given in g as `scale_to_pga_g` (scale_to_pga = 0.980665 m/s² is scale_to_pga_g = 0.100000 g)"),
        "{err}"
    );
    assert!(o.stdout.is_empty());
    let o = rockslide(&["list", new_path.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// rockslide shall advertise in `list` only the variants `run` accepts: a case asking the
/// predictor-corrector for the ground-displacement variant `eq12` under a mass
/// acceleration is refused by both, with the same located line naming what is available
/// (exit 2); the shipped case lists `paper`, which `run` accepts.
#[test]
fn list_and_run_accept_the_same_variants() {
    let dir = tempfile::tempdir().unwrap();
    let shipped = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/cases/pepo-mass-accel.toml"
    ))
    .unwrap();
    let line = "dt = 0.01               # the paper's spreadsheet step\n";
    assert!(shipped.contains(line));
    let case = dir.path().join("pc-eq12.toml");
    std::fs::write(
        &case,
        shipped.replace(line, "dt = 0.01\nvariants = [\"eq12\"]\n"),
    )
    .unwrap();
    let case = case.to_str().unwrap();
    let out = dir.path().join("out");
    let listed = rockslide(&["list", case]);
    let ran = rockslide(&["run", case, "--out", out.to_str().unwrap()]);
    let expected = "pc-eq12.toml:37:13: engines.predictor-corrector.variants[0]: \"eq12\" is not a variant of predictor-corrector for this scene; available: paper";
    for o in [&listed, &ran] {
        assert_eq!(o.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&o.stderr).contains(expected));
    }
    assert_eq!(listed.stderr, ran.stderr);
    assert!(!out.exists(), "nothing written");
    let o = rockslide(&["list", "cases/pepo-mass-accel.toml"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("predictor-corrector  paper (dt 0.01 s)"));
}

/// rockslide shall not panic on a closed pipe in any printing command: `newmark | head -0`
/// exits 0 with nothing on stderr (it printed through `print!`, which panics, exit 101).
#[test]
fn newmark_into_a_closed_pipe_is_not_a_panic() {
    let o = into_closed_pipe(&[
        "newmark",
        "cases/records/Loma_Prieta_1989_HSP-000.AT2",
        "--ky",
        "0.1",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(err.is_empty(), "{err}");
}

#[test]
fn timings_are_written_only_when_asked_and_change_no_other_file() {
    let (plain, timed) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let case = "cases/linear-sdof.toml";
    let o = rockslide(&["run", case, "--out", plain.path().to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = rockslide(&[
        "run",
        case,
        "--out",
        timed.path().to_str().unwrap(),
        "-q",
        "--timings",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let names = |d: &std::path::Path| {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    };
    assert!(!names(plain.path()).iter().any(|n| n.starts_with("timings")));
    let mut with = names(timed.path());
    with.retain(|n| !n.starts_with("timings"));
    assert_eq!(with, names(plain.path()));
    // one span per stage of the one case, and the whole command
    let md = std::fs::read_to_string(timed.path().join("timings.md")).unwrap();
    for stage in [
        "total",
        "engines",
        "reference",
        "analysis",
        "traces",
        "pages",
        "summary",
    ] {
        assert!(md.contains(&format!("| {stage} | 1 |")), "{stage}: {md}");
    }
    assert!(md.contains("| linear-sdof |"), "{md}");
    let json = std::fs::read_to_string(timed.path().join("timings.json")).unwrap();
    assert_eq!(json.matches("\"stage\"").count(), 7, "{json}");
}

#[test]
fn full_traces_is_for_the_default_command_only() {
    let o = rockslide(&["--full-traces", "list"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr)
            .contains("--full-traces applies to the default command only")
    );
}

//! Never clobber what is not ours, never abort, never hang: each defect of the fourth
//! hardening round pinned by a regression test named after what broke — output paths
//! that are devices or links, sizes that aborted on allocation, a reference search that
//! did not finish, rapier runs with no bound, a study that could not store μ = ∞, two
//! runs into one folder, commands that validated a case differently — and a proptest
//! fuzz of the case keys added since the last round (vertical, spatial, external,
//! OpenSees).

use std::path::{Path, PathBuf};
use std::process::Command;

use proptest::prelude::*;
use rockslide::case::Case;
use rockslide::registry::parse_case;

use crate::common::{repo, rockslide};
use rockslide::engine::rigid_body::variant as rapier_variant;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "rockslide-never-clobber-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A shipped case's text with each `(from, to)` replaced once (each must occur).
fn edited(name: &str, edits: &[(&str, &str)]) -> String {
    let mut text = std::fs::read_to_string(repo(name)).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from:?} not in {name}");
        text = text.replacen(from, to, 1);
    }
    text
}

/// The case's text up to its first `[engines.…]` section, then `engines`.
fn with_engines(name: &str, engines: &str) -> String {
    let text = std::fs::read_to_string(repo(name)).unwrap();
    let at = text.find("[engines.").unwrap();
    format!("{}{engines}", &text[..at])
}

fn parse(name: &str, text: &str) -> Result<Case, String> {
    parse_case(&repo(name), text).map_err(|e| e.to_string())
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

// ── 1. An output path that is a device or a link ─────────────────────────────────────

const RECORD: &str = "cases/records/Loma_Prieta_1989_HSP-000.AT2";

#[cfg(unix)]
#[test]
fn newmark_csv_into_a_fifo_or_a_link_keeps_them() {
    let dir = scratch("newmark");
    let fifo = dir.join("pipe");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let out = rockslide(&[
        "newmark",
        RECORD,
        "--ky",
        "0.1",
        "--csv",
        fifo.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("is a FIFO"), "{}", stderr(&out));
    use std::os::unix::fs::FileTypeExt;
    assert!(fifo.symlink_metadata().unwrap().file_type().is_fifo());

    let target = dir.join("target.csv");
    std::fs::write(&target, "old").unwrap();
    let link = dir.join("link.csv");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let out = rockslide(&[
        "newmark",
        RECORD,
        "--ky",
        "0.1",
        "--csv",
        link.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(link.symlink_metadata().unwrap().file_type().is_symlink());
    assert!(
        std::fs::read_to_string(&target)
            .unwrap()
            .starts_with("record,")
    );

    let slash = format!("{}/out/", dir.display());
    let out = rockslide(&["newmark", RECORD, "--ky", "0.1", "--csv", &slash]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("names a folder"), "{}", stderr(&out));
    std::fs::remove_dir_all(dir).unwrap();
}

// ── 2. Sizes that aborted on allocation ──────────────────────────────────────────────

#[test]
fn supports_123456789_is_a_located_error_not_an_abort() {
    let name = "cases/rpepo-mass-accel.toml";
    let text = edited(name, &[("supports = 10 ", "supports = 123456789 ")]);
    let e = parse(name, &text).unwrap_err();
    assert!(
        e.contains(":23:12: model.supports: is 123456789, but must be at most 1000"),
        "{e}"
    );
    let text = edited(name, &[("supports = 10 ", "supports = 1000 ")]);
    assert!(parse(name, &text).is_ok());
}

#[test]
fn a_3d_block_of_half_depth_1e300_is_a_located_error_not_an_abort() {
    let name = "cases/spatial/block-pulse-azimuth30.toml";
    for (depth, ok) in [("1e300", false), ("1e6", false), ("1000.0", true)] {
        let text = edited(
            name,
            &[("half_depth = 0.5 ", &format!("half_depth = {depth} "))],
        );
        match parse(name, &text) {
            Ok(_) => assert!(ok, "{depth} accepted"),
            Err(e) => {
                assert!(!ok, "{depth}: {e}");
                assert!(
                    e.contains("model.half_depth") && e.contains("at most 1000"),
                    "{e}"
                );
            }
        }
    }
}

#[test]
fn a_grid_of_supports_above_the_limit_is_a_located_error() {
    let rocking = "cases/rpepo-mass-accel.toml";
    let text = edited(rocking, &[("supports = 10 ", "supports = 1000 ")]);
    // a 3D rocking body: 11 rows of 1000 supports exceed the 10,000 of a base
    let text = text.replace(
        "[model.contact]",
        "half_depth = 0.5\nsupport_rows = 11\n[model.contact]",
    );
    let e = parse(rocking, &text).unwrap_err();
    assert!(
        e.contains("model.support_rows: is 11: 11 rows of 1000 supports"),
        "{e}"
    );
}

// ── 3. The vertical reference's hang ─────────────────────────────────────────────────

#[test]
fn kx_1e_300_under_a_vertical_pulse_refuses_the_reference_at_once() {
    let name = "cases/vertical/pepo-mass-accel-vertical.toml";
    let text = edited(name, &[("kx = 9.8696e8 ", "kx = 1e-300 ")]);
    let case = parse(name, &text).unwrap();
    // once 20,000 halvings of the event search per grid interval (24 s, growing with the
    // duration); now the first unbounded search is an error
    let e = rockslide::reference::for_case(&case).err().unwrap();
    assert!(e.contains("overflow double precision"), "{e}");
}

// ── 4. Unbounded rapier runs ─────────────────────────────────────────────────────────

#[test]
fn rapier_with_kx_1e300_is_refused_before_running() {
    let name = "cases/pepo-mass-accel.toml";
    let text = with_engines(name, "[engines.rapier]\n").replace("kx = 9.8696e8 ", "kx = 1e300 ");
    let case = parse(name, &text).unwrap();
    let engine = rockslide::registry::engine("rapier").unwrap();
    let e = engine
        .run(&case, rapier_variant::APPLIED_FORCE, case.run.dt)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("run.dt") && e.contains("10000 rapier steps an output step"),
        "{e}"
    );
}

#[test]
fn rapier_with_a_mass_of_1e_300_under_a_record_is_refused_before_running() {
    let name = "cases/records/pepo-northridge.toml";
    let text = with_engines(name, "[engines.rapier]\n")
        .replace("mass = 1.0e6 ", "mass = 1e-300 ")
        .replace("kx = 9.8696e8 ", "kx = 1e-282 ");
    let case = parse(name, &text).unwrap();
    let engine = rockslide::registry::engine("rapier").unwrap();
    for variant in [
        rapier_variant::KINEMATIC_GROUND,
        rapier_variant::INERTIAL_FORCE,
    ] {
        let e = engine
            .run(&case, variant, case.run.dt)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("outside the engine's validity"), "{e}");
    }
}

// ── 5. A study with μ = ∞ ────────────────────────────────────────────────────────────

#[test]
fn a_study_with_mu_inf_finishes_and_its_rerun_skips_the_point() {
    let dir = scratch("study-inf");
    let base = with_engines(
        "cases/records/pepo-loma-prieta.toml",
        "[engines.predictor-corrector]\n",
    )
    .replace(
        "record = \"",
        &format!("record = \"{}/", repo("cases/records").display()),
    );
    std::fs::write(dir.join("base.toml"), base).unwrap();
    let record = repo(RECORD);
    std::fs::write(
        dir.join("grid.toml"),
        format!(
            "title = \"mu inf\"\nbase = \"base.toml\"\nrecords = [{:?}]\npga_g = [0.1]\nmu = [inf]\npolarity = [1]\ntail = 1.0\nnewmark = false\n",
            record.display().to_string()
        ),
    )
    .unwrap();
    let (grid, out) = (dir.join("grid.toml"), dir.join("out"));
    let args = ["study", grid.to_str().unwrap(), "-o", out.to_str().unwrap()];
    let first = rockslide(&args);
    assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));
    let json = std::fs::read_to_string(out.join("runs/p0000.json")).unwrap();
    assert!(json.contains("\"mu\": \"inf\""), "{json}");
    let again = rockslide(&args);
    assert_eq!(again.status.code(), Some(0), "{}", stderr(&again));
    let said = String::from_utf8_lossy(&again.stdout);
    assert!(said.contains("1 already done"), "{said}");
    std::fs::remove_dir_all(dir).unwrap();
}

// ── 6. Two runs into one output folder ───────────────────────────────────────────────

#[test]
fn two_runs_into_one_folder_both_succeed() {
    let dir = scratch("two-runs");
    let out = dir.join("out");
    let spawn = || {
        Command::new(env!("CARGO_BIN_EXE_rockslide"))
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args([
                "run",
                "-q",
                "-o",
                out.to_str().unwrap(),
                "cases/pepo-mass-accel.toml",
            ])
            .spawn()
            .unwrap()
    };
    for _ in 0..3 {
        let (mut a, mut b) = (spawn(), spawn());
        assert!(a.wait().unwrap().success() && b.wait().unwrap().success());
    }
    let left: Vec<String> = std::fs::read_dir(out.join("pepo-mass-accel"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(rockslide::io::TEMP_SUFFIX))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    std::fs::remove_dir_all(dir).unwrap();
}

// ── 7. One validation for every command ──────────────────────────────────────────────

/// Each command's exit code and first error line on a case file.
fn every_command(case: &Path, dir: &Path) -> Vec<(String, Option<i32>, String)> {
    let (c, d) = (case.to_str().unwrap(), dir.to_str().unwrap());
    let csv = dir.join("ref.csv");
    [
        vec!["list", c],
        vec!["reference", c, "--out", csv.to_str().unwrap()],
        vec!["export", c, "--to", "opensees", "-o", d],
    ]
    .into_iter()
    .map(|args| {
        let out = rockslide(&args);
        let first = stderr(&out).lines().next().unwrap_or("").to_string();
        (args[0].to_string(), out.status.code(), first)
    })
    .collect()
}

#[test]
fn list_reference_and_export_refuse_what_run_refuses() {
    let dir = scratch("one-validation");
    let plain = with_engines(
        "cases/pepo-mass-accel.toml",
        "[engines.predictor-corrector]\n",
    );
    let spatial = with_engines("cases/spatial/pepo-pulse-azimuth30.toml", "");
    let bad = [
        (
            plain.clone(),
            "[engines.opensees]\nbogus = 1\n",
            "engines.opensees.bogus",
        ),
        (
            plain.clone(),
            "[engines.opensees]\ntimeout = nan\n",
            "engines.opensees.timeout",
        ),
        (
            plain.clone(),
            "[engines.opensees]\nlinks = \"wobbly\"\n",
            "engines.opensees.links",
        ),
        (
            plain.clone(),
            "[engines.rapier]\nsubsteps = 0\n",
            "engines.rapier.substeps",
        ),
        (
            plain.clone(),
            "[engines.fe]\nmax_iterations = 2.5\n",
            "engines.fe.max_iterations",
        ),
        (
            plain.clone(),
            "[engines.fe]\nsensitivity = \"yes\"\n",
            "engines.fe.sensitivity",
        ),
        (plain, "[engines.fe]\nwobble = 1\n", "engines.fe.wobble"),
        (
            spatial,
            "[engines.predictor-corrector]\nvariants = [\"eq12\"]\n[engines.fe]\n",
            "engines.predictor-corrector.variants",
        ),
    ];
    for (i, (head, engines, field)) in bad.iter().enumerate() {
        let case = dir.join(format!("bad{i}.toml"));
        std::fs::write(&case, format!("{head}{engines}")).unwrap();
        for (command, code, first) in every_command(&case, &dir) {
            assert_eq!(code, Some(2), "{command} accepted {engines:?}: {first}");
            assert!(first.contains(field), "{command}: {first}");
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_topic_on_a_csv_external_is_refused() {
    let name = "examples/external/pepo-external.toml";
    let text = edited(
        name,
        &[("skip_lines = 1 ", "topic = \"/x/state\"\nskip_lines = 1 ")],
    );
    let e = parse_case(&repo(name), &text).unwrap_err().to_string();
    assert!(
        e.contains("external[0].topic: applies to an MCAP results file"),
        "{e}"
    );
}

#[test]
fn sweep_repeats_1000000_is_refused() {
    let out = rockslide(&[
        "sweep",
        "cases/pepo-mass-accel.toml",
        "--repeats",
        "1000000",
        "-o",
        "/nonexistent-never-written",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("--repeats is 1000000, but must be from 1 to 100"),
        "{}",
        stderr(&out)
    );
}

// ── 8. The proptest fuzz covers the new case keys ────────────────────────────────────

/// Cases that carry the keys added since the last rounds: vertical motion, 3D scenes,
/// another program's results, the OpenSees and CalculiX participants, a station's three
/// components with its baseline.
const NEW_KEY_CASES: &[&str] = &[
    "cases/three-component/pepo-ridgecrest-ccc-xyz.toml",
    "cases/calculix/pepo-single-calculix.toml",
    "cases/vertical/pepo-mass-accel-vertical.toml",
    "cases/vertical/rpepo-mass-accel-vertical.toml",
    "cases/vertical/block-liftoff.toml",
    "cases/spatial/pepo-pulse-azimuth30-vertical.toml",
    "cases/spatial/block-chino-hills-pair.toml",
    "examples/external/pepo-external.toml",
    "cases/opensees/rpepo-opensees.toml",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn any_mutation_of_a_case_with_the_new_keys_gives_a_case_or_errors(
        which in 0usize..NEW_KEY_CASES.len(), at in 0usize..6000, with in "\\PC{0,12}"
    ) {
        let name = NEW_KEY_CASES[which];
        let text = std::fs::read_to_string(repo(name)).unwrap();
        let mut at = at.min(text.len());
        while !text.is_char_boundary(at) { at -= 1; }
        let mutated = format!("{}{with}{}", &text[..at], &text[at..]);
        let _ = parse_case(&repo(name), &mutated);
    }

    #[test]
    fn any_number_in_a_new_key_gives_a_case_or_a_located_error(
        which in 0usize..NEW_KEY_CASES.len(),
        value in prop_oneof![
            Just("inf".to_string()), Just("-inf".to_string()), Just("nan".to_string()),
            Just("1e300".to_string()), Just("-1e300".to_string()), Just("0".to_string()),
            Just("1e-300".to_string()), Just("123456789".to_string()),
            any::<f64>().prop_map(|x| format!("{x:e}")),
        ],
        nth in 0usize..40,
    ) {
        let name = NEW_KEY_CASES[which];
        let text = std::fs::read_to_string(repo(name)).unwrap();
        // replace the nth number after an `=` with `value`
        let mut seen = 0;
        let mut out = String::new();
        for line in text.lines() {
            let mut line = line.to_string();
            if let Some(eq) = line.find(" = ")
                && line[eq + 3..].starts_with(|c: char| c.is_ascii_digit() || c == '-')
            {
                if seen == nth {
                    let end = line[eq + 3..].find(|c: char| c.is_whitespace()).map_or(line.len(), |e| eq + 3 + e);
                    line = format!("{}{value}{}", &line[..eq + 3], &line[end..]);
                }
                seen += 1;
            }
            out.push_str(&line);
            out.push('\n');
        }
        if let Err(e) = parse_case(&repo(name), &out) {
            let first = e.to_string();
            prop_assert!(first.contains(".toml:"), "unlocated: {first}");
        }
    }
}

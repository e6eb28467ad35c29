//! Malformed and extreme input gives a clear located error or a result with a status —
//! never a panic, an abort, a hang or a write outside the output folder
//! (`cases/README.md`). Each defect found (in the files this module covers) is pinned
//! here, with a proptest fuzz of the readers so that CI keeps checking what `fuzz/` explores.

use std::path::{Path, PathBuf};
use std::process::Command;

use proptest::prelude::*;
use rockslide::case::limits::{DEFAULT_MAX_STEPS, MAX_JOBS, clamp_jobs};
use rockslide::case::record::{AccelUnit, parse_at2, parse_csv};
use rockslide::case::{Case, parse_case};
use rockslide::engine::fe::{FeOptions, simulate};
use rockslide::formats::read_mcap_bytes;
use rockslide::io::{inside, remove_stale_temporaries, write_atomically};

use crate::common::{repo, rockslide};

/// A shipped case's text with `from` replaced by `to` (which must occur).
fn text_with(name: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(repo(&format!("cases/{name}.toml"))).unwrap();
    assert!(text.contains(from), "{from:?} not in {name}");
    text.replacen(from, to, 1)
}

fn parse(name: &str, text: &str) -> Result<Case, String> {
    parse_case(&repo(&format!("cases/{name}.toml")), text).map_err(|e| e.to_string())
}

/// A small, fast case (predictor-corrector only, 20 steps) written into `dir`.
fn tiny_case(dir: &Path, file: &str, name: Option<&str>) -> PathBuf {
    let text = std::fs::read_to_string(repo("cases/pepo-mass-accel.toml")).unwrap();
    let run = text.find("[run]").unwrap();
    let head = match name {
        Some(n) => format!("name = {n:?}\n"),
        None => String::new(),
    };
    let body = &text[..run];
    let path = dir.join(file);
    std::fs::write(
        &path,
        format!(
            "{head}{body}[run]\nduration = 0.02\ndt = 0.001\n\n[engines.predictor-corrector]\n"
        ),
    )
    .unwrap();
    path
}

// ── Output only inside the output folder ─────────────────────────────────────────────

#[test]
fn case_names_that_would_escape_or_collide_are_located_errors() {
    for bad in [
        "",
        ".",
        "..",
        "../escaped",
        "/tmp/absolute",
        "a/b",
        "summary.csv",
        "summary",
    ] {
        let text = format!("name = {bad:?}\n{}", text_with("pepo-mass-accel", "", ""));
        let e = parse("pepo-mass-accel", &text).expect_err(bad);
        assert!(
            e.contains("pepo-mass-accel.toml:1:8: name: "),
            "{bad:?}: {e}"
        );
    }
    let ok = format!(
        "name = \"pepo_1.5-b\"\n{}",
        text_with("pepo-mass-accel", "", "")
    );
    assert_eq!(parse("pepo-mass-accel", &ok).unwrap().name, "pepo_1.5-b");
}

#[test]
fn escaping_names_write_nothing_and_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let case = tiny_case(dir.path(), "c.toml", Some("../escaped"));
    let o = rockslide(&["run", case.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("name: "));
    assert!(!dir.path().join("escaped").exists());
    assert!(!out.exists());
}

#[test]
fn two_cases_with_one_name_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let a = tiny_case(dir.path(), "a.toml", Some("same"));
    let b = tiny_case(dir.path(), "b.toml", Some("Same"));
    let o = rockslide(&[
        "run",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("b.toml:1:8: name: is \"Same\", the name of"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn output_paths_stay_inside_the_output_folder() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path().join("out");
    std::fs::create_dir_all(&root).unwrap();
    assert!(inside(&root, "case/report.html").is_ok());
    for bad in ["", "..", "../x", "/etc/passwd", "a/../../x"] {
        assert!(inside(&root, bad).is_err(), "{bad:?}");
    }
    #[cfg(unix)]
    {
        let elsewhere = dir.path().join("elsewhere");
        std::fs::create_dir_all(&elsewhere).unwrap();
        std::os::unix::fs::symlink(&elsewhere, root.join("link")).unwrap();
        let e = inside(&root, "link/report.html").unwrap_err().to_string();
        assert!(e.contains("symbolic link"), "{e}");
    }
}

// ── Leftovers ────────────────────────────────────────────────────────────────────────

#[test]
fn stale_temporaries_are_reused_or_removed() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("report.html");
    // an interrupted write of this very file: reused and renamed away
    std::fs::write(dir.path().join(".report.html.rockslide-tmp"), b"half").unwrap();
    write_atomically(&target, b"whole").unwrap();
    assert_eq!(std::fs::read(&target).unwrap(), b"whole");
    assert!(!dir.path().join(".report.html.rockslide-tmp").exists());
    // our other temporaries removed on request; a `tempfile` name (another tool's) kept
    // (left by an interrupted run: untouched for an hour)
    for f in [".summary.csv.rockslide-tmp", ".tmpAb12Cd", "keep.csv"] {
        std::fs::write(dir.path().join(f), b"x").unwrap();
        age(&dir.path().join(f), 3600);
    }
    // a temporary being written right now by another process is left alone
    std::fs::write(dir.path().join(".live.csv.rockslide-tmp"), b"x").unwrap();
    assert_eq!(remove_stale_temporaries(dir.path()).unwrap(), 1);
    let mut left: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(
        left,
        [
            ".live.csv.rockslide-tmp",
            ".tmpAb12Cd",
            "keep.csv",
            "report.html"
        ]
    );
}

#[test]
fn a_run_clears_what_an_interrupted_run_left() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let case = tiny_case(dir.path(), "tiny.toml", None);
    std::fs::create_dir_all(out.join("tiny")).unwrap();
    std::fs::write(out.join(".tmpQw3rty"), vec![0u8; 1000]).unwrap();
    std::fs::write(out.join("tiny/.tiny.mcap.rockslide-tmp"), vec![0u8; 1000]).unwrap();
    std::fs::write(
        out.join("tiny/.renamed-case.csv.rockslide-tmp"),
        vec![0u8; 1000],
    )
    .unwrap();
    for f in [".tmpQw3rty", "tiny/.renamed-case.csv.rockslide-tmp"] {
        age(&out.join(f), 3600);
    }
    let o = rockslide(&["run", case.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(o.status.code() == Some(0) || o.status.code() == Some(1));
    assert!(out.join("tiny/tiny.mcap").exists());
    assert!(out.join(".tmpQw3rty").exists(), "not our name: kept");
    assert!(!out.join("tiny/.tiny.mcap.rockslide-tmp").exists());
    assert!(!out.join("tiny/.renamed-case.csv.rockslide-tmp").exists());
}

// ── Resource bounds before work ──────────────────────────────────────────────────────

#[test]
fn a_step_count_above_the_limit_is_a_located_error() {
    let text = text_with("linear-sdof", "dt = 0.001\n", "dt = 1e-12\n");
    let e = parse("linear-sdof", &text).unwrap_err();
    assert!(
        e.contains("linear-sdof.toml:")
            && e.contains(": run.dt: is 1e-12 s, which needs 1.000e12 steps"),
        "{e}"
    );
    assert!(
        e.contains(&format!("the limit is {DEFAULT_MAX_STEPS}")),
        "{e}"
    );
    // an engine's own dt is checked too
    let text = text_with(
        "linear-sdof",
        "(docs/rapier-engine.md)\ndt = 0.001",
        "(docs/rapier-engine.md)\ndt = 1e-11",
    );
    let e = parse("linear-sdof", &text).unwrap_err();
    assert!(e.contains("engines.rapier.dt: is 1e-11 s"), "{e}");
}

#[test]
fn command_line_sizes_are_refused_before_work() {
    let case = "cases/linear-sdof.toml";
    for (args, says) in [
        (
            vec!["reference", case, "--dt", "1e-12", "-o", "x.csv"],
            "--dt is 1e-12 s",
        ),
        (
            vec!["sweep", case, "--rungs", "64"],
            "--rungs is 64, but the limit is 30",
        ),
        (
            vec!["sweep", case, "--ratio", "1e300"],
            "--ratio 1e300 over 8 rungs",
        ),
    ] {
        let started = std::time::Instant::now();
        let o = rockslide(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(started.elapsed().as_secs_f64() < 10.0, "{args:?}");
    }
    assert!(!Path::new(env!("CARGO_MANIFEST_DIR")).join("x.csv").exists());
}

#[test]
fn a_study_tail_above_the_step_limit_is_a_located_error() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("grid.toml");
    let base = repo("cases/records/pepo-loma-prieta.toml");
    std::fs::write(
        &grid,
        format!(
            "title = \"t\"\nbase = {:?}\npga_g = [0.1]\ntail = 1e6\n",
            base.display().to_string()
        ),
    )
    .unwrap();
    let e = rockslide::study::load_grid(&grid).unwrap_err().to_string();
    assert!(e.contains("grid.toml:4:8: tail: with record"), "{e}");
    assert!(e.contains("steps to cover"), "{e}");
}

#[test]
fn worker_counts_are_clamped_to_the_work() {
    assert_eq!(clamp_jobs(Some(100_000), 6), 6);
    assert_eq!(clamp_jobs(Some(100_000), 10_000), MAX_JOBS);
    assert_eq!(clamp_jobs(None, 0), 1);
}

// ── MCAP reader ──────────────────────────────────────────────────────────────────────

fn valid_mcap() -> Vec<u8> {
    std::fs::read(repo("fuzz/corpus/mcap_read/tiny.mcap")).unwrap()
}

#[test]
fn the_seed_mcap_reads() {
    let c = read_mcap_bytes(Path::new("tiny.mcap"), &valid_mcap()).unwrap();
    assert!(!c.channels.is_empty());
}

#[test]
fn a_huge_chunk_size_is_an_error_not_an_allocation() {
    let mut bytes = valid_mcap();
    // the first chunk (op 0x06): its uncompressed size at +9+16
    let mut chunk = 8;
    while bytes[chunk] != 0x06 {
        chunk += 9 + u64::from_le_bytes(bytes[chunk + 1..chunk + 9].try_into().unwrap()) as usize;
    }
    bytes[chunk + 9 + 16..chunk + 9 + 24].copy_from_slice(&(5u64 << 60).to_le_bytes());
    let e = read_mcap_bytes(Path::new("x.mcap"), &bytes)
        .unwrap_err()
        .to_string();
    assert!(e.contains("uncompressed bytes, above the limit"), "{e}");
}

#[test]
fn a_huge_record_length_or_a_cut_file_is_an_error() {
    let mut bytes = valid_mcap();
    bytes[9..17].copy_from_slice(&u64::MAX.to_le_bytes());
    let e = read_mcap_bytes(Path::new("x.mcap"), &bytes)
        .unwrap_err()
        .to_string();
    assert!(e.contains("claims 18446744073709551615 bytes"), "{e}");
    let whole = valid_mcap();
    for len in (0..whole.len()).step_by(97) {
        assert!(
            read_mcap_bytes(Path::new("x.mcap"), &whole[..len]).is_err(),
            "{len}"
        );
    }
}

/// Found by `cargo fuzz run mcap_read` (out-of-memory, a 4 GiB allocation): one key's
/// length inside the metadata record's map set to 0xFFFF000B. The `mcap` crate reserves a
/// string's declared length before reading it; every map entry is now checked to fit.
#[test]
fn a_huge_string_length_inside_a_metadata_map_is_an_error() {
    let bytes = std::fs::read(repo(
        "fuzz/regressions/mcap_read/metadata-map-string-length.mcap",
    ))
    .unwrap();
    let e = read_mcap_bytes(Path::new("x.mcap"), &bytes)
        .unwrap_err()
        .to_string();
    assert!(e.contains("a map string of 4294901771 bytes, only"), "{e}");
    // the same edit made to the seed: every map string of the seed's metadata records
    let mut seed = valid_mcap();
    let key = b"\x0b\0\0\0requirement";
    let at = seed
        .windows(key.len())
        .position(|w| w == key)
        .expect("the seed has a requirement key");
    seed[at..at + 4].copy_from_slice(&0xFFFF_000Bu32.to_le_bytes());
    assert!(read_mcap_bytes(Path::new("x.mcap"), &seed).is_err());
}

#[test]
fn every_single_byte_flip_gives_contents_or_an_error() {
    let whole = valid_mcap();
    for i in (0..whole.len()).step_by(7) {
        let mut bytes = whole.clone();
        bytes[i] ^= 0xff;
        let _ = read_mcap_bytes(Path::new("x.mcap"), &bytes);
    }
}

// ── fe Newton: round-off acceptance and step cutting ─────────────────────────────────

/// The reproducer: fe double, exact kinematics, Newmark, I = 10 kg·m², Δt = 1e-4
/// on the RPEPO. Before: "not converged" at t = 0.919 s, residual 1.2e-11 of the force
/// scale and correction 3e-14 m. Now the step is accepted at the round-off floor.
#[test]
fn fe_newton_does_not_stall_at_round_off() {
    let text = text_with(
        "rpepo-mass-accel",
        "integrator = \"hht\"\nalpha = -0.1\n",
        "integrator = \"newmark\"\nkinematics = \"exact\"\nrotational_inertia = 10.0\n",
    );
    let case = parse("rpepo-mass-accel", &text).unwrap();
    let (o, e) = FeOptions::parse(&case);
    assert!(e.is_empty(), "{e:?}");
    let run = simulate(&case, "double", 1e-4, &o).unwrap();
    assert!(run.status.completed(), "{}", run.status);
    assert_eq!(run.stats.steps, 20_000);
    // measured: no step at the floor (one before the double's supports were condensed
    // into series equivalents, docs/fe-engine.md "Cost"), none cut
    assert_eq!(run.stats.roundoff_accepted, Some(0));
    assert_eq!(run.stats.step_cuts, Some(0));
}

/// With Newton allowed too few iterations for some steps, those steps are cut (halved,
/// retried) instead of ending the run, and the result matches the uncut run.
#[test]
fn fe_cuts_steps_newton_cannot_finish() {
    let case = crate::common::case("rpepo-mass-accel");
    let (o, e) = FeOptions::parse(&case);
    assert!(e.is_empty(), "{e:?}");
    let full = simulate(&case, "single", 1e-3, &o).unwrap();
    let max_it = full.stats.max_step_iterations.unwrap();
    let mut tight = o;
    tight.newton.max_iterations = (max_it - 1) as usize;
    let cut = simulate(&case, "single", 1e-3, &tight).unwrap();
    assert!(cut.status.completed(), "{}", cut.status);
    let cuts = cut.stats.step_cuts.unwrap();
    assert!(cuts >= 1, "no step was cut");
    let peak = |r: &rockslide::engine::Run| {
        r.trace
            .column("rotation")
            .unwrap()
            .iter()
            .fold(0.0_f64, |m, x| m.max(x.abs()))
    };
    let (a, b) = (peak(&full), peak(&cut));
    // halving a few steps changes the Newmark solution by O(Δt²) locally
    assert!((a - b).abs() <= 1e-2 * a, "peak rotation {a} vs {b}");
}

// ── The defects, one by one: input → what happens now ─────────────────────
//
// Pinned elsewhere (kept there, named here so the table is complete):
//   AT2 NPTS 1e19 / 1e12, DT 1e-300, /dev/zero, non-UTF-8 record → records_formats.rs
//   exact reference with mass 1e-300 or kx 1e300 → references_records.rs
//   dt 1e-12, reference --dt 1e-12, tail 1e6, --rungs 64, --ratio 1e300, MCAP flips,
//   escaping names, stale temporaries of `run`, Newton at round-off → above in this module

/// A case file in `dir` from a shipped case with `from` replaced by `to`.
fn case_file_with(dir: &Path, name: &str, from: &str, to: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text_with(name, from, to)).unwrap();
    path
}

#[test]
fn the_exact_reference_time_does_not_grow_with_the_pulse_frequency() {
    // before: over 30 s at ω = 1e9 (a scan in proportion to the frequency)
    let text = text_with(
        "pepo-mass-accel",
        "omega = 15.707963267948966",
        "omega = 1e9",
    );
    let case = parse("pepo-mass-accel", &text).unwrap();
    let started = std::time::Instant::now();
    let why = rockslide::reference::for_case(&case)
        .err()
        .expect("refused");
    assert!(started.elapsed().as_secs_f64() < 1.0);
    // 1e9 rad/s over 1 s at 64 samples a half period: 1e9 · 64 / π ≈ 2.04e10 … the
    // message states the estimate it refused
    assert!(
        why.contains("θ = 1.000e9 rad/s") && why.contains("too fast"),
        "{why}"
    );
}

#[test]
fn stability_with_a_hundred_thousand_workers_runs_on_as_many_as_there_is_work() {
    let dir = tempfile::tempdir().unwrap();
    let started = std::time::Instant::now();
    let o = rockslide(&[
        "stability",
        "cases/stability/mu-zero.toml",
        "-j",
        "100000",
        "-q",
        "-o",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // before: minutes starting 100000 threads; now the pool has at most one per run
    assert!(started.elapsed().as_secs_f64() < 60.0);
    let json = std::fs::read_to_string(dir.path().join("stability/stability-timing.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let threads = v["threads"].as_u64().expect("threads recorded");
    let runs = v["runs"].as_array().unwrap().len() as u64;
    assert!(
        threads <= runs && threads >= 1,
        "{threads} threads for {runs} runs"
    );
}

#[test]
fn unknown_predictor_corrector_options_are_located_errors() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_file_with(
        dir.path(),
        "pepo-mass-accel",
        "dt = 0.01               # the paper's spreadsheet step\n",
        "dt = 0.01\ntolerance = 1e-3\n",
    );
    // `run`, `list` and `reference` all refuse it, at the key
    for args in [
        vec!["list", case.to_str().unwrap()],
        vec!["reference", case.to_str().unwrap(), "-o", "never.csv"],
        vec!["run", case.to_str().unwrap(), "-o", "never"],
    ] {
        let o = rockslide(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(
                "pepo-mass-accel.toml:37:13: engines.predictor-corrector.tolerance: unknown option"
            ),
            "{args:?}: {err}"
        );
    }
    assert!(!repo("never.csv").exists() && !repo("never").exists());
}

#[test]
fn list_and_reference_refuse_variants_run_refuses() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_file_with(
        dir.path(),
        "pepo-mass-accel",
        "variants = [\"single\", \"double\"]",
        "variants = [\"single\", \"triple\"]",
    );
    for args in [
        vec!["list", case.to_str().unwrap()],
        vec!["reference", case.to_str().unwrap(), "-o", "never.csv"],
    ] {
        let o = rockslide(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("engines.fe.variants[1]: \"triple\" is not a variant of fe"),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn no_excitation_with_signal_keys_is_a_located_error() {
    let text = text_with(
        "housner-free-rocking",
        "kind = \"none\"\n",
        "kind = \"none\"\namplitude = nan\n",
    );
    let e = parse("housner-free-rocking", &text).unwrap_err();
    assert!(
        e.contains("housner-free-rocking.toml:23:13: excitation.amplitude: does not apply to kind = \"none\""),
        "{e}"
    );
}

#[test]
fn a_variant_named_twice_is_a_located_error() {
    let text = text_with(
        "pepo-mass-accel",
        "variants = [\"single\", \"double\"]",
        "variants = [\"single\", \"double\", \"single\"]",
    );
    let e = parse("pepo-mass-accel", &text).unwrap_err();
    assert!(
        e.contains("engines.fe.variants[2]: \"single\" is already variants[0]"),
        "{e}"
    );
}

#[test]
fn a_csv_record_with_a_time_step_of_1e_300_is_an_error_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let record = dir.path().join("r.csv");
    std::fs::write(&record, "0, 0.1\n1e-300, 0.2\n2e-300, 0.1\n").unwrap();
    let o = rockslide(&[
        "newmark",
        record.to_str().unwrap(),
        "--ky",
        "0.1",
        "--unit",
        "g",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("r.csv:3: the time step is 1e-300 s, below the smallest sample interval"),
        "{err}"
    );
}

#[test]
fn negative_option_values_get_their_range_not_unexpected_argument() {
    let case = "cases/linear-sdof.toml";
    for (args, says) in [
        (
            vec!["reference", case, "--dt", "-1", "-o", "never.csv"],
            "--dt is -1 s, but must be > 0",
        ),
        (
            vec!["sweep", case, "--ratio", "-2"],
            "--ratio is -2, but must be a finite number above 1",
        ),
        (
            vec!["sweep", case, "--budget", "-1"],
            "--budget is -1 s, but must be >= 0",
        ),
        (
            vec![
                "newmark",
                "cases/records/Northridge_1994_PAC-175.csv",
                "--unit",
                "g",
                "--ky",
                "-0.1",
            ],
            "--ky: is -0.1, but must be positive",
        ),
        (
            vec![
                "newmark",
                "cases/records/Northridge_1994_PAC-175.csv",
                "--unit",
                "g",
                "--ky",
                "0.1",
                "--pga",
                "-1",
            ],
            "--pga: is -1, but must be positive",
        ),
    ] {
        let o = rockslide(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
    }
    assert!(!repo("never.csv").exists());
}

#[test]
fn a_case_file_that_is_not_utf8_is_refused_with_a_position() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("latin1.toml");
    let mut bytes = std::fs::read(repo("cases/pepo-mass-accel.toml")).unwrap();
    bytes.splice(0..0, b"# caf\xe9\n".iter().copied());
    std::fs::write(&path, bytes).unwrap();
    let e = rockslide::case::load_case(&path).unwrap_err().to_string();
    assert!(e.contains("latin1.toml:1:6:") && e.contains("UTF-8"), "{e}");
    if Path::new("/dev/zero").exists() {
        let e = rockslide::case::load_case(Path::new("/dev/zero"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("not a regular file"), "{e}");
        let e = rockslide::study::load_grid(Path::new("/dev/zero"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("the grid file is not a regular file"), "{e}");
    }
}

/// Set a file's modification time `secs` seconds into the past.
fn age(path: &Path, secs: u64) {
    let past = std::time::SystemTime::now() - std::time::Duration::from_secs(secs);
    std::fs::File::options()
        .write(true)
        .open(path)
        .unwrap()
        .set_modified(past)
        .unwrap();
}

#[test]
fn stale_temporaries_of_every_command_are_removed_fresh_ones_of_live_writers_kept() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for sub in ["runs", "stability", "case"] {
        std::fs::create_dir_all(out.join(sub)).unwrap();
    }
    let stale = [
        out.join(".study.json.rockslide-tmp"),
        out.join("runs/.p0001.json.rockslide-tmp"),
        out.join("stability/.stability.json.rockslide-tmp"),
    ];
    let live = out.join("runs/.p0002.json.rockslide-tmp"); // another shard, writing now
    let deep = out.join("case/deeper");
    std::fs::create_dir_all(&deep).unwrap();
    let too_deep = deep.join(".x.rockslide-tmp");
    let not_ours = out.join("runs/.p0003.json.partial");
    for f in stale.iter().chain([&live, &too_deep, &not_ours]) {
        std::fs::write(f, b"half").unwrap();
    }
    for f in stale.iter().chain([&too_deep, &not_ours]) {
        age(f, 3600);
    }
    #[cfg(unix)]
    {
        // a link out of the folder is not followed
        let elsewhere = dir.path().join("elsewhere");
        std::fs::create_dir_all(&elsewhere).unwrap();
        std::fs::write(elsewhere.join(".a.rockslide-tmp"), b"x").unwrap();
        age(&elsewhere.join(".a.rockslide-tmp"), 3600);
        std::os::unix::fs::symlink(&elsewhere, out.join("link")).unwrap();
    }
    assert_eq!(
        rockslide::io::remove_stale_temporaries_under(&out).unwrap(),
        3
    );
    assert!(stale.iter().all(|f| !f.exists()));
    assert!(live.exists() && too_deep.exists() && not_ours.exists());
    #[cfg(unix)]
    assert!(dir.path().join("elsewhere/.a.rockslide-tmp").exists());
}

#[test]
fn a_stability_run_clears_its_folder_of_stale_temporaries() {
    let dir = tempfile::tempdir().unwrap();
    let stale = dir.path().join("stability/.stability.md.rockslide-tmp");
    std::fs::create_dir_all(stale.parent().unwrap()).unwrap();
    std::fs::write(&stale, vec![0u8; 1000]).unwrap();
    age(&stale, 3600);
    let o = rockslide(&[
        "stability",
        "cases/stability/mu-zero.toml",
        "-q",
        "-o",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!stale.exists());
}

// ── Deterministic, byte-identical traces ─────────────────────────────────────────────

/// Every file under `dir` with extension `csv` or `mcap`, relative to `dir`, sorted.
fn trace_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if matches!(p.extension().and_then(|x| x.to_str()), Some("csv" | "mcap")) {
                out.push(p.strip_prefix(dir).unwrap().to_path_buf());
            }
        }
    }
    out.sort();
    out
}

#[test]
fn the_same_case_run_twice_gives_byte_identical_traces() {
    let dir = tempfile::tempdir().unwrap();
    let case = repo("cases/rpepo-mass-accel.toml");
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    for out in [&a, &b] {
        let o = rockslide(&[
            "run",
            case.to_str().unwrap(),
            "-q",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(
            matches!(o.status.code(), Some(0 | 1)),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let files = trace_files(&a);
    assert_eq!(files, trace_files(&b));
    assert!(
        files.iter().any(|f| f.extension().unwrap() == "mcap"),
        "{files:?}"
    );
    assert!(
        files
            .iter()
            .filter(|f| f.extension().unwrap() == "csv")
            .count()
            >= 2,
        "{files:?}"
    );
    for f in &files {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(x == y, "{} differs between two runs", f.display());
    }
}

/// Every file under `dir`, relative to `dir`, sorted.
fn all_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push(p.strip_prefix(dir).unwrap().to_path_buf());
            }
        }
    }
    out.sort();
    out
}

/// `rockslide args` with `RAYON_NUM_THREADS` set (the worker count of `run`, which has no
/// `-j`), expecting exit 0 or 1.
fn rockslide_on_threads(threads: usize, args: &[&str]) {
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args(args)
        .env("RAYON_NUM_THREADS", threads.to_string())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("rockslide runs");
    assert!(
        matches!(o.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A JSON document without its `wall_seconds` members (the timing part of `result.json`).
fn without_wall_times(text: &[u8]) -> serde_json::Value {
    fn strip(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Object(m) => {
                m.remove("wall_seconds");
                m.values_mut().for_each(strip);
            }
            serde_json::Value::Array(a) => a.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let mut v: serde_json::Value = serde_json::from_slice(text).unwrap();
    strip(&mut v);
    v
}

/// A report's lines without its provenance date (`**Date:**`, `<b>date:</b>`, …).
fn without_date(text: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(text)
        .lines()
        .filter(|l| !l.to_lowercase().contains("date:*") && !l.to_lowercase().contains("date:</b>"))
        .map(String::from)
        .collect()
}

/// Run and stability with one and with two workers: the same files, every trace (CSV,
/// MCAP), figure, CSV table and `stability.json` byte for byte; `result.json` apart from
/// its wall times, the reports apart from their date; only `stability-timing.json` differs
/// (the worker count and wall times, by design).
#[test]
fn outputs_are_byte_identical_across_thread_counts() {
    let dir = tempfile::tempdir().unwrap();
    let case = repo("cases/rpepo-mass-accel.toml");
    let out = |j: usize| dir.path().join(format!("j{j}"));
    for j in [1, 2] {
        let o = out(j);
        rockslide_on_threads(
            j,
            &[
                "run",
                case.to_str().unwrap(),
                "-q",
                "-o",
                o.to_str().unwrap(),
            ],
        );
        let js = j.to_string();
        rockslide_on_threads(
            j,
            &[
                "stability",
                "cases/stability/mu-zero.toml",
                "-j",
                &js,
                "-q",
                "-o",
                o.to_str().unwrap(),
            ],
        );
    }
    let (a, b) = (out(1), out(2));
    let files = all_files(&a);
    assert_eq!(files, all_files(&b));
    let mut byte_equal = 0;
    for f in &files {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        let name = f.file_name().unwrap().to_str().unwrap();
        match (name, f.extension().and_then(|e| e.to_str())) {
            ("stability-timing.json", _) => {
                let threads = |t: &[u8]| without_wall_times(t)["threads"].as_u64();
                assert_eq!((threads(&x), threads(&y)), (Some(1), Some(2)));
            }
            ("result.json", _) => assert_eq!(
                without_wall_times(&x),
                without_wall_times(&y),
                "{}",
                f.display()
            ),
            (_, Some("md" | "html")) => {
                assert_eq!(without_date(&x), without_date(&y), "{}", f.display())
            }
            _ => {
                assert!(x == y, "{} differs between 1 and 2 workers", f.display());
                byte_equal += 1;
            }
        }
    }
    // 6 trace CSVs + the MCAP and its Foxglove layout + 7 figures + 2 summary.csv (case,
    // suite); stability: json, csv, svg
    assert_eq!(byte_equal, 20, "{files:?}");
}

/// Found by the `record` fuzz target (`fuzz/regressions/record/`): three lines whose last
/// time is far off asked the resampler for 1.8e7 samples (0.9 GB, 6 s in `newmark`).
#[test]
fn a_csv_time_column_that_needs_too_many_samples_is_an_error() {
    let text = "# T0.65\n0.49,-001107\n0.52,-0.00\n550341.,0.03\n";
    let started = std::time::Instant::now();
    let e = parse_csv(Path::new("r.csv"), text, AccelUnit::G)
        .unwrap_err()
        .to_string();
    assert!(started.elapsed().as_secs_f64() < 0.5);
    // (550341 − 0.49) / 0.03 + 1 = 1.834e7 samples, above the 1e7 of the step limit
    assert!(
        e.contains("r.csv:1: the time column is not uniform and its smallest interval")
            && e.contains("would need 1.834e7 samples to resample; the limit is 10000000"),
        "{e}"
    );
}

// ── Study grids (the reader `fuzz/fuzz_targets/study_grid.rs` explores) ──────────────

/// A small base case driven by `rec.AT2` (the fuzz target's layout).
const GRID_BASE: &str = "title = \"t\"\nsource = \"s\"\nrequirement = \"r\"\n\n\
[model]\nkind = \"oscillator\"\nmass = 1.0e6\ngravity = 1.0\n\n\
[model.contact]\nkx = 9.8696e8\nkz = 3.94784e9\nmu = 0.5\n\n\
[excitation]\nkind = \"ground-acceleration\"\nrecord = \"rec.AT2\"\nscale_to_pga_g = 0.1\npolarity = 1\n\n\
[run]\nduration = 1.0\ndt = 0.005\n\n[engines.predictor-corrector]\nvariants = [\"ground-accel\"]\ndt = 0.001\n";

/// The fuzz corpus's full seed: 2 records × 2 PGAs × 3 μ × 2 polarities.
const GRID_SEED: &str = "title = \"fuzz grid\"\nbase = \"base.toml\"\n\
records = [\"rec.AT2\", { path = \"rec.csv\", unit = \"g\" }]\n\
pga_g = [0.05, 0.1]\nmu = [0.3, 0.5, inf]\npolarity = [1, -1]\ntail = 0.5\nnewmark = true\n";

/// A folder holding `base.toml`, `rec.AT2` (10 samples) and `rec.csv` (4 samples), made
/// once for every grid test.
fn grid_folder() -> &'static Path {
    static DIR: std::sync::OnceLock<tempfile::TempDir> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let at2 = "R\nFUZZ\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS= 10, DT= 0.0050 SEC\n\
                   0.0 0.01 0.02 0.01 0.0\n-0.01 -0.02 -0.01 0.0 0.0\n";
        let csv = "# t,a\n0.0,0.0\n0.01,0.02\n0.02,-0.01\n0.03,0.0\n";
        for (name, text) in [("base.toml", GRID_BASE), ("rec.AT2", at2), ("rec.csv", csv)] {
            std::fs::write(dir.path().join(name), text).unwrap();
        }
        dir
    })
    .path()
}

/// `text` read as the grid file `name` beside [`grid_folder`]'s base case and records.
fn load_grid_text(name: &str, text: &str) -> Result<rockslide::study::Grid, String> {
    let path = grid_folder().join(name);
    std::fs::write(&path, text).unwrap();
    rockslide::study::load_grid(&path).map_err(|e| e.to_string())
}

#[test]
fn the_seed_grid_expands_to_the_product_of_its_lists() {
    let g = load_grid_text("seed.toml", GRID_SEED).unwrap();
    assert_eq!(g.points.len(), 2 * 2 * 3 * 2);
    assert_eq!(g.records[0].record.samples.len(), 10);
    assert_eq!(g.records[1].record.samples.len(), 4);
    // record-major, then μ, polarity, amplitude
    let last = g.points.last().unwrap();
    assert_eq!(
        (last.record, last.mu, last.polarity),
        (1, Some(f64::INFINITY), -1.0)
    );
    // pga_g is in g: 0.1 g is 0.980665 m/s² (the points keep SI)
    assert_eq!(
        g.points[1].amplitude,
        rockslide::study::Amplitude::Pga(0.1 * 9.80665)
    );
}

#[test]
fn a_grid_pga_in_metres_per_second_squared_is_refused_with_the_g_key() {
    let e = load_grid_text(
        "old-pga.toml",
        "base = \"base.toml\"\npga = [0.980665, 1.96133]\n",
    )
    .unwrap_err();
    assert!(
        e.contains("old-pga.toml:2:7: pga: is no longer read: target PGAs are given in g as `pga_g` (in g: pga_g = [0.1, 0.2])"),
        "{e}"
    );
}

#[test]
fn a_grid_record_that_is_a_device_is_an_error_not_an_endless_read() {
    // before: the grid hashed the record with `fs::read` before the record reader's
    // checks, reading /dev/zero until memory ran out
    let e = load_grid_text(
        "device.toml",
        "base = \"base.toml\"\nrecords = [{ path = \"/dev/zero\", unit = \"g\" }]\n",
    )
    .unwrap_err();
    assert!(
        e.contains("/dev/zero: the record is not a regular file"),
        "{e}"
    );
}

#[test]
fn every_grid_error_is_located_and_reported_together() {
    let text = "base = \"base.toml\"\nrecords = [\"rec.AT2\", { path = \"missing.csv\", unit = \"furlong\" }]\n\
                pga_g = []\nscale = [-1]\nmu = [-0.1]\npolarity = [2]\ntail = -1\n";
    let e = load_grid_text("errors.toml", text).unwrap_err();
    for want in [
        "errors.toml:2:23: records[1]: unit \"furlong\"",
        "errors.toml:3:9: pga_g: must list at least one value",
        "errors.toml:4:10: scale[0]: is -1",
        "errors.toml:4:9: scale: give `pga_g`",
        "errors.toml:5:7: mu[0]: is -0.1",
        "errors.toml:6:13: polarity[0]: is 2",
        "errors.toml:7:8: tail: is -1",
    ] {
        assert!(e.contains(want), "{want:?} not in\n{e}");
    }
}

// ── proptest fuzz of the readers (CI keeps checking what fuzz/ explores) ─────────────

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn any_case_text_gives_a_case_or_errors(text in "\\PC{0,400}") {
        let _ = parse_case(Path::new("fuzz.toml"), &text);
    }

    #[test]
    fn any_mutated_case_gives_a_case_or_errors(at in 0usize..4000, with in "\\PC{0,12}") {
        let text = std::fs::read_to_string(repo("cases/pepo-mass-accel.toml")).unwrap();
        let mut at = at.min(text.len());
        while !text.is_char_boundary(at) { at -= 1; }
        let mutated = format!("{}{with}{}", &text[..at], &text[at..]);
        let _ = parse_case(&repo("cases/pepo-mass-accel.toml"), &mutated);
    }

    #[test]
    fn any_at2_text_gives_a_record_or_an_error(
        npts in "[0-9eE+.-]{0,24}", dt in "[0-9eE+.-]{0,24}", values in "[0-9eE+. -]{0,200}"
    ) {
        let text = format!("T\nE\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS= {npts}, DT= {dt} SEC\n{values}\n");
        let _ = parse_at2(Path::new("r.AT2"), &text, None);
    }

    #[test]
    fn any_csv_text_gives_a_record_or_an_error(text in "[0-9eE+.,# \n-]{0,300}") {
        let _ = parse_csv(Path::new("r.csv"), &text, AccelUnit::G);
    }

    #[test]
    fn any_mcap_mutation_gives_contents_or_an_error(
        edits in proptest::collection::vec((0usize..20_000, any::<u8>()), 1..8)
    ) {
        let mut bytes = valid_mcap();
        let n = bytes.len();
        for (i, b) in edits {
            bytes[i % n] = b;
        }
        let _ = read_mcap_bytes(Path::new("x.mcap"), &bytes);
    }

    #[test]
    fn any_grid_text_gives_a_grid_or_errors(text in "\\PC{0,300}") {
        let _ = load_grid_text("any.toml", &text);
    }

    #[test]
    fn any_mutated_grid_gives_a_grid_or_errors(at in 0usize..400, with in "\\PC{0,12}") {
        let mut at = at.min(GRID_SEED.len());
        while !GRID_SEED.is_char_boundary(at) { at -= 1; }
        let mutated = format!("{}{with}{}", &GRID_SEED[..at], &GRID_SEED[at..]);
        let _ = load_grid_text("mutated.toml", &mutated);
    }
}

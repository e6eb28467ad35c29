//! `rockslide trace-info` on good and damaged MCAP files (docs/traces.md).
//!
//! Requirement: rockslide shall read back an MCAP trace it wrote and describe it; a
//! truncated or corrupt MCAP file gives one clear message naming the file, exit code 2,
//! never a panic.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use rockslide::case::load_case;
use rockslide::formats::read_mcap_bytes;
use rockslide::report::write_case_outputs;
use rockslide::suite::run_case;

fn rockslide(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args(args)
        .output()
        .unwrap()
}

/// A real MCAP trace (the PEPO case, mass acceleration), written once per test binary.
fn good_file(dir: &Path) -> PathBuf {
    let case = load_case(Path::new("cases/pepo-mass-accel.toml")).unwrap();
    let result = run_case(case).unwrap();
    write_case_outputs(&result, dir)
        .unwrap()
        .join("pepo-mass-accel.mcap")
}

fn assert_clear_error(out: &Output, file: &Path) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        err.starts_with(&format!("error: {}", file.display())),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(out.stdout.is_empty());
}

#[test]
fn trace_info_describes_a_good_file() {
    let tmp = tempfile::tempdir().unwrap();
    let file = good_file(tmp.path());
    let out = rockslide(&["trace-info", file.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("/predictor-corrector/paper/state"), "{text}");
    assert!(text.contains("/reference/state"));
    assert!(text.contains("attachment pepo-mass-accel.toml (application/toml"));
    assert!(text.contains("simulation time 0 s to 1 s"));
}

#[test]
fn truncated_and_corrupt_files_give_one_clear_error() {
    let tmp = tempfile::tempdir().unwrap();
    let file = good_file(tmp.path());
    let bytes = std::fs::read(&file).unwrap();
    let bad = tmp.path().join("bad.mcap");

    // Truncated (a copy interrupted half-way), empty, not MCAP at all.
    for (what, content) in [
        ("truncated", bytes[..bytes.len() / 2].to_vec()),
        ("empty", Vec::new()),
        ("a CSV", b"time [s],force [N]\n0.0,1.0\n".to_vec()),
    ] {
        std::fs::write(&bad, &content).unwrap();
        let out = rockslide(&["trace-info", bad.to_str().unwrap()]);
        assert_clear_error(&out, &bad);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("not a readable MCAP file"), "{what}: {err}");
    }

    // Corrupt: a byte flipped inside the first chunk's compressed data (CRC mismatch).
    let summary = mcap::read::Summary::read(&bytes).unwrap().unwrap();
    let chunk = &summary.chunk_indexes[0];
    let at = (chunk.compressed_data_offset().unwrap() + chunk.compressed_size / 2) as usize;
    let mut corrupt = bytes.clone();
    corrupt[at] ^= 0x5a;
    std::fs::write(&bad, &corrupt).unwrap();
    let out = rockslide(&["trace-info", bad.to_str().unwrap()]);
    assert_clear_error(&out, &bad);

    // Missing file.
    let missing = tmp.path().join("missing.mcap");
    let out = rockslide(&["trace-info", missing.to_str().unwrap()]);
    assert_clear_error(&out, &missing);
}

#[test]
fn every_truncation_point_is_an_error_not_a_panic() {
    // Cut the file at 200 points spread over its length (and at every byte of the last
    // 64, where the footer and summary live): each must be an error.
    let tmp = tempfile::tempdir().unwrap();
    let bytes = std::fs::read(good_file(tmp.path())).unwrap();
    let n = bytes.len();
    let cuts = (0..200)
        .map(|k| k * n / 200)
        .chain(n - 64..n)
        .collect::<Vec<_>>();
    for cut in cuts {
        let r = read_mcap_bytes(Path::new("cut.mcap"), &bytes[..cut]);
        assert!(r.is_err(), "cut at {cut} of {n} read as valid");
    }
    assert!(read_mcap_bytes(Path::new("whole.mcap"), &bytes).is_ok());
}

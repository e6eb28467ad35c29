//! Long runs and their disk (issue 18, item 3): the estimate made before any work counts
//! the rows the trace files keep, so `[run] output_dt` lets a long run through.
//!
//! Requirements checked:
//! - a 10⁷-step predictor-corrector run (the PEPO for 10⁴ s at Δt = 1 ms) with
//!   `output_dt = 0.01` writes 10⁶ + 2 rows (the first row, one per 10 ms, and the
//!   last), priced at 2 copies (run and reference) × (25 CSV + 15 MCAP bytes) per value ×
//!   25 values per row = 2.0 GB; without `output_dt` every one of the 10⁷ + 1 rows is
//!   written: 20.0 GB. Both computed here from those counts, and both refused under a
//!   1 GB limit before any step runs.

use std::path::Path;
use std::process::Command;

use rockslide::trace::q;

/// The PEPO case, predictor-corrector only at Δt = 1 ms, for 10⁴ s, with `run_extra`
/// appended to its `[run]` table; written to `dir`.
fn long_pepo(dir: &Path, run_extra: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string(crate::common::repo("cases/pepo-mass-accel.toml")).unwrap();
    let head = &text[..text.find("[engines.").unwrap()];
    assert!(head.contains("duration = 1.0\ndt = 0.001\n"));
    let text = format!(
        "{}\n[engines.predictor-corrector]\ndt = 0.001\n",
        head.replace(
            "duration = 1.0\ndt = 0.001\n",
            &format!("duration = 10000.0\ndt = 0.001\n{run_extra}")
        )
    );
    let path = dir.join("long-pepo.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// `rockslide run` of `case` under a disk limit of 1 GB; its exit code and standard error.
fn run_under_1gb(case: &Path, out: &Path) -> (Option<i32>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args(["run", "--quiet", "--out"])
        .arg(out)
        .arg(case)
        // 16 GiB of memory: the disk estimate is under test, not the memory one (10⁷
        // rows × the catalogue's 37 values × 24 bytes is 8.9 GB, over the 8 GiB default)
        .env("ROCKSLIDE_MAX_MEMORY_BYTES", "17179869184")
        .env_remove("ROCKSLIDE_MAX_STEPS")
        .env("ROCKSLIDE_MAX_DISK_BYTES", "1000000000")
        .output()
        .unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn the_disk_estimate_counts_the_rows_kept_at_output_dt() {
    let values_per_row = 1.0 + q::ALL.len() as f64;
    let bytes_per_value = 2.0 * (25.0 + 15.0);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");

    let decimated = long_pepo(dir.path(), "output_dt = 0.01\n");
    let (code, stderr) = run_under_1gb(&decimated, &out);
    assert_eq!(code, Some(2), "{stderr}");
    let rows = 1e6 + 2.0;
    let gb = rows * values_per_row * bytes_per_value / 1e9;
    assert!(
        stderr.contains(&format!(
            "write 1000002 rows in all (one per run.output_dt), whose traces need about {gb:.1} GB of disk, over the limit of 1.0 GB"
        )),
        "{stderr}"
    );
    assert!(
        stderr.contains("ROCKSLIDE_MAX_DISK_BYTES=<bytes>"),
        "{stderr}"
    );

    let every_step = long_pepo(dir.path(), "");
    let (code, stderr) = run_under_1gb(&every_step, &out);
    assert_eq!(code, Some(2), "{stderr}");
    let gb = (1e7 + 1.0) * values_per_row * bytes_per_value / 1e9;
    assert!(
        stderr.contains(&format!(
            "write 10000001 rows in all (duration / dt each), whose traces need about {gb:.1} GB of disk"
        )),
        "{stderr}"
    );
    assert!(stderr.contains("or set run.output_dt"), "{stderr}");
    assert!(!out.join("long-pepo").exists(), "nothing written");
}

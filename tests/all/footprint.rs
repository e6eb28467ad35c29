//! Bounded memory and disk (docs/performance.md): a run whose traces would not fit is refused before
//! any work, with the case file, field, line, column and reason, and nothing written.
//!
//! Requirements checked:
//! - a 10⁸-step predictor-corrector run is refused at once (exit 2): by the step limit
//!   of case loading (it keeps every step), and with that limit raised, by the estimate
//!   computed here from its plan: 10⁸ + 1 rows × 12 values (time, the 7 channels and the
//!   contact's 4 fields the predictor-corrector records: counted in the files of a short
//!   run) × 8 bytes × 3 copies = 28.8 GB, over the 8 GiB default limit;
//! - the same run kept at `output_dt = 1` is streamed: it passes the step limit (10⁵ rows
//!   kept, 10⁸ steps ≤ 100 × the limit) and is priced by the rows it holds, 10⁵ + 2;
//! - the limits are overridden by the environment (a 1-byte limit refuses a 1,000-step
//!   run, a value that is not a number of bytes is an error naming the variable).

use std::path::Path;
use std::process::Command;

/// Values a row of the PEPO's predictor-corrector run records: time, force, resistance,
/// rel_disp, slide, vel, acc, pc_change, and the contact's N, T, slip, gap.
const VALUES_PER_ROW: u64 = 12;

/// The PEPO case, predictor-corrector only at Δt = 1 ms, for `duration` seconds, written
/// to `dir`; returns its path and the 1-based line and column of the duration's value.
fn pepo_case(dir: &Path, duration: &str) -> (std::path::PathBuf, (usize, usize)) {
    let text = std::fs::read_to_string(crate::common::repo("cases/pepo-mass-accel.toml")).unwrap();
    let head = &text[..text.find("[engines.").unwrap()];
    assert!(head.contains("duration = 1.0"));
    let text = format!(
        "{}\n[engines.predictor-corrector]\ndt = 0.001\n",
        head.replace("duration = 1.0", &format!("duration = {duration}"))
    );
    let (line, column) = text
        .lines()
        .enumerate()
        .find_map(|(i, l)| l.strip_prefix("duration = ").map(|_| (i + 1, 12)))
        .unwrap();
    let path = dir.join("long-pepo.toml");
    std::fs::write(&path, text).unwrap();
    (path, (line, column))
}

fn run(case: &Path, out: &Path, env: &[(&str, &str)]) -> std::process::Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rockslide"));
    c.args(["run", "--quiet", "--out"]).arg(out).arg(case);
    c.env_remove("ROCKSLIDE_MAX_MEMORY_BYTES")
        .env_remove("ROCKSLIDE_MAX_DISK_BYTES")
        .env_remove("ROCKSLIDE_MAX_STEPS");
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().unwrap()
}

#[test]
fn a_run_of_1e8_steps_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let (case, (line, column)) = pepo_case(dir.path(), "100000.0");
    let out = dir.path().join("out");
    let started = std::time::Instant::now();
    let o = run(&case, &out, &[]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("run.dt: "), "{stderr}");
    assert!(stderr.contains("ROCKSLIDE_MAX_STEPS"), "{stderr}");
    let o = run(&case, &out, &[("ROCKSLIDE_MAX_STEPS", "1000000000")]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    // 10⁸ steps (1e5 s / 1e-3 s) + the initial row; the values a row records
    let rows: u64 = 100_000_001;
    let values = VALUES_PER_ROW;
    let bytes = rows * values * 8 * 3;
    let shown = format!("{:.1} GB", bytes as f64 / 1e9);
    assert_eq!(shown, "28.8 GB");
    let expected_start = format!("{}:{line}:{column}: run.duration: ", case.display());
    assert!(stderr.contains(&expected_start), "{stderr}");
    for part in [
        format!(
            "{rows} rows in all (duration / dt each; {} values)",
            rows * values
        ),
        format!("about {shown} of memory"),
        "over the limit of 8.6 GB".to_string(),
        "ROCKSLIDE_MAX_MEMORY_BYTES=<bytes>".to_string(),
    ] {
        assert!(stderr.contains(&part), "{part:?} not in {stderr}");
    }
    assert!(!out.join("long-pepo").exists(), "nothing written");
    // refused from the plan: no engine step ran (10⁸ steps take seconds at least)
    assert!(started.elapsed().as_secs_f64() < 5.0);
}

#[test]
fn the_limits_are_overridden_by_the_environment() {
    let dir = tempfile::tempdir().unwrap();
    let (case, _) = pepo_case(dir.path(), "1.0");
    let out = dir.path().join("out");
    let o = run(&case, &out, &[("ROCKSLIDE_MAX_MEMORY_BYTES", "1")]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("1001 rows"), "{stderr}");
    assert!(stderr.contains("over the limit of 0.0 GB"), "{stderr}");

    let o = run(&case, &out, &[("ROCKSLIDE_MAX_DISK_BYTES", "lots")]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr
            .contains("ROCKSLIDE_MAX_DISK_BYTES is \"lots\", but must be a whole number of bytes"),
        "{stderr}"
    );

    let o = run(
        &case,
        &out,
        &[("ROCKSLIDE_MAX_MEMORY_BYTES", "17179869184")],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("long-pepo").join("long-pepo.mcap").is_file());
    // the values a row records, as the MCAP state messages carry them (time, the
    // channels, the contact's four fields; its contacts CSV is not written: it repeats
    // the run's columns)
    let m = rockslide::formats::read_mcap(&out.join("long-pepo").join("long-pepo.mcap")).unwrap();
    let state = m.state("/predictor-corrector/paper/state").unwrap();
    let values = 1 + state.channels.len() + 4 * state.contacts.count();
    assert_eq!(values as u64, VALUES_PER_ROW);
    assert!(
        !out.join("long-pepo")
            .join("predictor-corrector-paper-contacts.csv")
            .exists()
    );
}

#[test]
fn a_run_of_1e8_steps_kept_at_an_output_step_is_priced_by_the_rows_it_holds() {
    let dir = tempfile::tempdir().unwrap();
    let (case, _) = pepo_case(dir.path(), "100000.0\noutput_dt = 1.0");
    let out = dir.path().join("out");
    // a 1-byte memory limit shows the estimate without running the 10⁸ steps
    let o = run(&case, &out, &[("ROCKSLIDE_MAX_MEMORY_BYTES", "1")]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(!stderr.contains("ROCKSLIDE_MAX_STEPS"), "{stderr}");
    // the first row, one per second (10⁵), the last
    let held: u64 = 100_002;
    let bytes = held * VALUES_PER_ROW * 8 * 3;
    assert_eq!(format!("{:.1} GB", bytes as f64 / 1e9), "0.0 GB");
    for part in [
        format!(
            "record 100000001 rows in all and hold {held} (streamed runs keep one per run.output_dt; {} values)",
            held * VALUES_PER_ROW
        ),
        "about 0.0 GB of memory".to_string(),
    ] {
        assert!(stderr.contains(&part), "{part:?} not in {stderr}");
    }
}

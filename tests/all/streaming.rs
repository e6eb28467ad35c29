//! Long runs and their disk (docs/performance.md): the estimate made before any work counts
//! the rows the trace files keep, so `[run] output_dt` lets a long run through.
//!
//! Requirements checked:
//! - a 10⁷-step predictor-corrector run (the PEPO for 10⁴ s at Δt = 1 ms) with
//!   `output_dt = 0.01` writes 10⁶ + 2 rows (the first row, one per 10 ms, and the
//!   last), priced at the 12 values a row of the predictor-corrector records (time, 7
//!   channels, 4 contact fields) × 32 bytes per value (measured: 31.4, see
//!   `footprint.rs`) = 0.4 GB; without `output_dt` every one of the 10⁷ + 1 rows is
//!   written: 3.8 GB. Both computed here from those counts, and both refused under a
//!   100 MB limit before any step runs;
//! - a streamed run and a whole run of the same case give the same response quantities,
//!   history errors, invariants and checks bit for bit, every engine (each streams
//!   natively; rapier alone on each of its time loops, fe alone on each of its
//!   recorders), and the streamed run keeps exactly the rows the whole run's files keep;
//! - the bytes per value of the estimate against the files a run writes.

use std::path::Path;
use std::process::Command;

/// The PEPO case, predictor-corrector only at Δt = 1 ms, for 10⁴ s, with `run_extra`
/// appended to its `[run]` table; written to `dir`.
fn long_pepo(dir: &Path, run_extra: &str) -> std::path::PathBuf {
    pepo(dir, 10_000.0, run_extra)
}

/// The PEPO case, predictor-corrector only at Δt = 1 ms, for `duration` s, with
/// `run_extra` appended to its `[run]` table; written to `dir`.
fn pepo(dir: &Path, duration: f64, run_extra: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string(crate::common::repo("cases/pepo-mass-accel.toml")).unwrap();
    let head = &text[..text.find("[engines.").unwrap()];
    assert!(head.contains("duration = 1.0\ndt = 0.001\n"));
    let text = format!(
        "{}\n[engines.predictor-corrector]\ndt = 0.001\n",
        head.replace(
            "duration = 1.0\ndt = 0.001\n",
            &format!("duration = {duration:?}\ndt = 0.001\n{run_extra}")
        )
    );
    let path = dir.join("long-pepo.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// `rockslide run` of `case` under a disk limit of 100 MB; its exit code and standard error.
fn run_under_100mb(case: &Path, out: &Path) -> (Option<i32>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args(["run", "--quiet", "--out"])
        .arg(out)
        .arg(case)
        // 16 GiB of memory: the disk estimate is under test, not the memory one (10⁷
        // rows × the catalogue's 37 values × 24 bytes is 8.9 GB, over the 8 GiB default)
        .env("ROCKSLIDE_MAX_MEMORY_BYTES", "17179869184")
        .env_remove("ROCKSLIDE_MAX_STEPS")
        .env("ROCKSLIDE_MAX_DISK_BYTES", "100000000")
        .output()
        .unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn the_disk_estimate_counts_the_rows_kept_at_output_dt() {
    // time, force, resistance, rel_disp, slide, vel, acc, pc_change; N, T, slip, gap
    let values_per_row = 12.0;
    let bytes_per_value = 32.0;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");

    let decimated = long_pepo(dir.path(), "output_dt = 0.01\n");
    let (code, stderr) = run_under_100mb(&decimated, &out);
    assert_eq!(code, Some(2), "{stderr}");
    let rows = 1e6 + 2.0;
    let gb = rows * values_per_row * bytes_per_value / 1e9;
    assert!(
        stderr.contains(&format!(
            "write 1000002 rows in all (one per run.output_dt), whose traces need about {gb:.1} GB of disk, over the limit of 0.1 GB"
        )),
        "{stderr}"
    );
    assert!(
        stderr.contains("ROCKSLIDE_MAX_DISK_BYTES=<bytes>"),
        "{stderr}"
    );

    let every_step = long_pepo(dir.path(), "");
    let (code, stderr) = run_under_100mb(&every_step, &out);
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

/// The trace files of a 10⁴-step PEPO run (10 s, every step): 10⁴ + 1 rows of the 12
/// values the predictor-corrector records, against the estimate's 32 bytes per value.
#[test]
fn the_bytes_per_value_of_the_estimate_are_those_of_the_files() {
    let dir = tempfile::tempdir().unwrap();
    let case = pepo(dir.path(), 10.0, "");
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args(["run", "--quiet", "--out"])
        .arg(&out)
        .arg(&case)
        .output()
        .unwrap();
    assert!(out.join("long-pepo").join("result.json").is_file(), "{o:?}");
    let mut bytes = 0;
    for entry in std::fs::read_dir(out.join("long-pepo")).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let trace = name.ends_with(".mcap") || (name.ends_with(".csv") && name != "summary.csv");
        if trace {
            bytes += std::fs::metadata(&path).unwrap().len();
        }
    }
    let values = 10_001.0 * 12.0;
    let per_value = bytes as f64 / values;
    eprintln!("{bytes} bytes of trace files: {per_value:.2} bytes per value");
    assert!((30.0..=32.0).contains(&per_value), "{per_value}");
}

/// Streamed and whole analyses of the same case: a streamed run reads
/// its summaries at every step, as the whole run reads its columns.
mod streamed_equals_whole {
    use rockslide::case::Case;
    use rockslide::engine::Run;
    use rockslide::suite::{CaseResult, run_case_streaming_above};

    fn both(case: Case) -> (CaseResult, CaseResult) {
        let engines = rockslide::engine::all();
        // every engine streams natively (no trace held)
        let native: Vec<bool> = engines.iter().map(|e| e.streams_natively()).collect();
        assert_eq!(native, [true, true, true]);
        both_with(case, engines)
    }

    /// The case run whole and streamed (every run) by `engines`.
    /// The engine `id` alone.
    fn only(id: &str) -> Vec<Box<dyn rockslide::engine::Engine>> {
        let mut engines = rockslide::engine::all();
        engines.retain(|e| e.id() == id);
        engines
    }

    /// Engine `id` alone on `case`, streamed and whole: each row records the values the
    /// engine declares before running (the estimates' count), and the two results agree bit
    /// for bit (responses, history errors, invariants, checks, statistics, findings) with
    /// the rows of the files.
    fn assert_streams_as_whole(case: Case, id: &str) {
        let output_dt = case.run.output_dt;
        let (whole, streamed) = both_with(case.clone(), only(id));
        assert!(!whole.runs.is_empty());
        for r in &whole.runs {
            let recorded = 1 + r.trace.channels.len() + 4 * r.trace.contacts.count();
            let engine = &only(id)[0];
            let variants = engine.variants(&case.scene).unwrap();
            let variant = rockslide::engine::declared(&variants, &r.variant).unwrap();
            let declared = engine.recorded_values(&case, variant);
            assert_eq!(declared, Some(recorded), "{}", r.label());
        }
        assert_same(&whole, &streamed, |w| match output_dt {
            Some(o) => bits(&w.trace.at_output_step(o)),
            None => bits(&w.trace),
        });
    }

    fn both_with(
        case: Case,
        engines: Vec<Box<dyn rockslide::engine::Engine>>,
    ) -> (CaseResult, CaseResult) {
        let whole = run_case_streaming_above(case.clone(), &engines, u64::MAX).unwrap();
        let streamed = run_case_streaming_above(case, &engines, 0).unwrap();
        (whole, streamed)
    }

    fn bits(t: &rockslide::trace::Trace) -> Vec<u64> {
        t.time
            .iter()
            .chain(t.columns.iter().flatten())
            .chain(&t.contacts.values)
            .map(|x| x.to_bits())
            .collect()
    }

    /// Responses, history errors, invariants and checks, bit for bit; `kept` the rows the
    /// streamed run keeps of the whole run's trace.
    fn assert_same(whole: &CaseResult, streamed: &CaseResult, kept: impl Fn(&Run) -> Vec<u64>) {
        assert_eq!(whole.runs.len(), streamed.runs.len());
        for (i, (w, s)) in whole.runs.iter().zip(&streamed.runs).enumerate() {
            let label = w.label();
            assert_eq!(label, s.label());
            assert_eq!(w.status, s.status, "{label}");
            assert_eq!(w.stats, s.stats, "{label}");
            assert_eq!(w.findings, s.findings, "{label}");
            let (rw, rs) = (&whole.run_responses[i], &streamed.run_responses[i]);
            assert_eq!(
                rw.iter()
                    .map(|(k, v)| (*k, v.to_bits()))
                    .collect::<Vec<_>>(),
                rs.iter()
                    .map(|(k, v)| (*k, v.to_bits()))
                    .collect::<Vec<_>>(),
                "{label}: {rw:?} / {rs:?}"
            );
            let h =
                |r: &CaseResult| r.history_errors[i].map(|e| (e.max.to_bits(), e.rms.to_bits()));
            assert_eq!(h(whole), h(streamed), "{label}");
            let (kw, ks) = (kept(w), bits(&s.trace));
            let first = kw.iter().zip(&ks).position(|(a, b)| a != b);
            assert!(
                kw.len() == ks.len() && first.is_none(),
                "{label}: kept rows: {} and {} values, first difference at {first:?} ({} whole rows)",
                kw.len(),
                ks.len(),
                w.trace.len()
            );
        }
        let inv = |r: &CaseResult| {
            r.invariants
                .iter()
                .map(|c| {
                    (
                        c.invariant,
                        c.run.clone(),
                        c.worst.to_bits(),
                        c.at.map(f64::to_bits),
                    )
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(inv(whole), inv(streamed));
        assert!(!whole.invariants.is_empty());
        let checks = |r: &CaseResult| format!("{:?}", r.checks);
        assert_eq!(checks(whole), checks(streamed));
        assert_eq!(whole.gate_passed(), streamed.gate_passed());
    }

    #[test]
    fn every_engine_on_the_pepo_cases_and_a_record() {
        for name in [
            "pepo-mass-accel",
            "pepo-ground-disp",
            "records/pepo-northridge",
        ] {
            let case = crate::common::case(name);
            let output_dt = case.run.output_dt;
            let (whole, streamed) = both(case);
            assert!(whole.runs.len() >= 2, "{name}");
            // every row, or the rows of the files at the case's output step
            assert_same(&whole, &streamed, |w| match output_dt {
                Some(o) => bits(&w.trace.at_output_step(o)),
                None => bits(&w.trace),
            });
        }
    }

    #[test]
    fn a_run_kept_at_an_output_step_keeps_the_rows_of_the_files() {
        let case = crate::common::case_with(
            "pepo-mass-accel",
            "duration = 1.0\ndt = 0.001\n",
            "duration = 1.0\ndt = 0.001\noutput_dt = 0.0125\n",
        );
        let (whole, streamed) = both(case);
        // the first row, one per 12.5 ms (80), the last: what the files of the whole run keep
        for r in &streamed.runs {
            assert!(r.trace.len() < 90, "{}: {} rows", r.label(), r.trace.len());
        }
        assert_same(&whole, &streamed, |w| bits(&w.trace.at_output_step(0.0125)));
    }

    /// Every engine of the plan scenes (fe's 3D model, rapier; the predictor-corrector is
    /// planar and not applicable): the streamed counter reads slip episodes along the slip
    /// path as the whole trace does, bit for bit. On the PEPO under the Chino Hills pair
    /// every run counts 93 episodes read at every 1 ms step, as the reference's 93 plastic
    /// phases (measured 2026-11-24; the x component alone gave 105, 105 and 106: a slip
    /// that turns across x stops x's rate). Read off the rows kept at the case's 20 ms
    /// output step, 91 (the reference sampled every 20 ms: 91 too): the reference's two
    /// shortest sticks, 18.9 and 21.0 ms, hold no whole 20 ms step and join their neighbours. The block: 12 runs for rapier as the reference's 12
    /// (with its tipping locked; free to tip, it registered a round-off slip as its contact
    /// settled at t = 0 and counted 13).
    #[test]
    fn every_engine_on_the_plan_cases_counts_along_the_slip_path() {
        for (name, every_step) in [
            ("spatial/pepo-chino-hills-pair", 93.0),
            ("spatial/block-chino-hills-pair", 12.0),
        ] {
            let case = crate::common::case(name);
            let output_dt = case.run.output_dt.unwrap();
            let (whole, streamed) = both(case);
            assert!(!whole.runs.is_empty(), "{name}");
            assert_same(&whole, &streamed, |w| {
                bits(&w.trace.at_output_step(output_dt))
            });
            for (run, r) in whole.runs.iter().zip(&whole.run_responses) {
                assert_eq!(r["slip_episodes"], every_step, "{name} {}", run.label());
            }
            if name.starts_with("spatial/pepo") {
                assert_eq!(whole.runs.len(), 3, "fe, rapier's two grounds");
                for run in &whole.runs {
                    let kept = run.trace.at_output_step(output_dt);
                    let at_output_step = rockslide::analysis::responses(&kept)["slip_episodes"];
                    assert_eq!(at_output_step, 91.0, "{}", run.label());
                }
            }
        }
    }

    /// A shipped case with texts replaced, in order (each must occur).
    fn edited(name: &str, edits: &[(&str, &str)]) -> Case {
        let path = crate::common::repo(&format!("cases/{name}.toml"));
        let mut text = std::fs::read_to_string(&path).unwrap();
        for (from, to) in edits {
            assert!(text.contains(from), "{from:?} not in {name}");
            text = text.replacen(from, to, 1);
        }
        rockslide::case::parse_case(&path, &text).expect("edited case loads")
    }

    /// rapier alone, streaming natively, on each of its time loops: the oscillator
    /// (joint-limit contact and foot), the oscillator on a support under vertical motion,
    /// the block (and on the kinematic ground its step rule's pilot, which keeps only its
    /// path length), the block lifting off, the rocking body (computed supports,
    /// joint-limit supports, feet), and in plan the oscillator, the block on the kinematic
    /// ground (its pilot in plan) and the rocking grid: the same responses, history errors,
    /// invariants, checks, statistics and findings as the whole run, bit for bit, and the
    /// rows of its files; each run records the values the engine declares before running.
    #[test]
    fn rapier_natively_on_each_of_its_time_loops() {
        let foot = "[engines.rapier]\ncontact_model = \"foot\"\n#";
        let joints = "[engines.rapier]\ncontact_model = \"joint-limit\"\n#";
        // every row kept: a streamed run reads the tilt after the first impact off its kept
        // rows (analysis::streamed), which at the case's output step are not every row
        let short_northridge = ("duration = 22.0", "duration = 3.0");
        let every_row = ("output_dt = 0.02", "# output_dt = 0.02");
        let plan_rpepo: [(&str, &str); 3] = [
            ("[model]\n", "[model]\nhalf_depth = 0.3\nsupport_rows = 2\n"),
            ("cycles = 5.0 ", "cycles = 5.0\nazimuth_deg = 30 "),
            ("duration = 2.0 ", "duration = 0.5 "),
        ];
        let cases = [
            edited("pepo-mass-accel", &[]),
            edited("pepo-mass-accel", &[("[engines.rapier]", foot)]),
            edited("vertical/pepo-mass-accel-vertical", &[]),
            edited("rigid-sliding-block", &[]),
            edited("vertical/block-liftoff", &[]),
            edited("records/block-northridge", &[short_northridge, every_row]),
            edited(
                "rpepo-mass-accel",
                &[("duration = 2.0 ", "duration = 0.7 ")],
            ),
            edited(
                "rpepo-mass-accel",
                &[
                    ("[engines.rapier]", joints),
                    ("duration = 2.0 ", "duration = 0.7 "),
                ],
            ),
            edited(
                "rpepo-mass-accel",
                &[
                    ("[engines.rapier]", foot),
                    ("duration = 2.0 ", "duration = 0.7 "),
                ],
            ),
            edited("spatial/pepo-pulse-azimuth30", &[]),
            edited(
                "records/block-northridge",
                &[
                    ("mu = 0.185", "mu = 0.185\nhalf_depth = 1.0"),
                    ("polarity = 1", "polarity = 1\nazimuth_deg = 30"),
                    short_northridge,
                    every_row,
                ],
            ),
            edited("rpepo-mass-accel", &plan_rpepo),
        ];
        for case in cases {
            assert_streams_as_whole(case, "rapier");
        }
    }
    /// fe alone, streaming natively, on each of its recorders: the sliding oscillator's
    /// (the PEPO single, under mass acceleration and ground displacement), the general one
    /// (the PEPO double; the RPEPO single and double, whose sensitivity findings are read
    /// as the rows go by, and under vertical motion), and the 3D model's (the PEPO in plan,
    /// the RPEPO on a 10 × 2 grid): the same responses, history errors, invariants,
    /// checks, statistics and findings as the whole run, bit for bit, and the rows of its
    /// files; each run records the values the engine declares before running.
    #[test]
    fn fe_natively_on_each_of_its_recorders() {
        let short_rpepo = ("duration = 2.0 ", "duration = 0.7 ");
        let plan_rpepo: [(&str, &str); 3] = [
            ("[model]\n", "[model]\nhalf_depth = 0.3\nsupport_rows = 2\n"),
            ("cycles = 5.0 ", "cycles = 5.0\nazimuth_deg = 30 "),
            ("duration = 2.0 ", "duration = 0.5 "),
        ];
        let cases = [
            edited("pepo-mass-accel", &[]),
            edited("pepo-ground-disp", &[]),
            edited("rpepo-mass-accel", &[short_rpepo]),
            edited("vertical/rpepo-mass-accel-vertical", &[]),
            edited("spatial/pepo-pulse-azimuth30", &[]),
            edited("rpepo-mass-accel", &plan_rpepo),
        ];
        for case in cases {
            assert_streams_as_whole(case, "fe");
        }
        // the sensitivity findings (read as the rows go by) are among those compared
        let (whole, _) = both_with(edited("rpepo-mass-accel", &[short_rpepo]), only("fe"));
        assert!(
            whole.runs[0]
                .findings
                .iter()
                .any(|f| f.starts_with("sensitivity — rotational inertia ×10: peak |sliding|"))
        );
    }
}

/// A long run is streamed only where streaming bounds its memory: a natively streaming
/// engine over 5·10⁵ steps that keeps at most half its rows. The PEPO at Δt = 1 ms for
/// 1,000 s (10⁶ steps): without `output_dt` every row is kept, so streaming would hold the
/// same trace and only add the second pass — run whole; every 2 ms (half the rows):
/// streamed; every 1.5 ms (two thirds): whole; 10³ steps: whole.
#[test]
fn a_run_is_streamed_only_where_it_keeps_at_most_half_its_rows() {
    let dir = tempfile::tempdir().unwrap();
    let streamed = |duration: f64, run_extra: &str| {
        let case = rockslide::case::load_case(&pepo(dir.path(), duration, run_extra)).unwrap();
        let engines = rockslide::engine::all();
        let plan = rockslide::suite::plan(&case, &engines).unwrap();
        assert_eq!(plan.runs.len(), 1, "the predictor-corrector alone");
        rockslide::suite::streams(&case, &plan.runs[0])
    };
    assert!(!streamed(1000.0, ""));
    assert!(streamed(1000.0, "output_dt = 0.002\n"));
    assert!(!streamed(1000.0, "output_dt = 0.0015\n"));
    assert!(!streamed(1.0, "output_dt = 0.002\n"));
}

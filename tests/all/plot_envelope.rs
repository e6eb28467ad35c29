//! Figures of a streamed run (docs/performance.md): a run analysed as it streams keeps, for
//! every channel, the minimum and maximum of each of `ENVELOPE_BUCKETS` time slices over
//! every step, and its figures draw those instead of the rows kept at `output_dt`.
//!
//! Requirements checked:
//! - a streamed run's envelope equals the per-slice extremes of the same run made whole,
//!   bit for bit, every engine (those that do not stream natively forward their rows);
//! - it holds the peaks the kept rows miss (the whole trace's extreme of every channel);
//! - the figure of a streamed run draws the same lines as the whole run drawn from its
//!   per-slice extremes: the SVG files are byte-identical;
//! - its memory is fixed: 4 values per channel and slice, for 1 s as for 10 s of run (the
//!   allocations of the whole streamed analysis, envelope included, are counted equal
//!   for ten times the steps in `tests/no_alloc.rs`).

use rockslide::analysis::envelope::{ENVELOPE_BUCKETS, Envelope};
use rockslide::case::Case;
use rockslide::report::write_case_outputs;
use rockslide::suite::{CaseResult, run_case_streaming_above};

/// The PEPO under its mass acceleration for `duration` s, every engine at Δt = 1 ms (the
/// predictor-corrector too: the case's own 10 ms is coarser than the kept rows), rows kept
/// every 12.5 ms.
fn pepo(duration: &str) -> Case {
    let path = crate::common::repo("cases/pepo-mass-accel.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let (run, pc) = (
        "duration = 1.0\ndt = 0.001\n",
        "dt = 0.01               # the paper's spreadsheet step",
    );
    assert!(text.contains(run) && text.contains(pc));
    let text = text
        .replace(
            run,
            &format!("duration = {duration}\ndt = 0.001\noutput_dt = 0.0125\n"),
        )
        .replace(pc, "dt = 0.001");
    rockslide::case::parse_case(&path, &text).expect("modified case loads")
}

/// The case run whole (no run streamed) and streamed (every run).
fn both(case: Case) -> (CaseResult, CaseResult) {
    let engines = rockslide::engine::all();
    let whole = run_case_streaming_above(case.clone(), &engines, u64::MAX).unwrap();
    let streamed = run_case_streaming_above(case, &engines, 0).unwrap();
    (whole, streamed)
}

#[test]
fn a_streamed_runs_envelope_is_its_whole_runs_per_slice_extremes_and_keeps_the_peaks() {
    let case = pepo("1.0");
    let duration = case.run.duration;
    let (whole, streamed) = both(case);
    assert_eq!(whole.runs.len(), streamed.runs.len());
    let mut missed_by_kept_rows = 0;
    for (i, (w, s)) in whole.runs.iter().zip(&streamed.runs).enumerate() {
        let label = w.label();
        assert!(
            whole.envelope(i).is_none(),
            "{label}: a whole run draws its trace"
        );
        let envelope = streamed
            .envelope(i)
            .expect("a streamed run has an envelope");
        assert_eq!(
            *envelope,
            Envelope::of_trace(&w.trace, duration, ENVELOPE_BUCKETS),
            "{label}"
        );
        assert!(s.trace.len() < 90 && w.trace.len() > 1000, "{label}");
        for (c, q) in w.trace.channels.iter().enumerate() {
            let max = |v: &[f64]| v.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x));
            let whole_max = max(&w.trace.columns[c]);
            let drawn_max = max(&envelope
                .points(q.key)
                .unwrap()
                .iter()
                .map(|p| p.1)
                .collect::<Vec<_>>());
            assert_eq!(
                drawn_max.to_bits(),
                whole_max.to_bits(),
                "{label} {}",
                q.key
            );
            if max(&s.trace.columns[c]) < whole_max {
                missed_by_kept_rows += 1;
            }
        }
    }
    eprintln!("channel peaks the kept rows miss: {missed_by_kept_rows}");
    // the rows kept every 12.5 ms miss peaks of a 1-kHz run (6 channel peaks of the
    // three engines' runs, measured); the envelope has every one
    assert!(
        missed_by_kept_rows >= 6,
        "{missed_by_kept_rows}: measured 6"
    );
}

#[test]
fn a_streamed_runs_figures_are_those_of_the_whole_run_drawn_from_its_extremes() {
    let case = pepo("1.0");
    let duration = case.run.duration;
    let (mut whole, mut streamed) = both(case);
    whole.envelopes = whole
        .runs
        .iter()
        .map(|r| Some(Envelope::of_trace(&r.trace, duration, ENVELOPE_BUCKETS)))
        .collect();
    // the reference is sampled at the times kept, which differ: compared without it
    whole.reference = Err("left out".into());
    streamed.reference = Err("left out".into());
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let (a, b) = (
        write_case_outputs(&whole, a.path()).unwrap(),
        write_case_outputs(&streamed, b.path()).unwrap(),
    );
    let mut compared = 0;
    for file in [
        "plot-force-resistance.svg",
        "plot-relative-displacement.svg",
        "plot-sliding.svg",
    ] {
        let (x, y) = (
            std::fs::read_to_string(a.join(file)).unwrap(),
            std::fs::read_to_string(b.join(file)).unwrap(),
        );
        assert!(x.matches(" d=\"M").count() >= 3, "{file}");
        assert!(x == y, "{file} differs");
        compared += 1;
    }
    assert_eq!(compared, 3);
}

#[test]
fn an_envelope_holds_the_same_values_for_ten_times_the_run() {
    let held = |duration: &str| {
        let (_, streamed) = both(pepo(duration));
        let pc = streamed
            .runs
            .iter()
            .position(|r| r.engine == "predictor-corrector")
            .unwrap();
        let e = streamed.envelope(pc).unwrap();
        (
            e.values_held(),
            e.channels.len(),
            streamed.runs[pc].stats.steps,
        )
    };
    let (short, channels, steps) = held("1.0");
    let (long, _, steps_long) = held("10.0");
    assert_eq!((steps, steps_long), (1000, 10_000));
    assert_eq!(short, 4 * channels * ENVELOPE_BUCKETS);
    assert_eq!(long, short);
}

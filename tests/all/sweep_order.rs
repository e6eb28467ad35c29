//! Convergence of the predictor-corrector measured by `rockslide sweep`: the observed
//! order of accuracy on the linear SDOF (closed-form Duhamel reference) and on the PEPO
//! mass-acceleration problem (exact event-driven reference).
//!
//! Requirement (docs/sweep-and-stability.md): "for each engine and case, a Δt ladder; per rung the error
//! against the reference …, with the observed order of accuracy."
//! Expectation: average acceleration is second order (Newmark 1959); with one predicting
//! and one correcting pass the paper's method keeps that order on smooth responses. On
//! the PEPO the slip events could cost an order; we measure and pin what we see.

use std::path::Path;

use rockslide::case::load_case;
use rockslide::sweep::Options;
use rockslide::sweep::work_precision::{SweepResult, sweep_case};

fn sweep(case: &str, rungs: usize) -> SweepResult {
    let case = load_case(Path::new(case)).expect("case loads");
    let opts = Options {
        rungs,
        repeats: 1,
        quiet: true,
        ..Options::default()
    };
    sweep_case(&case, &opts).expect("sweep runs")
}

/// Linear SDOF, Δt = T/10 … T/1280 (8 rungs, ratio 2). Measured: fitted order 1.963,
/// local orders 1.72, 1.91, 1.99, 2.00, 2.00, 2.00, 2.00 (the coarse rungs are outside the
/// asymptotic range), max error 5.53e-1 at T/10 down to 4.37e-5 at T/1280.
#[test]
fn predictor_corrector_is_second_order_on_the_linear_sdof() {
    let r = sweep("cases/linear-sdof.toml", 8);
    assert!(r.exact_basis, "the Duhamel solution is the basis");
    let s = r
        .series
        .iter()
        .find(|s| s.label == "predictor-corrector/paper")
        .expect("the predictor-corrector applies");
    assert_eq!(s.rungs.len(), 8);
    assert!(s.rungs.iter().all(|g| g.completed() && g.deterministic));
    // The asymptotic range: the four finest pairs.
    for p in &s.local_orders[3..] {
        let p = p.expect("finite errors");
        assert!((p - 2.0).abs() < 0.01, "local order {p}");
    }
    let fitted = s.fitted_order.unwrap();
    assert!((fitted - 1.963).abs() < 0.01, "fitted order {fitted}");
    // Richardson on the peak displacement recovers the order too (measured 2.047).
    assert_eq!(s.richardson[0].quantity, "peak relative displacement");
    let rich = s.richardson[0].estimate.expect("monotone convergence");
    assert!(
        (rich.order - 2.0).abs() < 0.06,
        "Richardson order {}",
        rich.order
    );
}

/// PEPO, half-sine mass acceleration, same ladder. Measured: fitted order 2.001 on the max
/// error of x (local orders 2.11, 2.08, 1.74, 2.16, 2.06, 1.82, 2.14 — the slip events make
/// them wander about 2), max error 5.77e-2 at T/10 and 3.26e-6 at T/1280; slip start and
/// end times within one step at every rung (2.87 ms at Δt = 20 ms, 0.072 ms at 0.156 ms).
#[test]
fn predictor_corrector_order_on_the_pepo() {
    let r = sweep("cases/pepo-mass-accel.toml", 8);
    assert!(r.exact_basis);
    let s = &r.series[0];
    assert_eq!(s.label, "predictor-corrector/paper");
    let fitted = s.fitted_order.unwrap();
    assert!((fitted - 2.0).abs() < 0.02, "fitted order {fitted}");
    for p in &s.local_orders {
        let p = p.unwrap();
        assert!((1.7..2.2).contains(&p), "local order {p}");
    }
    for g in &s.rungs {
        let e = g.error.expect("error against the exact reference");
        assert_eq!(e.events_missing, 0);
        let ev = e.event_time.expect("slip start and end");
        assert!(ev <= g.dt, "event time error {ev} s at Δt = {} s", g.dt);
    }
    let first = s.rungs[0].error.unwrap().max;
    let last = s.rungs[7].error.unwrap().max;
    assert!((first - 5.773e-2).abs() < 1e-4 && (last - 3.260e-6).abs() < 1e-8);
}

/// The ladder itself: from T/10 down, two decades with 8 rungs at ratio 2.
#[test]
fn ladder_starts_at_a_tenth_of_the_period_and_spans_two_decades() {
    let r = sweep("cases/pepo-mass-accel.toml", 8);
    assert!((r.period.0 - 0.2).abs() < 1e-6); // T = 2π√(M/Kx) = 0.2 s
    let dts: Vec<f64> = r.series[0].rungs.iter().map(|g| g.dt).collect();
    assert!((dts[0] - r.period.0 / 10.0).abs() < 1e-15 && (dts[0] - 0.02).abs() < 1e-6);
    assert!(dts[0] / dts[7] >= 100.0);
}

/// The FE engine (Newmark average acceleration) on the linear SDOF against Duhamel:
/// second order. Measured (release and test builds alike): local orders on the four finest
/// pairs of an 8-rung ladder 2.00 (1.9995 … 2.0001), fitted 1.978 with the coarse rungs;
/// the energy audit closes to round-off (≤ 1e-10: average acceleration conserves the
/// trapezoidal energy exactly).
#[test]
fn fe_is_second_order_on_the_linear_sdof() {
    let r = sweep("cases/linear-sdof.toml", 8);
    for label in ["fe/single", "fe/double"] {
        let s = r.series.iter().find(|s| s.label == label).expect(label);
        assert!(s.rungs.iter().all(|g| g.completed()));
        for p in &s.local_orders[3..] {
            let p = p.expect("finite errors");
            assert!((p - 2.0).abs() < 0.01, "{label}: local order {p}");
        }
        let fine = s.fine_order.unwrap();
        assert!((fine - 2.0).abs() < 0.01, "{label}: fine order {fine}");
        for g in &s.rungs {
            let e = g.energy.as_ref().unwrap().relative_error;
            assert!(e < 1e-10, "{label}: energy {e}");
        }
    }
}

/// The cost budget: with a budget far below the cost of the ladder every series keeps
/// its three coarsest rungs, the finer ones are skipped and the sweep's page says so. The
/// typed result written as `sweep.json` reads back equal, field for field.
#[test]
fn the_cost_budget_caps_rungs_and_says_so() {
    let case = load_case(Path::new("cases/linear-sdof.toml")).unwrap();
    let opts = Options {
        rungs: 8,
        repeats: 1,
        quiet: true,
        budget: Some(1e-9),
        ..Options::default()
    };
    let r = sweep_case(&case, &opts).unwrap();
    for s in &r.series {
        assert_eq!(s.rungs.len(), 3, "{}", s.label);
        let k = s.skipped.as_ref().expect("skipped");
        assert!(
            (k.from_dt - r.period.0 / 80.0).abs() < 1e-15,
            "{}",
            k.from_dt
        );
    }
    let dir = tempfile::tempdir().unwrap();
    r.save(dir.path()).unwrap();
    assert_eq!(SweepResult::load(dir.path()).unwrap().unwrap(), r);
    rockslide::present::sweep::write_sweep(&r, dir.path()).unwrap();
    let md = std::fs::read_to_string(dir.path().join("sweep.md")).unwrap();
    assert!(md.contains("**Cost budget:** 3 of 8 rungs run"), "{md}");
    // sweep.csv: one row per rung run, as csv::Reader reads it.
    let mut csv = csv::Reader::from_path(dir.path().join("sweep.csv")).unwrap();
    let rows = csv.records().collect::<Result<Vec<_>, _>>().unwrap();
    let rungs: usize = r.series.iter().map(|s| s.rungs.len()).sum();
    assert_eq!(rows.len(), rungs);
}

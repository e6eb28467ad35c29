//! Stability classes and limits: a run far beyond the predictor-corrector's stability
//! limit is classified as diverged with the time it happened, a fine run as accurate, the
//! measured limit matches the method's closed-form amplification, and a panicking engine
//! is a diverged result, never a crash.
//!
//! Requirement (docs/sweep-and-stability.md): "classify each run as accurate, inaccurate, diverged (NaN/Inf, or
//! energy growth) or not converged (Newton), with the time and reason. A diverging run is
//! a result, never a crash."

use crate::common::registered;
use rockslide::engine::fe::Fe;
use rockslide::engine::predictor_corrector::PredictorCorrector;
use std::path::Path;

use rockslide::analysis::energy::audit;
use rockslide::analysis::history_difference;
use rockslide::analysis::stability::{Class, Criteria, classify};
use rockslide::case::{Case, Scene, load_case};
use rockslide::engine::predictor_corrector::variant as pc_variant;
use rockslide::engine::{self, Arrangement, Engine, NotApplicable, Run};
use rockslide::error::InputError;
use rockslide::reference;
use rockslide::run::guarded;
use rockslide::sweep::stability::study;
use rockslide::sweep::{Options, characteristic_period};

fn pc() -> Box<dyn Engine> {
    registered(&PredictorCorrector)
}

/// Classify the predictor-corrector on `case` at Δt = `ratio`·T.
fn class_at(case: &Case, ratio: f64) -> Class {
    let t = characteristic_period(case).0;
    let run = pc().run(case, pc_variant::PAPER, ratio * t).unwrap();
    let energy = audit(&run.trace, &case.scene, Arrangement::Single).unwrap();
    let exact = reference::for_case(case).unwrap();
    let at = reference::sample(exact.as_ref(), &run.trace.time);
    let error = history_difference(&run.trace, &at, "rel_disp").map(|e| e.0);
    classify(
        Ok(&run.status),
        &run.trace,
        Some(&energy),
        error,
        &Criteria::default(),
    )
}

/// μ = 1000 (never slips: a linear oscillator). At Δt = T/2, far beyond the limit, the
/// scheme's amplification per step is 6.1 (|λ| of its 2×2 step matrix at ωΔt = π): the
/// energy audit sees growth at the first step, t = Δt = 0.1 s (measured). At T/100 the run
/// is accurate (measured max error 7.16e-3 of the peak); at 0.3·T stable but inaccurate
/// (measured 7.67e-1).
#[test]
fn far_beyond_the_limit_is_diverged_with_its_time() {
    let case = load_case(Path::new("cases/stability/mu-large.toml")).unwrap();
    let c = class_at(&case, 0.5);
    assert!(c.diverged(), "{c:?}");
    let t = c.time().expect("a time");
    assert!((t - 0.1).abs() < 1e-6, "diverged at {t}");
    assert!(c.reason().contains("energy growth"), "{}", c.reason());
    assert_eq!(class_at(&case, 0.01), Class::Accurate);
    // Just inside the limit (ωΔt = 1.9): stable, but far from accurate.
    assert_eq!(class_at(&case, 0.3), Class::Inaccurate);
}

/// The measured practical limit against the closed form: one predicting and one correcting
/// pass of average acceleration on ẍ = −ω²x give a step matrix whose spectral radius
/// reaches 1 at ωΔt = 2, i.e. Δt/T = 1/π = 0.318310 (derived by hand, checked numerically
/// outside this crate). Measured bracket on mu-large: [0.31829, 0.31831].
#[test]
fn measured_limit_of_the_predictor_corrector_is_one_over_pi() {
    let case = load_case(Path::new("cases/stability/mu-large.toml")).unwrap();
    let opts = Options {
        quiet: true,
        ..Options::default()
    };
    let r = study(&[case], &opts).unwrap();
    let l = r
        .limits
        .iter()
        .find(|l| l.label == "predictor-corrector/paper")
        .unwrap();
    assert_eq!(l.stable_up_to, Some(0.3));
    let (lo, hi, _) = l.refined.clone().expect("bisection ran");
    let theory = 1.0 / std::f64::consts::PI;
    assert!(lo <= theory + 2e-5 && hi >= theory - 2e-5, "[{lo}, {hi}]");
    assert!(hi - lo < 1e-4);
    assert_eq!(l.accurate_up_to, Some(0.02));
    // The typed result survives `stability.json` exactly — diverged runs' non-finite
    // energies included (serialised again, the text is the same).
    let dir = tempfile::tempdir().unwrap();
    r.save(dir.path()).unwrap();
    let back = rockslide::sweep::StabilityResult::load(dir.path())
        .unwrap()
        .unwrap();
    let text = |x: &rockslide::sweep::StabilityResult| serde_json::to_string(x).unwrap();
    assert_eq!(text(&back), text(&r));
    assert_eq!(back.limits, r.limits);
}

/// An engine that panics half-way: the guarded runner turns it into a result.
struct Panicky;

impl Engine for Panicky {
    fn id(&self) -> &'static str {
        "panicky"
    }
    fn description(&self) -> &'static str {
        "panics on every run (test double)"
    }
    fn variants(&self, _: &Scene) -> Result<Vec<engine::Variant>, NotApplicable> {
        Ok(vec![engine::Variant::single("only")])
    }
    fn run(&self, _: &Case, _: engine::Variant, dt: f64) -> Result<Run, InputError> {
        panic!("step matrix singular at dt = {dt}");
    }
}

#[test]
fn a_panicking_engine_is_a_diverged_result() {
    let case = load_case(Path::new("cases/pepo-mass-accel.toml")).unwrap();
    let timed =
        guarded(&Panicky, &case, engine::Variant::single("only"), 0.01, 3).expect("no input error");
    let msg = timed.run.as_ref().unwrap_err();
    assert!(msg.contains("singular at dt = 0.01"), "{msg}");
    let c = classify(
        Err(msg),
        &Default::default(),
        None,
        None,
        &Criteria::default(),
    );
    assert!(c.diverged() && c.time().is_none());
}

/// FE on the stiffest double arrangement (Kx1/Kx2 = 1e6) with at most 2 Newton
/// iterations per step (`cases/stability/stiff-ratio-1e6-newton-2.toml`): at Δt = T/20
/// the first slip needs more, and the run is classified `not converged` with its time and
/// residual (measured: t = 0.4 s, relative residual 4.9e-5 after 2 iterations) while a
/// finer run with the same budget converges and is accurate.
#[test]
fn starved_newton_is_not_converged_with_time_and_residual() {
    let case = load_case(Path::new("cases/stability/stiff-ratio-1e6-newton-2.toml")).unwrap();
    let fe = registered(&Fe);
    let t = characteristic_period(&case).0;
    let exact = reference::for_case(&case).unwrap();
    let class = |ratio: f64| {
        let timed = guarded(
            fe.as_ref(),
            &case,
            engine::fe::variant::DOUBLE_ELEMENT,
            ratio * t,
            1,
        )
        .unwrap();
        let run = timed.run.unwrap();
        let at = reference::sample(exact.as_ref(), &run.trace.time);
        let error = if run.status.completed() {
            history_difference(&run.trace, &at, "rel_disp").map(|e| e.0)
        } else {
            None
        };
        classify(
            Ok(&run.status),
            &run.trace,
            None,
            error,
            &Criteria::default(),
        )
    };
    let c = class(0.05);
    match &c {
        Class::NotConverged { time, reason } => {
            // Measured: t = 0.4000 s, "2 iterations: relative residual 4.945e-5".
            assert!((time - 0.4).abs() < 1e-6, "{time}");
            assert!(
                reason.contains("2 iterations") && reason.contains("residual"),
                "{reason}"
            );
        }
        other => panic!("expected not converged, got {other:?}"),
    }
    assert_eq!(class(0.01), Class::Accurate);
}

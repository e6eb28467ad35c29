//! The one guarded run: an engine that panics is a recorded result carrying its message,
//! under `check` as under `sweep`, `stability` and `study` — never an aborted command.
//!
//! Requirement (docs/sweep-and-stability.md): "A diverging run is a result, never a crash"; one
//! guarded, timed function runs every engine.

use rockslide::case::Scene;
use rockslide::engine::{self, Engine, NotApplicable, RunStatus};
use rockslide::error::InputError;
use rockslide::record::CaseRecord;
use rockslide::run::{Outcome, guard, guarded};
use rockslide::suite::run_case_with;

use crate::common::case;

/// Panics on every run (a test double; no shipped engine has an option that panics).
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
    fn run(
        &self,
        _: &rockslide::case::Case,
        _: engine::Variant,
        dt: f64,
    ) -> Result<engine::Run, InputError> {
        panic!("element stiffness singular at dt = {dt}");
    }
}

/// The guard itself, on closures: a value passes through, a panic becomes its text.
#[test]
fn the_guard_returns_the_value_or_the_panic_message() {
    assert_eq!(guard(|| 2 + 2), Ok(4));
    let msg = guard(|| -> f64 { panic!("no trace at step {}", 17) }).unwrap_err();
    assert_eq!(msg, "no trace at step 17");
}

/// `check`'s path (`run_case` with the registry's engines plus one that panics): the case
/// runs to the end, every real engine's run is there and completed, the panicking one is
/// a diverged run whose status carries the panic's message, and a gated tolerance on it
/// fails the gate instead of crashing it. The report is written and names the panic.
#[test]
fn check_records_a_panicking_engine_and_runs_the_others() {
    let mut c = case("pepo-mass-accel");
    c.engines.insert("panicky".into(), Default::default());
    let mut t = c.tolerances[0].clone();
    t.runs = Some("panicky".into());
    t.field = "tolerance[panicky]".into();
    c.tolerances.push(t);
    let mut engines = engine::all();
    engines.push(Box::new(Panicky));
    let r = run_case_with(c, &engines).expect("no input error");
    // predictor-corrector, fe single and double, rapier, and the panicking one.
    assert_eq!(r.runs.len(), 5);
    for run in r.runs.iter().filter(|run| run.engine != "panicky") {
        assert!(run.status.completed(), "{}: {}", run.label(), run.status);
    }
    let p = r.runs.iter().find(|run| run.engine == "panicky").unwrap();
    assert_eq!(p.label(), "panicky/only");
    match &p.status {
        RunStatus::Diverged { time, reason } => {
            assert!(time.is_nan(), "the time of a panic is unknown");
            assert!(
                reason.contains("panicked") && reason.contains("singular at dt = 0.001"),
                "{reason}"
            );
        }
        s => panic!("expected a diverged run, got {s:?}"),
    }
    assert!(p.trace.is_empty());
    let failures = rockslide::verdict::failures(std::slice::from_ref(&r));
    assert!(
        failures
            .iter()
            .any(|f| f.gated && f.engines.starts_with("panicky/only")),
        "{failures:?}"
    );
    assert!(!r.gate_passed());
    let dir = tempfile::tempdir().unwrap();
    let folder = rockslide::report::write_case_outputs(&r, dir.path()).expect("report written");
    let md = std::fs::read_to_string(folder.join("report.md")).unwrap();
    assert!(
        md.contains("singular at dt = 0.001"),
        "the report names the panic"
    );
    // The typed record beside it reads back with the panic, its unknown time and the
    // gate's verdict.
    let record = CaseRecord::load(&folder).unwrap();
    assert!(!record.gate_passed);
    assert_eq!(record.runs.len(), 5);
    let p = record.runs.iter().find(|r| r.engine == "panicky").unwrap();
    match &p.outcome {
        Outcome::Diverged { time, reason } => {
            assert!(time.is_nan() && reason.contains("singular at dt = 0.001"))
        }
        o => panic!("{o:?}"),
    }
    assert!(record.failures.iter().any(|f| f.contains("panicky/only")));
    assert_eq!(record.runs[0], CaseRecord::of(&r).runs[0]);
}

/// The sweep's and the stability study's path: repeats stop at the first panic, whose
/// message is the outcome and whose time is the one timing.
#[test]
fn a_guarded_run_of_a_panicking_engine_is_its_message() {
    let c = case("linear-sdof");
    let t =
        guarded(&Panicky, &c, engine::Variant::single("only"), 0.02, 3).expect("no input error");
    assert_eq!(
        t.seconds.len(),
        1,
        "the first repeat panicked: no more repeats"
    );
    assert!(t.time_stats().is_some());
    assert_eq!(
        Outcome::of(&t.run).to_string(),
        "panicked: element stiffness singular at dt = 0.02"
    );
}

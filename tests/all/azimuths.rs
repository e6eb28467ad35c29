//! A station case run at a set of azimuths (`x_azimuths_deg`, docs/records-and-studies.md).
//!
//! Requirements checked:
//! - the figures of a set at an azimuth are those of the single case with that
//!   `x_azimuth_deg`, bit for bit, for every participant;
//! - the maximum over the set is the largest value of the table, at its first argmax; the
//!   governing azimuth is the reference's argmax of peak sliding, and the case's own runs
//!   and traces are the governing azimuth's;
//! - along one axis a + 180° is the other polarity: the exact reference's peak is the same
//!   and its residual changes sign (why the set spans 360° there);
//! - a check that fails at one azimuth fails the gate, named with its azimuth;
//! - `result.json` carries every azimuth's figures;
//! - a bad set (empty, not finite, out of range, given twice, beside `x_azimuth_deg`, a
//!   step that does not divide the span) is an input error located at its element.

use rockslide::azimuths::{AzimuthSweep, REFERENCE};
use rockslide::case::parse_case;
use rockslide::record::CaseRecord;
use rockslide::suite::{CaseResult, run_case};

use crate::common::repo;

/// The PEPO along one azimuth under CI.CCC's horizontal and vertical (the shipped
/// `pepo-ridgecrest-ccc-xz` scene, 6 s from 30 s of the file at Δt = 1 ms so that a
/// test runs in a second), with `azimuth` in `[excitation.station]` and `rest` appended.
fn case_text(azimuth: &str, rest: &str) -> String {
    format!(
        r#"
name = "ccc-azimuths"
[model]
kind = "oscillator"
mass = 1.0e6
gravity = 9.81
[model.contact]
kx = 9.8696e8
kz = 3.94784e9
mu = 0.3
[excitation]
kind = "ground-acceleration"
[excitation.station]
file = "../records/Ridgecrest_2019_CI.CCC.RAW"
{azimuth}
start = 30.0
components = "xz"
[run]
duration = 6.0
dt = 0.001
output_dt = 0.01
{rest}
"#
    )
}

/// The case text parsed as if it were a file of `cases/three-component/`.
fn parse(text: &str) -> Result<rockslide::case::Case, rockslide::error::InputErrors> {
    parse_case(&repo("cases/three-component/azimuth-test.toml"), text)
}

fn run(text: &str) -> CaseResult {
    run_case(parse(text).expect("the case loads")).expect("the case runs")
}

const ENGINES: &str = "[engines.predictor-corrector]\n[engines.fe]\n[engines.rapier]\n\
    [[tolerance]]\nquantity = \"peak_abs_sliding\"\npercent = 100\n";

fn sweep(r: &CaseResult) -> &AzimuthSweep {
    r.azimuths
        .as_deref()
        .expect("a case with a set has a sweep")
}

#[test]
fn a_set_at_an_azimuth_is_the_case_at_that_azimuth_bit_for_bit_and_its_maxima_are_the_table_s() {
    let set = run(&case_text("x_azimuths_deg = [0, 90, 210, 300]", ENGINES));
    let single = run(&case_text("x_azimuth_deg = 90.0", ENGINES));
    let s = sweep(&set);
    assert_eq!(s.span_deg, 360.0);
    assert_eq!(s.peak_key, "peak_abs_sliding");
    assert_eq!(s.residual_key, "residual_sliding");
    assert_eq!(s.participants[0], REFERENCE);
    assert_eq!(s.participants.len(), 1 + single.runs.len());
    let at_90 = s.points.iter().find(|p| p.azimuth_deg == 90.0).unwrap();
    let bits = |x: Option<f64>| x.map(f64::to_bits);
    let reference = &single.reference.as_ref().unwrap().responses;
    assert_eq!(
        bits(at_90.figures[0].peak_sliding),
        bits(reference.get("peak_abs_sliding").copied())
    );
    assert_eq!(
        bits(at_90.figures[0].residual_sliding),
        bits(reference.get("residual_sliding").copied())
    );
    for (run, responses) in single.runs.iter().zip(&single.run_responses) {
        let f = at_90
            .figures
            .iter()
            .find(|f| f.participant == run.label())
            .unwrap();
        assert!(run.status.completed(), "{}", run.label());
        assert_eq!(
            bits(f.peak_sliding),
            bits(responses.get("peak_abs_sliding").copied()),
            "{}",
            run.label()
        );
        assert_eq!(
            bits(f.residual_sliding),
            bits(responses.get("residual_sliding").copied()),
            "{}",
            run.label()
        );
    }
    // the maxima: the largest of each column, at its first argmax; the reference's is
    // at least its value at every azimuth
    for (i, m) in s.maxima.iter().enumerate() {
        let column: Vec<f64> = s
            .points
            .iter()
            .map(|p| p.figures[i].peak_sliding.unwrap())
            .collect();
        let largest = column.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let argmax = column.iter().position(|&v| v == largest).unwrap();
        let max = m.peak_sliding.unwrap();
        assert_eq!(max.value.to_bits(), largest.to_bits(), "{}", m.participant);
        assert_eq!(max.azimuth_deg, s.points[argmax].azimuth_deg);
        if m.participant == REFERENCE {
            assert!(column.iter().all(|&v| max.value >= v));
            assert_eq!(s.governing, argmax, "the reference's argmax governs");
        }
    }
    // the case's own runs are the governing azimuth's
    let governing = &s.points[s.governing];
    for (run, responses) in set.runs.iter().zip(&set.run_responses) {
        let f = governing
            .figures
            .iter()
            .find(|f| f.participant == run.label())
            .unwrap();
        assert_eq!(
            bits(f.peak_sliding),
            bits(responses.get("peak_abs_sliding").copied())
        );
    }
    assert!(
        set.gate_passed(),
        "{:?}",
        rockslide::verdict::failures(&[set])
    );
}

#[test]
fn along_one_axis_the_opposite_azimuth_is_the_other_polarity() {
    let r = run(&case_text(
        "x_azimuths_deg = [30, 210]",
        "[engines.predictor-corrector]\n[[tolerance]]\nquantity = \"peak_abs_sliding\"\npercent = 100\n",
    ));
    let s = sweep(&r);
    let (a, b) = (&s.points[0].figures[0], &s.points[1].figures[0]);
    let (pa, pb) = (a.peak_sliding.unwrap(), b.peak_sliding.unwrap());
    let (ra, rb) = (a.residual_sliding.unwrap(), b.residual_sliding.unwrap());
    assert!(pa > 1e-3, "the scene slides: {pa}");
    assert!((pa - pb).abs() <= 1e-9 * pa, "{pa} vs {pb}");
    assert!((ra + rb).abs() <= 1e-9 * pa, "{ra} vs {rb}");
    assert!(ra.abs() > 1e-4, "a residual to change sign: {ra}");
}

#[test]
fn a_check_that_fails_at_one_azimuth_fails_the_gate_and_names_it() {
    // the predictor-corrector's peak sliding within 1e-9 % of the exact one: it fails at
    // every azimuth and on the maximum
    let rest = "[engines.predictor-corrector]\n[[tolerance]]\nquantity = \"peak_abs_sliding\"\n\
                percent = 1e-9\n";
    let r = run(&case_text("x_azimuths_deg = [0, 120]", rest));
    let failures = rockslide::verdict::failures(std::slice::from_ref(&r));
    assert!(!r.gate_passed());
    for a in [0, 120] {
        let here = format!("at x_azimuth_deg = {a}");
        assert!(
            failures.iter().any(|f| f.field.ends_with(&here)),
            "{here}: {failures:?}"
        );
    }
    assert!(
        failures
            .iter()
            .any(|f| f.field.ends_with("maximum over x_azimuths_deg")),
        "{failures:?}"
    );
    let record = CaseRecord::of(&r);
    let sweep = record.azimuths.expect("result.json carries the set");
    assert_eq!(sweep.points.len(), 2);
    assert_eq!(sweep.points[1].azimuth_deg, 120.0);
    assert!(!record.gate_passed);
}

/// The first error of a case text, as `field: reason` with its line.
fn error_of(azimuths: &str) -> (String, String, Option<usize>) {
    let text = case_text(azimuths, "[engines.predictor-corrector]\n");
    let errors = parse(&text).expect_err("a bad set is refused");
    let e = &errors.0[0];
    (e.field.clone(), e.reason.clone(), e.line)
}

#[test]
fn a_bad_set_is_a_located_error() {
    let line = case_text("@", "")
        .lines()
        .position(|l| l == "@")
        .map(|i| i + 1);
    for (set, field, says) in [
        (
            "x_azimuths_deg = []",
            "excitation.station.x_azimuths_deg",
            "is empty",
        ),
        (
            "x_azimuths_deg = [0, nan]",
            "excitation.station.x_azimuths_deg[1]",
            "finite",
        ),
        (
            "x_azimuths_deg = [0, 360]",
            "excitation.station.x_azimuths_deg[1]",
            "up to (not including) 360",
        ),
        (
            "x_azimuths_deg = [-15]",
            "excitation.station.x_azimuths_deg[0]",
            "from 0",
        ),
        (
            "x_azimuths_deg = [30, 60, 30]",
            "excitation.station.x_azimuths_deg[2]",
            "again (also at [0])",
        ),
        (
            "x_azimuths_deg = [0, \"north\"]",
            "excitation.station.x_azimuths_deg[1]",
            "must be a number",
        ),
        (
            "x_azimuths_deg = { step = 7 }",
            "excitation.station.x_azimuths_deg.step",
            "divides 360",
        ),
        (
            "x_azimuths_deg = { step = 0.5 }",
            "excitation.station.x_azimuths_deg.step",
            "more than the 360",
        ),
        (
            "x_azimuths_deg = [0, 90]\nx_azimuth_deg = 90.0",
            "excitation.station.x_azimuths_deg",
            "cannot be given with x_azimuth_deg",
        ),
    ] {
        let (f, reason, at) = error_of(set);
        assert_eq!(f, field, "{set}: {reason}");
        assert!(reason.contains(says), "{set}: {reason}");
        assert!(at.is_some() && at >= line, "{set}: line {at:?}");
    }
}

#[test]
fn a_plan_scene_spans_180_degrees_and_a_step_expands_to_the_span() {
    let plan = |set: &str| {
        case_text(set, "[engines.fe]\n").replace("components = \"xz\"", "components = \"xyz\"")
    };
    let (f, reason, _) = {
        let errors = parse(&plan("x_azimuths_deg = [0, 180]")).expect_err("180 is 0 mirrored");
        let e = &errors.0[0];
        (e.field.clone(), e.reason.clone(), e.line)
    };
    assert_eq!(f, "excitation.station.x_azimuths_deg[1]");
    assert!(reason.contains("up to (not including) 180"), "{reason}");
    let case = parse(&plan("x_azimuths_deg = { step = 15 }")).unwrap();
    let set = case.azimuths.as_ref().unwrap();
    let expected: Vec<f64> = (0..12).map(|i| 15.0 * i as f64).collect();
    assert_eq!(set.degrees, expected);
    assert_eq!(case.azimuth_count(), 12);
    let axis = parse(&case_text("x_azimuths_deg = { step = 30 }", "")).unwrap();
    assert_eq!(axis.azimuth_count(), 12);
    assert_eq!(axis.azimuths.as_ref().unwrap().degrees[11], 330.0);
}

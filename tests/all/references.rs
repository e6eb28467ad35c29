//! The references against each other and against an independent quadrature: rockslide
//! shall anchor its engines on solutions that are themselves verified.

use crate::common;

use rockslide::case::Model;
use rockslide::reference::{Duhamel, EpoExact, ExactSolution, SineForcing};

fn max_rel_diff(
    a: &dyn ExactSolution,
    b: &dyn ExactSolution,
    duration: f64,
    channel: usize,
) -> f64 {
    let (mut ra, mut rb) = (vec![0.0; 8], vec![0.0; 8]);
    let (mut peak, mut diff) = (0.0_f64, 0.0_f64);
    for i in 0..=4000 {
        let t = duration * i as f64 / 4000.0;
        a.eval(t, &mut ra);
        b.eval(t, &mut rb);
        peak = peak.max(rb[channel].abs());
        diff = diff.max((ra[channel] - rb[channel]).abs());
    }
    diff / peak
}

/// With μ = ∞ the event-driven elastic-plastic solution never slips and must equal the
/// Duhamel closed form (two different formulations: state transition from each event vs
/// Chopra's transient + steady state). Required: 1e-9; measured 2.5e-16 (mass
/// force) and 8.0e-17 (support displacement), so the bound is 1e-13.
#[test]
fn exact_elastic_plastic_equals_duhamel_without_slip() {
    for (name, from) in [
        ("linear-sdof", "mu = inf"),
        ("pepo-ground-disp", "mu = 0.5\n\n[model.double]"),
    ] {
        let case = if name == "linear-sdof" {
            common::case(name)
        } else {
            common::case_with(name, from, "mu = inf\n\n[model.double]")
        };
        let Model::Oscillator(osc) = &case.scene.model else {
            panic!()
        };
        let forcing = SineForcing::of(&case.scene.excitation, osc.mass).unwrap();
        let exact = EpoExact::new(osc, forcing.clone(), case.run.duration).unwrap();
        let duhamel = Duhamel::new(osc, forcing, case.run.duration).unwrap();
        assert_eq!(exact.slips().len(), 0);
        let d = max_rel_diff(&exact, &duhamel, case.run.duration, 2);
        assert!(d < 1e-13, "{name}: relative difference {d:e}");
        let dv = max_rel_diff(&exact, &duhamel, case.run.duration, 4);
        assert!(dv < 1e-13, "{name}: velocity difference {dv:e}");
    }
}

/// The Duhamel closed form against a direct composite-Simpson quadrature of the Duhamel
/// integral x(t) = 1/(Mω) ∫ F(τ) sin ω(t − τ) dτ (undamped, mass force). With 20,000
/// panels the quadrature error is ~1e-15 relative; measured agreement 4.7e-15.
#[test]
fn duhamel_closed_form_equals_quadrature() {
    let case = common::case("linear-sdof");
    let Model::Oscillator(osc) = &case.scene.model else {
        panic!()
    };
    let forcing = SineForcing::of(&case.scene.excitation, osc.mass).unwrap();
    let duhamel = Duhamel::new(osc, forcing.clone(), 1.0).unwrap();
    let w = osc.omega();
    let mut out = vec![0.0; 8];
    let mut worst = 0.0_f64;
    for t in [0.05_f64, 0.13, 0.2, 0.31, 0.77, 1.0] {
        let upper: f64 = t.min(forcing.td);
        let n = 20_000;
        let h = upper / n as f64;
        let f = |tau: f64| forcing.p0 * (forcing.theta * tau).sin() * (w * (t - tau)).sin();
        let mut sum = f(0.0) + f(upper);
        for i in 1..n {
            sum += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        let x = sum * h / 3.0 / (osc.mass * w);
        duhamel.eval(t, &mut out);
        worst = worst.max((out[2] - x).abs() / 1.754935e-3);
    }
    assert!(worst < 2e-14, "quadrature vs closed form: {worst:e}");
}

/// Properties the exact solution must have: |R| ≤ Ru everywhere, slip only while
/// |R| = Ru, and friction work ≥ 0 (slip increments have the sign of R).
#[test]
fn exact_solution_respects_the_friction_law() {
    for name in ["pepo-mass-accel", "pepo-ground-disp"] {
        let case = common::case(name);
        let Model::Oscillator(osc) = &case.scene.model else {
            panic!()
        };
        let forcing = SineForcing::of(&case.scene.excitation, osc.mass).unwrap();
        let exact = EpoExact::new(osc, forcing, case.run.duration).unwrap();
        let ru = osc.friction_limit();
        let mut prev = exact.state(0.0);
        for i in 1..=100_000 {
            let s = exact.state(i as f64 * 1e-5);
            assert!(
                s.2.abs() <= ru * (1.0 + 1e-12),
                "{name}: |R| = {} > Ru",
                s.2
            );
            let dslip = s.3 - prev.3;
            if dslip.abs() > 1e-15 {
                // a sample pair may straddle a stop event: one end is at the limit
                let r = if s.2.abs() >= prev.2.abs() {
                    s.2
                } else {
                    prev.2
                };
                assert!(r.abs() >= ru * (1.0 - 1e-9), "{name}: slip below the limit");
                assert!(dslip * r > 0.0, "{name}: negative friction work");
            }
            prev = s;
        }
    }
}

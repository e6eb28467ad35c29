//! The rigid-block references on the case files, checked against closed forms derived
//! here independently: Newmark's slide start and post-pulse slide (rigid-plastic block),
//! Housner's onset of rocking and the linearised free-rocking impact time.

use std::path::Path;

use rockslide::case::{Model, load_case};
use rockslide::reference::{HousnerRocking, NewmarkBlock, SineForcing};
use rockslide::suite::solve_reference;

/// The sliding-block case: slide starts at asin(μg/A)/θ; after the pulse the relative
/// velocity decays at μg, so the slide stops at t_end = td + v(td)/μg and the final slide
/// is u(td) + v(td)²/(2μg) — both checked against the event-driven reference.
#[test]
fn newmark_block_on_its_case() {
    let c = load_case(Path::new("cases/rigid-sliding-block.toml")).unwrap();
    let Model::RigidBlock(b) = &c.scene.model else {
        panic!("rigid block")
    };
    let f = SineForcing::of(&c.scene.excitation, b.mass).unwrap();
    let sol = NewmarkBlock::new(b, f.clone(), c.run.duration).unwrap();
    let (a, th, mug): (f64, f64, f64) = (4.905, 2.0 * std::f64::consts::PI, 0.2 * 9.81);
    let slides = sol.slides();
    assert_eq!(slides.len(), 1, "one slide: {slides:?}");
    assert!((slides[0].0 - (mug / a).asin() / th).abs() < 1e-12);
    let td = f.td;
    let (u_td, v_td) = sol.state(td);
    assert!(v_td < 0.0, "the block lags the ground");
    let t_end = td + v_td.abs() / mug;
    assert!(
        (slides[0].1 - t_end).abs() < 1e-9,
        "{} vs {t_end}",
        slides[0].1
    );
    let u_end = u_td - v_td * v_td / (2.0 * mug);
    assert!((sol.state(c.run.duration).0 - u_end).abs() < 1e-12);
    // and the suite picks Newmark for this case
    assert!(
        solve_reference(&c)
            .unwrap()
            .solution
            .method()
            .starts_with("Newmark")
    );
}

/// The pulse case rocks: rocking starts when |ag| first exceeds g·tan α.
#[test]
fn housner_pulse_starts_rocking_at_the_overturning_threshold() {
    let c = load_case(Path::new("cases/housner-pulse.toml")).unwrap();
    let r = solve_reference(&c).unwrap();
    assert!(r.solution.method().starts_with("Housner"));
    // ag = 0.3g sin(4πt) reaches g·tan α = 0.2 g at t = asin(2/3)/(4π) = 0.058 s
    let t_on = (2.0_f64 / 3.0).asin() / (4.0 * std::f64::consts::PI);
    let mut phi = [0.0; 5];
    r.solution.eval(t_on - 1e-3, &mut phi);
    assert_eq!(phi[0], 0.0, "at rest before the threshold");
    r.solution.eval(t_on + 0.02, &mut phi);
    // ground pushes right: the inertial force tips the block left, pivot on the left
    // corner, rotation counter-clockwise (positive)
    assert!(phi[0] > 0.0, "rocking after the threshold: {}", phi[0]);
}

/// Free rocking of a slender block from θ0: linearised Housner gives the first impact at
/// t1 = acosh(α/(α − θ0))/p, p = √(3g/4R); the nonlinear reference must approach it as
/// α → 0 (measured relative gap 1.14e-3 at α = 0.2, 1.17e-5 at α = 0.02: second order, ×97).
#[test]
fn free_rocking_tends_to_the_linearised_closed_form() {
    let none = SineForcing {
        p0: 0.0,
        theta: 1.0,
        td: 0.0,
        velocity_jumps: vec![],
        ground_amplitude: None,
    };
    let mut gaps = Vec::new();
    for b in [0.2, 0.02] {
        let block = rockslide::case::RigidBlock {
            mass: 1.0,
            gravity: 9.81,
            half_width: b,
            half_height: 1.0,
            mu: 10.0,
            initial_tilt: 0.5 * b.atan(),
        };
        let sol = HousnerRocking::new(&block, none.clone(), 6.0).unwrap();
        let alpha = b.atan();
        let p = (3.0 * 9.81 / (4.0 * b.hypot(1.0))).sqrt();
        let t_lin = (alpha / (alpha - block.initial_tilt)).acosh() / p;
        let gap = (sol.impacts[0] / t_lin - 1.0).abs();
        println!(
            "α = {alpha}: nonlinear {} s, linearised {t_lin} s, gap {gap:.2e}",
            sol.impacts[0]
        );
        gaps.push(gap);
    }
    assert!(gaps[0] < 1.5e-3 && gaps[1] < 2e-5);
    assert!(
        gaps[1] < gaps[0] / 50.0,
        "the gap shrinks like α²: {gaps:?}"
    );
}

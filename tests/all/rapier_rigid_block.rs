//! The rapier engine on rigid-block scenes against the independent references:
//! Newmark's sliding block (residual sliding, friction force, slip end) and Housner's
//! rocking block (impact times, tilt after an impact), both ground-motion routes, and
//! bit-identical determinism. Tolerances are the measured errors (stated at each assert,
//! at the settings of the case files) with a small margin, so a regression fails.

use std::path::Path;

use rockslide::analysis::responses;
use rockslide::case::{Case, load_case};
use rockslide::engine::Engine;
use rockslide::engine::rigid_body::Rapier;
use rockslide::engine::rigid_body::variant as rapier_variant;
use rockslide::reference;
use rockslide::suite::solve_reference;

fn case(name: &str) -> Case {
    load_case(Path::new(&format!("cases/{name}.toml"))).expect("case loads")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// rockslide shall slide a rigid block with exactly the scene's μ (Newmark 1965).
#[test]
fn sliding_block_matches_newmark() {
    let c = case("rigid-sliding-block");
    let reference = solve_reference(&c).unwrap();
    let r_res = reference.responses["residual_sliding"];
    let mu_mg = 0.2 * 1000.0 * 9.81;
    // measured at dt = 1 ms, 4 substeps, Simplified friction:
    //   kinematic ground: residual −0.2815668 m vs −0.2809445 m (0.22 %), inertial 0.005 %
    for (variant, tol) in [
        (rapier_variant::KINEMATIC_GROUND, 0.003),
        (rapier_variant::INERTIAL_FORCE, 1e-4),
    ] {
        let run = Rapier.run(&c, variant, c.dt_for("rapier")).unwrap();
        assert!(run.status.completed());
        let r = responses(&run.trace);
        let e = rel(r["residual_sliding"], r_res);
        println!(
            "{variant}: residual {} vs {r_res} ({e:.2e})",
            r["residual_sliding"]
        );
        assert!(e < tol, "{variant}: residual sliding off by {e:.3e}");
        // friction force while sliding = μMg: measured peak 1962.37 N vs 1962 N (0.02 %)
        let e = rel(r["peak_resistance"], mu_mg);
        println!(
            "{variant}: peak resistance {} ({e:.2e})",
            r["peak_resistance"]
        );
        assert!(e < 5e-4, "{variant}: friction force off by {e:.3e}");
        // slip end read the same way off both traces (slip-rate threshold): measured
        // equal to the step (0.828 s both)
        let sampled = reference::sample(reference.solution.as_ref(), &run.trace.time);
        let end_ref = responses(&sampled)["slip_end"];
        let end = r["slip_end"];
        println!("{variant}: slip end {end} vs {end_ref}");
        assert!(
            (end - end_ref).abs() <= 1.01e-3,
            "{variant}: slip end {end} vs {end_ref}"
        );
    }
}

/// The Coulomb friction model of rapier gives a lower effective μ on this block: the
/// reason the engine defaults to the Simplified model. Measured: 0.1745 instead of 0.2.
#[test]
fn coulomb_friction_model_undershoots_mu() {
    let text = std::fs::read_to_string("cases/rigid-sliding-block.toml")
        .unwrap()
        .replace(
            "[engines.rapier]",
            "[engines.rapier]\nfriction_model = \"coulomb\"",
        );
    let c = rockslide::case::parse_case(Path::new("coulomb.toml"), &text).unwrap();
    let run = Rapier
        .run(&c, rapier_variant::INERTIAL_FORCE, 1e-3)
        .unwrap();
    let mu_eff = responses(&run.trace)["peak_resistance"] / (1000.0 * 9.81);
    println!("effective μ with the Coulomb model: {mu_eff}");
    assert!((mu_eff - 0.1745).abs() < 0.002, "effective μ {mu_eff}");
}

/// rockslide shall reproduce Housner's impact times and tilt decay of a free-rocking block.
#[test]
fn free_rocking_matches_housner() {
    let c = case("housner-free-rocking");
    let reference = solve_reference(&c).unwrap();
    let run = Rapier
        .run(&c, rapier_variant::FIXED_GROUND, c.dt_for("rapier"))
        .unwrap();
    let r = responses(&run.trace);
    // measured at dt = 1 ms, 16 substeps: first impact 0.49644 s vs 0.49656 s (0.02 %),
    // second 1.3531 s vs 1.3585 s (0.4 %), tilt after the first impact 0.08375 rad vs
    // 0.08434 rad (−0.7 %: rapier's plastic impact loses a little more energy than
    // Housner's r; the gap shrinks slowly with the substep, see docs/rapier-engine.md).
    for (key, tol) in [
        ("first_impact", 5e-4),
        ("second_impact", 6e-3),
        ("peak_tilt_after_impact", 1e-2),
    ] {
        let e = rel(r[key], reference.responses[key]);
        println!(
            "{key}: {} vs {} ({e:.2e})",
            r[key], reference.responses[key]
        );
        assert!(e < tol, "{key} off by {e:.3e}");
    }
    // rapier loses more energy per impact than Housner: the sign is part of the finding
    assert!(r["peak_tilt_after_impact"] < reference.responses["peak_tilt_after_impact"]);
}

/// rockslide shall reproduce the rocking response to a one-sine pulse by both routes.
#[test]
fn pulse_rocking_matches_housner_by_both_routes() {
    let c = case("housner-pulse");
    let reference = solve_reference(&c).unwrap();
    // measured at dt = 1 ms, 16 substeps (kinematic / inertial): first impact +0.46 % /
    // +0.13 %, second −0.49 % / −0.32 %, peak rotation −1.10 % / −0.63 %
    for (variant, tol_first, tol_rot) in [
        (rapier_variant::KINEMATIC_GROUND, 6e-3, 1.4e-2),
        (rapier_variant::INERTIAL_FORCE, 2e-3, 8e-3),
    ] {
        let run = Rapier.run(&c, variant, c.dt_for("rapier")).unwrap();
        let r = responses(&run.trace);
        for (key, tol) in [
            ("first_impact", tol_first),
            ("second_impact", 6e-3),
            ("peak_rotation", tol_rot),
        ] {
            let e = rel(r[key], reference.responses[key]);
            println!(
                "{variant} {key}: {} vs {} ({e:.2e})",
                r[key], reference.responses[key]
            );
            assert!(e < tol, "{variant}: {key} off by {e:.3e}");
        }
    }
}

/// rockslide shall give a bit-identical trace when the same case runs twice.
#[test]
fn same_case_twice_gives_bit_identical_traces() {
    for (name, variant) in [
        ("housner-pulse", rapier_variant::KINEMATIC_GROUND),
        ("rigid-sliding-block", rapier_variant::INERTIAL_FORCE),
        ("pepo-mass-accel", rapier_variant::APPLIED_FORCE),
    ] {
        let c = case(name);
        let a = Rapier.run(&c, variant, 2e-3).unwrap();
        let b = Rapier.run(&c, variant, 2e-3).unwrap();
        assert_eq!(a.trace.time.len(), b.trace.time.len());
        for (ca, cb) in a.trace.columns.iter().zip(&b.trace.columns) {
            for (x, y) in ca.iter().zip(cb) {
                assert_eq!(x.to_bits(), y.to_bits(), "{name}: traces differ");
            }
        }
    }
}

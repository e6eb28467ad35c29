//! The rapier engine on the paper's RPEPO (rocking body on ten spring-jointed feet):
//! static preload, no creep at rest (the solver trap of the vertical load path through
//! joints), and the two ground-motion routes agreeing. No exact reference exists (SPEC
//! §2); the engine's own convergence is in docs/rapier-engine.md.

use std::path::Path;

use rockslide::analysis::responses;
use rockslide::case::{Case, parse_case};
use rockslide::engine::Engine;
use rockslide::engine::rigid_body::Rapier;

/// The paper's RPEPO (SPEC §1.1) with the given excitation and extra rapier options.
fn rpepo(excitation: &str, duration: f64, options: &str) -> Case {
    let text = format!(
        r#"
[model]
kind = "rocking-body"
mass = 1.0e6
gravity = 9.81
cm_height = 0.625
half_width = 0.5
supports = 10
[model.contact]
kx = 2.4e9
kz = 3.94784e8
mu = 0.5
[excitation]
{excitation}
[run]
duration = {duration}
dt = 0.001
[engines.rapier]
{options}
"#
    );
    parse_case(Path::new("rpepo.toml"), &text).expect("case parses")
}

/// rockslide shall start the RPEPO from static equilibrium and keep it there unloaded.
#[test]
fn rests_in_static_equilibrium_without_creep() {
    let c = rpepo(r#"kind = "none""#, 0.5, "");
    let run = Rapier.run(&c, "fixed-ground", 1e-3).unwrap();
    let t = &run.trace;
    let w = 1.0e6 * 9.81;
    let n0 = t.column("normal").unwrap()[0];
    // measured: normal force 9.8081 MN vs W = 9.81 MN (−0.02 %), base shear 1.1 N
    println!("normal {n0}, shear {}", t.column("base_shear").unwrap()[0]);
    assert!((n0 / w - 1.0).abs() < 5e-4);
    assert!(t.column("base_shear").unwrap()[0].abs() < 100.0);
    // measured: |slide| ≤ 1.5e-11 m over 0.5 s with the default 8 sweeps
    let creep = t
        .column("slide")
        .unwrap()
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    println!("creep {creep:e}");
    assert!(creep < 1e-9, "the loaded feet creep: {creep} m");
}

/// With rapier's default single Gauss–Seidel sweep the loaded feet creep under zero
/// horizontal load (measured 0.39 mm in 0.45 s): why the engine uses 8 for this scene.
#[test]
fn one_sweep_lets_loaded_feet_creep() {
    let c = rpepo(r#"kind = "none""#, 0.5, "pgs_iterations = 1");
    let run = Rapier.run(&c, "fixed-ground", 1e-3).unwrap();
    let creep = responses(&run.trace)["min_sliding"].abs();
    println!("creep with one sweep {creep:e}");
    assert!(creep > 1e-4, "expected creep, got {creep} m");
}

/// rockslide shall offer both ground-motion routes and they shall agree: measured on the
/// support-displacement RPEPO to 1.0 s at dt = 1 ms, peak uplift and rotation differ by
/// < 0.1 %, first full lift-off at the same step.
#[test]
fn ground_routes_agree() {
    let c = rpepo(
        r#"kind = "ground-displacement"
shape = "sine-pulse"
amplitude = 9.939e-4
omega = 31.41592653589793
cycles = 5.0"#,
        1.0,
        "",
    );
    let a = responses(&Rapier.run(&c, "kinematic-ground", 1e-3).unwrap().trace);
    let b = responses(&Rapier.run(&c, "inertial-force", 1e-3).unwrap().trace);
    for key in ["peak_uplift", "peak_rotation", "peak_base_shear"] {
        let e = (a[key] / b[key] - 1.0).abs();
        println!("{key}: {} vs {} ({e:.2e})", a[key], b[key]);
        assert!(e < 2e-3, "{key}: routes differ by {e}");
    }
}

/// rockslide shall give a bit-identical trace twice, also with ten feet and lift-off.
#[test]
fn rpepo_is_deterministic() {
    let c = rpepo(
        r#"kind = "mass-acceleration"
shape = "sine-pulse"
amplitude = 0.981
omega = 31.41592653589793
cycles = 5.0"#,
        1.0,
        "",
    );
    let a = Rapier.run(&c, "applied-force", 2e-3).unwrap();
    let b = Rapier.run(&c, "applied-force", 2e-3).unwrap();
    assert!(
        responses(&a.trace)["peak_uplift"] > 1e-3,
        "the run lifts off"
    );
    for (ca, cb) in a.trace.columns.iter().zip(&b.trace.columns) {
        for (x, y) in ca.iter().zip(cb) {
            assert_eq!(x.to_bits(), y.to_bits());
        }
    }
}

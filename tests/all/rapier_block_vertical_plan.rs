//! rapier's rigid block in plan under a vertical component: the lift-off block of
//! cases/vertical/block-liftoff (a horizontal half-sine of 0.5 g, a downward vertical one of
//! 1.5 g) made a 3D scene, its horizontal pulse along azimuth 30°, on both routes, against
//! the exact planar block with its flight (crates/reference/src/vertical/block.rs) taken
//! along that azimuth: the block slides along its drive, lifts off where g + a_v reaches
//! 0 (the closed form t = asin(2/3)/θ), flies and lands. The plan-motion block reference
//! has no flight, so the block in plan is gated against it only where it stays in contact
//! (cases/three-component/block-ridgecrest-ccc-xyz). Bounds are the measured errors
//! (2026-11-29), stated at each assert, with a small margin.
//!
//! rockslide shall compute the sliding in plan of a rigid block whose vertical ground
//! motion exceeds 1 g, with the airborne phase.

use rockslide::analysis::responses;
use rockslide::case::Case;
use rockslide::engine::rigid_body::Rapier;
use rockslide::engine::rigid_body::variant as rapier_variant;
use rockslide::engine::{Engine, Run, Variant};
use rockslide::suite::solve_reference;

use crate::common::{case, case_edited};

/// The lift-off block as a 3D scene: half-depth 1 m, its horizontal pulse at `deg`°.
fn liftoff_in_plan(deg: f64) -> Case {
    case_edited(
        "vertical/block-liftoff",
        &[
            ("mu = 0.3", "mu = 0.3\nhalf_depth = 1.0"),
            (
                "amplitude = 4.905 ",
                &format!("azimuth_deg = {deg}\namplitude = 4.905 "),
            ),
        ],
    )
}

fn run(c: &Case, variant: Variant) -> Run {
    let r = Rapier.run(c, variant, c.dt_for("rapier")).unwrap();
    assert!(r.status.completed(), "{}", r.status);
    r
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b) / b.abs()
}

/// A plan channel pair (x, y) of a run along azimuth `deg` and across it.
fn along_across(r: &Run, key: &str, deg: f64) -> (Vec<f64>, Vec<f64>) {
    let x = r.trace.column(key).unwrap();
    let y = r.trace.column(&format!("{key}_y")).unwrap();
    let (s, c) = deg.to_radians().sin_cos();
    x.iter()
        .zip(y)
        .map(|(x, y)| (x * c + y * s, -x * s + y * c))
        .unzip()
}

/// rockslide shall compute the sliding in plan of a rigid block that lifts off: rapier's
/// block on both routes against the exact planar block along the drive.
#[test]
fn block_lifting_off_in_plan_against_the_planar_reference_along_its_drive() {
    let deg = 30.0;
    let c = liftoff_in_plan(deg);
    assert!(c.scene.spatial().is_some() && c.scene.vertical().is_some());
    let exact = solve_reference(&case("vertical/block-liftoff")).unwrap();
    let residual = exact.responses["residual_sliding"];
    let uplift = exact.responses["peak_uplift"];
    let liftoff = exact.responses["first_liftoff"];
    // g + a_v = g − 1.5 g·sin θt reaches 0 at sin θt = 2/3 (θ = 2π rad/s)
    let closed_form = (2.0_f64 / 3.0).asin() / (2.0 * std::f64::consts::PI);
    // measured 6.7e-9 s (the reference locates its events by root finding)
    assert!((liftoff - closed_form).abs() < 1e-8, "{liftoff}");
    // measured 2026-11-29 (residual along the drive, peak uplift, first full lift-off
    // − exact): inertial force +1.82e-4, −3.08e-5, +0.86 ms (the output step's
    // resolution); kinematic ground −1.13e-3, +4.51e-3, and its contacts chatter (µm
    // bounces on the ground that drops by a velocity step at every rapier step) from
    // 0.063 s, so its first zero (0.080 s) is not the lift-off and is not gated
    for (variant, bounds) in [
        (rapier_variant::INERTIAL_FORCE, [2e-4, 4e-5, 1e-3]),
        (
            rapier_variant::KINEMATIC_GROUND,
            [1.2e-3, 5e-3, f64::INFINITY],
        ),
    ] {
        let r = run(&c, variant);
        let got = responses(&r.trace);
        let (along, across) = along_across(&r, "slide", deg);
        let across = across.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let e_res = rel(*along.last().unwrap(), residual);
        let e_up = rel(got["peak_uplift"], uplift);
        let d_lift = got["first_liftoff"] - liftoff;
        println!(
            "{variant}: residual along {:.6e} m ({e_res:+.3e}), across {across:.3e} m, peak uplift {:.6e} m ({e_up:+.3e}), first lift-off {:.5} s ({d_lift:+.2e} s)",
            along.last().unwrap(),
            got["peak_uplift"],
            got["first_liftoff"]
        );
        assert!(e_res.abs() < bounds[0], "{variant} residual {e_res}");
        assert!(e_up.abs() < bounds[1], "{variant} uplift {e_up}");
        assert!(d_lift.abs() < bounds[2], "{variant} lift-off {d_lift}");
        // measured 5.7e-15 / 9.4e-16 m: the slide stays along the drive to round-off
        assert!(across < 1e-14, "{variant} across {across}");
        // the contact block's rows [N, |T|, slip, gap]: |T| ≤ μ·N wherever N > 0, the
        // flight's rows carrying no force at all
        let mut worst = f64::NEG_INFINITY;
        for f in r.trace.contacts.values.chunks(4) {
            if f[0] > 0.0 {
                worst = worst.max(f[1] / (0.3 * f[0]) - 1.0);
            } else {
                assert_eq!(f[1], 0.0, "{variant}: friction without a normal force");
            }
        }
        println!("  cone: worst |T|/(μN) − 1 = {worst:e}");
        assert!(worst < 1e-14, "{variant} cone {worst}");
    }
}

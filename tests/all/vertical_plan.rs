//! Vertical motion in a bidirectional (3D) scene: the plan-motion oscillator's friction
//! circle of radius μ·N(t) (crates/reference/src/bidirectional/epo.rs), against the
//! references it must reduce to — the plan reference itself when a_v ≡ 0 (bit for bit
//! with a rigid vertical contact), the planar vertical reference when the motion stays on
//! one axis (azimuth 0, and rotated at 30°) — and a closed form (a constant a_v scales the
//! cone: the onset under a constant plan acceleration moves to μ·(g + a_v)); then the
//! shipped case pepo-pulse-azimuth30-vertical through rapier and fe. Bounds are the
//! measured errors (2026-11-24), stated at each assert, with a small margin.
//!
//! rockslide shall compute the sliding in plan of an elastic-plastic oscillator and a
//! block whose circular friction limit follows the normal force under vertical motion.

use std::path::Path;
use std::sync::Arc;

use crate::common::case;
use rockslide::analysis::responses;
use rockslide::case::{Case, Model, NormalForce, Oscillator, Signal, load_case};
use rockslide::engine::Run;
use rockslide::engine::fe::variant as fe_variant;
use rockslide::engine::rigid_body::variant as rapier_variant;
use rockslide::reference::bidirectional::{PlanBlock, PlanDrive, PlanEpo, rotate};
use rockslide::reference::vertical::{EpoConstants, LinearInputs, VerticalEpo};
use rockslide::suite::solve_reference;

/// The shipped case.
const CASE: &str = "cases/spatial/pepo-pulse-azimuth30-vertical.toml";

/// The planar PEPO with the vertical pulse (dynamic normal force).
fn planar() -> (Case, Oscillator) {
    let c = case("vertical/pepo-mass-accel-vertical");
    let Model::Oscillator(o) = c.scene.model.clone() else {
        unreachable!()
    };
    (c, o)
}

/// `f` sampled every `dt` over [0, end] as a record.
fn record(dt: f64, end: f64, f: impl Fn(f64) -> f64) -> Signal {
    let n = (end / dt).round() as usize;
    let samples: Arc<[f64]> = (0..=n).map(|i| f(i as f64 * dt)).collect();
    Signal::Record {
        dt,
        samples,
        label: "test".into(),
    }
}

/// A mass-acceleration drive `h` along azimuth `deg`, vertical `v` with `normal`.
fn drive(h: &Signal, deg: f64, v: Option<(&Signal, NormalForce)>) -> PlanDrive {
    let th = deg.to_radians();
    let d = PlanDrive::new(
        Some(h.clone()),
        [th.cos(), th.sin()],
        None,
        [-th.sin(), th.cos()],
        1.0,
    );
    match v {
        Some((s, nf)) => d.with_vertical(s.clone()).with_normal_force(nf),
        None => d,
    }
}

/// The planar case's two pulses, sampled every 1 ms as records (linear in between: the
/// inputs on which both references are exact).
fn sampled_pulses(c: &Case) -> (Signal, Signal) {
    let rockslide::case::Excitation::MassAcceleration(h) = &c.scene.excitation else {
        unreachable!()
    };
    let v = &c.scene.vertical().unwrap().signal;
    (
        record(1e-3, 1.2, |t| h.value(t)),
        record(1e-3, 1.2, |t| v.value(t)),
    )
}

#[test]
fn a_vertical_component_of_zero_is_the_plan_reference() {
    let (c, o) = planar();
    let (h, _) = sampled_pulses(&c);
    let zero = record(1e-3, 1.2, |_| 0.0);
    let base = PlanEpo::solve(&o, &drive(&h, 30.0, None), 1.0, 1e-4).unwrap();
    // rigid vertical contact: μ·M·(g + 0) is μ·M·g and Ṙ = 0: bit for bit
    let rigid = PlanEpo::solve(
        &o,
        &drive(&h, 30.0, Some((&zero, NormalForce::QuasiStatic))),
        1.0,
        1e-4,
    )
    .unwrap();
    assert_eq!(base.samples, rigid.samples);
    assert_eq!(base.slips, rigid.slips);
    // Kz: δ starts at g/ωz², whose rounding leaves a vertical vibration of a few ε
    let dynamic = PlanEpo::solve(
        &o,
        &drive(&h, 30.0, Some((&zero, NormalForce::Dynamic))),
        1.0,
        1e-4,
    )
    .unwrap();
    let gap = base
        .samples
        .iter()
        .zip(&dynamic.samples)
        .map(|(a, b)| (a.slip[0] - b.slip[0]).hypot(a.slip[1] - b.slip[1]))
        .fold(0.0, f64::max);
    let peak = base.peak_resultant().0;
    println!(
        "Kz with a_v ≡ 0: largest slip gap {gap:.3e} m of {peak:.6e} m, {} / {} samples",
        dynamic.samples.len(),
        base.samples.len()
    );
    assert_eq!(base.samples.len(), dynamic.samples.len());
    // measured 9.1e-18 m (1.0e-15 of the peak): round-off
    assert!(gap <= 2e-15 * peak, "{gap}");
}

/// The plan reference at `deg` against the planar vertical reference on the same
/// piecewise-linear inputs: the largest |p_plan − p_2D·e₁| and |u_plan − u_2D·e₁| over
/// the planar grid, m, and the residual slip.
fn against_planar(normal: NormalForce, deg: f64, step: f64) -> (f64, f64) {
    let (c, o) = planar();
    let (h, v) = sampled_pulses(&c);
    let plan = PlanEpo::solve(&o, &drive(&h, deg, Some((&v, normal))), 1.0, step).unwrap();
    let inputs =
        LinearInputs::sample(1e-3, 1.0, "records".into(), |t| (h.value(t), v.value(t))).unwrap();
    let constants = EpoConstants {
        m: o.mass,
        k: o.contact.kx,
        mu: o.contact.mu,
        g: o.gravity,
        kz: match normal {
            NormalForce::Dynamic => Some(o.contact.kz),
            NormalForce::QuasiStatic => None,
        },
    };
    let exact = VerticalEpo::new(constants, inputs).unwrap();
    let e = rotate([1.0, 0.0], deg.to_radians());
    let mut worst: f64 = 0.0;
    for (i, s) in exact.history.states.iter().enumerate() {
        let t = i as f64 * 1e-3;
        let (u, _, p) = plan.state(t);
        let du = (u[0] - s.u * e[0]).hypot(u[1] - s.u * e[1]);
        let dp = (p[0] - s.up * e[0]).hypot(p[1] - s.up * e[1]);
        worst = worst.max(du).max(dp);
    }
    let residual = exact.history.states.last().unwrap().up;
    println!(
        "{normal:?} at {deg}°, step {step:e}: largest gap {worst:.3e} m, residual slip {residual:.6e} m, {} / {} slips",
        plan.slips.len(),
        exact.history.slips.len()
    );
    assert_eq!(plan.slips.len(), exact.history.slips.len());
    (worst, residual)
}

#[test]
fn on_one_axis_it_is_the_planar_vertical_reference_with_kz() {
    let mut gaps = Vec::new();
    for step in [4e-4, 2e-4, 1e-4] {
        gaps.push(against_planar(NormalForce::Dynamic, 0.0, step).0);
    }
    for w in gaps.windows(2) {
        println!("observed order {:.2}", (w[0] / w[1]).log2());
    }
    let (turned, residual) = against_planar(NormalForce::Dynamic, 30.0, 1e-4);
    // measured 4.2e-12, 3.0e-13, 2.5e-14 m (orders 3.8, 3.6: RK4) of a 17.4 mm slip;
    // at 30° the same 2.5e-14 m
    assert!(gaps[2] < 1e-9 * residual.abs(), "{gaps:?}");
    assert!((turned - gaps[2]).abs() < 1e-3 * residual.abs(), "{turned}");
}

#[test]
fn on_one_axis_it_is_the_planar_vertical_reference_rigid() {
    let (gap, residual) = against_planar(NormalForce::QuasiStatic, 0.0, 1e-4);
    let (turned, _) = against_planar(NormalForce::QuasiStatic, 30.0, 1e-4);
    // measured 9.2e-15 and 9.1e-15 m of a 16.4 mm slip (RK4 at 0.1 ms)
    assert!(gap < 1e-9 * residual.abs(), "{gap}");
    assert!(turned < 1e-9 * residual.abs(), "{turned}");
}

/// A step of mass acceleration d along 30° under a constant a_v (rigid vertical contact):
/// stuck, K·|u| = M·d·(1 − cos ωt), so the slip starts where that reaches μ·M·(g + a_v):
/// cos ωt* = 1 − μ·(g + a_v)/d.
#[test]
fn a_constant_vertical_acceleration_moves_the_onset_to_mu_g_plus_av() {
    let (_, o) = planar();
    let (d, av) = (0.5, -0.3);
    let h = record(0.01, 1.2, |_| d);
    let v = record(0.01, 1.2, |_| av);
    let plan = PlanEpo::solve(
        &o,
        &drive(&h, 30.0, Some((&v, NormalForce::QuasiStatic))),
        0.3,
        1e-4,
    )
    .unwrap();
    let limit = o.contact.mu * (o.gravity + av);
    let onset = (1.0 - limit / d).acos() / o.omega();
    let got = plan.slips[0].0;
    println!(
        "onset {got:.15} s, closed form {onset:.15} s ({:+.3e} s); without a_v it would be {:.6} s",
        got - onset,
        (1.0 - o.contact.mu * o.gravity / d).acos() / o.omega()
    );
    // measured +3.2e-14 s (the bisection's last float); without a_v: 0.05 s
    assert!((got - onset).abs() < 1e-12, "{got} vs {onset}");
    // the block: a ramp d = r·t starts sliding at |d| = μ·(g + a_v)
    let ramp = record(0.01, 1.2, |t| 2.0 * t);
    let block = PlanBlock::solve(
        0.5,
        1.0,
        &drive(&ramp, 30.0, None).with_vertical(v.clone()),
        0.5,
        1e-4,
    )
    .unwrap();
    let start = block.slides[0].0;
    println!(
        "block onset {start:.15} s, closed form {:.15} s",
        limit / 2.0
    );
    // measured 0.175 s to the digits printed (μ·(g + a_v)/r = 0.35/2)
    assert!((start - limit / 2.0).abs() < 1e-12, "{start}");
}

fn run(c: &Case, engine: &str, variant: rockslide::engine::Variant) -> Run {
    let e = rockslide::engine::all()
        .into_iter()
        .find(|e| e.id() == engine)
        .unwrap();
    let r = e.run(c, variant, c.dt_for(engine)).unwrap();
    assert!(r.status.completed(), "{}", r.status);
    r
}

#[test]
fn the_shipped_case_against_its_reference() {
    let c = load_case(Path::new(CASE)).unwrap();
    let reference = solve_reference(&c).unwrap();
    let r = &reference.responses;
    println!(
        "reference: peak {:.9e} residual {:.9e} resultant {:.9e}, slip {:.6}–{:.6} s",
        r["peak_relative_displacement"],
        r["residual_sliding"],
        r["residual_resultant_sliding"],
        r["slip_start"],
        r["slip_end"]
    );
    // the planar vertical case's reference (its pulses sampled every 0.1 ms, linear in
    // between, against the plan reference's sine pulses): the same slip, rotated
    let planar = solve_reference(&case("vertical/pepo-mass-accel-vertical")).unwrap();
    let rel = |a: f64, b: f64| (a - b) / b.abs();
    let gap = rel(
        r["residual_resultant_sliding"],
        planar.responses["residual_sliding"],
    );
    println!(
        "planar vertical reference: residual {:.9e} ({gap:+.3e})",
        planar.responses["residual_sliding"]
    );
    // measured +5.3e-7: the planar reference's 0.1 ms sampling of the pulses
    assert!(gap.abs() < 1e-6, "{gap}");
    // measured: rapier −8.7e-8 (peak), +3.5e-7 (slips); fe −6.7e-5 (the planar vertical
    // case's fe errors); events at the 1 ms output step's resolution: −0.80 ms, +0.24 ms
    for (engine, variant, bound) in [
        ("rapier", rapier_variant::APPLIED_FORCE, 1e-6),
        ("fe", fe_variant::SINGLE_ELEMENT, 7e-5),
    ] {
        let run = run(&c, engine, variant);
        let got = responses(&run.trace);
        for k in [
            "peak_relative_displacement",
            "residual_sliding",
            "peak_resultant_sliding",
            "residual_resultant_sliding",
        ] {
            let e = rel(got[k], r[k]);
            println!("{engine} {k}: {} vs {} ({e:+.3e})", got[k], r[k]);
            assert!(e.abs() < bound, "{engine} {k}: {e}");
        }
        let start = got["slip_start"] - r["slip_start"];
        let end = got["slip_end"] - r["slip_end"];
        println!("{engine}: slip start {start:+.2e} s, end {end:+.2e} s");
        assert!((-1e-3..=0.0).contains(&start) && (0.0..=3e-4).contains(&end));
        assert_eq!(got["slip_episodes"], r["slip_episodes"]);
    }
}

/// The planar RPEPO with its vertical pulse as a 3D scene: two rows of supports at
/// y = ±0.3 m, each support's stiffnesses as given, the pulse at `azimuth`°.
fn rpepo_vertical_3d(stiffness: (&str, &str), azimuth: f64) -> Case {
    let path = Path::new("cases/vertical/rpepo-mass-accel-vertical.toml");
    let mut text = std::fs::read_to_string(path).unwrap();
    for (from, to) in [
        ("[model]\n", "[model]\nhalf_depth = 0.3\nsupport_rows = 2\n"),
        ("kx = 2.4e9 ", stiffness.0),
        ("kz = 3.94784e8 ", stiffness.1),
        (
            "cycles = 5.0                 # 1.0 s",
            &format!("cycles = 5.0\nazimuth_deg = {azimuth}"),
        ),
    ] {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    rockslide::case::parse_case(path, &text).unwrap()
}

/// Largest |a − b| over two equally long columns, and the peak |b|.
fn gap_and_peak(a: &Run, b: &Run, key: &str) -> (f64, f64) {
    let (x, y) = (a.trace.column(key).unwrap(), b.trace.column(key).unwrap());
    assert_eq!(x.len(), y.len());
    let gap = x
        .iter()
        .zip(y)
        .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
    (gap, y.iter().fold(0.0_f64, |m, p| m.max(p.abs())))
}

/// In one plane (pulse at 0°, each planar support split into two rows carrying half its
/// stiffnesses) rapier's 3D grid under the vertical pulse is its planar applied-force
/// RPEPO under it: the same −M·a_v over each step, the same supports.
#[test]
fn rocking_grid_in_plane_under_vertical_motion_is_the_planar_rpepo() {
    let plane = run(
        &load_case(Path::new("cases/vertical/rpepo-mass-accel-vertical.toml")).unwrap(),
        "rapier",
        rapier_variant::APPLIED_FORCE,
    );
    let grid = run(
        &rpepo_vertical_3d(("kx = 1.2e9 ", "kz = 1.97392e8 "), 0.0),
        "rapier",
        rapier_variant::APPLIED_FORCE,
    );
    // measured over the 2 s: CM x 1.27e-12 m of 7.5 mm, CM z 5.2e-14 m of 3.6 mm,
    // rotation 8.6e-9 of 11.0 mrad, sliding 3.0e-11 m of 4.9 mm, uplift 1.14e-8 m of
    // 3.7 mm (the 6-DOF body's quaternion update against the planar angle, through the
    // impacts, as without the vertical pulse)
    for (key, bound) in [
        ("cm_x", 2e-12),
        ("cm_z", 1e-13),
        ("rotation", 1e-8),
        ("slide", 5e-11),
        ("uplift", 1.5e-8),
    ] {
        let (gap, peak) = gap_and_peak(&grid, &plane, key);
        println!("{key}: max |Δ| {gap:.3e} of peak {peak:.3e}");
        assert!(gap < bound, "{key}: {gap}");
    }
}

/// The 10 × 2 grid at 30° under the vertical pulse (each support the RPEPO's contact):
/// rapier against fe's 3D model (no exact answer for rocking; the two engines agree to
/// 0.03–0.15 % without the vertical pulse, tests/all/rapier_space.rs).
#[test]
fn rocking_grid_at_30_degrees_under_vertical_motion_against_fe() {
    let c = rpepo_vertical_3d(("kx = 2.4e9 ", "kz = 3.94784e8 "), 30.0);
    let fe = run(&c, "fe", fe_variant::SINGLE_ELEMENT);
    let r = run(&c, "rapier", rapier_variant::APPLIED_FORCE);
    let fewest = |x: &Run| {
        x.trace
            .column("contacts")
            .unwrap()
            .iter()
            .fold(f64::INFINITY, |m, c| m.min(*c))
    };
    println!(
        "fewest supports in contact: rapier {}, fe {}",
        fewest(&r),
        fewest(&fe)
    );
    // the body never leaves all its supports
    assert!(fewest(&r) > 0.0 && fewest(&fe) > 0.0);
    // measured: CM x / y −0.034 / −0.056 %, CM z −0.52 % (of 0.20 mm), resultant sliding
    // +0.127 % (of 10 µm), uplift +0.005 %, rotation −0.034 %, rotation x −0.056 %
    for (key, bound) in [
        ("cm_x", 5e-4),
        ("cm_y", 7e-4),
        ("cm_z", 6e-3),
        ("slide_resultant", 1.5e-3),
        ("uplift", 1e-4),
        ("rotation", 5e-4),
        ("rotation_x", 7e-4),
    ] {
        let peak = |x: &Run| {
            x.trace
                .column(key)
                .unwrap()
                .iter()
                .fold(0.0_f64, |m, p| m.max(p.abs()))
        };
        let (a, b) = (peak(&r), peak(&fe));
        println!(
            "{key}: rapier {a:.4e} fe {b:.4e} ({:+.3} %)",
            100.0 * (a - b) / b
        );
        assert!(((a - b) / b).abs() < bound, "{key}");
    }
}

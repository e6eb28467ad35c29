//! The energy audit (input = kinetic + strain + friction + damping) closes on the exact
//! reference and on the predictor-corrector, to tolerances measured here.
//!
//! Requirement (docs/sweep-and-stability.md): "An energy audit (input = kinetic + strain + friction +
//! damping) per run shows each engine's physical consistency."

use std::path::Path;

use rockslide::analysis::energy::audit;
use rockslide::case::{Model, load_case};
use rockslide::engine::predictor_corrector::variant as pc_variant;
use rockslide::engine::{self, Arrangement};
use rockslide::suite::solve_reference;

/// The exact references sampled every 1e-5 s: the audit's trapezoidal ∫F dx is the only
/// approximation, so it closes to O(h²). Measured relative errors: PEPO 2.65e-9, linear
/// SDOF (Duhamel) 6.09e-9, PEPO support displacement 8.89e-9 (its two ground-velocity
/// jumps booked as impulse work ½M(v⁺² − v⁻²)).
#[test]
fn audit_closes_on_the_exact_references() {
    for (file, tol) in [
        ("cases/pepo-mass-accel.toml", 5e-9),
        ("cases/linear-sdof.toml", 1e-8),
        ("cases/pepo-ground-disp.toml", 1.5e-8),
    ] {
        let case = load_case(Path::new(file)).unwrap();
        let r = solve_reference(&case).unwrap();
        let s = audit(&r.trace, &case.scene, Arrangement::Single)
            .unwrap()
            .summary();
        assert!(s.relative_error < tol, "{file}: {}", s.relative_error);
    }
}

/// Independent check of the friction term: during slip |R| = Ru, so ∫R dxp is Ru times
/// the slip path length Σ|Δxp|; PEPO Ru = μ·M·g = 0.5 MN.
#[test]
fn friction_work_is_ru_times_the_slip_path() {
    let case = load_case(Path::new("cases/pepo-mass-accel.toml")).unwrap();
    let r = solve_reference(&case).unwrap();
    let h = audit(&r.trace, &case.scene, Arrangement::Single).unwrap();
    let slide = r.trace.column("slide").unwrap();
    let path: f64 = slide.windows(2).map(|w| (w[1] - w[0]).abs()).sum();
    let Model::Oscillator(o) = &case.scene.model else {
        unreachable!()
    };
    let expected = o.friction_limit() * path;
    let got = *h.friction.last().unwrap();
    assert!(
        ((got - expected) / expected).abs() < 1e-6,
        "{got} vs {expected}"
    );
    assert!(expected > 4000.0); // ≈ 0.5 MN × 8.76 mm
}

/// The predictor-corrector on the PEPO: its balance error is numerical dissipation that
/// vanishes at third order. Measured relative errors: 1.47e-2 (T/10), 2.33e-3 (T/20),
/// 2.99e-4, 3.77e-5, 4.72e-6 (T/160), 5.89e-7, 7.37e-8, 9.22e-9 (T/1280); ratios per
/// halving 6.3, 7.8, 7.9, 8.0, 8.0, 8.0, 8.0.
#[test]
fn audit_closes_on_the_predictor_corrector_at_third_order() {
    let case = load_case(Path::new("cases/pepo-mass-accel.toml")).unwrap();
    let pc = engine::all()
        .into_iter()
        .find(|e| e.id() == "predictor-corrector")
        .unwrap();
    let rel = |dt: f64| {
        let run = pc.run(&case, pc_variant::PAPER, dt).unwrap();
        let s = audit(&run.trace, &case.scene, Arrangement::Single)
            .unwrap()
            .summary();
        // Energy is lost, never created, by this dissipative scheme.
        assert!(s.end_error >= 0.0, "created energy at Δt = {dt}");
        s.relative_error
    };
    let (e160, e640, e1280) = (rel(0.2 / 160.0), rel(0.2 / 640.0), rel(0.2 / 1280.0));
    assert!(e160 < 5e-6, "{e160}");
    assert!(e1280 < 1e-8, "{e1280}");
    let ratio = e640 / e1280;
    assert!((ratio - 8.0).abs() < 0.1, "ratio {ratio}");
}

/// A trace without the channels the audit needs is skipped with the reason, not guessed.
#[test]
fn audit_names_what_it_lacks() {
    let case = load_case(Path::new("cases/pepo-mass-accel.toml")).unwrap();
    let t = rockslide::trace::Trace::with_channels(&[&rockslide::trace::q::REL_DISP], 0);
    let why = audit(&t, &case.scene, Arrangement::Single).unwrap_err();
    assert!(why.contains("force") && why.contains("resistance"), "{why}");
}

/// Rigid blocks (Newmark 1965 and Housner 1963): the audit in the ground's
/// frame (kinetic incl. rotation, potential M·g·z_cm, friction ∫R dxp, impact losses at
/// pivot changes) closes on the exact references. Measured relative errors: Newmark
/// sliding block 3.58e-10 (all input work to friction: 551.2 J), Housner free rocking
/// 1.74e-6, Housner one-sine pulse 3.69e-6 (velocities by central differences on the
/// 1e-5 s sampling). Impact losses, free rocking: 44.05 J of the 146.86 J initial energy.
#[test]
fn audit_closes_on_the_rigid_block_references() {
    for (file, tol) in [
        ("cases/rigid-sliding-block.toml", 1e-9),
        ("cases/housner-free-rocking.toml", 3e-6),
        ("cases/housner-pulse.toml", 6e-6),
    ] {
        let case = load_case(Path::new(file)).unwrap();
        let r = solve_reference(&case).unwrap();
        let s = audit(&r.trace, &case.scene, Arrangement::Single)
            .unwrap()
            .summary();
        assert!(s.relative_error < tol, "{file}: {}", s.relative_error);
    }
    // Newmark: no rocking, so no impact; the friction work is μ·M·g times the slip path.
    let case = load_case(Path::new("cases/rigid-sliding-block.toml")).unwrap();
    let r = solve_reference(&case).unwrap();
    let s = audit(&r.trace, &case.scene, Arrangement::Single)
        .unwrap()
        .summary();
    let slide = r.trace.column("slide").unwrap();
    let path: f64 = slide.windows(2).map(|w| (w[1] - w[0]).abs()).sum();
    let Model::RigidBlock(b) = &case.scene.model else {
        unreachable!()
    };
    let expected = b.mu * b.mass * b.gravity * path;
    assert!(((s.friction - expected) / expected).abs() < 1e-6);
    assert_eq!(s.impact, 0.0);
    // Housner free rocking: the energy lost in impacts is what the potential lost.
    let case = load_case(Path::new("cases/housner-free-rocking.toml")).unwrap();
    let r = solve_reference(&case).unwrap();
    let s = audit(&r.trace, &case.scene, Arrangement::Single)
        .unwrap()
        .summary();
    assert!(
        s.impact > 0.25 * s.supplied,
        "impact {} of {}",
        s.impact,
        s.supplied
    );
}

/// A rocking body on ten elastic supports cannot be audited from its trace: the message
/// names what is missing.
#[test]
fn rocking_body_audit_names_the_missing_channels() {
    let case = load_case(Path::new("cases/rpepo-mass-accel.toml")).unwrap();
    let t = rockslide::trace::Trace::default();
    let why = audit(&t, &case.scene, Arrangement::Single).unwrap_err();
    assert!(
        why.contains("tangential force") && why.contains("energy_error"),
        "{why}"
    );
}

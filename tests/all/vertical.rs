//! Vertical ground motion (docs/vertical-motion.md): the exact references against an independent
//! adaptive integrator (≤ 1e-8 m), their horizontal-only limit against today's references
//! (round-off), the predictor-corrector against them at its observed order, lift-off, the
//! friction bound on the instantaneous N, and fe and rapier saying "not applicable".
//!
//! rockslide shall compute the sliding of a contact whose friction limit μ·N(t) follows a
//! vertical ground motion, exactly where a closed form per interval exists.

use crate::common::{case, case_with, order, repo};
use crate::vertical_integrator::{Y, advance};
use rockslide::case::{Case, NormalForce, load_case};
use rockslide::engine::fe::variant as fe_variant;
use rockslide::engine::predictor_corrector::variant as pc_variant;
use rockslide::engine::rigid_body::variant as rapier_variant;
use rockslide::reference::block_record::{BlockRecord, Sliding};
use rockslide::reference::vertical::{
    BlockPhase, EpoConstants, LinearInputs, VerticalBlock, VerticalEpo,
};
use rockslide::reference::{EpoRecord, ExactSolution};

fn vertical_case(name: &str) -> Case {
    case(&format!("vertical/{name}"))
}

/// Contact phase of the integrated oscillator.
#[derive(Clone, Copy, Debug)]
enum Osc {
    Stick {
        up: f64,
    },
    Slip {
        dir: f64,
    },
    /// The compression-only contact open: free flight, the stick point with the mass.
    Open,
}

/// The oscillator integrated independently on the reference's grid: u at every grid point.
/// With Kz the contact opens where N reaches 0 (flight: δ'' = g + a_v, u'' = d) and closes
/// unstressed where the gap does (the stick point at the mass).
fn integrate_epo(c: &EpoConstants, inputs: &LinearInputs) -> Vec<f64> {
    let (m, k, mu, g) = (c.m, c.k, c.mu, c.g);
    let normal = |y: &Y, av: f64| match c.kz {
        Some(kz) => kz * y[2].max(0.0),
        None => m * (g + av),
    };
    let h = inputs.h;
    let mut y: Y = [0.0, 0.0, c.kz.map_or(0.0, |kz| m * g / kz), 0.0];
    let mut phase = Osc::Stick { up: 0.0 };
    let mut out = vec![0.0];
    let scale = [1e-13, 1e-12, 1e-15, 1e-13];
    for i in 1..inputs.drive.len() {
        let (t0, t1) = ((i - 1) as f64 * h, i as f64 * h);
        let (d0, d1) = (inputs.drive[i - 1], inputs.drive[i]);
        let (a0, a1) = (inputs.vertical[i - 1], inputs.vertical[i]);
        let gamma = (a1 - a0) / h;
        let lin = move |t: f64| ((d0 + (d1 - d0) * (t - t0) / h), (a0 + gamma * (t - t0)));
        let mut t = t0;
        let mut events = 0;
        while t < t1 {
            events += 1;
            assert!(events < 100, "integrator: too many events at {t}");
            let rhs = |t: f64, y: &Y| {
                let (d, av) = lin(t);
                let n = normal(y, av);
                let acc = match phase {
                    Osc::Stick { up } => d - k * (y[0] - up) / m,
                    Osc::Slip { dir } => d - dir * mu * n / m,
                    Osc::Open => d,
                };
                let az = match (c.kz, phase) {
                    (Some(_), Osc::Open) => g + av,
                    (Some(kz), _) => g + av - kz * y[2] / m,
                    (None, _) => 0.0,
                };
                [y[1], acc, y[3], az]
            };
            // the contact opens where the compression falls through 0 (with Kz)
            let opens = |y: &Y| match c.kz {
                Some(_) => -y[2] - 1e-15,
                None => f64::NEG_INFINITY,
            };
            let event = |t: f64, y: &Y| {
                let (_, av) = lin(t);
                let n = normal(y, av);
                match phase {
                    Osc::Stick { up } => {
                        (k * (y[0] - up).abs() - mu * n - 1e-8 * mu * m * g).max(opens(y))
                    }
                    Osc::Slip { dir } => {
                        let rate = match c.kz {
                            Some(kz) => kz * y[3],
                            None => m * gamma,
                        };
                        (-(dir * y[1] - mu * rate / k) - 1e-14).max(opens(y))
                    }
                    Osc::Open => y[2] - 1e-15,
                }
            };
            let (te, ye, hit) = advance(&rhs, &event, t, t1, y, &scale);
            (t, y) = (te, ye);
            if hit {
                let (_, av) = lin(t);
                phase = match phase {
                    Osc::Open => Osc::Stick { up: y[0] },
                    _ if opens(&y) > 0.0 => Osc::Open,
                    Osc::Stick { up } => Osc::Slip {
                        dir: (y[0] - up).signum(),
                    },
                    Osc::Slip { dir } => Osc::Stick {
                        up: y[0] - dir * mu * normal(&y, av) / k,
                    },
                };
            }
        }
        out.push(y[0]);
    }
    out
}

fn epo_constants(c: &Case) -> EpoConstants {
    let rockslide::case::Model::Oscillator(o) = &c.scene.model else {
        panic!("an oscillator case")
    };
    let v = c.scene.vertical().expect("a vertical component");
    EpoConstants {
        m: o.mass,
        k: o.contact.kx,
        mu: o.contact.mu,
        g: o.gravity,
        kz: (v.normal_force == NormalForce::Dynamic).then_some(o.contact.kz),
    }
}

/// Largest |u_reference − u_integrated| over the grid points, m.
fn epo_against_integrator(c: &Case) -> (f64, VerticalEpo) {
    let inputs = LinearInputs::of_scene(&c.scene, c.run.duration).unwrap();
    let consts = epo_constants(c);
    let reference = VerticalEpo::new(consts, inputs.clone()).unwrap();
    let integrated = integrate_epo(&consts, &inputs);
    let worst = reference
        .history
        .states
        .iter()
        .zip(&integrated)
        .map(|(s, u)| (s.u - u).abs())
        .fold(0.0, f64::max);
    (worst, reference)
}

#[test]
fn oscillator_reference_agrees_with_an_independent_integrator() {
    for name in [
        "pepo-mass-accel-vertical",
        "pepo-mass-accel-vertical-rigid",
        "pepo-northridge-vertical",
    ] {
        let (worst, reference) = epo_against_integrator(&vertical_case(name));
        println!(
            "{name}: max |Δu| = {worst:.3e} m, {} slips",
            reference.history.slips.len()
        );
        assert!(worst <= 1e-8, "{name}: {worst:e} m");
        assert!(!reference.history.slips.is_empty(), "{name} slides");
    }
}

#[test]
fn oscillator_reference_through_contact_openings_agrees_with_the_integrator() {
    // Northridge with its synthetic vertical and the contact's Kz: the 10 Hz vertical
    // oscillator rings the compression-only contact open (flights, then elastic landings
    // with the stick point reset).
    let c = case_with(
        "vertical/pepo-northridge-vertical",
        "normal_force = \"quasi-static\"",
        "normal_force = \"dynamic\"",
    );
    let (worst, reference) = epo_against_integrator(&c);
    let flights = &reference.history.flights;
    println!(
        "Northridge, dynamic N: max |Δu| = {worst:.3e} m, {} slips, {} flights, first {:?}",
        reference.history.slips.len(),
        flights.len(),
        flights.first()
    );
    assert!(worst <= 1e-8, "{worst:e} m");
    assert!(!flights.is_empty());
}

/// Phase of the integrated block.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Blk {
    Stuck,
    Sliding(f64),
    Air,
}

/// The rigid block integrated independently: u at every grid point and the first lift-off.
fn integrate_block(mu: f64, g: f64, inputs: &LinearInputs) -> (Vec<f64>, Option<f64>) {
    let h = inputs.h;
    let mut y: Y = [0.0; 4]; // u, v, z, w
    let mut phase = Blk::Stuck;
    let mut out = vec![0.0];
    let mut first_lift = None;
    let scale = [1e-13, 1e-12, 1e-13, 1e-12];
    for i in 1..inputs.drive.len() {
        let (t0, t1) = ((i - 1) as f64 * h, i as f64 * h);
        let (d0, d1) = (inputs.drive[i - 1], inputs.drive[i]);
        let (a0, a1) = (inputs.vertical[i - 1], inputs.vertical[i]);
        let lin = move |t: f64| {
            let f = (t - t0) / h;
            (d0 + (d1 - d0) * f, g + a0 + (a1 - a0) * f)
        };
        let mut t = t0;
        let mut events = 0;
        while t < t1 {
            events += 1;
            assert!(events < 100, "integrator: too many events at {t}");
            let rhs = |t: f64, y: &Y| {
                let (d, ge) = lin(t);
                match phase {
                    Blk::Stuck => [0.0; 4],
                    Blk::Sliding(s) => [y[1], d - s * mu * ge, 0.0, 0.0],
                    Blk::Air => [y[1], d, y[3], -ge],
                }
            };
            let event = |t: f64, y: &Y| {
                let (d, ge) = lin(t);
                match phase {
                    Blk::Stuck => (-ge).max(d.abs() - mu * ge - 1e-12),
                    Blk::Sliding(s) => (-ge).max(-s * y[1] - 1e-15),
                    Blk::Air => -y[2] - 1e-15,
                }
            };
            let (te, ye, hit) = advance(&rhs, &event, t, t1, y, &scale);
            (t, y) = (te, ye);
            if hit {
                let (d, ge) = lin(t);
                phase = match phase {
                    _ if ge < 0.0 && phase != Blk::Air => {
                        first_lift.get_or_insert(t);
                        (y[2], y[3]) = (0.0, 0.0);
                        Blk::Air
                    }
                    Blk::Stuck => Blk::Sliding(d.signum()),
                    Blk::Sliding(_) => {
                        y[1] = 0.0;
                        Blk::Stuck
                    }
                    Blk::Air => {
                        // plastic impact, friction impulse ≤ μ·|w| against the slide
                        y[1] = y[1].signum() * (y[1].abs() - mu * y[3].abs()).max(0.0);
                        (y[2], y[3]) = (0.0, 0.0);
                        if y[1] == 0.0 {
                            Blk::Stuck
                        } else {
                            Blk::Sliding(y[1].signum())
                        }
                    }
                };
            }
        }
        out.push(y[0]);
    }
    (out, first_lift)
}

#[test]
fn lift_off_block_reference_agrees_with_an_independent_integrator() {
    let c = load_case(&repo("cases/vertical/block-liftoff.toml")).unwrap();
    let inputs = LinearInputs::of_scene(&c.scene, c.run.duration).unwrap();
    let rockslide::case::Model::RigidBlock(b) = &c.scene.model else {
        panic!()
    };
    let reference =
        VerticalBlock::new(b.mass, b.mu, b.gravity, Sliding::TwoWay, inputs.clone()).unwrap();
    let (integrated, lift) = integrate_block(b.mu, b.gravity, &inputs);
    let worst = reference
        .history
        .states
        .iter()
        .zip(&integrated)
        .map(|(s, u)| (s.u - u).abs())
        .fold(0.0, f64::max);
    let flights: Vec<_> = reference
        .history
        .motions
        .iter()
        .filter(|m| m.phase == BlockPhase::Airborne)
        .collect();
    println!(
        "block lift-off: max |Δu| = {worst:.3e} m, residual {:.6} m, flights {:?}",
        reference.history.states.last().unwrap().u,
        flights
    );
    assert!(worst <= 1e-8, "{worst:e} m");
    // g + a_v = g(1 − 1.5 sin θt) < 0 from sin θt = 2/3: t = asin(2/3)/θ (the linear
    // sampling moves it by O(h²))
    let expected = (2.0_f64 / 3.0).asin() / (2.0 * std::f64::consts::PI);
    assert_eq!(flights.len(), 1);
    assert!(
        (flights[0].start - expected).abs() < 1e-6,
        "{}",
        flights[0].start
    );
    assert!((lift.unwrap() - flights[0].start).abs() < 1e-9);
    let exact = reference.exact_quantities();
    let first = exact.iter().find(|(k, _)| *k == "first_liftoff").unwrap().1;
    assert_eq!(first, flights[0].start);
}

#[test]
fn without_a_vertical_motion_the_references_are_todays_to_round_off() {
    // the oscillator under Northridge, vertical zero: against EpoRecord
    let c = case("records/pepo-northridge");
    let rockslide::case::Model::Oscillator(o) = &c.scene.model else {
        panic!()
    };
    let Some(rockslide::case::Signal::Record { dt, samples, .. }) = c.scene.excitation.signal()
    else {
        panic!()
    };
    let last = (samples.len() - 1) as f64 * dt;
    let at = |t: f64| {
        let i = ((t / dt).round() as usize).min(samples.len());
        (-samples.get(i).copied().unwrap_or(0.0), 0.0)
    };
    let inputs = LinearInputs::sample(*dt, last, String::new(), at).unwrap();
    let consts = EpoConstants {
        m: o.mass,
        k: o.contact.kx,
        mu: o.contact.mu,
        g: o.gravity,
        kz: Some(o.contact.kz),
    };
    let vertical = VerticalEpo::new(consts, inputs).unwrap();
    let today = EpoRecord::new(o, *dt, samples.to_vec(), last).unwrap();
    let times: Vec<f64> = (0..samples.len()).map(|i| i as f64 * dt).collect();
    let (a, b) = (
        rockslide::reference::sample(&vertical, &times),
        rockslide::reference::sample(&today, &times),
    );
    let worst = |key: &str| {
        let (x, y) = (a.column(key).unwrap(), b.column(key).unwrap());
        x.iter()
            .zip(y)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max)
    };
    let (du, dslide) = (worst("rel_disp"), worst("slide"));
    println!("oscillator, a_v = 0: max |Δu| = {du:.3e} m, max |Δslip| = {dslide:.3e} m");
    assert!(du <= 1e-13 && dslide <= 1e-13, "{du:e} {dslide:e}");

    // the rigid block under Northridge, vertical zero: against BlockRecord
    let c = case("records/block-northridge");
    let rockslide::case::Model::RigidBlock(b) = &c.scene.model else {
        panic!()
    };
    let Some(rockslide::case::Signal::Record { dt, samples, .. }) = c.scene.excitation.signal()
    else {
        panic!()
    };
    let drive: Vec<f64> = samples.iter().map(|a| -a).collect();
    let n = drive.len();
    let inputs = LinearInputs::sample(*dt, (n - 1) as f64 * dt, String::new(), |t| {
        (drive[((t / dt).round() as usize).min(n - 1)], 0.0)
    })
    .unwrap();
    let vertical = VerticalBlock::new(b.mass, b.mu, b.gravity, Sliding::TwoWay, inputs).unwrap();
    let today = BlockRecord::solve(*dt, &drive, b.mu * b.gravity, Sliding::TwoWay, 0.0).unwrap();
    let worst = vertical
        .history
        .states
        .iter()
        .zip(&today.disp)
        .map(|(s, u)| (s.u - u).abs())
        .fold(0.0, f64::max);
    println!("block, a_v = 0: max |Δu| = {worst:.3e} m");
    assert!(worst <= 1e-13, "{worst:e}");
}

/// Largest |u_pc − u_reference| over the run's steps, over the reference's peak |u|.
fn pc_error(c: &Case, dt: f64) -> f64 {
    use rockslide::engine::Engine;
    let run = rockslide::engine::predictor_corrector::PredictorCorrector
        .run(c, pc_variant::PAPER, dt)
        .unwrap();
    let reference = rockslide::reference::for_case(c).unwrap();
    let exact = rockslide::reference::sample(reference.as_ref(), &run.trace.time);
    let (u, x) = (
        run.trace.column("rel_disp").unwrap(),
        exact.column("rel_disp").unwrap(),
    );
    let peak = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    u.iter()
        .zip(x)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / peak
}

#[test]
fn predictor_corrector_converges_to_the_vertical_reference() {
    // The paper's scheme with Ru(t) = μ·N(t) and N stepped by the same scheme: observed
    // order of the max error of u (normalised by its peak) on the Δt ladder 2, 1, 0.5 ms.
    for name in ["pepo-mass-accel-vertical", "pepo-mass-accel-vertical-rigid"] {
        let c = vertical_case(name);
        let e: Vec<f64> = [2e-3, 1e-3, 5e-4]
            .iter()
            .map(|&dt| pc_error(&c, dt))
            .collect();
        let (p1, p2) = (order(e[0], e[1], 2e-3, 1e-3), order(e[1], e[2], 1e-3, 5e-4));
        println!("{name}: errors {e:?}, observed orders {p1:.3} {p2:.3}");
        // measured: 1.02e-4 and 8.9e-5 at 1 ms; orders 1.70, 2.34 (dynamic N) and 2.02,
        // 1.94 (rigid vertical contact): second order, as the average-acceleration scheme
        assert!(e[1] < 1.1e-4, "{name}: {:e}", e[1]);
        assert!(p1 > 1.65 && p2 > 1.65, "{name}: orders {p1} {p2}");
    }
}

#[test]
fn the_friction_bound_uses_the_instantaneous_normal_force() {
    use rockslide::engine::Engine;
    let c = vertical_case("pepo-mass-accel-vertical");
    let run = rockslide::engine::predictor_corrector::PredictorCorrector
        .run(&c, pc_variant::PAPER, 1e-3)
        .unwrap();
    let block = &run.trace.contacts;
    let normal: Vec<f64> = (0..block.len()).map(|i| block.at(i, 0).normal).collect();
    let (lo, hi) = normal
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(a, b), n| (a.min(*n), b.max(*n)));
    // N breathes: M·g = 1 MN at rest, well below and above it during the pulse
    assert!(lo < 0.4e6 && hi > 1.3e6, "N from {lo} to {hi}");
    // |T| ≤ μ·N(t) at every step, and at the limit while slipping
    let mut at_limit = 0;
    for i in 0..block.len() {
        let s = block.at(i, 0);
        assert!(
            s.tangential.abs() <= 0.5 * s.normal * (1.0 + 1e-12),
            "step {i}"
        );
        if s.tangential.abs() >= 0.5 * s.normal * (1.0 - 1e-12) {
            at_limit += 1;
        }
    }
    assert!(at_limit > 100, "{at_limit} steps at the limit");
    // and the trace carries N(t) beside R(t)
    assert_eq!(run.trace.column("normal").unwrap(), normal.as_slice());
    // the invariant the gate checks holds on this run ...
    let checks = rockslide::invariants::check_run(&c, &run);
    let bound = |checks: &[rockslide::invariants::InvariantCheck]| {
        checks
            .iter()
            .find(|k| k.invariant == "friction_bound")
            .unwrap()
            .worst
    };
    assert_eq!(bound(&checks), 0.0);
    // ... and fails a tangential force within μ·M·g but beyond μ·N(t) (here N = lo)
    let mut broken = run.clone();
    let i = normal.iter().position(|n| *n == lo).unwrap();
    let t = 0.5 * 0.5 * (lo + 1e6); // between μ·N(t) and μ·M·g
    broken.trace.contacts.values[i * 4 + 1] = t;
    let checks = rockslide::invariants::check_run(&c, &broken);
    let expected = (t - 0.5 * lo) / (0.5 * 1e6);
    assert!(
        (bound(&checks) - expected).abs() < 1e-12,
        "{}",
        bound(&checks)
    );
}

#[test]
fn engines_say_which_vertical_scenes_they_do_not_model() {
    // fe and rapier model the contact's Kz: a rigid vertical contact (quasi-static N) is
    // not their oscillator; the predictor-corrector runs both.
    let dynamic = vertical_case("pepo-mass-accel-vertical");
    let rigid = vertical_case("pepo-mass-accel-vertical-rigid");
    for engine in rockslide::engine::all() {
        let (id, v) = (engine.id(), engine.variants(&dynamic.scene));
        match id {
            "predictor-corrector" => {
                let paper = pc_variant::PAPER;
                assert_eq!(v.unwrap(), vec![paper]);
                assert_eq!(engine.variants(&rigid.scene).unwrap(), vec![paper]);
                continue;
            }
            "fe" => assert_eq!(v.unwrap(), vec![fe_variant::SINGLE_ELEMENT]),
            _ => assert_eq!(v.unwrap(), vec![rapier_variant::APPLIED_FORCE]),
        }
        let why = engine.variants(&rigid.scene).unwrap_err().0;
        assert!(
            why.contains("vertical stiffness Kz: a rigid vertical contact (normal_force = \"quasi-static\") is not its model"),
            "{id}: {why}"
        );
    }
    // rapier's feet model does not take vertical motion: a located error
    let c = crate::common::case_with(
        "vertical/pepo-mass-accel-vertical",
        "[engines.rapier]",
        "[engines.rapier]\ncontact_model = \"foot\"\n",
    );
    use rockslide::engine::Engine;
    let e = rockslide::engine::rigid_body::Rapier
        .run(&c, rapier_variant::APPLIED_FORCE, 1e-3)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("engines.rapier.contact_model: \"foot\" does not take vertical ground motion"),
        "{e}"
    );
}

#[test]
fn a_vertical_component_without_gravity_or_with_a_bad_key_is_a_located_error() {
    let path = repo("cases/vertical/pepo-mass-accel-vertical.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let bad = text
        .replace(
            "gravity = 1.0           # m/s², the paper's value",
            "gravity = 0.0",
        )
        .replace("normal_force = \"dynamic\"", "normal_force = \"elastic\"");
    let errs = rockslide::case::parse_case(&path, &bad)
        .unwrap_err()
        .to_string();
    println!("{errs}");
    assert!(
        errs.contains("excitation.vertical: needs gravity"),
        "{errs}"
    );
    assert!(
        errs.contains("excitation.vertical.normal_force: is \"elastic\", but must be"),
        "{errs}"
    );
    let bad = text.replace("cycles = 0.5\nnormal_force", "cycles = -1.0\nnormal_force");
    let errs = rockslide::case::parse_case(&path, &bad)
        .unwrap_err()
        .to_string();
    assert!(
        errs.contains(":38:") && errs.contains("excitation.vertical.cycles"),
        "{errs}"
    );
}

/// Residual sliding of the exact reference of `c`, m.
fn exact_residual(c: &Case) -> f64 {
    let reference = rockslide::reference::for_case(c).unwrap();
    let t = [c.run.duration];
    let s = rockslide::reference::sample(reference.as_ref(), &t);
    *s.column("slide").unwrap().last().unwrap()
}

#[test]
fn the_vertical_component_changes_residual_sliding() {
    // The finding of docs/vertical-motion.md: residual sliding with the vertical component
    // against the horizontal-only run, both exact.
    // (case with the vertical, horizontal-only case, residuals in mm as measured)
    let pairs = [
        (
            "vertical/pepo-mass-accel-vertical",
            "pepo-mass-accel",
            17.4148,
            8.7562,
        ),
        (
            "vertical/pepo-mass-accel-vertical-rigid",
            "pepo-mass-accel",
            16.4339,
            8.7562,
        ),
        (
            "vertical/pepo-northridge-vertical",
            "records/pepo-northridge",
            14.1024,
            4.3486,
        ),
    ];
    for (with, without, with_mm, without_mm) in pairs {
        let (a, b) = (case(with), case(without));
        let (ra, rb) = (exact_residual(&a) * 1e3, exact_residual(&b) * 1e3);
        println!(
            "{with}: residual {ra:.4} mm, horizontal only {rb:.4} mm: {:+.2} %",
            100.0 * (ra / rb - 1.0)
        );
        assert!((ra - with_mm).abs() < 1e-4 && (rb - without_mm).abs() < 1e-4);
    }
    // on the contact's Kz, through the openings, at 6 s (the case's run) against the
    // horizontal-only run to 6 s
    let (a, b) = (
        case("vertical/pepo-northridge-vertical-dynamic"),
        case_with(
            "records/pepo-northridge",
            "duration = 25.0",
            "duration = 6.0",
        ),
    );
    let (ra, rb) = (exact_residual(&a) * 1e3, exact_residual(&b) * 1e3);
    println!("Northridge on Kz at 6 s: {ra:.4} mm, horizontal only {rb:.4} mm");
    assert!((ra - 20.9022).abs() < 1e-4 && (rb - 4.6061).abs() < 1e-4);
    // and the horizontal-only case is the vertical one without its vertical table
    let c = case_with(
        "vertical/pepo-mass-accel-vertical",
        "amplitude = -0.6666666666666666",
        "amplitude = 0.0",
    );
    assert!((exact_residual(&c) * 1e3 - 8.7562).abs() < 1e-4);
}

/// A case in a fresh folder beside `pair.csv` (its text given), loaded.
fn pair_case(tag: &str, csv: &[u8], horizontal: &str, vertical: &str) -> Result<Case, String> {
    let dir = std::env::temp_dir().join(format!("rs-pair-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("pair.csv"), csv).unwrap();
    let text = format!(
        "title = \"pair\"\nsource = \"test\"\nrequirement = \"test\"\n\n[model]\nkind = \"oscillator\"\nmass = 1.0e6\ngravity = 1.0\n\n[model.contact]\nkx = 9.8696e8\nkz = 3.94784e9\nmu = 0.5\n\n[excitation]\nkind = \"ground-acceleration\"\nrecord = \"pair.csv\"\nrecord_unit = \"g\"\n{horizontal}\n\n[excitation.vertical]\nrecord = \"pair.csv\"\nrecord_unit = \"g\"\n{vertical}\n\n[run]\nduration = 0.1\ndt = 0.01\n"
    );
    let path = dir.join("case.toml");
    std::fs::write(&path, &text).unwrap();
    let out = load_case(&path).map_err(|e| e.to_string());
    std::fs::remove_dir_all(&dir).unwrap();
    out
}

#[test]
fn a_horizontal_vertical_pair_in_one_csv_is_one_excitation_with_a_scale_per_component() {
    // time, horizontal, vertical; a byte-order mark and CRLF line ends, as other readers
    let csv =
        b"\xEF\xBB\xBF# pair\r\ntime,h,v\r\n0.0,0.0,0.0\r\n0.02,0.1,-0.05\r\n0.04,-0.2,0.02\r\n";
    let c = pair_case(
        "ok",
        csv,
        "record_column = 1\nscale_to_pga_g = 0.1",
        "record_column = 2\nscale_to_pga_g = 0.05",
    )
    .unwrap();
    let g = rockslide::case::record::STANDARD_GRAVITY;
    let h = c.scene.excitation.signal().unwrap();
    let v = &c.scene.vertical().unwrap().signal;
    // each component scaled to its own PGA: h peaks at −0.2 g → −0.1 g, v at −0.05 g → −0.05 g
    assert!((h.value(0.04) + 0.1 * g).abs() < 1e-12, "{}", h.value(0.04));
    assert!((h.value(0.02) - 0.05 * g).abs() < 1e-12);
    assert!(
        (v.value(0.02) + 0.05 * g).abs() < 1e-12,
        "{}",
        v.value(0.02)
    );
    assert!((v.value(0.04) - 0.02 * g).abs() < 1e-12);
    // a missing column is located in the record file, under the case field
    let e = pair_case("short", csv, "record_column = 1", "record_column = 3").unwrap_err();
    assert!(
        e.contains("pair.csv:3:")
            && e.contains("excitation.vertical.record")
            && e.contains(
                "expected at least 4 columns (time in s, then acceleration column 3 in g), found 3"
            ),
        "{e}"
    );
    // a three-column file without a column, and a column below 1
    let e = pair_case("none", csv, "", "record_column = 2").unwrap_err();
    assert!(
        e.contains("expected 2 columns (time in s, acceleration in g), found 3"),
        "{e}"
    );
    let e = pair_case("zero", csv, "record_column = 1", "record_column = 0").unwrap_err();
    assert!(
        e.contains("excitation.vertical.record_column: is 0, but must be at least 1"),
        "{e}"
    );
    // a bad number in the vertical column: line and column of the token
    let bad = b"0.0,0.0,0.0\n0.02,0.1,x\n";
    let e = pair_case("bad", bad, "record_column = 1", "record_column = 2").unwrap_err();
    assert!(e.contains("pair.csv:2:10"), "{e}");
}

//! CalculiX: the scene export (`rockslide export CASE --to calculix`) and CalculiX as a
//! live participant (`[engines.calculix]`); the ANSYS deck (`--to ansys`, written, never
//! run here). The live tests run `ccx`; when it is absent they are listed as ignored,
//! saying why; where it is required (`CI=true`, or `ROCKSLIDE_REQUIRE_CALCULIX`, set by
//! `.ci/run` after installing it) its absence fails them.

use std::collections::HashMap;
use std::process::Command;

use rockslide::calculix::{NOT_FOUND, available};
use rockslide::case::{Model, RockingBody, parse_case};
use rockslide::export::{ansys, calculix};
use rockslide::suite::{CaseResult, run_case};

use crate::common::{case, present_or_skip, repo, rockslide};

/// Whether the live tests can run (`ccx` found), or why not.
fn live(test: &str) -> bool {
    present_or_skip(
        test,
        available().is_some(),
        "ROCKSLIDE_REQUIRE_CALCULIX",
        NOT_FOUND,
    )
}

fn run_index(r: &CaseResult, label: &str) -> usize {
    r.runs
        .iter()
        .position(|x| x.label() == label)
        .unwrap_or_else(|| panic!("no run {label}"))
}

/// The deck's `** scene:` comment line carries the rocking body's numbers exactly.
fn assert_rocking_scene_line(deck: &str, r: &RockingBody) {
    let scene = pairs(deck, "** scene:");
    // The case states its inertia: the deck must carry that number, not one it derives.
    let inertia = r.rotational_inertia;
    assert!(
        inertia > 0.0,
        "the RPEPO case states its rotational inertia"
    );
    for (k, v) in [
        ("mass", r.mass),
        ("gravity", r.gravity),
        ("cm_height", r.cm_height),
        ("half_width", r.half_width),
        ("supports", r.supports as f64),
        ("rotational_inertia", inertia),
        ("kx", r.contact.kx),
        ("kz", r.contact.kz),
        ("mu", r.contact.mu),
    ] {
        assert_eq!(scene[k], v, "{k}");
    }
}

/// A case run live with its CalculiX participant completed: the result and that run's
/// index.
fn run_calculix(name: &str) -> (CaseResult, usize) {
    let r = run_case(case(name)).unwrap();
    let i = run_index(&r, "calculix/external");
    assert!(r.runs[i].status.completed(), "{:?}", r.runs[i].findings);
    (r, i)
}

/// Every gated check of the case passes (and there is at least one).
fn assert_gate_passes(r: &CaseResult) {
    let gated: Vec<_> = r.checks.iter().filter(|c| c.gated).collect();
    assert!(!gated.is_empty(), "the case gates nothing");
    assert!(
        gated
            .iter()
            .all(|c| c.verdict == rockslide::analysis::Verdict::Pass),
        "{gated:?}"
    );
}

/// The `name = value` pairs of a deck's comment line that starts with `prefix`.
fn pairs(deck: &str, prefix: &str) -> HashMap<String, f64> {
    let line = deck
        .lines()
        .find(|l| l.starts_with(prefix))
        .unwrap_or_else(|| panic!("no line {prefix}"));
    line[prefix.len()..]
        .split(',')
        .map(|p| {
            let (k, v) = p.split_once('=').unwrap();
            (k.trim().to_string(), v.trim().parse().unwrap())
        })
        .collect()
}

/// Every number of the scene is in the CalculiX deck exactly: the header's, the contact
/// cards' (the slope at Kz, μ and the stick slope Kx per m² of a 1 m² slave face; μ2 = ∞
/// written as 1e6), the mass, the static overclosures M·g/Kz.
#[test]
fn the_calculix_deck_carries_the_scenes_numbers_exactly() {
    let c = case("calculix/pepo-single-calculix");
    let Model::Oscillator(o) = &c.scene.model else {
        panic!("an oscillator")
    };
    let settings = rockslide::export::deck::DeckSettings {
        arrangement: rockslide::case::Arrangement::Double,
        ..calculix::settings(&c).unwrap()
    };
    let export = calculix::export_with(&c, &settings).unwrap();
    let deck = String::from_utf8(export.files[0].bytes.clone()).unwrap();
    let scene = pairs(&deck, "** scene:");
    let d = o.double.as_ref().unwrap();
    for (k, v) in [
        ("mass", o.mass),
        ("gravity", o.gravity),
        ("kx", o.contact.kx),
        ("kz", o.contact.kz),
        ("mu", o.contact.mu),
        ("kx1", d.lower.kx),
        ("kz1", d.lower.kz),
        ("mu1", d.lower.mu),
        ("kx2", d.upper.kx),
        ("kz2", d.upper.kz),
        ("mu2", d.upper.mu),
    ] {
        assert_eq!(scene[k], v, "{k}");
    }
    // the numbers of the line after the `nth` line that is `marker`
    let after = |marker: &str, nth: usize| -> Vec<f64> {
        let mut found = deck
            .lines()
            .enumerate()
            .filter(|(_, l)| *l == marker)
            .map(|(i, _)| deck.lines().nth(i + 1).unwrap());
        let line = found.nth(nth).unwrap();
        line.split(',').map(|f| f.trim().parse().unwrap()).collect()
    };
    let slope = "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR";
    assert_eq!(after(slope, 0), [d.lower.kz]);
    assert_eq!(after(slope, 1), [d.upper.kz]);
    assert_eq!(after("*FRICTION", 0), [d.lower.mu, d.lower.kx]);
    assert_eq!(after("*FRICTION", 1), [1e6, d.upper.kx]);
    assert_eq!(after("*MASS, ELSET=EMASS", 0), [o.mass]);
    // the middle plate's mass Kx1·Δt², 1010 kg at Δt = 1e-4 s: its inertia stiffness under
    // Newmark average acceleration, m/(Δt²/4), four times element 1's stick slope
    let middle = after("*MASS, ELSET=EMIDDLE", 0)[0];
    assert!((middle / 1010.0 - 1.0).abs() < 1e-12, "{middle}");
    assert!(deck.contains("*ELEMENT, TYPE=MASS, ELSET=EMIDDLE\n12, 9\n"));
    // the middle plate (node 9) and the body plate (node 17) start at their overclosures
    let z = |node: &str| -> f64 {
        let line = deck.lines().find(|l| l.starts_with(node)).unwrap();
        line.rsplit(',').next().unwrap().trim().parse().unwrap()
    };
    // (a computed coordinate, written to 13 significant digits)
    let weight = o.mass * o.gravity;
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-12;
    assert!(close(z("9, "), -weight / d.lower.kz));
    assert!(close(
        z("17, "),
        -weight / d.lower.kz + 0.1 - weight / d.upper.kz
    ));
    assert!(
        deck.contains("*DYNAMIC, DIRECT, ALPHA=0.0\n1e-4, 1.0\n"),
        "dt and duration"
    );
    // the half-sine sampled at every step: 2001 points to 0.2 s, then one zero after it
    let amplitude: Vec<&str> = deck
        .lines()
        .skip_while(|l| !l.starts_with("*AMPLITUDE"))
        .skip(1)
        .take_while(|l| !l.starts_with('*'))
        .collect();
    assert_eq!(amplitude.len(), 2002);
    assert_eq!(amplitude[2001], "0.2001, 0.0");
    assert_eq!(amplitude[1000], "0.1, 1.0");
    // every data line's fields fit CalculiX's 20 characters (keyword lines are not read
    // by fields)
    assert!(
        deck.lines()
            .all(|l| l.starts_with('*') || l.split(',').all(|f| f.trim().len() <= 20))
    );
}

/// The RPEPO's CalculiX deck: every scene number on the header line and in its card (the
/// slopes Kz/a² and Kx/a² per m² of an a × a support face, μ, the two point masses M/2 at
/// ±√(I/M), the supports' places, the centre of mass's height), the weight ramped over
/// the vertical period 2π·√(M/(n·Kz)) = 0.1 s, the pulse shifted by the ramp, HHT-α at
/// the case's Δt; the double arrangement refused, naming the setting.
#[test]
fn the_calculix_rpepo_deck_carries_the_scenes_numbers_exactly() {
    use rockslide::export::calculix_rocking::{FACE, FIELDS_PER_LINE};
    let out = tempfile::tempdir().unwrap();
    let p = rockslide(&[
        "export",
        "cases/rpepo-mass-accel.toml",
        "--to",
        "calculix",
        "-o",
        out.path().to_str().unwrap(),
        "-q",
    ]);
    assert!(p.status.success(), "{}", String::from_utf8_lossy(&p.stderr));
    let dir = out.path().join("rpepo-mass-accel");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "single only");
    let deck = std::fs::read_to_string(dir.join("calculix_model.inp")).unwrap();
    let c = case("rpepo-mass-accel");
    let Model::RockingBody(r) = &c.scene.model else {
        panic!("a rocking body")
    };
    assert_rocking_scene_line(&deck, r);
    let inertia = r.rotational_inertia;
    let lines: Vec<&str> = deck.lines().collect();
    let numbers =
        |line: &str| -> Vec<f64> { line.split(',').map(|f| f.trim().parse().unwrap()).collect() };
    let after = |marker: &str| -> Vec<f64> {
        let i = lines
            .iter()
            .position(|l| *l == marker)
            .unwrap_or_else(|| panic!("{marker}"));
        numbers(lines[i + 1])
    };
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-12;
    let area = FACE * FACE;
    let slope = after("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR");
    assert_eq!(slope, [r.contact.kz / area]);
    assert!(close(slope[0] * area, r.contact.kz));
    let friction = after("*FRICTION");
    assert_eq!(friction, [r.contact.mu, r.contact.kx / area]);
    assert!(close(friction[1] * area, r.contact.kx));
    // the mass and the inertia: M/2 on each of nodes 1002 and 1003, at ∓√(I/M) in X
    assert_eq!(after("*MASS, ELSET=EMASS"), [r.mass / 2.0]);
    let node = |n: u64| -> Vec<f64> {
        let prefix = format!("{n}, ");
        let line = lines.iter().find(|l| l.starts_with(&prefix)).unwrap();
        numbers(line)[1..].to_vec()
    };
    let (left, right) = (node(1002), node(1003));
    assert!(close(
        r.mass / 2.0 * (left[0].powi(2) + right[0].powi(2)),
        inertia
    ));
    assert_eq!(left[0], -right[0]);
    assert_eq!(node(1000), [0.0, 0.0, r.cm_height], "the centre of mass");
    // each support's face: centred on the scene's abscissa, a wide, on the ground (Z = 0)
    for (i, x) in r.support_positions().iter().enumerate() {
        let first = 1101 + 8 * i as u64;
        let (a, b) = (node(first), node(first + 1));
        assert!(((a[0] + b[0]) / 2.0 - x).abs() < 1e-15, "support {i}");
        assert!((b[0] - a[0] - FACE).abs() < 1e-15, "support {i}");
        assert_eq!((a[2], b[2]), (0.0, 0.0), "support {i}");
    }
    assert!(deck.contains(&format!(
        "*CLOAD, AMPLITUDE=WEIGHT\n1000, 3, {}\n",
        rockslide::export::deck::num(-r.weight())
    )));
    assert!(deck.contains(&format!(
        "*CLOAD, AMPLITUDE=EXCITATION\nBODY, 1, {}\n",
        rockslide::export::deck::num(r.mass)
    )));
    // the ramp: the vertical period 2π·√(M/(n·Kz)) = 0.1 s, in whole 1 ms output steps
    let period = std::f64::consts::TAU * (r.mass / (r.supports as f64 * r.contact.kz)).sqrt();
    assert!((period - 0.1).abs() < 1e-6, "{period}");
    assert!(deck.contains("*AMPLITUDE, NAME=WEIGHT\n0.0, 0.0\n0.1, 1.0\n2.1, 1.0\n"));
    assert!(deck.contains("*STEP, NLGEOM, INC=2110\n*DYNAMIC, DIRECT, ALPHA=-0.1\n1e-3, 2.1\n"));
    // the pulse: zero to one step before the ramp's end, then a·sin(θt) at ramp + t
    let Some(rockslide::case::Signal::SinePulse {
        amplitude, omega, ..
    }) = c.scene.excitation.signal()
    else {
        panic!("a sine pulse")
    };
    let start = lines
        .iter()
        .position(|l| *l == "*AMPLITUDE, NAME=EXCITATION")
        .unwrap();
    assert_eq!(numbers(lines[start + 1]), [0.0, 0.0]);
    let before = numbers(lines[start + 2]);
    assert!(
        (before[0] - 0.099).abs() < 1e-15 && before[1] == 0.0,
        "{before:?}"
    );
    for k in [0usize, 25, 333, 1000] {
        let point = numbers(lines[start + 3 + k]);
        let t = k as f64 * c.run.dt;
        assert!((point[0] - (0.1 + t)).abs() < 1e-12, "{k}: {point:?}");
        assert!(
            (point[1] - amplitude * (omega * t).sin()).abs() < 1e-12,
            "{k}"
        );
    }
    // what the live reader needs: the centre of mass, the rotation node, the ground's total
    for request in [
        "*NODE PRINT, NSET=BODY, FREQUENCY=1\nU, V\n",
        "*NODE PRINT, NSET=ROTATION, FREQUENCY=1\nU\n",
        "*NODE PRINT, NSET=GROUND, FREQUENCY=1, TOTALS=ONLY\nRF\n",
    ] {
        assert!(deck.contains(request), "{request}");
    }
    assert!(deck.contains("*RIGID BODY, NSET=RIGID, REF NODE=1000, ROT NODE=1001\n"));
    assert!(deck.contains("*NSET, NSET=BODY\n1000\n*NSET, NSET=ROTATION\n1001\n"));
    // every data line within CalculiX's limits: 16 entries, 20 characters each
    assert!(deck.lines().all(|l| l.starts_with('*')
        || (l.split(',').count() <= FIELDS_PER_LINE
            && l.split(',').all(|f| f.trim().len() <= 20))));
    let settings = rockslide::export::deck::DeckSettings {
        arrangement: rockslide::case::Arrangement::Double,
        ..calculix::settings(&c).unwrap()
    };
    let e = calculix::export_with(&c, &settings)
        .unwrap_err()
        .to_string();
    assert!(e.contains("engines.calculix.variants"), "{e}");
}

/// `rockslide export --to calculix` writes both arrangements inside the output folder;
/// a scene the deck cannot model is a located error with nothing written.
#[test]
fn the_calculix_export_writes_its_decks_and_refuses_what_it_cannot_model() {
    let out = tempfile::tempdir().unwrap();
    let o = out.path().to_str().unwrap();
    let p = rockslide(&[
        "export",
        "cases/pepo-mass-accel.toml",
        "--to",
        "calculix",
        "-o",
        o,
        "-q",
    ]);
    assert!(p.status.success(), "{}", String::from_utf8_lossy(&p.stderr));
    let dir = out.path().join("pepo-mass-accel");
    let single = std::fs::read_to_string(dir.join("calculix_model.inp")).unwrap();
    let double = std::fs::read_to_string(dir.join("calculix_model_double.inp")).unwrap();
    assert!(single.contains("kx = 9.8696e8") && !single.contains("NAME=ELEMENT2"));
    assert!(
        double.contains("kx1 = 1.01e11") && double.contains("*SURFACE INTERACTION, NAME=ELEMENT2")
    );
    for (name, field) in [
        ("rigid-sliding-block", "model.kind"),
        ("vertical/pepo-mass-accel-vertical", "excitation.vertical"),
    ] {
        let out = tempfile::tempdir().unwrap();
        let p = rockslide(&[
            "export",
            &format!("cases/{name}.toml"),
            "--to",
            "calculix",
            "-o",
            out.path().to_str().unwrap(),
        ]);
        assert_eq!(p.status.code(), Some(2), "{name}");
        let err = String::from_utf8_lossy(&p.stderr);
        assert!(err.contains(field), "{name}: {err}");
        assert_eq!(std::fs::read_dir(out.path()).unwrap().count(), 0);
    }
    // an unknown option of the section, located
    let path = repo("cases/calculix/pepo-single-calculix.toml");
    let text = std::fs::read_to_string(&path).unwrap().replace(
        "[engines.calculix]",
        "[engines.calculix]\nsolver = \"pardiso\"",
    );
    let e = calculix::export(&parse_case(&path, &text).unwrap())
        .unwrap_err()
        .to_string();
    assert!(e.contains("engines.calculix.solver"), "{e}");
}

/// The Abaqus decks: every scene number on the header line and in its card (the contact
/// slope at Kz, μ with the elastic slip μ·N/Kx, the mass, the rotary inertia, the supports'
/// places and overclosures), "not executed by rockslide", the results script's header row.
#[test]
fn the_abaqus_decks_carry_the_scenes_numbers_exactly() {
    let out = tempfile::tempdir().unwrap();
    let o = out.path().to_str().unwrap();
    for name in ["pepo-mass-accel", "pepo-ground-disp", "rpepo-mass-accel"] {
        let p = rockslide(&[
            "export",
            &format!("cases/{name}.toml"),
            "--to",
            "abaqus",
            "-o",
            o,
            "-q",
        ]);
        assert!(
            p.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&p.stderr)
        );
    }
    let read =
        |case: &str, file: &str| std::fs::read_to_string(out.path().join(case).join(file)).unwrap();
    let after = |deck: &str, marker: &str| -> Vec<f64> {
        let i = deck
            .lines()
            .position(|l| l == marker)
            .unwrap_or_else(|| panic!("{marker}"));
        let line = deck.lines().nth(i + 1).unwrap();
        line.split(',').map(|f| f.trim().parse().unwrap()).collect()
    };
    // the PEPO, double arrangement: both contacts, the mass
    let c = case("pepo-mass-accel");
    let Model::Oscillator(osc) = &c.scene.model else {
        panic!("an oscillator")
    };
    let d = osc.double.as_ref().unwrap();
    let deck = read("pepo-mass-accel", "abaqus_model_double.inp");
    assert!(deck.contains("** NOT EXECUTED BY ROCKSLIDE"));
    let scene = pairs(&deck, "** scene:");
    for (k, v) in [
        ("mass", osc.mass),
        ("gravity", osc.gravity),
        ("kx", d.lower.kx),
        ("kz", d.lower.kz),
        ("mu", d.lower.mu),
        ("kx2", d.upper.kx),
        ("kz2", d.upper.kz),
        ("mu2", d.upper.mu),
    ] {
        assert_eq!(scene[k], v, "{k}");
    }
    let weight = osc.mass * osc.gravity;
    assert_eq!(
        after(&deck, "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR"),
        [d.lower.kz]
    );
    let slip = format!(
        "*FRICTION, ELASTIC SLIP={}",
        rockslide::export::deck::num(d.lower.mu * weight / d.lower.kx)
    );
    assert_eq!(after(&deck, &slip), [d.lower.mu]);
    assert_eq!(after(&deck, "*MASS, ELSET=EMASS"), [osc.mass]);
    assert!(deck.contains("*DYNAMIC, DIRECT, ALPHA=0.0, INITIAL=NO\n1e-3, 1.0\n"));
    let script = read("pepo-mass-accel", "abaqus_model_double_csv.py");
    assert!(
        script.contains(
            "out.write('time [s],rel_disp [m],slide [m],resistance [N],vel [m/s],node_disp [m]\\n')"
        ),
        "{script}"
    );
    // the PEPO under a ground displacement: imposed on the ground, its column written
    let deck = read("pepo-ground-disp", "abaqus_model.inp");
    assert!(deck.contains("*BOUNDARY, AMPLITUDE=EXCITATION\nGROUND, 1, 1, 1.0"));
    assert!(read("pepo-ground-disp", "abaqus_model_csv.py").contains(",ground_disp [m]"));
    // the RPEPO: the rigid body, its supports, the contact per support
    let c = case("rpepo-mass-accel");
    let Model::RockingBody(r) = &c.scene.model else {
        panic!("a rocking body")
    };
    let deck = read("rpepo-mass-accel", "abaqus_model.inp");
    assert_rocking_scene_line(&deck, r);
    let inertia = r.rotational_inertia;
    assert_eq!(
        after(&deck, "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR"),
        [r.contact.kz]
    );
    let share = r.weight() / r.supports as f64;
    let slip = format!(
        "*FRICTION, ELASTIC SLIP={}",
        rockslide::export::deck::num(r.contact.mu * share / r.contact.kx)
    );
    assert_eq!(after(&deck, &slip), [r.contact.mu]);
    assert_eq!(after(&deck, "*MASS, ELSET=EMASS"), [r.mass]);
    assert_eq!(
        after(&deck, "*ROTARY INERTIA, ELSET=EINERTIA"),
        [inertia; 3]
    );
    let settle = -share / r.contact.kz;
    for (i, x) in r.support_positions().iter().enumerate() {
        let node = format!("{}, ", 1001 + i);
        let line = deck.lines().find(|l| l.starts_with(&node)).unwrap();
        let xyz: Vec<f64> = line
            .split(',')
            .skip(1)
            .map(|f| f.trim().parse().unwrap())
            .collect();
        assert_eq!(xyz[..2], [*x, 0.0], "support {i}");
        assert!(
            (xyz[2] / settle - 1.0).abs() < 1e-12,
            "support {i}: {}",
            xyz[2]
        );
    }
    assert!(deck.contains(&format!(
        "*CLOAD\n1000, 3, {}",
        rockslide::export::deck::num(-r.weight())
    )));
    assert!(read("rpepo-mass-accel", "abaqus_model_csv.py").contains(
        "time [s],rel_disp [m],slide [m],resistance [N],cm_x [m],cm_z [m],rotation [rad],base_shear [N],normal [N]"
    ));
    // the RPEPO's double arrangement is refused, naming the setting
    let settings = rockslide::export::deck::DeckSettings {
        arrangement: rockslide::case::Arrangement::Double,
        ..rockslide::export::abaqus::settings(&c).unwrap()
    };
    let e = rockslide::export::abaqus::export_with(&c, &settings)
        .unwrap_err()
        .to_string();
    assert!(e.contains("engines.abaqus.variants"), "{e}");
}

/// The ANSYS deck: every scene number as an APDL parameter, the paper's settings, the
/// header row rockslide reads, and "not executed by rockslide".
#[test]
fn the_ansys_deck_carries_the_scene_and_the_papers_settings() {
    let out = tempfile::tempdir().unwrap();
    let o = out.path().to_str().unwrap();
    for name in ["pepo-mass-accel", "pepo-ground-disp", "rpepo-mass-accel"] {
        let p = rockslide(&[
            "export",
            &format!("cases/{name}.toml"),
            "--to",
            "ansys",
            "-o",
            o,
            "-q",
        ]);
        assert!(
            p.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&p.stderr)
        );
    }
    let param = |deck: &str, name: &str| -> f64 {
        let prefix = format!("{name} = ");
        deck.lines()
            .find_map(|l| l.strip_prefix(&prefix))
            .unwrap_or_else(|| panic!("no {name}"))
            .parse()
            .unwrap()
    };
    let c = case("pepo-mass-accel");
    let Model::Oscillator(osc) = &c.scene.model else {
        panic!()
    };
    let single =
        std::fs::read_to_string(out.path().join("pepo-mass-accel/ansys_model.inp")).unwrap();
    assert_eq!(param(&single, "MASS"), osc.mass);
    assert_eq!(param(&single, "GRAV"), osc.gravity);
    assert_eq!(param(&single, "KX1"), osc.contact.kx);
    assert_eq!(param(&single, "KZ1"), osc.contact.kz);
    assert_eq!(param(&single, "MU1"), osc.contact.mu);
    let double =
        std::fs::read_to_string(out.path().join("pepo-mass-accel/ansys_model_double.inp")).unwrap();
    let d = osc.double.as_ref().unwrap();
    assert_eq!(param(&double, "KX1"), d.lower.kx);
    assert_eq!(param(&double, "KX2"), d.upper.kx);
    assert_eq!(param(&double, "KZ2"), d.upper.kz);
    assert!(
        double.contains("KEYOPT,2,10,1"),
        "element 2 rough (mu = inf)"
    );
    for deck in [&single, &double] {
        assert!(deck.contains("NOT EXECUTED BY ROCKSLIDE"));
        assert!(
            deck.contains("KEYOPT,1,2,1") && deck.contains("KEYOPT,1,3,0"),
            "pure penalty, no weak spring"
        );
        assert!(deck.contains("CNVTOL,F,,0.005,2") && deck.contains("CNVTOL,U,,0.05,2"));
        assert!(deck.contains(&format!(
            "DELTIM,{}\n",
            rockslide::export::deck::num(c.run.dt)
        )));
        assert!(deck.contains("('time [s],rel_disp [m],slide [m],resistance [N]"));
    }
    let ground =
        std::fs::read_to_string(out.path().join("pepo-ground-disp/ansys_model.inp")).unwrap();
    assert!(ground.contains("D,1,UX,%LOADTAB%") && ground.contains(",ground_disp [m]')"));
    let r = case("rpepo-mass-accel");
    let Model::RockingBody(body) = &r.scene.model else {
        panic!()
    };
    let rocking =
        std::fs::read_to_string(out.path().join("rpepo-mass-accel/ansys_model.inp")).unwrap();
    assert_eq!(param(&rocking, "HCM"), body.cm_height);
    assert_eq!(param(&rocking, "HALFB"), body.half_width);
    assert_eq!(param(&rocking, "KX1"), body.contact.kx);
    // ten supports at the scene's abscissae, each a CONTA178 from its ground node
    for (i, x) in body.support_positions().into_iter().enumerate() {
        let line = format!("N,{},{},0,0", 101 + i, rockslide::export::deck::num(x));
        assert!(rocking.contains(&line), "{line}");
        assert!(rocking.contains(&format!("E,{},{}\n", 201 + i, 101 + i)));
    }
    assert_eq!(
        rocking.matches("\nE,2").count(),
        body.supports,
        "one CONTA178 per support"
    );
    // the loading table: the half-sine's value at t = 0.1 s, times the mass
    let Some(rockslide::case::Signal::SinePulse {
        amplitude, omega, ..
    }) = r.scene.excitation.signal()
    else {
        panic!()
    };
    let k = (0.1 / r.run.dt).round() as usize;
    let t = k as f64 * r.run.dt;
    let v = param(&rocking, &format!("LOADTAB({},1)", k + 1));
    assert!((v / (body.mass * amplitude * (omega * t).sin()) - 1.0).abs() < 1e-12);
    let _ = ansys::SECTION;
}

/// Without ccx the case says why CalculiX does not take part, and the rest is gated.
#[test]
fn without_ccx_the_case_says_not_applicable() {
    let out = tempfile::tempdir().unwrap();
    let p = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("ROCKSLIDE_CCX", "rockslide-no-such-ccx")
        .args([
            "run",
            "cases/calculix/pepo-single-calculix.toml",
            "-q",
            "-o",
        ])
        .arg(out.path())
        .output()
        .unwrap();
    let report =
        std::fs::read_to_string(out.path().join("pepo-single-calculix/report.md")).unwrap();
    assert!(
        report.contains(
            "calculix: not applicable — CalculiX not found (apt-get install calculix-ccx)"
        ),
        "{}",
        String::from_utf8_lossy(&p.stderr)
    );
}

/// PEPO: CalculiX (penalty contact with Coulomb friction, dt 1e-4) against the exact
/// solution.
#[test]
#[cfg_attr(
    not(live_calculix),
    ignore = "CalculiX not found (apt-get install calculix-ccx); ROCKSLIDE_REQUIRE_CALCULIX=1 runs it"
)]
fn calculix_pepo_matches_the_exact_solution() {
    if !live("calculix_pepo_matches_the_exact_solution") {
        return;
    }
    let (r, i) = run_calculix("calculix/pepo-single-calculix");
    let exact = &r.reference.as_ref().unwrap().responses;
    let mine = &r.run_responses[i];
    let d = |k: &str| 100.0 * (mine[k] / exact[k] - 1.0);
    // the targets: residual sliding 1 %, peak relative displacement 0.5 %; measured
    // −0.000067 % and −0.000065 % (see the case file)
    assert!(
        d("residual_sliding").abs() < 1e-4,
        "{}",
        d("residual_sliding")
    );
    assert!(
        d("peak_relative_displacement").abs() < 1e-4,
        "{}",
        d("peak_relative_displacement")
    );
    assert!((mine["slip_end"] - exact["slip_end"]).abs() <= 1e-3,);
    assert_gate_passes(&r);
}

/// PEPO, the paper's double arrangement: CalculiX (element 1 slides, element 2 elastic,
/// the middle plate's mass Kx1·Δt², dt 1e-4) against the exact solution, whose slider is
/// the two elements in series.
#[test]
#[cfg_attr(
    not(live_calculix),
    ignore = "CalculiX not found (apt-get install calculix-ccx); ROCKSLIDE_REQUIRE_CALCULIX=1 runs it"
)]
fn calculix_pepo_double_matches_the_exact_solution() {
    if !live("calculix_pepo_double_matches_the_exact_solution") {
        return;
    }
    let (r, i) = run_calculix("calculix/pepo-double-calculix");
    let exact = &r.reference.as_ref().unwrap().responses;
    let mine = &r.run_responses[i];
    let d = |k: &str| 100.0 * (mine[k] / exact[k] - 1.0);
    // the targets: residual sliding 1 %, peak relative displacement 0.5 %; measured
    // −0.0903 % and −0.0907 % (see the case file): the middle plate's inertia, 0.1 % of
    // the body's mass
    assert!(
        (d("residual_sliding") + 0.0903).abs() < 0.001,
        "{}",
        d("residual_sliding")
    );
    assert!(
        (d("peak_relative_displacement") + 0.0907).abs() < 0.001,
        "{}",
        d("peak_relative_displacement")
    );
    // the finding: the middle plate's bursts of stick and slip at the end of sliding
    // (measured 6 episodes, the last ending at 0.2978 s, 2.6 ms before the exact end)
    assert!(mine["slip_episodes"] >= 2.0, "{}", mine["slip_episodes"]);
    let early = exact["slip_end"] - mine["slip_end"];
    assert!((0.001..0.004).contains(&early), "{early}");
    assert_gate_passes(&r);
}

/// RPEPO: CalculiX (a rigid body on ten penalty faces, the weight ramped over the vertical
/// period, HHT −0.1, dt 2e-4) against fe at matched settings over the pulse's first
/// 0.56 s: the events and peaks within the case's measured differences, the ramp's time
/// taken off (the trace starts at 0 from the static state), the invariants held.
#[test]
#[cfg_attr(
    not(live_calculix),
    ignore = "CalculiX not found (apt-get install calculix-ccx); ROCKSLIDE_REQUIRE_CALCULIX=1 runs it"
)]
fn calculix_rpepo_matches_fe_at_matched_settings() {
    if !live("calculix_rpepo_matches_fe_at_matched_settings") {
        return;
    }
    let (r, i) = run_calculix("calculix/rpepo-mass-accel-calculix");
    let fe = run_index(&r, "fe/single");
    let run = &r.runs[i];
    // the ramp's 0.1 s taken off: 0 to 0.56 s every increment, at rest on the static
    // overclosure at t = 0 (cm_z from M·g/(n·Kz): within 1 µm)
    let time = &run.trace.time;
    assert_eq!(time.len(), 2801);
    assert!(time[0].abs() < 1e-12 && (time[2800] - 0.56).abs() < 1e-9);
    let cm_z = run.trace.column("cm_z").unwrap();
    assert!(cm_z[0].abs() < 1e-6, "{}", cm_z[0]);
    let normal = run.trace.column("normal").unwrap();
    // the weight to +0.0017 % at the ramp's end (measured 9,810,164 N at dt = 2e-4 s)
    assert!((normal[0] / 9.81e6 - 1.0).abs() < 2e-5, "{}", normal[0]);
    let mine = &r.run_responses[i];
    let theirs = &r.run_responses[fe];
    let d = |k: &str| 100.0 * (mine[k] / theirs[k] - 1.0);
    // measured (the case file): rotation −0.031 %, uplift −0.111 %, sliding −0.258 %
    assert!(d("peak_rotation").abs() < 0.05, "{}", d("peak_rotation"));
    assert!(d("peak_uplift").abs() < 0.15, "{}", d("peak_uplift"));
    assert!(d("peak_sliding").abs() < 0.3, "{}", d("peak_sliding"));
    assert!(
        (mine["slip_start"] - theirs["slip_start"]).abs() < 2.5e-4,
        "{} {}",
        mine["slip_start"],
        theirs["slip_start"]
    );
    // the invariants on CalculiX's own sums: |base shear| ≤ μ·N, N ≥ 0
    let invariants: Vec<_> = r
        .invariants
        .iter()
        .filter(|c| c.run == "calculix/external")
        .collect();
    assert!(invariants.len() >= 2, "{invariants:?}");
    assert!(invariants.iter().all(|c| c.holds()), "{invariants:?}");
    assert_gate_passes(&r);
}

/// A live run past its time limit is a run that did not converge, saying why.
#[test]
#[cfg_attr(
    not(live_calculix),
    ignore = "CalculiX not found (apt-get install calculix-ccx); ROCKSLIDE_REQUIRE_CALCULIX=1 runs it"
)]
fn a_calculix_run_past_its_time_limit_is_a_failed_run() {
    if !live("a_calculix_run_past_its_time_limit_is_a_failed_run") {
        return;
    }
    let c = crate::common::case_with(
        "calculix/pepo-single-calculix",
        "dt = 1.0e-4 ",
        "timeout = 0.001\ndt = 1.0e-4 ",
    );
    let r = run_case(c).unwrap();
    let run = &r.runs[run_index(&r, "calculix/external")];
    assert!(!run.status.completed());
    assert!(
        run.findings[0].contains("did not finish within 0.001 s"),
        "{:?}",
        run.findings
    );
}

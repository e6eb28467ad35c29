//! The CalculiX (`ccx`) export: the PEPO, single or double, as a runnable `.inp` deck whose
//! `*NODE PRINT` requests write to the `.dat` file what rockslide reads back
//! (`rockslide-formats`' `calculix_dat`), so that CalculiX takes part live as `calculix`.
//!
//! The slider is an elastic-perfectly-plastic unit cube in simple shear (one `C3D8`,
//! von Mises plasticity with ν = 0): shear stiffness G·A/h = Kx, yield in shear
//! σy/√3 = μ·M·g — the exact elastic-perfectly-plastic oscillator of the paper, as
//! OpenSees's `ElasticPP` is. Measured with CalculiX 2.20 on `pepo-mass-accel`: residual
//! sliding −0.000067 % against the exact solution at Δt = 1e-4 s. CalculiX's own penalty
//! contact with Coulomb friction (`*CONTACT PAIR`, `*FRICTION`) is not used: in CalculiX
//! 2.20's implicit dynamics its energy-based impact rules (`checkimpacts`) cut the
//! increment of a persistent frictional contact to 1e-7 s or stop the run as diverging
//! (measured, `docs/decks.md`). Settings come from `[engines.calculix]` (`dt`, `variants`,
//! `timeout`), see [`DeckSettings::from_case`].

use std::fmt::Write as _;

use rockslide_core::case::{Case, Contact, Excitation, Model, Oscillator, Signal};
use rockslide_core::error::InputError;

use crate::deck::{DeckSettings, check_scene, num, one_line};
use crate::{Export, ExportFile, ExportResult};

/// The case section that configures the export and asks for the live run.
pub const SECTION: &str = "calculix";

/// Job name of the single arrangement's deck (`<job>.inp`, results `<job>.dat`).
pub const JOB: &str = "calculix_model";

/// The deck's and its results' file names of an arrangement.
pub fn names(double: bool) -> (String, String) {
    let job = if double {
        format!("{JOB}_double")
    } else {
        JOB.to_string()
    };
    (format!("{job}.inp"), format!("{job}.dat"))
}

/// The massless node between the two elements of the double arrangement.
const MIDDLE_NODE: u64 = 5;
/// A ground node (its displacement is the ground's).
const GROUND_NODE: u64 = 1;

/// Node sets the `.dat` file names (CalculiX prints them upper case).
pub const SET_BODY: &str = "BODY";
/// The double arrangement's massless node.
pub const SET_MIDDLE: &str = "MIDDLE";
/// The ground's nodes: their reaction is the slider's force, with the sign reversed.
pub const SET_GROUND: &str = "GROUND";
/// One ground node: the ground's displacement and velocity.
pub const SET_GROUND_REF: &str = "GROUNDREF";

/// The settings a case asks for (`[engines.calculix]`).
pub fn settings(case: &Case) -> Result<DeckSettings, InputError> {
    DeckSettings::from_case(case, SECTION)
}

/// The deck of a case with its own settings.
pub fn export(case: &Case) -> ExportResult {
    export_with(case, &settings(case)?)
}

/// The deck of a case with the given settings.
pub fn export_with(case: &Case, settings: &DeckSettings) -> ExportResult {
    check_scene(case, "CalculiX", settings.double())?;
    let o = match &case.scene.model {
        Model::Oscillator(o) => o,
        _ => {
            return Err(case.field_error(
                "model.kind",
                "is \"rocking-body\": the CalculiX deck writes the PEPO (single and double); the RPEPO needs CalculiX's frictional contact, which its 2.20 implicit dynamics does not run (docs/decks.md); `--to ansys` writes the RPEPO",
            ));
        }
    };
    let (lower, upper) = arrangement(case, o, settings.double())?;
    let mut deck = header(case, o, settings);
    mesh(&mut deck, o, lower, upper);
    excitation(&mut deck, case, settings)?;
    step(&mut deck, case, o, settings);
    let (name, results) = names(settings.double());
    Ok(Export {
        files: vec![ExportFile {
            name,
            bytes: deck.into_bytes(),
        }],
        results,
    })
}

/// Element 1 (the slider) and element 2 (elastic, the double arrangement's upper one).
fn arrangement<'a>(
    case: &Case,
    o: &'a Oscillator,
    double: bool,
) -> Result<(&'a Contact, Option<&'a Contact>), InputError> {
    if !double {
        return Ok((&o.contact, None));
    }
    let d = o.double.as_ref().expect("checked by check_scene");
    if d.upper.mu.is_finite() {
        return Err(case.field_error(
            "model.double.mu2",
            "must be inf for the CalculiX deck: element 2 is elastic (only element 1 slides)",
        ));
    }
    Ok((&d.lower, Some(&d.upper)))
}

/// What the deck is, how to run it, the scene's numbers, the model chosen and why.
fn header(case: &Case, o: &Oscillator, settings: &DeckSettings) -> String {
    let mut h = String::new();
    let _ = writeln!(
        h,
        "** CalculiX (ccx) model of the rockslide case \"{}\": {}",
        case.name,
        one_line(&case.title)
    );
    let _ = writeln!(h, "** Source: {}", one_line(&case.source));
    let _ = writeln!(
        h,
        "** Written by rockslide {} (`rockslide export CASE --to calculix`). Units: SI (kg, N, m, s).",
        env!("CARGO_PKG_VERSION")
    );
    h.push_str(
        "** Run: ccx -i JOB (JOB = this file's name without .inp; Debian: apt-get install calculix-ccx).\n\
         **      The *NODE PRINT requests write the body's U and V and the ground's total RF to JOB.dat,\n\
         **      which rockslide reads back (a case with [engines.calculix] runs this deck live).\n",
    );
    let _ = write!(
        h,
        "** scene: mass = {}, gravity = {}, kx = {}, kz = {}, mu = {}",
        num(o.mass),
        num(o.gravity),
        num(o.contact.kx),
        num(o.contact.kz),
        num(o.contact.mu)
    );
    if let Some(d) = o.double.as_ref().filter(|_| settings.double()) {
        let _ = write!(
            h,
            ", kx1 = {}, kz1 = {}, mu1 = {}, kx2 = {}, kz2 = {}, mu2 = {}",
            num(d.lower.kx),
            num(d.lower.kz),
            num(d.lower.mu),
            num(d.upper.kx),
            num(d.upper.kz),
            num(d.upper.mu)
        );
    }
    h.push('\n');
    let _ = writeln!(
        h,
        "** settings: dt = {} s, output every {} increment(s), {} increments, {} arrangement",
        num(settings.dt),
        settings.output_every,
        settings.steps,
        settings.arrangement.name()
    );
    h.push_str(MODEL);
    h
}

/// The model chosen, and why: written in every deck.
const MODEL: &str = "\
** Model (measured with CalculiX 2.20 on the rockslide scenes):
** - The slider is a unit cube (one C3D8, A = h = 1 m) in simple shear: its bottom face is the
**   ground, its top face moves with the body (*EQUATION), vertical and lateral motion fixed.
**   Elastic G = Kx (E = 2 Kx, nu = 0), von Mises perfectly plastic with sigma_y = sqrt(3) mu M g:
**   it yields in shear at mu M g, the elastic-perfectly-plastic oscillator of the paper (the
**   CONTA178 in sticking and sliding with a constant normal force M g). Slip = deformation -
**   force/Kx. The normal stiffness Kz does not enter the PEPO (the normal force is constant).
** - The double arrangement stacks a second cube, elastic with G = Kx2 (mu2 = inf), between a
**   massless middle node set and the body: element 1 slides, element 2 stays elastic.
** - Implicit dynamics, *DYNAMIC DIRECT with ALPHA = 0 (Newmark average acceleration) at the
**   case's dt, CalculiX's default Newton controls. Ground acceleration is applied in
**   relative coordinates (a force -M ag(t) on the body); a ground displacement is imposed on
**   the ground nodes (the body's relative displacement is then U(body) - U(ground)).
";

/// Nodes, elements, sets, materials and constraints.
fn mesh(deck: &mut String, o: &Oscillator, lower: &Contact, upper: Option<&Contact>) {
    let layers = if upper.is_some() { 2 } else { 1 };
    deck.push_str("*NODE\n");
    for layer in 0..=layers {
        for (i, (x, y)) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
            .into_iter()
            .enumerate()
        {
            let _ = writeln!(deck, "{}, {x:?}, {y:?}, {}.0", 4 * layer + i + 1, layer);
        }
    }
    let body = 4 * layers + 1;
    deck.push_str("*ELEMENT, TYPE=C3D8, ELSET=SLIDER\n1, 1, 2, 3, 4, 5, 6, 7, 8\n");
    if upper.is_some() {
        deck.push_str("*ELEMENT, TYPE=C3D8, ELSET=UPPER\n2, 5, 6, 7, 8, 9, 10, 11, 12\n");
    }
    let _ = writeln!(
        deck,
        "*ELEMENT, TYPE=MASS, ELSET=EMASS\n{}, {body}\n*MASS, ELSET=EMASS\n{}",
        10 * layers + 1,
        num(o.mass)
    );
    let _ = writeln!(
        deck,
        "*NSET, NSET={SET_GROUND}\n1, 2, 3, 4\n*NSET, NSET={SET_GROUND_REF}\n{GROUND_NODE}\n*NSET, NSET={SET_BODY}\n{body}"
    );
    if upper.is_some() {
        let _ = writeln!(deck, "*NSET, NSET={SET_MIDDLE}\n{MIDDLE_NODE}");
    }
    deck.push_str("*NSET, NSET=MOVING\n");
    let moving: Vec<String> = (5..=4 * layers + 4).map(|n| n.to_string()).collect();
    let _ = writeln!(deck, "{}", moving.join(", "));
    // every node of a layer moves with its first node: uniform simple shear
    deck.push_str("*EQUATION\n");
    for layer in 1..=layers {
        let first = 4 * layer + 1;
        for n in first + 1..first + 4 {
            let _ = writeln!(deck, "2\n{n}, 1, 1.0, {first}, 1, -1.0");
        }
    }
    material(deck, "SLIDER", lower.kx, o.mass * o.gravity * lower.mu);
    deck.push_str("*SOLID SECTION, ELSET=SLIDER, MATERIAL=SLIDER\n");
    if let Some(u) = upper {
        material(deck, "UPPER", u.kx, f64::INFINITY);
        deck.push_str("*SOLID SECTION, ELSET=UPPER, MATERIAL=UPPER\n");
    }
}

/// A unit cube's material: shear stiffness `kx`, yield in shear at `limit` (none if infinite).
fn material(deck: &mut String, name: &str, kx: f64, limit: f64) {
    let _ = writeln!(
        deck,
        "*MATERIAL, NAME={name}\n*ELASTIC\n{}, 0.0",
        num(2.0 * kx)
    );
    if limit.is_finite() {
        let _ = writeln!(deck, "*PLASTIC\n{}, 0.0", num(3f64.sqrt() * limit));
    }
}

/// The amplitude (`EXCITATION`) of the signal, sampled where CalculiX interpolates it.
fn excitation(deck: &mut String, case: &Case, settings: &DeckSettings) -> Result<(), InputError> {
    let Some(signal) = case.scene.excitation.signal() else {
        return Ok(());
    };
    deck.push_str("*AMPLITUDE, NAME=EXCITATION\n");
    let points: Vec<(f64, f64)> = match signal {
        // a pulse sampled at every step (Newmark sees the load at the step ends only)
        Signal::SinePulse { .. } => {
            let last = (signal.end() / settings.dt).ceil() as usize + 1;
            (0..=last.min(settings.steps))
                .map(|k| {
                    let t = k as f64 * settings.dt;
                    (t, signal.value(t))
                })
                .collect()
        }
        // a record: its samples, linear in between (the references' convention), zero after
        Signal::Record { dt, samples, .. } => samples
            .iter()
            .enumerate()
            .map(|(i, v)| (i as f64 * dt, *v))
            .chain(std::iter::once((samples.len() as f64 * dt, 0.0)))
            .collect(),
    };
    for (t, v) in points {
        let _ = writeln!(deck, "{}, {}", num(t), num(v));
    }
    Ok(())
}

/// Boundary conditions, the dynamic step, the load and the output requests.
fn step(deck: &mut String, case: &Case, o: &Oscillator, settings: &DeckSettings) {
    let excitation = &case.scene.excitation;
    deck.push_str("*BOUNDARY\nGROUND, 2, 3\nMOVING, 2, 3\n");
    if !matches!(excitation, Excitation::GroundDisplacement(_)) {
        deck.push_str("GROUND, 1, 1\n");
    }
    let _ = writeln!(
        deck,
        "*STEP, INC={}\n*DYNAMIC, DIRECT, ALPHA=0.0\n{}, {}",
        settings.steps + 10,
        num(settings.dt),
        num(settings.steps as f64 * settings.dt)
    );
    match excitation {
        Excitation::None => {}
        Excitation::MassAcceleration(_) => {
            let _ = writeln!(
                deck,
                "*CLOAD, AMPLITUDE=EXCITATION\n{SET_BODY}, 1, {}",
                num(o.mass)
            );
        }
        Excitation::GroundAcceleration(_) => {
            let _ = writeln!(
                deck,
                "*CLOAD, AMPLITUDE=EXCITATION\n{SET_BODY}, 1, {}",
                num(-o.mass)
            );
        }
        Excitation::GroundDisplacement(_) => {
            deck.push_str("*BOUNDARY, AMPLITUDE=EXCITATION\nGROUND, 1, 1, 1.0\n");
        }
    }
    let every = settings.output_every;
    let _ = writeln!(
        deck,
        "*NODE PRINT, NSET={SET_BODY}, FREQUENCY={every}\nU, V\n*NODE PRINT, NSET={SET_GROUND}, FREQUENCY={every}, TOTALS=ONLY\nRF"
    );
    if settings.double() {
        let _ = writeln!(deck, "*NODE PRINT, NSET={SET_MIDDLE}, FREQUENCY={every}\nU");
    }
    if matches!(excitation, Excitation::GroundDisplacement(_)) {
        let _ = writeln!(
            deck,
            "*NODE PRINT, NSET={SET_GROUND_REF}, FREQUENCY={every}\nU, V"
        );
    }
    deck.push_str("*END STEP\n");
}

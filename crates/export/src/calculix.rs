//! The CalculiX (`ccx`) export: the PEPO, single or double, as a runnable `.inp` deck of
//! penalty contact with Coulomb friction (the model in [`crate::inp`], shared with the
//! Abaqus deck), and the RPEPO's single arrangement ([`crate::calculix_rocking`]), whose
//! `*NODE PRINT` requests write to the `.dat` file what rockslide reads back
//! (`rockslide-formats`' `calculix_dat`), so that CalculiX takes part live as `calculix`.
//!
//! The PEPO: implicit dynamics (`*DYNAMIC, DIRECT, ALPHA=0.0`: Newmark average
//! acceleration at the case's Δt). CalculiX 2.20 judges an implicit dynamic step with
//! contact by energy rules relative to the model's largest energy so far (`checkimpacts`,
//! a tolerance fixed at 0.02 in its source): a model at rest has none, so the first
//! increments of contact fail them and a fixed-increment run stops as diverging. The deck adds an energy reference: a
//! free body of constant kinetic energy (5e11 J), coupled to nothing and loaded by
//! nothing, so that the rules are relative to a large constant energy. Measured on
//! `pepo-mass-accel`: residual sliding within 0.01 % of the exact solution (docs/decks.md).
//! Settings come from `[engines.calculix]` (`dt`, `variants`, `timeout`), see
//! [`DeckSettings::from_case`].

use std::fmt::Write as _;

use rockslide_core::case::{Case, Contact, Excitation, Model, Oscillator, RockingBody};
use rockslide_core::error::InputError;

use crate::calculix_rocking;
use crate::deck::{DeckSettings, check_scene, num};
use crate::inp::{self, Dialect, Layout, list};
use crate::{Export, ExportResult};

pub use crate::inp::{SET_BODY, SET_GROUND, SET_GROUND_REF, SET_MIDDLE};

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

/// The energy reference: a free C3D8 far from the model, mass 1e24 kg moving at 1e-6 m/s
/// in X (kinetic energy 5e11 J), coupled to nothing.
const REFERENCE_FIRST_NODE: u64 = 101;
const REFERENCE_ELEMENT: u64 = 9;
const REFERENCE_DENSITY: f64 = 1.0e24;
const REFERENCE_SPEED: f64 = 1.0e-6;

/// The node whose displacement and velocity are the body's.
pub fn body_node(double: bool) -> u64 {
    if double { 17 } else { 9 }
}

/// The double arrangement's middle node (its first plate node).
pub const MIDDLE_NODE: u64 = 9;

/// The element of the middle plate's point mass.
const MIDDLE_MASS_ELEMENT: u64 = 12;

/// The double arrangement's middle plate's mass, kg: Kx1·Δt², so that its inertia
/// stiffness under Newmark average acceleration, m/(Δt²/4), is 4·Kx1. The paper's middle
/// node is massless; CalculiX's Newton iteration cannot solve it once element 1 sticks
/// (docs/decks.md): from a slipping state it steps 2μN/Kx2 across a stick band 2μN/Kx1
/// wide, a hundred times narrower, and lands on the other slipping side, for ever. With
/// this inertia every step stays inside the band. 1010 kg at Δt = 1e-4 s on the paper's
/// Kx1 = 1.01e11 N/m: 0.1 % of the body's 1e6 kg.
pub fn middle_mass(kx1: f64, dt: f64) -> f64 {
    kx1 * dt * dt
}

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
    let deck = match &case.scene.model {
        Model::Oscillator(o) => oscillator(case, o, settings)?,
        Model::RockingBody(r) => rocking(case, r, settings)?,
        Model::RigidBlock(_) => unreachable!("refused by check_scene"),
    };
    let (name, results) = names(settings.double());
    Ok(Export::deck(name, deck, results))
}

/// The PEPO's deck (single or double).
fn oscillator(case: &Case, o: &Oscillator, settings: &DeckSettings) -> Result<String, InputError> {
    let (lower, upper) = arrangement(case, o, settings.double())?;
    let layout = Layout::pepo(o, lower, upper);
    debug_assert_eq!(layout.body_node(), body_node(settings.double()));
    let mut deck = header(case);
    deck.push_str(&oscillator_scene(o, settings));
    deck.push_str(MODEL);
    inp::plates(&mut deck, &layout);
    inp::constraints(&mut deck, o.mass, &layout);
    if settings.double() {
        middle_mass_card(&mut deck, lower, settings.dt);
    }
    energy_reference(&mut deck);
    inp::contact_pairs(&mut deck, &layout, o.mass * o.gravity, Dialect::Calculix);
    inp::amplitude(&mut deck, case, settings);
    step(&mut deck, case, o, settings);
    Ok(deck)
}

/// The RPEPO's deck ([`calculix_rocking`]).
fn rocking(case: &Case, r: &RockingBody, settings: &DeckSettings) -> Result<String, InputError> {
    let mut deck = header(case);
    let _ = writeln!(
        deck,
        "** scene: mass = {}, gravity = {}, cm_height = {}, half_width = {}, supports = {}, rotational_inertia = {}, kx = {}, kz = {}, mu = {}",
        num(r.mass),
        num(r.gravity),
        num(r.cm_height),
        num(r.half_width),
        r.supports,
        num(crate::opensees::rotational_inertia(r)),
        num(r.contact.kx),
        num(r.contact.kz),
        num(r.contact.mu)
    );
    let _ = writeln!(
        deck,
        "** settings: dt = {} s, output every {} increment(s), {} increments after a ramp of {} s, {} arrangement",
        num(settings.dt),
        settings.output_every,
        settings.steps,
        num(calculix_rocking::ramp(case, r, settings)),
        settings.arrangement.name()
    );
    deck.push_str(calculix_rocking::MODEL);
    calculix_rocking::deck(&mut deck, case, r, settings, energy_reference)?;
    Ok(deck)
}

/// Element 1 (the slider) and element 2 (μ = ∞, the double arrangement's upper one).
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

/// What the deck is and how to run it.
fn header(case: &Case) -> String {
    let mut h = inp::title_lines("CalculiX (ccx)", "calculix", case);
    h.push_str(
        "** Run: ccx -i JOB (JOB = this file's name without .inp; Debian: apt-get install calculix-ccx).\n\
         **      The *NODE PRINT requests write the body's U and V and the ground's total RF to JOB.dat,\n\
         **      which rockslide reads back (a case with [engines.calculix] runs this deck live).\n",
    );
    h
}

/// The PEPO's numbers and settings, two comment lines.
fn oscillator_scene(o: &Oscillator, settings: &DeckSettings) -> String {
    let mut h = String::new();
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
    h
}

/// The model chosen, and why: written in every deck.
const MODEL: &str = "\
** Model (measured with CalculiX 2.20 on the rockslide scenes):
** - Penalty contact with Coulomb friction, face to face: the body is a 1 m x 1 m plate (C3D8)
**   on a ground block whose top face is 3 m x 3 m. *SURFACE BEHAVIOR,
**   PRESSURE-OVERCLOSURE=LINEAR at Kz and *FRICTION mu with the stick slope Kx (per m2 of
**   the 1 m2 slave face: the scene's stiffnesses). The double arrangement puts a 1 m x 1 m
**   middle plate between the ground (element 1, slides) and a 3 m x 3 m body plate
**   (element 2, mu = inf written as 1e6). The paper's middle node is massless; CalculiX's
**   Newton iteration cycles without end on it once element 1 sticks (its steps from a
**   slipping state overshoot the stick band 2 mu N / Kx1), so the middle plate carries a
**   point mass Kx1 dt^2 (inertia stiffness 4 Kx1 under Newmark average acceleration;
**   1010 kg, 0.1 % of the body, at dt = 1e-4 s on the paper's Kx1).
** - The PEPO's normal force is the weight: each contact starts at its static overclosure
**   M g / Kz and the plates move in X only (Z and Y fixed, *EQUATION ties each plate's
**   nodes to its first node). The body's mass is a point mass on its plate's first node.
** - Implicit dynamics, *DYNAMIC DIRECT with ALPHA = 0 (Newmark average acceleration) at the
**   case's dt. Ground acceleration is applied in relative coordinates (a force -M ag(t) on
**   the body); a ground displacement is imposed on the ground block's nodes.
** - Energy reference (element 9, nodes 101-108): CalculiX 2.20 judges an implicit dynamic
**   step with contact by energy rules relative to the model's largest energy so far
**   (checkimpacts); the model starts at rest, so its first contact increments fail them and
**   a fixed-increment run stops. This free block (1e24 kg at 1e-6 m/s: 5e11 J of constant
**   kinetic energy, coupled to nothing) makes the rules relative to a large constant energy.
";

/// The middle plate's point mass ([`middle_mass`]) on its first node.
fn middle_mass_card(deck: &mut String, lower: &Contact, dt: f64) {
    let _ = writeln!(
        deck,
        "*ELEMENT, TYPE=MASS, ELSET=EMIDDLE\n{MIDDLE_MASS_ELEMENT}, {MIDDLE_NODE}\n*MASS, ELSET=EMIDDLE\n{}",
        num(middle_mass(lower.kx, dt))
    );
}

/// The free block of constant kinetic energy (see the deck's header).
fn energy_reference(deck: &mut String) {
    let n0 = REFERENCE_FIRST_NODE;
    deck.push_str("*NODE\n");
    for (layer, z) in [0.0, 1.0].into_iter().enumerate() {
        for (i, (x, y)) in [(10.0, 0.0), (11.0, 0.0), (11.0, 1.0), (10.0, 1.0)]
            .into_iter()
            .enumerate()
        {
            let n = n0 + 4 * layer as u64 + i as u64;
            let _ = writeln!(deck, "{n}, {}, {}, {}", num(x), num(y), num(z));
        }
    }
    let nodes = n0..=n0 + 7;
    let _ = writeln!(
        deck,
        "*ELEMENT, TYPE=C3D8, ELSET=ENERGYREF\n{REFERENCE_ELEMENT}, {}\n*NSET, NSET=ENERGYREF\n{}",
        list(nodes.clone()),
        list(nodes)
    );
    let _ = writeln!(
        deck,
        "*MATERIAL, NAME=ENERGYREF\n*ELASTIC\n1e14, 0.0\n*DENSITY\n{}\n*SOLID SECTION, ELSET=ENERGYREF, MATERIAL=ENERGYREF\n*INITIAL CONDITIONS, TYPE=VELOCITY\nENERGYREF, 1, {}",
        num(REFERENCE_DENSITY),
        num(REFERENCE_SPEED)
    );
}

/// Boundary conditions, the dynamic step, the load and the output requests.
fn step(deck: &mut String, case: &Case, o: &Oscillator, settings: &DeckSettings) {
    inp::boundary(deck, case);
    deck.push_str("ENERGYREF, 2, 3\n");
    let _ = writeln!(
        deck,
        "*STEP, INC={}\n*DYNAMIC, DIRECT, ALPHA=0.0\n{}, {}",
        settings.steps + 10,
        num(settings.dt),
        num(settings.steps as f64 * settings.dt)
    );
    inp::excitation_load(deck, case, o.mass, SET_BODY, SET_GROUND);
    if let (Some(d), Excitation::GroundAcceleration(_)) = (
        o.double.as_ref().filter(|_| settings.double()),
        &case.scene.excitation,
    ) {
        let mass = middle_mass(d.lower.kx, settings.dt);
        inp::excitation_load(deck, case, mass, SET_MIDDLE, SET_GROUND);
    }
    let every = settings.output_every;
    let _ = writeln!(
        deck,
        "*NODE PRINT, NSET={SET_BODY}, FREQUENCY={every}\nU, V\n*NODE PRINT, NSET={SET_GROUND}, FREQUENCY={every}, TOTALS=ONLY\nRF"
    );
    if settings.double() {
        let _ = writeln!(deck, "*NODE PRINT, NSET={SET_MIDDLE}, FREQUENCY={every}\nU");
    }
    if inp::moving_ground(case) {
        let _ = writeln!(
            deck,
            "*NODE PRINT, NSET={SET_GROUND_REF}, FREQUENCY={every}\nU, V"
        );
    }
    deck.push_str("*END STEP\n");
}

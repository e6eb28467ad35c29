//! The CalculiX deck of the RPEPO (single arrangement): a rigid body on its supports, each
//! support a small slave face in penalty contact with Coulomb friction against the ground,
//! run from rest under gravity ramped over the body's vertical period.
//!
//! The body is a `*RIGID BODY` (reference node at the centre of mass, a rotation node;
//! Y and the rotations about X and Z fixed). CalculiX has no rotary inertia element, so
//! the case's rotary inertia I is two point masses M/2 at ±√(I/M) from the centre of mass
//! in X (together the mass M and the inertia I about Y). Each support is an a × a face
//! (a = 0.01 m) starting just closed, its penalty slopes the support's stiffnesses per a²
//! (a face tilting with the body adds about Kz·a²/12 of rocking stiffness, 1e-5 of the
//! supports' Kz·b²); the master face is the ground block's 4 m × 2 m top.
//!
//! CalculiX computes the accelerations at a dynamic step's start without its contact
//! elements (docs/decks.md), so a body resting under its weight starts falling and keeps
//! a vertical oscillation of the normal force. The deck ramps the weight linearly from
//! zero over a whole number of output steps nearest the vertical period
//! 2π·√(M/(n·Kz)): a linear ramp over one period leaves no oscillation behind. The
//! excitation starts after the ramp, in the same step, its times shifted by the ramp;
//! the live reader takes the ramp's time off.
//!
//! `*STEP, NLGEOM` (the body turns exactly) and `*DYNAMIC, DIRECT, ALPHA=-0.1` (HHT-α:
//! the nearly massless rotation has a mode far above the step's frequency, which average
//! acceleration would carry undamped, as in the fe engine's cases) at the case's Δt.

use std::fmt::Write as _;

use rockslide_core::case::{Case, Excitation, RockingBody};
use rockslide_core::error::InputError;

use crate::deck::{DeckSettings, num};
use crate::inp::{self, SET_BODY, SET_GROUND, SET_GROUND_REF, list};

/// The side of a support's square slave face, m.
pub const FACE: f64 = 0.01;

/// HHT-α of the step.
pub const ALPHA: f64 = -0.1;

/// The centre of mass: the rigid body's reference node.
pub const CM_NODE: u64 = 1000;
/// The rigid body's rotation node (its U1, U2, U3 are the rotations about X, Y, Z).
pub const ROT_NODE: u64 = 1001;
/// The two point masses' nodes.
const MASS_NODES: [u64; 2] = [1002, 1003];
/// The first support's first node; support i's nodes follow from `+ 8·i`.
const SUPPORT_FIRST_NODE: u64 = 1101;
/// The first support's element.
const SUPPORT_FIRST_ELEMENT: u64 = 101;
/// Node set of the rotation node.
pub const SET_ROTATION: &str = "ROTATION";

/// The ground block: X within ±2 m, Y within ±1 m, Z from −1 m to its top face at 0.
const GROUND_HALF_LENGTH: f64 = 2.0;
const GROUND_HALF_WIDTH: f64 = 1.0;

/// The weight's ramp, s: the whole number of the case's output steps (`run.output_dt`,
/// else `run.dt`, at least Δt) nearest the body's vertical period on its n supports,
/// 2π·√(M/(n·Kz)), at least one output step; the same for the exported deck and the live
/// run (which prints every increment).
pub fn ramp(case: &Case, r: &RockingBody, settings: &DeckSettings) -> f64 {
    ramp_steps(case, r, settings) as f64 * settings.dt
}

/// The ramp's increments (see [`ramp`]).
pub fn ramp_steps(case: &Case, r: &RockingBody, settings: &DeckSettings) -> usize {
    let period = std::f64::consts::TAU * (r.mass / (r.supports as f64 * r.contact.kz)).sqrt();
    let output_step = case.run.output_dt.unwrap_or(case.run.dt).max(settings.dt);
    let every = ((output_step / settings.dt).round() as usize).max(1);
    let out = every as f64 * settings.dt;
    ((period / out).round().max(1.0) as usize) * every
}

/// The radius of the two point masses M/2 about the centre of mass: I = M·r².
pub fn mass_radius(r: &RockingBody, inertia: f64) -> f64 {
    (inertia / r.mass).sqrt()
}

/// The RPEPO's deck body (after the header): nodes, rigid body, masses, contact, loads,
/// the step and the output requests. `reference` writes the energy reference block.
pub fn deck(
    deck: &mut String,
    case: &Case,
    r: &RockingBody,
    settings: &DeckSettings,
    reference: impl Fn(&mut String),
) -> Result<(), InputError> {
    if settings.double() {
        return Err(case.field_error(
            "engines.calculix.variants",
            "is [\"double\"]: the CalculiX deck writes the RPEPO's single arrangement (the ANSYS deck writes both)",
        ));
    }
    let inertia = crate::opensees::rotational_inertia(r);
    let ramp_steps = ramp_steps(case, r, settings);
    let ramp = ramp_steps as f64 * settings.dt;
    nodes(deck, r, inertia);
    elements(deck, r);
    reference(deck);
    contact(deck, r);
    let _ = writeln!(
        deck,
        "*AMPLITUDE, NAME=WEIGHT\n0.0, 0.0\n{}, 1.0\n{}, 1.0",
        num(ramp),
        num(ramp + settings.steps as f64 * settings.dt)
    );
    inp::amplitude_after(deck, case, settings, ramp);
    step(deck, case, r, settings, ramp_steps);
    Ok(())
}

/// The ground block's corners, the centre of mass, the rotation node, the point masses
/// and each support's a × a × a cube, its bottom face on the ground's top (Z = 0).
fn nodes(deck: &mut String, r: &RockingBody, inertia: f64) {
    let (gx, gy) = (GROUND_HALF_LENGTH, GROUND_HALF_WIDTH);
    deck.push_str("*NODE\n");
    for (layer, z) in [-1.0, 0.0].into_iter().enumerate() {
        for (i, (x, y)) in [(-gx, -gy), (gx, -gy), (gx, gy), (-gx, gy)]
            .into_iter()
            .enumerate()
        {
            let _ = writeln!(
                deck,
                "{}, {}, {}, {}",
                1 + 4 * layer + i,
                num(x),
                num(y),
                num(z)
            );
        }
    }
    let h = num(r.cm_height);
    let _ = writeln!(deck, "{CM_NODE}, 0.0, 0.0, {h}\n{ROT_NODE}, 0.0, 0.0, {h}");
    // the same digits on both sides (the negative's text fits 20 characters): the two
    // masses mirror each other exactly
    let left = num(-mass_radius(r, inertia));
    let right = &left[1..];
    for (node, x) in MASS_NODES.into_iter().zip([left.as_str(), right]) {
        let _ = writeln!(deck, "{node}, {x}, 0.0, {h}");
    }
    let half = FACE / 2.0;
    for (i, x) in r.support_positions().into_iter().enumerate() {
        let first = support_first_node(i);
        for (layer, z) in [0.0, FACE].into_iter().enumerate() {
            for (j, (dx, dy)) in [(-half, -half), (half, -half), (half, half), (-half, half)]
                .into_iter()
                .enumerate()
            {
                let n = first + 4 * layer as u64 + j as u64;
                let _ = writeln!(deck, "{n}, {}, {}, {}", num(x + dx), num(dy), num(z));
            }
        }
    }
}

/// Numbers on lines of at most [`FIELDS_PER_LINE`] (CalculiX reads no more on a line).
fn rows(items: &[u64]) -> String {
    items
        .chunks(FIELDS_PER_LINE)
        .map(|c| list(c.iter().copied()))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The most entries CalculiX reads on one data line.
pub const FIELDS_PER_LINE: usize = 16;

fn support_first_node(i: usize) -> u64 {
    SUPPORT_FIRST_NODE + 8 * i as u64
}

/// The ground block and the supports (stiff C3D8), the point masses, the node sets and
/// the rigid body.
fn elements(deck: &mut String, r: &RockingBody) {
    let _ = writeln!(
        deck,
        "*ELEMENT, TYPE=C3D8, ELSET=GROUNDBLOCK\n1, {}",
        list(1..=8)
    );
    deck.push_str("*ELEMENT, TYPE=C3D8, ELSET=SUPPORTS\n");
    for i in 0..r.supports {
        let first = support_first_node(i);
        let _ = writeln!(
            deck,
            "{}, {}",
            SUPPORT_FIRST_ELEMENT + i as u64,
            list(first..first + 8)
        );
    }
    let _ = writeln!(
        deck,
        "*ELEMENT, TYPE=MASS, ELSET=EMASS\n11, {}\n12, {}\n*MASS, ELSET=EMASS\n{}",
        MASS_NODES[0],
        MASS_NODES[1],
        num(r.mass / 2.0)
    );
    let body: Vec<u64> = MASS_NODES
        .into_iter()
        .chain(SUPPORT_FIRST_NODE..support_first_node(r.supports))
        .collect();
    let _ = writeln!(
        deck,
        "*NSET, NSET={SET_GROUND}\n{g}\n*NSET, NSET={SET_GROUND_REF}\n1\n*NSET, NSET={SET_BODY}\n{CM_NODE}\n\
         *NSET, NSET={SET_ROTATION}\n{ROT_NODE}\n*NSET, NSET=RIGID\n{}\n\
         *MATERIAL, NAME=STIFF\n*ELASTIC\n1e14, 0.0\n\
         *SOLID SECTION, ELSET=GROUNDBLOCK, MATERIAL=STIFF\n*SOLID SECTION, ELSET=SUPPORTS, MATERIAL=STIFF\n\
         *RIGID BODY, NSET=RIGID, REF NODE={CM_NODE}, ROT NODE={ROT_NODE}",
        rows(&body),
        g = list(1..=8)
    );
}

/// The supports' bottom faces pressed into the ground's top: linear pressure–overclosure
/// at Kz/a², Coulomb friction μ with the stick slope Kx/a² (per m² of an a × a face: the
/// support's stiffnesses).
fn contact(deck: &mut String, r: &RockingBody) {
    let area = FACE * FACE;
    let c = &r.contact;
    let _ = writeln!(
        deck,
        "*SURFACE, NAME=SUPPORTFACES, TYPE=ELEMENT\nSUPPORTS, S1\n*SURFACE, NAME=GROUNDTOP, TYPE=ELEMENT\n1, S2\n\
         *CONTACT PAIR, INTERACTION=SUPPORT, TYPE=SURFACE TO SURFACE\nSUPPORTFACES, GROUNDTOP\n\
         *SURFACE INTERACTION, NAME=SUPPORT\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{}\n*FRICTION\n{}, {}",
        num(c.kz / area),
        num(c.mu),
        num(c.kx / area)
    );
}

/// The boundary conditions, the step, the weight and the excitation, the output requests.
fn step(
    deck: &mut String,
    case: &Case,
    r: &RockingBody,
    settings: &DeckSettings,
    ramp_steps: usize,
) {
    let _ = writeln!(
        deck,
        "*BOUNDARY\n{SET_GROUND}, 2, 3\n{CM_NODE}, 2, 2\n{ROT_NODE}, 1, 1\n{ROT_NODE}, 3, 3\nENERGYREF, 2, 3"
    );
    if !inp::moving_ground(case) {
        let _ = writeln!(deck, "{SET_GROUND}, 1, 1");
    }
    let total = settings.steps + ramp_steps;
    let _ = writeln!(
        deck,
        "*STEP, NLGEOM, INC={}\n*DYNAMIC, DIRECT, ALPHA={}\n{}, {}\n*CLOAD, AMPLITUDE=WEIGHT\n{CM_NODE}, 3, {}",
        total + 10,
        num(ALPHA),
        num(settings.dt),
        num(total as f64 * settings.dt),
        num(-r.weight())
    );
    inp::excitation_load(deck, case, r.mass, SET_BODY, SET_GROUND);
    let every = settings.output_every;
    let _ = writeln!(
        deck,
        "*NODE PRINT, NSET={SET_BODY}, FREQUENCY={every}\nU, V\n*NODE PRINT, NSET={SET_ROTATION}, FREQUENCY={every}\nU\n*NODE PRINT, NSET={SET_GROUND}, FREQUENCY={every}, TOTALS=ONLY\nRF"
    );
    if matches!(case.scene.excitation, Excitation::GroundDisplacement(_)) {
        let _ = writeln!(
            deck,
            "*NODE PRINT, NSET={SET_GROUND_REF}, FREQUENCY={every}\nU, V"
        );
    }
    deck.push_str("*END STEP\n");
}

/// The model chosen, and why: written in every RPEPO deck.
pub const MODEL: &str = "\
** Model (measured with CalculiX 2.20 against rockslide's fe engine, docs/decks.md):
** - The body is a *RIGID BODY: reference node 1000 at the centre of mass, rotation node 1001
**   (its U2 is the rotation about Y), Y and the rotations about X and Z fixed. Its mass and
**   the case's rotary inertia I are two point masses M/2 at +-sqrt(I/M) from the centre of
**   mass in X (CalculiX has no rotary inertia element).
** - Each support is a 0.01 m x 0.01 m face (the bottom of a small cube in the rigid body)
**   starting just closed, in face-to-face penalty contact with the ground block's 4 m x 2 m
**   top: *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR at Kz / a2 and *FRICTION mu with
**   the stick slope Kx / a2 (a = 0.01 m: per face, the support's stiffnesses).
** - The weight is ramped linearly from zero at the centre of mass over the body's vertical
**   period 2 pi sqrt(M / (n Kz)) (rounded to whole output steps): at a dynamic step's start
**   CalculiX computes the accelerations without the contact, so a body loaded by its full
**   weight at t = 0 starts falling; a linear ramp over one period leaves no vertical
**   oscillation. The excitation starts after the ramp (its times shifted by the ramp).
** - Implicit dynamics with NLGEOM, *DYNAMIC DIRECT with ALPHA = -0.1 (HHT: damps the nearly
**   massless rotation's mode) at the case's dt, fixed increments.
** - Energy reference (element 9, nodes 101-108): a free block of constant kinetic energy
**   (1e24 kg at 1e-6 m/s), coupled to nothing, so that CalculiX's energy rules for contact
**   increments (checkimpacts) are relative to a large constant energy.
";

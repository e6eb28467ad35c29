//! What the CalculiX and Abaqus decks share: the Abaqus input syntax both read, and the
//! paper's PEPO written in it as penalty contact with Coulomb friction.
//!
//! The model: a ground block whose top face is 3 m × 3 m, and the body as a 1 m × 1 m
//! plate standing on it (for the double arrangement, a 1 m × 1 m middle plate on the
//! ground and a 3 m × 3 m body plate on the middle one). Every contact is a face-to-face
//! pair whose slave face is 1 m² and lies inside its master face at any slip the scenes
//! reach, so that the penalty slopes per square metre are the scene's stiffnesses:
//! `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR` at Kz, `*FRICTION` μ with the stick
//! slope Kx. The plates move in X only: the PEPO's normal force is the weight, held
//! constant by starting each contact at its static overclosure M·g/Kz and fixing Z.

use std::fmt::Write as _;

use rockslide_core::case::{Case, Contact, Excitation, Oscillator, Signal};

use crate::deck::{DeckSettings, num, one_line};

/// The slave faces' area, m²: the penalty slopes per square metre are the stiffnesses.
pub const SLAVE_AREA: f64 = 1.0;

/// Thickness of a plate, m (the plates do not deform: it only shapes the elements).
const PLATE: f64 = 0.1;

/// μ written for a contact that never slips (μ = ∞ in the scene): its limit μ·N is 10⁶
/// times its normal force, far above any force the scenes reach.
pub const ROUGH_MU: f64 = 1.0e6;

/// Node sets the decks name (CalculiX prints them upper case).
pub const SET_BODY: &str = "BODY";
/// The double arrangement's middle plate's first node.
pub const SET_MIDDLE: &str = "MIDDLE";
/// The ground's nodes: their reaction is the slider's force, with the sign reversed.
pub const SET_GROUND: &str = "GROUND";
/// One ground node: the ground's displacement and velocity.
pub const SET_GROUND_REF: &str = "GROUNDREF";

/// The ground block's first node (its displacement is the ground's).
pub const GROUND_NODE: u64 = 1;

/// Where a plate is: its first node and element, its square's side, its bottom face's Z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plate {
    /// The first of its eight nodes (the one the others follow in X).
    pub first_node: u64,
    /// Its element number.
    pub element: u64,
    /// Lower and upper X (and Y) of its square, m.
    pub span: (f64, f64),
    /// Z of its bottom face, m.
    pub bottom: f64,
}

impl Plate {
    /// Its eight node numbers.
    pub fn nodes(&self) -> std::ops::RangeInclusive<u64> {
        self.first_node..=self.first_node + 7
    }
}

/// The PEPO as plates: the ground block, then the moving plates from the ground up.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// The ground block (its top face at Z = 0).
    pub ground: Plate,
    /// The middle plate (double arrangement only).
    pub middle: Option<Plate>,
    /// The body's plate; its first node carries the mass.
    pub body: Plate,
    /// The contact elements from the ground up: slave face, master face, contact.
    pub contacts: Vec<Pair>,
}

/// One contact: a slave face (element, face label) pressed into a master face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair {
    /// The interaction's name, `ELEMENT1` or `ELEMENT2` (the paper's element numbers).
    pub name: &'static str,
    /// Slave face: element and face (`S1` bottom, `S2` top of a C3D8).
    pub slave: (u64, &'static str),
    /// Master face.
    pub master: (u64, &'static str),
    /// Its stiffnesses and friction.
    pub contact: Contact,
}

/// Narrow square (the slave faces) and wide square (the master faces), m.
const NARROW: (f64, f64) = (0.0, 1.0);
const WIDE: (f64, f64) = (-1.0, 2.0);

impl Layout {
    /// The single arrangement (one contact, `lower`) or the double one (`lower` slides,
    /// `upper` elastic), each contact starting at its static overclosure M·g/Kz.
    pub fn pepo(o: &Oscillator, lower: &Contact, upper: Option<&Contact>) -> Self {
        let weight = o.mass * o.gravity;
        let ground = Plate {
            first_node: 1,
            element: 1,
            span: WIDE,
            bottom: -1.0,
        };
        let first = Plate {
            first_node: 9,
            element: 2,
            span: NARROW,
            bottom: -weight / (lower.kz * SLAVE_AREA),
        };
        let mut contacts = vec![Pair {
            name: "ELEMENT1",
            slave: (2, "S1"),
            master: (1, "S2"),
            contact: *lower,
        }];
        let Some(upper) = upper else {
            return Layout {
                ground,
                middle: None,
                body: first,
                contacts,
            };
        };
        // the middle plate's top face (slave) presses into the wide body plate's bottom
        let body = Plate {
            first_node: 17,
            element: 3,
            span: WIDE,
            bottom: first.bottom + PLATE - weight / (upper.kz * SLAVE_AREA),
        };
        contacts.push(Pair {
            name: "ELEMENT2",
            slave: (2, "S2"),
            master: (3, "S1"),
            contact: *upper,
        });
        Layout {
            ground,
            middle: Some(first),
            body,
            contacts,
        }
    }

    /// The moving plates, from the ground up.
    pub fn moving(&self) -> impl Iterator<Item = &Plate> {
        self.middle.iter().chain(std::iter::once(&self.body))
    }

    /// The body's node (its mass, its displacement).
    pub fn body_node(&self) -> u64 {
        self.body.first_node
    }
}

/// Which program reads the deck: the few cards whose syntax differs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dialect {
    /// CalculiX 2.20 (`ccx`).
    Calculix,
    /// Abaqus/Standard.
    Abaqus,
}

/// `*NODE` and `*ELEMENT` of every plate (C3D8, bottom face `S1`, top face `S2`).
pub fn plates(deck: &mut String, layout: &Layout) {
    deck.push_str("*NODE\n");
    for plate in std::iter::once(&layout.ground).chain(layout.moving()) {
        let (lo, hi) = plate.span;
        let height = if plate.element == 1 { 1.0 } else { PLATE };
        for (layer, z) in [plate.bottom, plate.bottom + height]
            .into_iter()
            .enumerate()
        {
            for (i, (x, y)) in [(lo, lo), (hi, lo), (hi, hi), (lo, hi)]
                .into_iter()
                .enumerate()
            {
                let n = plate.first_node + 4 * layer as u64 + i as u64;
                let _ = writeln!(deck, "{n}, {}, {}, {}", num(x), num(y), num(z));
            }
        }
    }
    for plate in std::iter::once(&layout.ground).chain(layout.moving()) {
        let nodes: Vec<String> = plate.nodes().map(|n| n.to_string()).collect();
        let _ = writeln!(
            deck,
            "*ELEMENT, TYPE=C3D8, ELSET=PLATE{}\n{}, {}",
            plate.element,
            plate.element,
            nodes.join(", ")
        );
    }
    let _ = writeln!(
        deck,
        "*NSET, NSET={SET_GROUND}\n{}\n*NSET, NSET={SET_GROUND_REF}\n{GROUND_NODE}\n*NSET, NSET={SET_BODY}\n{}",
        list(layout.ground.nodes()),
        layout.body_node()
    );
    if let Some(m) = &layout.middle {
        let _ = writeln!(deck, "*NSET, NSET={SET_MIDDLE}\n{}", m.first_node);
    }
}

/// The element number of the body's point mass.
const MASS_ELEMENT: u64 = 11;

/// The body's point mass, the plates' X ties and sections: each moving plate's nodes
/// follow its first node in X (`*EQUATION`), every plate a stiff elastic C3D8 (the plates
/// do not deform: their nodes move together). Node set `MOVING`: the moving plates' nodes.
pub fn constraints(deck: &mut String, mass: f64, layout: &Layout) {
    let _ = writeln!(
        deck,
        "*ELEMENT, TYPE=MASS, ELSET=EMASS\n{MASS_ELEMENT}, {}\n*MASS, ELSET=EMASS\n{}",
        layout.body_node(),
        num(mass)
    );
    deck.push_str("*NSET, NSET=MOVING\n");
    let moving: Vec<u64> = layout.moving().flat_map(|p| p.nodes()).collect();
    let _ = writeln!(deck, "{}", list(moving));
    deck.push_str("*EQUATION\n");
    for plate in layout.moving() {
        for n in plate.nodes().skip(1) {
            let _ = writeln!(deck, "2\n{n}, 1, 1.0, {}, 1, -1.0", plate.first_node);
        }
    }
    deck.push_str("*MATERIAL, NAME=PLATE\n*ELASTIC\n1e14, 0.0\n");
    for plate in std::iter::once(&layout.ground).chain(layout.moving()) {
        let _ = writeln!(
            deck,
            "*SOLID SECTION, ELSET=PLATE{}, MATERIAL=PLATE",
            plate.element
        );
    }
}

/// The boundary conditions: the ground fixed (free in X under a ground displacement, which
/// the step imposes), the moving plates in X only.
pub fn boundary(deck: &mut String, case: &Case) {
    deck.push_str("*BOUNDARY\nGROUND, 2, 3\nMOVING, 2, 3\n");
    if !moving_ground(case) {
        deck.push_str("GROUND, 1, 1\n");
    }
}

/// Numbers separated by commas.
pub fn list(items: impl IntoIterator<Item = u64>) -> String {
    items
        .into_iter()
        .map(|n| n.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The slave and master surfaces, the contact pairs and their interactions: linear
/// pressure–overclosure at Kz per m², Coulomb friction μ with the stick stiffness Kx per m²
/// (CalculiX: the stick slope; Abaqus: the elastic slip μ·p/Kx at the static pressure p).
pub fn contact_pairs(deck: &mut String, layout: &Layout, normal: f64, dialect: Dialect) {
    for pair in &layout.contacts {
        let c = &pair.contact;
        let _ = writeln!(
            deck,
            "*SURFACE, NAME={0}S, TYPE=ELEMENT\n{1}, {2}\n*SURFACE, NAME={0}M, TYPE=ELEMENT\n{3}, {4}",
            pair.name, pair.slave.0, pair.slave.1, pair.master.0, pair.master.1
        );
        let _ = writeln!(
            deck,
            "*CONTACT PAIR, INTERACTION={0}, TYPE=SURFACE TO SURFACE\n{0}S, {0}M\n*SURFACE INTERACTION, NAME={0}\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{1}",
            pair.name,
            num(c.kz / SLAVE_AREA)
        );
        let mu = if c.mu.is_finite() { c.mu } else { ROUGH_MU };
        match dialect {
            Dialect::Calculix => {
                let _ = writeln!(deck, "*FRICTION\n{}, {}", num(mu), num(c.kx / SLAVE_AREA));
            }
            Dialect::Abaqus => {
                // Abaqus states the stick stiffness as an elastic slip distance: the slip
                // at which Kx reaches the friction limit μ·N
                let _ = writeln!(
                    deck,
                    "*FRICTION, ELASTIC SLIP={}\n{}",
                    num(mu * normal / c.kx),
                    num(mu)
                );
            }
        }
    }
}

/// The amplitude `EXCITATION` of the case's signal, sampled where the program
/// interpolates it (nothing without a signal).
pub fn amplitude(deck: &mut String, case: &Case, settings: &DeckSettings) {
    amplitude_after(deck, case, settings, 0.0);
}

/// [`amplitude`] with the signal's times shifted by `start`, s (a whole number of steps):
/// zero until one step before `start`, so that the increments see the signal from
/// `start` on, as a run starting there sees it from zero.
pub fn amplitude_after(deck: &mut String, case: &Case, settings: &DeckSettings, start: f64) {
    let Some(signal) = case.scene.excitation.signal() else {
        return;
    };
    deck.push_str("*AMPLITUDE, NAME=EXCITATION\n");
    if start > 0.0 {
        let _ = writeln!(deck, "0.0, 0.0\n{}, 0.0", num(start - settings.dt));
    }
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
        let _ = writeln!(deck, "{}, {}", num(start + t), num(v));
    }
}

/// The load of the excitation, inside the step: a force ±M·a(t) on the body node, or the
/// ground's displacement imposed on `ground` (a node set or node).
pub fn excitation_load(deck: &mut String, case: &Case, mass: f64, body: &str, ground: &str) {
    match &case.scene.excitation {
        Excitation::None => {}
        Excitation::MassAcceleration(_) => {
            let _ = writeln!(
                deck,
                "*CLOAD, AMPLITUDE=EXCITATION\n{body}, 1, {}",
                num(mass)
            );
        }
        Excitation::GroundAcceleration(_) => {
            let _ = writeln!(
                deck,
                "*CLOAD, AMPLITUDE=EXCITATION\n{body}, 1, {}",
                num(-mass)
            );
        }
        Excitation::GroundDisplacement(_) => {
            let _ = writeln!(deck, "*BOUNDARY, AMPLITUDE=EXCITATION\n{ground}, 1, 1, 1.0");
        }
    }
}

/// Whether the ground moves (a ground displacement is imposed on it).
pub fn moving_ground(case: &Case) -> bool {
    matches!(case.scene.excitation, Excitation::GroundDisplacement(_))
}

/// A deck's first three comment lines: which program's model of which case, its source,
/// the rockslide version and command that wrote it (`program` as the header names it,
/// `to` as `rockslide export --to` spells it).
pub fn title_lines(program: &str, to: &str, case: &Case) -> String {
    let mut h = String::new();
    let _ = writeln!(
        h,
        "** {program} model of the rockslide case \"{}\": {}",
        case.name,
        one_line(&case.title)
    );
    let _ = writeln!(h, "** Source: {}", one_line(&case.source));
    let _ = writeln!(
        h,
        "** Written by rockslide {} (`rockslide export CASE --to {to}`). Units: SI (kg, N, m, s).",
        env!("CARGO_PKG_VERSION")
    );
    h
}

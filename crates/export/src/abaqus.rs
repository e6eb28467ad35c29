//! The Abaqus/Standard export: the PEPO (single and double) and the RPEPO (single) as
//! input decks of penalty contact with Coulomb friction, with a post-processing script
//! that writes rockslide's CSV from the output database.
//!
//! The PEPO is the model CalculiX runs ([`crate::inp`], shared card for card: plates,
//! ties, contact pairs, amplitude, loads); Abaqus states the stick stiffness as an elastic
//! slip distance (`*FRICTION, ELASTIC SLIP=γ`, stiffness μ·p/γ), written as μ·M·g/Kx so
//! that the stiffness at the PEPO's constant pressure is Kx. The RPEPO is a rigid body
//! (`*RIGID BODY`, the mass and the case's rotary inertia at the centre of mass) on its
//! supports, each support a node of a node-based slave surface (contact area 1, so the
//! pressure–overclosure slope is the support's Kz) against the ground block's top face.
//!
//! Abaqus cannot run here: the deck is written from the Abaqus Keywords Reference and is
//! **not executed by rockslide** (its header says so). History output is requested every
//! output step; `abaqus python JOB_csv.py JOB.odb` (the script written beside the deck,
//! Abaqus Scripting Reference: `odbAccess`) writes `JOB.csv` with rockslide's header
//! row, which `rockslide check CASE --external abaqus=JOB.csv` reads without a column map.

use std::fmt::Write as _;

use rockslide_core::case::{Case, Model, Oscillator, RockingBody};
use rockslide_core::error::InputError;

use crate::deck::{DeckSettings, check_scene, num};
use crate::inp::{self, Dialect, GROUND_NODE, Layout, SET_BODY, SET_GROUND, list};
use crate::{Export, ExportFile, ExportResult};

/// The case section whose `dt` and `variants` the deck follows.
pub const SECTION: &str = "abaqus";

/// The RPEPO's centre-of-mass node and its first support node.
pub const CM_NODE: u64 = 1000;
const SUPPORT_NODE: u64 = 1001;

/// The job name of an arrangement.
fn job(double: bool) -> &'static str {
    if double {
        "abaqus_model_double"
    } else {
        "abaqus_model"
    }
}

/// The deck's and its results' file names of an arrangement.
pub fn names(double: bool) -> (String, String) {
    let job = job(double);
    (format!("{job}.inp"), format!("{job}.csv"))
}

/// The post-processing script's file name (`<job>_csv.py`).
pub fn script_name(double: bool) -> String {
    format!("{}_csv.py", job(double))
}

/// The settings a case asks for (`[engines.abaqus]`, else the run's).
pub fn settings(case: &Case) -> Result<DeckSettings, InputError> {
    DeckSettings::from_case(case, SECTION)
}

/// The deck (and its post-processing script) of a case with the given settings.
pub fn export_with(case: &Case, settings: &DeckSettings) -> ExportResult {
    check_scene(case, "Abaqus", settings.double())?;
    let (name, results) = names(settings.double());
    let script_file = script_name(settings.double());
    let mut deck = header(case, settings, &script_file);
    let columns = match &case.scene.model {
        Model::Oscillator(o) => oscillator(&mut deck, case, o, settings)?,
        Model::RockingBody(r) => rocking(&mut deck, case, r, settings)?,
        Model::RigidBlock(_) => unreachable!("refused by check_scene"),
    };
    Ok(Export {
        files: vec![
            ExportFile {
                name,
                bytes: deck.into_bytes(),
            },
            ExportFile {
                bytes: script(&columns, &script_file).into_bytes(),
                name: script_file,
            },
        ],
        results,
    })
}

/// What the deck is, that rockslide does not run it, how to run it.
fn header(case: &Case, settings: &DeckSettings, script: &str) -> String {
    let mut h = inp::title_lines("Abaqus/Standard", "abaqus", case);
    h.push_str(
        "** NOT EXECUTED BY ROCKSLIDE: Abaqus cannot run where rockslide is tested. Written from the\n\
         ** Abaqus Keywords Reference (*CONTACT PAIR, *SURFACE INTERACTION, *SURFACE BEHAVIOR,\n\
         ** *FRICTION, *RIGID BODY, *DYNAMIC, *OUTPUT); check it against the release you run.\n\
         ** Run: abaqus job=JOB interactive (JOB = this file's name without .inp), then:\n",
    );
    let _ = writeln!(
        h,
        "**      abaqus python {script} JOB.odb (writes JOB.csv with rockslide's header row;\n\
         **      rockslide check CASE --external abaqus=JOB.csv reads it)"
    );
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

/// The scene's numbers on one comment line (`** scene: name = value, …`).
fn scene_line(deck: &mut String, pairs: &[(&str, f64)]) {
    let text: Vec<String> = pairs
        .iter()
        .map(|(k, v)| match *k {
            "supports" => format!("{k} = {v}"),
            _ => format!("{k} = {}", num(*v)),
        })
        .collect();
    let _ = writeln!(deck, "** scene: {}", text.join(", "));
}

/// One column of rockslide's CSV: its header, and the Python expression the script
/// computes it with, over the node histories (`h('U1', 9)`: node 9's U1 at row `i`) and
/// the ground's summed reactions `rf1`, `rf3`.
type Column = (&'static str, String);

/// A node's history output at the script's current row.
fn h(output: &str, node: u64) -> String {
    format!("h('{output}', {node})")
}

/// The PEPO: the shared plates model, history output of the body, middle and ground.
fn oscillator(
    deck: &mut String,
    case: &Case,
    o: &Oscillator,
    settings: &DeckSettings,
) -> Result<Vec<Column>, InputError> {
    let (lower, upper) = match (settings.double(), &o.double) {
        (true, Some(d)) => (&d.lower, Some(&d.upper)),
        _ => (&o.contact, None),
    };
    if upper.is_some_and(|u| u.mu.is_finite()) {
        return Err(case.field_error(
            "model.double.mu2",
            "must be inf for the Abaqus deck: element 2 is elastic (only element 1 slides)",
        ));
    }
    let mut scene = vec![
        ("mass", o.mass),
        ("gravity", o.gravity),
        ("kx", lower.kx),
        ("kz", lower.kz),
        ("mu", lower.mu),
    ];
    if let Some(u) = upper {
        scene.extend([("kx2", u.kx), ("kz2", u.kz), ("mu2", u.mu)]);
    }
    scene_line(deck, &scene);
    deck.push_str(PEPO_MODEL);
    let layout = Layout::pepo(o, lower, upper);
    inp::plates(deck, &layout);
    inp::constraints(deck, o.mass, &layout);
    inp::contact_pairs(deck, &layout, o.mass * o.gravity, Dialect::Abaqus);
    inp::amplitude(deck, case, settings);
    inp::boundary(deck, case);
    step_header(deck, settings);
    inp::excitation_load(deck, case, o.mass, SET_BODY, SET_GROUND);
    let body = layout.body_node();
    let slider = layout.middle.map_or(body, |m| m.first_node);
    history(deck, settings, &[body, slider]);
    let ground = h("U1", GROUND_NODE);
    let mut columns: Vec<Column> = vec![
        ("time [s]", "t".into()),
        ("rel_disp [m]", format!("{} - {ground}", h("U1", body))),
        (
            "slide [m]",
            format!("{} - {ground} + rf1 / {}", h("U1", slider), num(lower.kx)),
        ),
        ("resistance [N]", "-rf1".into()),
        (
            "vel [m/s]",
            format!("{} - {}", h("V1", body), h("V1", GROUND_NODE)),
        ),
    ];
    if layout.middle.is_some() {
        columns.push(("node_disp [m]", format!("{} - {ground}", h("U1", slider))));
    }
    if inp::moving_ground(case) {
        columns.push(("ground_disp [m]", ground));
    }
    Ok(columns)
}

const PEPO_MODEL: &str = "\
** Model: penalty contact with Coulomb friction, face to face (the model rockslide runs in
** CalculiX): the body is a 1 m x 1 m plate (C3D8) on a ground block whose top face is
** 3 m x 3 m; *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR at Kz per m2 of the 1 m2 slave
** face; *FRICTION mu with ELASTIC SLIP = mu M g / Kx (the stick stiffness mu p / gamma is Kx
** at the PEPO's constant pressure). The double arrangement puts a massless 1 m x 1 m middle
** plate between the ground (element 1, slides) and a 3 m x 3 m body plate (element 2,
** mu = inf written as 1e6). The normal force is the weight: each contact starts at its
** static overclosure M g / Kz, the plates move in X only (*EQUATION ties each plate's nodes
** to its first node). Implicit dynamics, *DYNAMIC with ALPHA = 0 (trapezoidal rule) at the
** case's dt, fixed increments (DIRECT), no initial-acceleration solve (INITIAL=NO: the
** model starts in equilibrium).
";

/// The step, fixed increments at the case's Δt.
fn step_header(deck: &mut String, settings: &DeckSettings) {
    let _ = writeln!(
        deck,
        "*STEP, NAME=DYNAMIC, INC={}\n*DYNAMIC, DIRECT, ALPHA=0.0, INITIAL=NO\n{}, {}",
        settings.steps + 10,
        num(settings.dt),
        num(settings.steps as f64 * settings.dt)
    );
}

/// History output every output step: U, UR2 and V of `nodes`; U, V and RF of the ground's
/// nodes (the script sums the reactions: the ground's total). Ends the step.
fn history(deck: &mut String, settings: &DeckSettings, nodes: &[u64]) {
    let _ = writeln!(
        deck,
        "*NSET, NSET=TRACKED\n{}\n*OUTPUT, HISTORY, FREQUENCY={}\n*NODE OUTPUT, NSET=TRACKED\nU1, U3, UR2, V1\n*NODE OUTPUT, NSET={SET_GROUND}\nU1, V1, RF1, RF3\n*END STEP",
        list(nodes.iter().copied()),
        settings.output_every
    );
}

/// The RPEPO: a rigid body on its supports (node-to-surface contact against the ground).
fn rocking(
    deck: &mut String,
    case: &Case,
    r: &RockingBody,
    settings: &DeckSettings,
) -> Result<Vec<Column>, InputError> {
    if settings.double() {
        return Err(case.field_error(
            &format!("engines.{SECTION}.variants"),
            "is [\"double\"]: the Abaqus deck writes the RPEPO's single arrangement (the ANSYS deck writes both)",
        ));
    }
    let c = &r.contact;
    let inertia = crate::opensees::rotational_inertia(r);
    scene_line(
        deck,
        &[
            ("mass", r.mass),
            ("gravity", r.gravity),
            ("cm_height", r.cm_height),
            ("half_width", r.half_width),
            ("supports", r.supports as f64),
            ("rotational_inertia", inertia),
            ("kx", c.kx),
            ("kz", c.kz),
            ("mu", c.mu),
        ],
    );
    deck.push_str(RPEPO_MODEL);
    let share = r.weight() / r.supports as f64;
    let settle = -share / c.kz;
    rocking_mesh(deck, r, settle);
    let _ = writeln!(
        deck,
        "*SURFACE, NAME=SUPPORTS, TYPE=NODE\nSUPPORTS, 1.0\n*SURFACE, NAME=GROUNDTOP, TYPE=ELEMENT\n1, S2\n\
         *CONTACT PAIR, INTERACTION=SUPPORT\nSUPPORTS, GROUNDTOP\n*SURFACE INTERACTION, NAME=SUPPORT\n\
         *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{}\n*FRICTION, ELASTIC SLIP={}\n{}",
        num(c.kz),
        num(c.mu * share / c.kx),
        num(c.mu)
    );
    inp::amplitude(deck, case, settings);
    let _ = writeln!(
        deck,
        "*BOUNDARY\n{SET_GROUND}, 2, 3\n{CM_NODE}, 2, 2\n{CM_NODE}, 4, 4\n{CM_NODE}, 6, 6"
    );
    if !inp::moving_ground(case) {
        let _ = writeln!(deck, "{SET_GROUND}, 1, 1");
    }
    step_header(deck, settings);
    let _ = writeln!(deck, "*CLOAD\n{CM_NODE}, 3, {}", num(-r.weight()));
    inp::excitation_load(deck, case, r.mass, SET_BODY, SET_GROUND);
    history(deck, settings, &[CM_NODE]);
    let g = h("U1", GROUND_NODE);
    // the base centre O is h below the CM: u_O = u_cm − h·θ (θ = UR2, right-handed about
    // +Y, turns +Z towards +X); rockslide's rotation lifts the +x edge: −UR2
    let base = format!(
        "{} - {} * {}",
        h("U1", CM_NODE),
        num(r.cm_height),
        h("UR2", CM_NODE)
    );
    Ok(vec![
        ("time [s]", "t".into()),
        ("rel_disp [m]", format!("{base} - {g}")),
        (
            "slide [m]",
            format!("{base} - {g} + rf1 / ({} * {})", r.supports, num(c.kx)),
        ),
        ("resistance [N]", "-rf1".into()),
        ("cm_x [m]", format!("{} - {g}", h("U1", CM_NODE))),
        ("cm_z [m]", h("U3", CM_NODE)),
        ("rotation [rad]", format!("-{}", h("UR2", CM_NODE))),
        ("base_shear [N]", "-rf1".into()),
        ("normal [N]", "rf3".into()),
    ])
}

/// The ground block (nodes 1-8, top face at Z = 0, wider than the base by 1 m each side),
/// the centre of mass and the supports at their static overclosure `settle` (< 0), the
/// rigid body and its mass and rotary inertia.
fn rocking_mesh(deck: &mut String, r: &RockingBody, settle: f64) {
    let reach = r.half_width + 1.0;
    deck.push_str("*NODE\n");
    for (layer, z) in [-1.0, 0.0].into_iter().enumerate() {
        for (i, (x, y)) in [(-reach, -1.0), (reach, -1.0), (reach, 1.0), (-reach, 1.0)]
            .into_iter()
            .enumerate()
        {
            let n = 1 + 4 * layer + i;
            let _ = writeln!(deck, "{n}, {}, {}, {}", num(x), num(y), num(z));
        }
    }
    let _ = writeln!(deck, "{CM_NODE}, 0.0, 0.0, {}", num(settle + r.cm_height));
    let positions = r.support_positions();
    for (i, x) in positions.iter().enumerate() {
        let n = SUPPORT_NODE + i as u64;
        let _ = writeln!(deck, "{n}, {}, 0.0, {}", num(*x), num(settle));
    }
    let supports = SUPPORT_NODE..SUPPORT_NODE + positions.len() as u64;
    let _ = writeln!(
        deck,
        "*ELEMENT, TYPE=C3D8, ELSET=GROUNDBLOCK\n1, {g}\n*NSET, NSET={SET_GROUND}\n{g}\n*NSET, NSET=SUPPORTS\n{}\n*NSET, NSET={SET_BODY}\n{CM_NODE}",
        list(supports),
        g = list(1..=8)
    );
    let _ = writeln!(
        deck,
        "*MATERIAL, NAME=GROUND\n*ELASTIC\n1e14, 0.0\n*SOLID SECTION, ELSET=GROUNDBLOCK, MATERIAL=GROUND\n\
         *RIGID BODY, REF NODE={CM_NODE}, TIE NSET=SUPPORTS\n\
         *ELEMENT, TYPE=MASS, ELSET=EMASS\n11, {CM_NODE}\n*MASS, ELSET=EMASS\n{}\n\
         *ELEMENT, TYPE=ROTARYI, ELSET=EINERTIA\n12, {CM_NODE}\n*ROTARY INERTIA, ELSET=EINERTIA\n{i}, {i}, {i}",
        num(r.mass),
        i = num(crate::opensees::rotational_inertia(r))
    );
}

const RPEPO_MODEL: &str = "\
** Model: the RPEPO as a rigid body (*RIGID BODY, reference node 1000 at the centre of mass,
** the mass and the case's rotary inertia there) tied to its supports (nodes 1001 on), each
** support a node of a node-based slave surface (contact area 1.0, so the pressure is the
** support's force) against the ground block's top face: *SURFACE BEHAVIOR,
** PRESSURE-OVERCLOSURE=LINEAR at Kz, *FRICTION mu with ELASTIC SLIP = mu (M g / n) / Kx (the
** stick stiffness mu p / gamma is Kx at the static support force M g / n and follows the
** support's force as it changes, where CONTA178's stays Kx). Lift-off is free (no tension).
** The supports start at their static overclosure M g / (n Kz) under the weight, applied at
** the centre of mass from the step's start. Implicit dynamics, *DYNAMIC with ALPHA = 0 at
** the case's dt, fixed increments (DIRECT), no initial-acceleration solve (INITIAL=NO).
";

/// The `abaqus python` script that writes rockslide's CSV from the output database.
fn script(columns: &[Column], name: &str) -> String {
    let headers: Vec<&str> = columns.iter().map(|c| c.0).collect();
    let row: Vec<&str> = columns.iter().map(|c| c.1.as_str()).collect();
    format!(
        "# Written by rockslide: rockslide's CSV from an Abaqus output database.\n\
         # Not executed by rockslide. Run: abaqus python {name} JOB.odb  ->  JOB.csv\n\
         # (Abaqus Scripting Reference: odbAccess, HistoryRegion, HistoryOutput.data).\n\
         import sys\n\
         from odbAccess import openOdb\n\
         \n\
         odb = openOdb(sys.argv[1], readOnly=True)\n\
         step = odb.steps.values()[-1]\n\
         series = {{}}  # (output, node label) -> [(time, value), ...]\n\
         for key, region in step.historyRegions.items():\n\
         \x20   if key.startswith('Node '):\n\
         \x20       label = int(key.split('.')[-1])\n\
         \x20       for name, output in region.historyOutputs.items():\n\
         \x20           series[(name, label)] = output.data\n\
         ground = sorted(label for (name, label) in series if name == 'RF1')\n\
         times = [t for (t, _) in series[('RF1', ground[0])]]\n\
         out = open(sys.argv[1].rsplit('.', 1)[0] + '.csv', 'w')\n\
         out.write('{header}\\n')\n\
         for i, t in enumerate(times):\n\
         \x20   h = lambda output, node: series[(output, node)][i][1]\n\
         \x20   rf1 = sum(h('RF1', n) for n in ground)\n\
         \x20   rf3 = sum(h('RF3', n) for n in ground)\n\
         \x20   row = [{row}]\n\
         \x20   out.write(','.join('%.12e' % x for x in row) + '\\n')\n\
         out.close()\n",
        header = headers.join(","),
        row = row.join(", "),
    )
}

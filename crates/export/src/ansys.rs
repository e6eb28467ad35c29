//! The ANSYS Mechanical APDL export: the paper's own models — the PEPO on a single
//! CONTA178 or two in series, the RPEPO on ten CONTA178 supports — as an input deck with
//! the paper's solution settings (Δt of the case, pure penalty, no weak spring across an
//! open gap, the default force (0.5 %) and displacement (5 %) convergence tolerances),
//! both loadings (mass acceleration, ground displacement) and records (a force −M·ag(t)
//! on the mass). POST26 collects the responses and `*VWRITE` writes them as a CSV with
//! rockslide's header row (`time [s],rel_disp [m],…`), which `--external ansys=FILE`
//! reads without a column map.
//!
//! ANSYS cannot run here: the deck is written from the element and command documentation
//! (ANSYS Mechanical APDL Element Reference: CONTA178, MASS21, MPC184; Command Reference:
//! ANTYPE, TRNOPT, DELTIM, CNVTOL, *DIM TABLE, POST26 NSOL/RFORCE/ADD, *VGET, *VWRITE),
//! each choice cited in the deck, and is **not executed by rockslide**.

use std::fmt::Write as _;

use rockslide_core::case::{Case, Contact, Excitation, Model, Oscillator, RockingBody, Signal};
use rockslide_core::error::InputError;

use crate::deck::{DeckSettings, check_scene, num, one_line};
use crate::{Export, ExportResult};

/// The case section whose `dt` and `variants` the deck follows.
pub const SECTION: &str = "ansys";

/// The deck's and its results' file names of an arrangement.
pub fn names(double: bool) -> (String, String) {
    let job = if double {
        "ansys_model_double"
    } else {
        "ansys_model"
    };
    (format!("{job}.inp"), format!("{job}.csv"))
}

/// The settings a case asks for (`[engines.ansys]`, else the run's).
pub fn settings(case: &Case) -> Result<DeckSettings, InputError> {
    DeckSettings::from_case(case, SECTION)
}

/// The deck of a case with the given settings.
pub fn export_with(case: &Case, settings: &DeckSettings) -> ExportResult {
    check_scene(case, "ANSYS", settings.double())?;
    let (name, results) = names(settings.double());
    let mut deck = header(case, settings, &results);
    match &case.scene.model {
        Model::Oscillator(o) => oscillator(&mut deck, case, o, settings)?,
        Model::RockingBody(r) => rocking(&mut deck, case, r, settings)?,
        Model::RigidBlock(_) => unreachable!("refused by check_scene"),
    }
    Ok(Export::deck(name, deck, results))
}

/// What the deck is, that rockslide does not run it, the scene's numbers, the settings.
fn header(case: &Case, settings: &DeckSettings, results: &str) -> String {
    let mut h = String::new();
    let _ = writeln!(
        h,
        "! ANSYS Mechanical APDL model of the rockslide case \"{}\": {}",
        case.name,
        one_line(&case.title)
    );
    let _ = writeln!(h, "! Source: {}", one_line(&case.source));
    let _ = writeln!(
        h,
        "! Written by rockslide {} (`rockslide export CASE --to ansys`). Units: SI (kg, N, m, s, rad).",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(
        h,
        "! NOT EXECUTED BY ROCKSLIDE: ANSYS is not available where rockslide runs. Written from the\n\
         ! ANSYS Mechanical APDL Element and Command References (cited at each choice below);\n\
         ! check the real-constant order and KEYOPTs against the release you run.\n\
         ! Run: ansys -b -i THIS_FILE -o THIS_FILE.out; it writes {results} (rockslide's header\n\
         !      row), read back with: rockslide check CASE --external ansys={results}"
    );
    let _ = writeln!(
        h,
        "! settings: dt = {} s, output every {} substep(s), {} substeps, {} arrangement",
        num(settings.dt),
        settings.output_every,
        settings.steps,
        settings.arrangement.name()
    );
    h.push_str("/BATCH\n/PREP7\n");
    h
}

/// The scene's numbers as APDL parameters (each read back by the tests).
fn parameters(deck: &mut String, pairs: &[(&str, f64)]) {
    for (name, value) in pairs {
        let _ = writeln!(deck, "{name} = {}", num(*value));
    }
}

/// A CONTA178 element type and real-constant set for one contact: pure penalty, no weak
/// spring, gap along Z, Coulomb friction μ (an infinite μ is a bonded element, rough).
fn conta178(deck: &mut String, id: usize, c: &Contact) {
    let _ = writeln!(
        deck,
        "! CONTA178 (Element Reference, CONTA178): 3D node-to-node contact, UX/UY/UZ (KEYOPT(1)=0),\n\
         ! pure penalty (KEYOPT(2)=1, the paper's choice), no weak spring across an open gap\n\
         ! (KEYOPT(3)=0), contact normal along global Z (KEYOPT(5)=3){}\n\
         ET,{id},CONTA178\nKEYOPT,{id},1,0\nKEYOPT,{id},2,1\nKEYOPT,{id},3,0\nKEYOPT,{id},5,3",
        if c.mu.is_finite() {
            ""
        } else {
            ", rough (KEYOPT(10)=1: no sliding, mu = inf)"
        }
    );
    if !c.mu.is_finite() {
        let _ = writeln!(deck, "KEYOPT,{id},10,1");
    }
    let _ = writeln!(
        deck,
        "! real constants R1..R5: FKN (normal penalty, N/m), GAP = 0, START = 0, FKS (sticking, N/m), REDFACT\n\
         R,{id},KZ{id},0.0,0.0,KX{id},0.0"
    );
    if c.mu.is_finite() {
        let _ = writeln!(deck, "MP,MU,{id},MU{id}   ! Coulomb friction (MP,MU)");
    }
}

/// A table parameter `name` of the signal against TIME (linear in between, as the
/// references assume), scaled by `factor`.
fn table(deck: &mut String, name: &str, signal: &Signal, factor: f64, settings: &DeckSettings) {
    let points: Vec<(f64, f64)> = match signal {
        Signal::SinePulse { .. } => {
            let last = ((signal.end() / settings.dt).ceil() as usize + 1).min(settings.steps);
            (0..=last)
                .map(|k| {
                    let t = k as f64 * settings.dt;
                    (t, signal.value(t))
                })
                .collect()
        }
        Signal::Record { dt, samples, .. } => samples
            .iter()
            .enumerate()
            .map(|(i, v)| (i as f64 * dt, *v))
            .chain(std::iter::once((samples.len() as f64 * dt, 0.0)))
            .collect(),
    };
    let _ = writeln!(
        deck,
        "! *DIM,TABLE against TIME (Command Reference, *DIM): {} points, linear in between\n*DIM,{name},TABLE,{},1,1,TIME",
        points.len(),
        points.len()
    );
    for (i, (t, v)) in points.iter().enumerate() {
        let _ = writeln!(
            deck,
            "{name}({},0) = {}\n{name}({},1) = {}",
            i + 1,
            num(*t),
            i + 1,
            num(v * factor)
        );
    }
}

/// The loading's table (`LOADTAB`) and where it acts: a force on `mass_node` (mass
/// acceleration, or −M·ag for a record), or a displacement of `ground_nodes`.
fn loading(
    deck: &mut String,
    case: &Case,
    mass: f64,
    settings: &DeckSettings,
) -> Option<(&'static str, f64)> {
    let signal = case.scene.excitation.signal()?;
    let (what, factor) = match case.scene.excitation {
        Excitation::MassAcceleration(_) => ("force", mass),
        Excitation::GroundAcceleration(_) => ("force", -mass),
        Excitation::GroundDisplacement(_) => ("ground", 1.0),
        Excitation::None => return None,
    };
    table(deck, "LOADTAB", signal, factor, settings);
    Some((what, factor))
}

/// The solution: a static gravity load step, then the transient with the paper's settings.
fn solution(deck: &mut String, settings: &DeckSettings, nlgeom: bool) {
    let _ = writeln!(
        deck,
        "FINISH\n/SOLU\n\
         ANTYPE,TRANS            ! transient (ANTYPE)\n\
         TRNOPT,FULL             ! full method (TRNOPT)\n\
         NLGEOM,{}\n\
         CNVTOL,F,,0.005,2       ! force convergence 0.5 % (the default, as in the paper)\n\
         CNVTOL,U,,0.05,2        ! displacement convergence 5 % (as in the paper)\n\
         OUTRES,ALL,ALL\n\
         ! load step 1: gravity, static (TIMINT,OFF) at a tiny time\n\
         TIMINT,OFF\nTIME,1.0e-8\nNSUBST,1\nSOLVE\n\
         ! load step 2: the transient at the case's dt, no automatic stepping (AUTOTS,OFF)\n\
         TIMINT,ON\nAUTOTS,OFF\nDELTIM,{}\nTIME,{}\nKBC,0\nSOLVE\nFINISH",
        if nlgeom { "ON" } else { "OFF" },
        num(settings.dt),
        num(settings.steps as f64 * settings.dt)
    );
}

/// POST26 variables into an array, then `*VWRITE` of the CSV with its header row.
fn write_csv(deck: &mut String, results: &str, columns: &[(&str, usize)]) {
    let _ = writeln!(
        deck,
        "! results as rockslide's CSV: POST26 variables (NSOL, RFORCE, ADD) copied by *VGET\n\
         ! into an array and written by *VWRITE (Command Reference), one row per substep\n\
         *GET,NROWS,VARI,,NSETS\n*DIM,OUT,ARRAY,NROWS,{}",
        columns.len()
    );
    for (i, (_, var)) in columns.iter().enumerate() {
        let _ = writeln!(deck, "VGET,OUT(1,{}),{var}", i + 1);
    }
    if let Some(c) = columns.iter().position(|(n, _)| *n == "cm_z [m]") {
        let _ = writeln!(
            deck,
            "! cm_z from the settled state: row 1 is the static gravity step\n*DO,I,NROWS,1,-1\nOUT(I,{c1}) = OUT(I,{c1}) - OUT(1,{c1})\n*ENDDO",
            c1 = c + 1
        );
    }
    let names: Vec<&str> = columns.iter().map(|(n, _)| *n).collect();
    let stem = results.trim_end_matches(".csv");
    let _ = writeln!(deck, "*CFOPEN,{stem},csv\n*VWRITE\n('{}')", names.join(","));
    let args: Vec<String> = (1..=columns.len()).map(|i| format!("OUT(1,{i})")).collect();
    let format: Vec<&str> = vec!["E17.9"; columns.len()];
    let _ = writeln!(
        deck,
        "*VWRITE,{}\n({})\n*CFCLOS\nFINISH",
        args.join(","),
        format.join(",',',")
    );
}

/// The PEPO: ground node 1, mass node 2 (single) or middle node 3 between two CONTA178.
fn oscillator(
    deck: &mut String,
    case: &Case,
    o: &Oscillator,
    settings: &DeckSettings,
) -> Result<(), InputError> {
    let (lower, upper) = match (settings.double(), &o.double) {
        (true, Some(d)) => (&d.lower, Some(&d.upper)),
        _ => (&o.contact, None),
    };
    let mut values = vec![
        ("MASS", o.mass),
        ("GRAV", o.gravity),
        ("KX1", lower.kx),
        ("KZ1", lower.kz),
    ];
    if lower.mu.is_finite() {
        values.push(("MU1", lower.mu));
    }
    if let Some(u) = upper {
        values.extend([("KX2", u.kx), ("KZ2", u.kz)]);
        if u.mu.is_finite() {
            values.push(("MU2", u.mu));
        }
    }
    parameters(deck, &values);
    conta178(deck, 1, lower);
    if let Some(u) = upper {
        conta178(deck, 2, u);
    }
    deck.push_str(
        "! MASS21 (Element Reference): 3D point mass without rotary inertia (KEYOPT(3)=2)\n\
         ET,9,MASS21\nKEYOPT,9,3,2\nR,9,MASS,MASS,MASS\n\
         N,1,0,0,0\nN,2,0,0,0\n",
    );
    let mass_node = 2;
    if upper.is_some() {
        deck.push_str("N,3,0,0,0\nTYPE,1\nREAL,1\nMAT,1\nE,1,3\nTYPE,2\nREAL,2\nMAT,2\nE,3,2\n");
    } else {
        deck.push_str("TYPE,1\nREAL,1\nMAT,1\nE,1,2\n");
    }
    let _ = writeln!(deck, "TYPE,9\nREAL,9\nE,{mass_node}");
    let load = loading(deck, case, o.mass, settings);
    deck.push_str("D,ALL,UY,0\n");
    match load {
        Some(("ground", _)) => deck.push_str("D,1,UX,%LOADTAB%\nD,1,UZ,0\n"),
        _ => deck.push_str("D,1,UX,0\nD,1,UZ,0\n"),
    }
    let _ = writeln!(
        deck,
        "F,{mass_node},FZ,-MASS*GRAV   ! the weight: normal force M g"
    );
    if let Some(("force", _)) = load {
        let _ = writeln!(deck, "F,{mass_node},FX,%LOADTAB%");
    }
    solution(deck, settings, false);
    let (_, results) = names(settings.double());
    let _ = writeln!(
        deck,
        "/POST26\nNUMVAR,20\nNSOL,2,{mass_node},U,X,UMASS\nNSOL,3,1,U,X,UGROUND\nRFORCE,4,1,F,X,RFX\n\
         ADD,5,2,3,,REL,,,1,-1            ! rel_disp = U(mass) - U(ground)\n\
         ADD,6,4,,,RES,,,-1               ! resistance = -(ground reaction)"
    );
    let slip_base = if upper.is_some() {
        deck.push_str("NSOL,8,3,U,X,UMID\nADD,9,8,3,,NODE,,,1,-1            ! node_disp = U(middle) - U(ground)\n");
        9
    } else {
        5
    };
    let _ = writeln!(
        deck,
        "ADD,7,{slip_base},6,,SLIDE,,,1,-1/KX1    ! slide = deformation - force/Kx (element 1)"
    );
    let mut columns = vec![
        ("time [s]", 1),
        ("rel_disp [m]", 5),
        ("slide [m]", 7),
        ("resistance [N]", 6),
    ];
    if upper.is_some() {
        columns.push(("node_disp [m]", 9));
    }
    if matches!(case.scene.excitation, Excitation::GroundDisplacement(_)) {
        columns.push(("ground_disp [m]", 3));
    }
    write_csv(deck, &results, &columns);
    Ok(())
}

/// The RPEPO: the CM node 1 (MASS21 with the stated rotary inertia), rigid MPC184 links
/// to the base centre 2 and the supports 101.., each a CONTA178 (or two in series) from a
/// fixed ground node 201...
fn rocking(
    deck: &mut String,
    case: &Case,
    r: &RockingBody,
    settings: &DeckSettings,
) -> Result<(), InputError> {
    let (lower, upper) = match (settings.double(), &r.double) {
        (true, Some(d)) => (&d.lower, Some(&d.upper)),
        _ => (&r.contact, None),
    };
    rocking_parameters(deck, r, lower, upper);
    rocking_model(deck, r, upper.is_some());
    rocking_loads(deck, case, r.mass, settings);
    solution(deck, settings, true);
    rocking_results(deck, r.supports, settings);
    Ok(())
}

/// The body's and the supports' numbers as parameters, and the contact elements' types.
fn rocking_parameters(
    deck: &mut String,
    r: &RockingBody,
    lower: &Contact,
    upper: Option<&Contact>,
) {
    let inertia = crate::opensees::rotational_inertia(r);
    let mut values = vec![
        ("MASS", r.mass),
        ("GRAV", r.gravity),
        ("HCM", r.cm_height),
        ("HALFB", r.half_width),
        ("INERTIA", inertia),
        ("KX1", lower.kx),
        ("KZ1", lower.kz),
        ("MU1", lower.mu),
    ];
    if let Some(u) = upper {
        values.extend([("KX2", u.kx), ("KZ2", u.kz)]);
    }
    parameters(deck, &values);
    let _ = writeln!(deck, "NSUP = {}", r.supports);
    conta178(deck, 1, lower);
    if let Some(u) = upper {
        conta178(deck, 2, u);
    }
}

/// The nodes and elements: the CM's mass, the rigid base, and each support's contact
/// (two in series, through a middle node 301.., for the double supports).
fn rocking_model(deck: &mut String, r: &RockingBody, double: bool) {
    deck.push_str(
        "! MASS21 (Element Reference): 3D mass with rotary inertia (KEYOPT(3)=0); the paper's model has\n\
         ! none, the case states a small one (see the case file)\n\
         ET,9,MASS21\nKEYOPT,9,3,0\nR,9,MASS,MASS,MASS,INERTIA,INERTIA,INERTIA\n\
         ! MPC184 rigid beam (KEYOPT(1)=1, Element Reference MPC184): the rigid massless base\n\
         ET,8,MPC184\nKEYOPT,8,1,1\n\
         N,1,0,0,HCM\nN,2,0,0,0\nTYPE,9\nREAL,9\nE,1\nTYPE,8\nE,1,2\n",
    );
    for (i, x) in r.support_positions().into_iter().enumerate() {
        let (base, ground, middle) = (101 + i, 201 + i, 301 + i);
        let _ = writeln!(deck, "N,{base},{},0,0\nN,{ground},{},0,0", num(x), num(x));
        let _ = writeln!(deck, "TYPE,8\nE,1,{base}");
        if double {
            let _ = writeln!(
                deck,
                "N,{middle},{},0,0\nTYPE,1\nREAL,1\nMAT,1\nE,{ground},{middle}\nTYPE,2\nREAL,2\nMAT,2\nE,{middle},{base}",
                num(x)
            );
        } else {
            let _ = writeln!(deck, "TYPE,1\nREAL,1\nMAT,1\nE,{ground},{base}");
        }
    }
}

/// The constraints, the weight at the CM and the ground motion: a displacement of the
/// ground nodes or a force at the CM.
fn rocking_loads(deck: &mut String, case: &Case, mass: f64, settings: &DeckSettings) {
    let load = loading(deck, case, mass, settings);
    deck.push_str(
        "D,ALL,UY,0\nD,1,ROTX,0\nD,1,ROTZ,0\nNSEL,S,NODE,,201,299\nD,ALL,UZ,0\nD,ALL,ROTX,0\nD,ALL,ROTY,0\nD,ALL,ROTZ,0\n",
    );
    match load {
        Some(("ground", _)) => deck.push_str("D,ALL,UX,%LOADTAB%\n"),
        _ => deck.push_str("D,ALL,UX,0\n"),
    }
    deck.push_str("NSEL,ALL\nF,1,FZ,-MASS*GRAV   ! the weight at the CM\n");
    if let Some(("force", _)) = load {
        deck.push_str("F,1,FX,%LOADTAB%\n");
    }
}

/// POST26: the trace's quantities from the nodes' solution and the ground nodes'
/// reactions, written as rockslide's CSV.
fn rocking_results(deck: &mut String, supports: usize, settings: &DeckSettings) {
    let (_, results) = names(settings.double());
    deck.push_str(
        "/POST26\nNUMVAR,200\n\
         NSOL,2,1,U,X,CMX\nNSOL,3,1,U,Z,CMZ\nNSOL,4,1,ROT,Y,ROTY\nNSOL,5,2,U,X,UO\nNSOL,6,201,U,X,UG\n\
         ADD,7,5,6,,REL,,,1,-1            ! rel_disp = U(base centre) - U(ground)\n\
         ADD,8,2,6,,CMREL,,,1,-1          ! cm_x relative to the ground\n\
         ADD,9,4,,,ROT,,,-1               ! rotation = -ROTY (rockslide: positive lifts the +x edge)\n\
         ! base shear and normal force: the ground nodes' reactions summed (RFORCE, ADD)\n\
         RFORCE,10,201,F,X,SH\nRFORCE,11,201,F,Z,NZ\nADD,12,10,,,SHEAR,,,-1\nADD,13,11,,,NORMAL\n",
    );
    for i in 1..supports {
        let _ = writeln!(
            deck,
            "RFORCE,14,{g},F,X,FXI\nRFORCE,15,{g},F,Z,FZI\nADD,12,12,14,,SHEAR,,,1,-1\nADD,13,13,15,,NORMAL",
            g = 201 + i
        );
    }
    let _ = writeln!(
        deck,
        "ADD,16,7,12,,SLIDE,,,1,-1/(NSUP*KX1) ! slide: base centre minus the mean elastic deformation"
    );
    write_csv(
        deck,
        &results,
        &[
            ("time [s]", 1),
            ("rel_disp [m]", 7),
            ("slide [m]", 16),
            ("resistance [N]", 12),
            ("cm_x [m]", 8),
            ("cm_z [m]", 3),
            ("rotation [rad]", 9),
            ("base_shear [N]", 12),
            ("normal [N]", 13),
        ],
    );
}

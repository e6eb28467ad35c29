//! Other programs' result files as the programs write them
//! (docs/verify-your-own-code.md).
//!
//! Requirements checked:
//! - rockslide shall read a SAP2000 table export (long tables, units row, page header,
//!   `;` with decimal commas, BOM, CRLF), an ANSYS POST26 `PRVAR` listing (banner on
//!   every page), an Abaqus XY report (`NoValue`) and OpenSees recorder files (named by
//!   the recorder command, or by the script that holds it) back to the fe engine's trace
//!   they were written from, to the digits printed (10 significant), and gate them like an
//!   engine (the SAP2000 "Acceptable" default against the exact solution);
//! - rockslide shall read SAP2000's tables exported to Excel (one sheet per table, number
//!   cells) back to the fe engine's numbers, within 4 ulp, and gate them alike;
//! - an external run is checked like an engine on the channels it provides: a normal force
//!   written compression-negative (SAP2000's link `P`) fails `compression` and
//!   `friction_bound` until the map gives its sign, and then passes; an invariant its
//!   file cannot support is listed as not provided, never a zero that passes.
//!
//! Each fixture is written here from the fe trace, in the layout the program documents
//! (`crates/formats/src/external/` says each layout; the malformed variants of every
//! layout are unit tests there).

use std::fmt::Write as _;
use std::path::Path;

use rockslide::case::{Invariant, parse_case};
use rockslide::suite::{CaseResult, run_case};

/// The paper's PEPO under a half-sine mass acceleration, fe single (M·g = 1000 kN,
/// μ·M·g = 500 kN).
const PEPO: &str = r#"
name = "pepo-programs"
[model]
kind = "oscillator"
mass = 1.0e6
gravity = 1.0
[model.contact]
kx = 9.8696e8
kz = 3.94784e9
mu = 0.5
[excitation]
kind = "mass-acceleration"
shape = "sine-pulse"
amplitude = 1.0
omega = 15.707963267948966
cycles = 0.5
[run]
duration = 1.0
dt = 0.001
[engines.fe]
variants = ["single"]
"#;

/// The weight M·g of [`PEPO`], N.
const WEIGHT: f64 = 1.0e6;

/// Relative error of a value printed to 10 significant digits (half a unit of the last),
/// with room for the unit's conversion.
const PRINTED: f64 = 5.0e-10 * 1.01;

fn run_text(dir: &Path, text: &str) -> CaseResult {
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap();
    run_case(parse_case(&path, text).expect("case loads")).expect("case runs")
}

fn run_of<'a>(r: &'a CaseResult, label: &str) -> &'a rockslide::engine::Run {
    r.runs.iter().find(|x| x.label() == label).unwrap()
}

/// The fe run's time, relative displacement, slide and resistance.
struct Fe {
    time: Vec<f64>,
    rel_disp: Vec<f64>,
    slide: Vec<f64>,
    resistance: Vec<f64>,
}

fn fe(dir: &Path) -> Fe {
    let r = run_text(dir, PEPO);
    let t = &run_of(&r, "fe/single").trace;
    Fe {
        time: t.time.clone(),
        rel_disp: t.column("rel_disp").unwrap().to_vec(),
        slide: t.column("slide").unwrap().to_vec(),
        resistance: t.column("resistance").unwrap().to_vec(),
    }
}

/// `x` to 10 significant digits in E notation (`1.234567890E-3`).
fn e10(x: f64) -> String {
    format!("{x:.9E}")
}

/// `x` to 10 significant digits as a European export writes it: a decimal comma.
fn comma10(x: f64) -> String {
    format!("{x:.9e}").replace('.', ",")
}

/// A SAP2000 export of the fe run: joint 2's `U1` (mm), link 1's `P` (kN, tension
/// positive: the weight as −1000) and `V2` (kN), CRLF, a BOM, `;` and decimal commas, a
/// units row and the field names repeated at row 500 (a page header).
fn sap2000(fe: &Fe) -> String {
    let mut s = String::from("\u{feff}TABLE:  \"Joint Displacements\"\r\n");
    let joints = "Joint;OutputCase;CaseType;StepType;StepNum;U1;U2;U3\r\n\
                  Text;Text;Text;Text;Sec;mm;mm;mm\r\n";
    s.push_str(joints);
    for (i, t) in fe.time.iter().enumerate() {
        if i == 500 {
            s.push_str(joints);
        }
        let u = comma10(fe.rel_disp[i] * 1000.0);
        writeln!(s, "1;TH;NonDirHist;Time;{};0;0;0\r", comma10(*t)).unwrap();
        writeln!(s, "2;TH;NonDirHist;Time;{};{u};0;0\r", comma10(*t)).unwrap();
    }
    s.push_str("\r\nTABLE:  \"Element Forces - Links\"\r\n");
    s.push_str("Link;LinkElem;OutputCase;CaseType;StepType;StepNum;P;V2\r\n");
    s.push_str("Text;Text;Text;Text;Text;Sec;KN;KN\r\n");
    for (i, t) in fe.time.iter().enumerate() {
        let v2 = comma10(fe.resistance[i] / 1000.0);
        writeln!(s, "1;1;TH;NonDirHist;Time;{};-1000;{v2}\r", comma10(*t)).unwrap();
    }
    s
}

/// An ANSYS POST26 listing of the fe run: `UX_2` (m), `FX_1` (the ground's reaction,
/// N: minus the resistance), `SLIP_1` (m), the banner and header on every page of 60 rows.
fn ansys(fe: &Fe) -> String {
    let mut s = String::from(" /POST26\n PRVAR,2,3,4\n");
    for (i, t) in fe.time.iter().enumerate() {
        if i % 60 == 0 {
            s.push_str("\n ***** ANSYS POST26 VARIABLE LISTING *****\n\n");
            s.push_str("    TIME          2 UX_2              3 FX_1              4 SLIP_1\n");
            s.push_str("                  UX                  FX                  SLIDE\n");
        }
        let (u, r, p) = (fe.rel_disp[i], -fe.resistance[i], fe.slide[i]);
        writeln!(
            s,
            " {:>16} {:>18} {:>18} {:>18}",
            e10(*t),
            e10(u),
            e10(r),
            e10(p)
        )
        .unwrap();
    }
    s
}

/// An Abaqus XY report of the fe run: `U:U1 PI: MASS-1 N: 2` (m), `RF:RF1 PI: GROUND-1
/// N: 1` (N, minus the resistance) and an unmapped `ALLKE` with `NoValue` at first.
fn abaqus(fe: &Fe) -> String {
    let mut s = String::from("\n");
    writeln!(
        s,
        "{:>20}{:>28}{:>28}{:>20}\n",
        "X", "U:U1 PI: MASS-1 N: 2", "RF:RF1 PI: GROUND-1 N: 1", "ALLKE"
    )
    .unwrap();
    for (i, t) in fe.time.iter().enumerate() {
        let ke = if i == 0 { "NoValue".into() } else { e10(0.0) };
        let (u, r) = (fe.rel_disp[i], -fe.resistance[i]);
        writeln!(s, "{:>20}{:>28}{:>28}{:>20}", e10(*t), e10(u), e10(r), ke).unwrap();
    }
    s
}

/// OpenSees recorder files of the fe run: node 2's DOFs 1 and 2 (`disp.out`) and element
/// 1's global forces (`force.out`: −R on node 1, R on node 2), with `-time`.
fn opensees(fe: &Fe) -> (String, String) {
    let (mut disp, mut force) = (String::new(), String::new());
    for (i, t) in fe.time.iter().enumerate() {
        writeln!(disp, "{} {} 0", e10(*t), e10(fe.rel_disp[i])).unwrap();
        let r = fe.resistance[i];
        writeln!(force, "{} {} {}", e10(*t), e10(-r), e10(r)).unwrap();
    }
    (disp, force)
}

/// A script whose recorders write the two files.
const OPENSEES_SCRIPT: &str = "import openseespy.opensees as ops\n\
ops.recorder('Node', '-file', 'disp.out', '-time', '-node', 2, '-dof', 1, 2, 'disp')\n\
ops.recorder('Element', '-file', 'force.out', '-time', '-ele', 1, 'force')\n";

/// The externals reading the five files.
const EXTERNALS: &str = r#"
[[external]]
label = "sap2000"
file = "sap2000.csv"
program = "SAP2000 (fixture: the fe run in its table-export layout)"
format = "sap2000"
output_case = "TH"
columns = { "Joint 2: U1" = "rel_disp", "Link 1: P" = { quantity = "normal", scale = -1 }, "Link 1: V2" = "resistance" }

[[external]]
label = "ansys"
file = "file.out"
program = "ANSYS (fixture: the fe run as a POST26 PRVAR listing)"
format = "ansys"
columns = { "UX_2" = "rel_disp [m]", "FX_1" = { quantity = "resistance [N]", scale = -1 }, "SLIP_1" = "slide [m]" }

[[external]]
label = "abaqus"
file = "pepo.rpt"
program = "Abaqus (fixture: the fe run as an XY report)"
format = "abaqus"
columns = { "U:U1 PI: MASS-1 N: 2" = "rel_disp [m]", "RF:RF1 PI: GROUND-1 N: 1" = { quantity = "resistance [N]", scale = -1 } }

[[external]]
label = "opensees-disp"
file = "disp.out"
program = "OpenSees (fixture: the fe run as a Node recorder)"
format = "opensees"
recorder = "recorder Node -file disp.out -time -node 2 -dof 1 2 disp"
columns = { "node 2 dof 1 disp" = "rel_disp [m]" }

[[external]]
label = "opensees-force"
file = "force.out"
program = "OpenSees (fixture: the fe run as an Element recorder)"
format = "opensees"
script = "model.py"
columns = { "element 1 force 2" = "resistance [N]" }
"#;

/// Whether `read` equals `fe` to the printed digits, sample by sample.
fn equal_to_print(label: &str, key: &str, read: &[f64], fe: &[f64]) {
    assert_eq!(read.len(), fe.len(), "{label} {key}: samples");
    for (i, (a, b)) in read.iter().zip(fe).enumerate() {
        assert!(
            (a - b).abs() <= PRINTED * b.abs(),
            "{label} {key}[{i}]: {a} read, {b} written"
        );
    }
}

#[test]
fn each_program_s_layout_reads_back_the_fe_trace_and_passes_the_default_gate() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let fe = fe(d);
    std::fs::write(d.join("sap2000.csv"), sap2000(&fe)).unwrap();
    std::fs::write(d.join("file.out"), ansys(&fe)).unwrap();
    std::fs::write(d.join("pepo.rpt"), abaqus(&fe)).unwrap();
    let (disp, force) = opensees(&fe);
    std::fs::write(d.join("disp.out"), disp).unwrap();
    std::fs::write(d.join("force.out"), force).unwrap();
    std::fs::write(d.join("model.py"), OPENSEES_SCRIPT).unwrap();
    let r = run_text(d, &format!("{PEPO}{EXTERNALS}"));
    let channels: [(&str, &[&str]); 5] = [
        ("sap2000", &["rel_disp", "resistance"]),
        ("ansys", &["rel_disp", "resistance", "slide"]),
        ("abaqus", &["rel_disp", "resistance"]),
        ("opensees-disp", &["rel_disp"]),
        ("opensees-force", &["resistance"]),
    ];
    for (label, keys) in channels {
        let run = run_of(&r, &format!("{label}/external"));
        let t = &run.trace;
        // Abaqus: the first X, where ALLKE has NoValue, is read (ALLKE is not mapped)
        equal_to_print(label, "time", &t.time, &fe.time);
        for key in keys {
            let written = match *key {
                "rel_disp" => &fe.rel_disp,
                "resistance" => &fe.resistance,
                _ => &fe.slide,
            };
            equal_to_print(label, key, t.column(key).unwrap(), written);
        }
        assert_eq!(
            t.channels.len(),
            keys.len() + usize::from(label == "sap2000")
        );
        // gated by default against the exact solution, every check passing
        let checks: Vec<_> = r.checks.iter().filter(|c| c.run == run.label()).collect();
        assert!(!checks.is_empty(), "{label}: no checks");
        assert!(
            checks.iter().all(|c| c.gated && c.basis == "reference"),
            "{label}"
        );
        assert!(
            checks
                .iter()
                .all(|c| c.verdict == rockslide::analysis::Verdict::Pass),
            "{label}: {checks:?}"
        );
    }
    let sap = run_of(&r, "sap2000/external");
    assert_eq!(
        sap.trace.column("normal").unwrap(),
        vec![WEIGHT; fe.time.len()]
    );
    let notes = sap.findings.join("\n");
    let rows = format!(
        "SAP2000/ETABS/CSiBridge table export, {} rows",
        fe.time.len()
    );
    for said in [
        rows.as_str(),
        "converted to SI: rel_disp [mm], normal [kN], resistance [kN]",
        "sign and scale: \"Link 1: P\" × -1 → normal",
        "decimal commas read as decimal points",
    ] {
        assert!(notes.contains(said), "{said}\n{notes}");
    }
    let pages = format!("{} listing page(s) joined", fe.time.len().div_ceil(60));
    assert!(run_of(&r, "ansys/external").findings.contains(&pages));
    assert!(r.gate_passed());
}

/// The SAP2000 export with `P` mapped as written (tension-positive), then with its sign.
#[test]
fn a_compression_negative_normal_force_fails_until_the_map_gives_its_sign() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let fe = fe(d);
    std::fs::write(d.join("sap2000.csv"), sap2000(&fe)).unwrap();
    let external = |p: &str| {
        format!(
            "{PEPO}\n[[external]]\nlabel = \"sap2000\"\nfile = \"sap2000.csv\"\n\
             program = \"SAP2000\"\nformat = \"sap2000\"\n\
             columns = {{ \"Joint 2: U1\" = \"rel_disp\", \"Link 1: P\" = {p}, \"Link 1: V2\" = \"resistance\" }}\n"
        )
    };
    let invariant = |r: &CaseResult, which: Invariant| {
        r.invariants
            .iter()
            .find(|i| i.run == "sap2000/external" && i.invariant == which)
            .cloned()
            .unwrap()
    };
    let peak_r = fe.resistance.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
    let mu_w = 0.5 * WEIGHT;

    // as written: N = −M·g
    let before = run_text(d, &external("\"normal\""));
    let compression = invariant(&before, Invariant::Compression);
    assert_eq!(compression.worst, 1.0); // −N / (M·g)
    assert!(compression.fails());
    let bound = invariant(&before, Invariant::FrictionBound);
    // (|T| − μN) / (μ·M·g) with N = −M·g: 1 + max|T| / (μ·M·g)
    assert!(
        (bound.worst - (1.0 + peak_r / mu_w)).abs() < 1e-9,
        "{bound:?}"
    );
    assert!(bound.fails());
    assert!(!before.gate_passed());

    // with its sign: N = M·g
    let after = run_text(d, &external("{ quantity = \"normal\", scale = -1 }"));
    let compression = invariant(&after, Invariant::Compression);
    assert_eq!(compression.worst, -1.0);
    assert!(!compression.fails());
    let bound = invariant(&after, Invariant::FrictionBound);
    assert!(
        (bound.worst - (peak_r - mu_w) / mu_w).abs() < 1e-9,
        "{bound:?}"
    );
    assert!(!bound.fails());
    assert!(after.gate_passed());

    // no slide in a SAP2000 link table: stick/slip is not provided, never a zero
    let run = run_of(&after, "sap2000/external");
    assert!(
        !after
            .invariants
            .iter()
            .any(|i| i.run == "sap2000/external" && i.invariant == Invariant::StickSlip)
    );
    let notes = run.findings.join("\n");
    assert!(
        notes.contains("invariants not provided by the file: stick_slip (no slide); dissipation (no slide); penetration (no per-contact gaps); energy_balance (no energy_input, no energy_error)"),
        "{notes}"
    );
}

/// The fe run's trace as SAP2000 exports its tables to Excel:
/// `tests/data/external/sap2000-pepo.xlsx`, written with openpyxl by `make_sap2000_xlsx.py`
/// beside it from the fe trace of [`PEPO`] (`rockslide run` on it writes `fe-single.csv`): the
/// sheets "Joint Displacements" (joints 1 and 2, `U1` in m) and "Element Forces - Links"
/// (link 1, `P` −1000 kN, `V2` the resistance in kN), numbers as number cells.
const SAP2000_XLSX: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/external/sap2000-pepo.xlsx"
);

/// Whether `read` equals `written` within 4 ulp, sample by sample.
fn equal_to_ulps(key: &str, read: &[f64], written: &[f64]) {
    assert_eq!(read.len(), written.len(), "{key}: samples");
    for (i, (a, b)) in read.iter().zip(written).enumerate() {
        assert!(
            (a - b).abs() <= 4.0 * f64::EPSILON * b.abs(),
            "{key}[{i}]: {a} read, {b} written"
        );
    }
}

#[test]
fn a_sap2000_excel_export_reads_back_the_fe_trace_and_passes_the_default_gate() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let fe = fe(d);
    std::fs::copy(SAP2000_XLSX, d.join("sap2000.xlsx")).unwrap();
    let external = r#"
[[external]]
label = "sap2000"
file = "sap2000.xlsx"
program = "SAP2000 (fixture: the fe run exported to Excel)"
format = "sap2000"
output_case = "TH"
columns = { "Joint 2: U1" = "rel_disp", "Link 1: P" = { quantity = "normal", scale = -1 }, "Link 1: V2" = "resistance" }
"#;
    let r = run_text(d, &format!("{PEPO}{external}"));
    let run = run_of(&r, "sap2000/external");
    let t = &run.trace;
    // number cells hold the f64 written, read back bit for bit; the fixture was written
    // from the run's CSV, whose times are the output grid's (one ulp from the times this
    // run accumulates), and kN go back to N through ÷1000 and ×1000: within 4 ulp
    equal_to_ulps("time", &t.time, &fe.time);
    equal_to_ulps("rel_disp", t.column("rel_disp").unwrap(), &fe.rel_disp);
    equal_to_ulps(
        "resistance",
        t.column("resistance").unwrap(),
        &fe.resistance,
    );
    assert_eq!(t.column("normal").unwrap(), vec![WEIGHT; fe.time.len()]);
    let notes = run.findings.join("\n");
    let rows = format!(
        "SAP2000/ETABS/CSiBridge tables exported to Excel, {} rows",
        fe.time.len()
    );
    for said in [
        rows.as_str(),
        "tables \"Joint Displacements\", \"Element Forces - Links\", OutputCase \"TH\"",
        "converted to SI: normal [kN], resistance [kN]",
        "sign and scale: \"Link 1: P\" × -1 → normal",
    ] {
        assert!(notes.contains(said), "{said}\n{notes}");
    }
    let checks: Vec<_> = r.checks.iter().filter(|c| c.run == run.label()).collect();
    assert!(!checks.is_empty());
    assert!(
        checks.iter().all(|c| c.gated
            && c.basis == "reference"
            && c.verdict == rockslide::analysis::Verdict::Pass),
        "{checks:?}"
    );
    assert!(r.gate_passed());
}

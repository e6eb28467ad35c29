//! Each program's layout read, and each malformed variant refused at its line and column.
//! The texts follow the layouts the programs document (module docs of each reader).

use rockslide_core::case::{ColumnMap, ExternalFormat, ExternalLayout};

use super::read_external;

fn format(layout: ExternalLayout, columns: &[(&str, &str, f64)]) -> ExternalFormat {
    ExternalFormat {
        layout: Some(layout),
        columns: columns
            .iter()
            .map(|(a, b, s)| ColumnMap {
                from: a.to_string(),
                to: b.to_string(),
                scale: *s,
            })
            .collect(),
        ..Default::default()
    }
}

/// Write `text` as `name` in a fresh folder and read it with `format`.
fn read(
    name: &str,
    text: &str,
    format: &ExternalFormat,
) -> Result<rockslide_core::case::ExternalTrace, String> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    read_external(&path, format).map_err(|e| {
        let prefix = format!("{}:", path.display());
        e.to_string().replace(&prefix, &format!("{name}:"))
    })
}

/// A SAP2000 export: BOM, CRLF, `;` with decimal commas, two tables, a units row, a
/// repeated page header, an envelope row, a second output case.
const SAP: &str = "\u{feff}TABLE:  \"Joint Displacements\"\r\n\
Joint;OutputCase;CaseType;StepType;StepNum;U1;U2;U3\r\n\
Text;Text;Text;Text;Sec;mm;mm;mm\r\n\
1;TH;LinDirHist;Time;0;0;0;0\r\n\
2;TH;LinDirHist;Time;0;0;0;0\r\n\
2;TH;LinDirHist;Time;0,01;1,5;0;0\r\n\
Joint;OutputCase;CaseType;StepType;StepNum;U1;U2;U3\r\n\
Text;Text;Text;Text;Sec;mm;mm;mm\r\n\
2;TH;LinDirHist;Time;0,02;2,5;0;0\r\n\
2;TH;LinDirHist;Max;;2,5;0;0\r\n\
2;DEAD;LinStatic;;;9;9;9\r\n\
\r\n\
TABLE:  \"Element Forces - Links\"\r\n\
Link;LinkElem;OutputCase;CaseType;StepType;StepNum;P;V2\r\n\
Text;Text;Text;Text;Text;Sec;KN;KN\r\n\
1;1;TH;LinDirHist;Time;0;-1000;0\r\n\
1;1;TH;LinDirHist;Time;0,01;-1000;250\r\n\
1;1;TH;LinDirHist;Time;0,02;-1000;500\r\n";

/// An ETABS export: tab-separated, the object named by `UniqueName` beside `Story` and
/// `Label`, the steps numbered (`StepType` `Step`, `StepNum` unitless).
const ETABS: &str = "TABLE:  \"Joint Displacements\"\n\
Story\tLabel\tUniqueName\tOutputCase\tCaseType\tStepType\tStepNum\tUx\tUy\tUz\n\
Text\tText\tText\tText\tText\tText\tUnitless\tmm\tmm\tmm\n\
Base\t1\t1\tTH\tLinModHist\tStep\t0\t0\t0\t0\n\
Story1\t1\t7\tTH\tLinModHist\tStep\t0\t0\t0\t0\n\
Story1\t1\t7\tTH\tLinModHist\tStep\t1\t0.25\t0\t0\n\
Story1\t1\t7\tTH\tLinModHist\tStep\t2\t0.75\t0\t-0.01\n\
Story1\t1\t7\tTH\tLinModHist\tMax\t\t0.75\t0\t0\n";

fn etabs_format(step_dt: Option<f64>) -> ExternalFormat {
    let mut f = format(
        ExternalLayout::CsiTables,
        &[("UniqueName 7: Ux", "rel_disp", 1.0)],
    );
    f.step_dt = step_dt;
    f
}

#[test]
fn an_etabs_table_with_numbered_steps_reads_time_as_step_times_dt() {
    let t = read("etabs.txt", ETABS, &etabs_format(Some(0.005))).unwrap();
    assert_eq!(t.trace.time, [0.0, 0.005, 0.01]);
    assert_eq!(t.trace.column("rel_disp").unwrap(), [0.0, 0.00025, 0.00075]);
    let notes = t.notes.join("\n");
    for said in [
        "StepType \"Step\": time = StepNum × 0.005 s (4 rows)",
        "1 envelope rows (Max, Min) skipped",
    ] {
        assert!(notes.contains(said), "{said}\n{notes}");
    }
    // `Step By Step` is the same
    let by = ETABS.replace("\tStep\t", "\tStep By Step\t");
    assert_eq!(
        read("etabs.txt", &by, &etabs_format(Some(0.005)))
            .unwrap()
            .trace,
        t.trace
    );
}

#[test]
fn malformed_etabs_steps_are_located() {
    let e = |text: &str, step_dt| read("etabs.txt", text, &etabs_format(step_dt)).unwrap_err();
    assert_eq!(
        e(ETABS, None),
        "etabs.txt:4:29: StepType \"Step\": the rows are numbered steps; give the time between two steps with `step_dt` (s)"
    );
    assert_eq!(
        e(
            &ETABS.replace("Step\t1\t0.25", "Step\t1.5\t0.25"),
            Some(0.005)
        ),
        "etabs.txt:6:31: StepNum 1.5: a numbered step (StepType \"Step\") is a whole number ≥ 0"
    );
    assert_eq!(
        e(
            &ETABS.replace("Step\t2\t0.75", "Step\t2\t0.7x5"),
            Some(0.005)
        ),
        "etabs.txt:7:33: table \"Joint Displacements\", field \"Ux\": \"0.7x5\" is not a number"
    );
}

fn sap_format() -> ExternalFormat {
    let mut f = format(
        ExternalLayout::CsiTables,
        &[
            ("Joint 2: U1", "rel_disp", 1.0),
            ("Link 1: P", "normal", -1.0),
            ("Link 1: V2", "resistance [kN]", 1.0),
        ],
    );
    f.output_case = Some("TH".into());
    f
}

#[test]
fn a_sap2000_long_table_is_pivoted_with_its_units_row_and_the_map_s_sign() {
    let t = read("sap.csv", SAP, &sap_format()).unwrap();
    assert_eq!(t.trace.time, [0.0, 0.01, 0.02]);
    assert_eq!(t.trace.column("rel_disp").unwrap(), [0.0, 0.0015, 0.0025]);
    assert_eq!(t.trace.column("normal").unwrap(), [1e6, 1e6, 1e6]);
    assert_eq!(t.trace.column("resistance").unwrap(), [0.0, 250e3, 500e3]);
    let notes = t.notes.join("\n");
    for said in [
        "tables \"Joint Displacements\", \"Element Forces - Links\", OutputCase \"TH\" (1 rows of other output cases skipped)",
        "1 envelope rows (Max, Min) skipped",
        "converted to SI: rel_disp [mm], normal [kN], resistance [kN]",
        "sign and scale: \"Link 1: P\" × -1 → normal",
        "decimal commas read as decimal points",
    ] {
        assert!(notes.contains(said), "{said}\n{notes}");
    }
    // recognised without `format`
    let mut f = sap_format();
    f.layout = None;
    assert_eq!(read("sap.csv", SAP, &f).unwrap().trace, t.trace);
}

#[test]
fn malformed_sap2000_exports_are_located() {
    let e = |text: &str, f: &ExternalFormat| read("sap.csv", text, f).unwrap_err();
    let f = sap_format();
    assert_eq!(
        e(&SAP.replace("0,01;1,5", "0,01;1,5x"), &f),
        "sap.csv:6:27: table \"Joint Displacements\", field \"U1\": \"1,5x\" is not a number"
    );
    assert_eq!(
        e(&SAP.replace("Time;0,02;2,5", "Time;0,005;2,5"), &f),
        "sap.csv:9:22: StepNum: time 0.005 does not increase for \"Joint 2: U1\" (its row before, line 6, is at 0.01)"
    );
    assert_eq!(
        e(
            &SAP.replace(
                "1;1;TH;LinDirHist;Time;0;-1000;0",
                "1;1;TH;LinDirHist;Time;0;-1000"
            ),
            &f
        ),
        "sap.csv:16:26: table \"Element Forces - Links\": has 7 fields, but its field names have 8"
    );
    assert_eq!(
        e(&SAP.replace("Time;0,01;1,5", "Mode;1;1,5"), &f),
        "sap.csv:6:17: StepType \"Mode\": the rows are not times or steps; export the time history step by step (SAP2000: Direct History Results, Step-by-Step: StepType `Time`; ETABS: StepType `Step`)"
    );
    let mut any_case = sap_format();
    any_case.output_case = None;
    assert_eq!(
        e(SAP, &any_case),
        "sap.csv:11:3: OutputCase \"DEAD\": the file has several output cases (\"TH\", \"DEAD\"); name the one to read with `output_case`"
    );
    let mut wrong_unit = sap_format();
    wrong_unit.columns[0].to = "rel_disp [m]".into();
    assert_eq!(
        e(SAP, &wrong_unit),
        "sap.csv:5:24: \"Joint 2: U1\": the map says [m], the file's units say \"mm\""
    );
    let mut unknown = sap_format();
    unknown.columns[0].from = "Joint 3: U1".into();
    assert!(e(SAP, &unknown).starts_with(
        "sap.csv:1:1: the column map names \"Joint 3: U1\", but the file has no such series; its series: \"Joint 1: U1\""
    ));
    assert_eq!(
        e("Joint,OutputCase\n1,TH\n", &f),
        "sap.csv:1:1: is not in a table: an export starts each table with a `TABLE: \"…\"` line"
    );
    assert!(
        e("TABLE: \"Joint Displacements\"\nJoint,OutputCase,U1\n", &f)
            .starts_with("sap.csv:2:1: table \"Joint Displacements\": the field names have no OutputCase, StepType and StepNum")
    );
}

/// An ANSYS POST26 listing over two pages, with the item labels under the names and an
/// output file's text around it.
const PRVAR: &str = " /OUTPUT FILE= file.out\n\
\n\
 ***** ANSYS POST26 VARIABLE LISTING *****\n\
\n\
  TIME        2 UX_2         3 FX_1         4 SLIP_1\n\
              UX             FX             SLIDE\n\
  0.0000       0.0000        0.0000         0.0000\n\
  0.10000E-01  0.12345E-02  -0.25000E+06    0.0000\n\
\n\
 ***** ANSYS POST26 VARIABLE LISTING *****\n\
\n\
  TIME        2 UX_2         3 FX_1         4 SLIP_1\n\
              UX             FX             SLIDE\n\
  0.20000E-01  0.25000E-02  -0.50000E+06    0.50000E-03\n\
\n\
 PRINTOUT RESUMED BY /GOP\n";

fn ansys_format() -> ExternalFormat {
    format(
        ExternalLayout::AnsysPrvar,
        &[
            ("UX_2", "rel_disp [m]", 1.0),
            ("FX_1", "resistance [N]", -1.0),
            ("SLIP_1", "slide", 1.0),
        ],
    )
}

#[test]
fn an_ansys_prvar_listing_is_read_across_its_pages() {
    let t = read("file.out", PRVAR, &ansys_format()).unwrap();
    assert_eq!(t.trace.time, [0.0, 0.01, 0.02]);
    assert_eq!(
        t.trace.column("rel_disp").unwrap(),
        [0.0, 0.0012345, 0.0025]
    );
    assert_eq!(t.trace.column("resistance").unwrap(), [0.0, 250e3, 500e3]);
    assert_eq!(t.trace.column("slide").unwrap(), [0.0, 0.0, 0.0005]);
    assert!(t.notes.iter().any(|n| n == "2 listing page(s) joined"));
    let mut f = ansys_format();
    f.layout = None;
    assert_eq!(read("file.out", PRVAR, &f).unwrap().trace, t.trace);
}

#[test]
fn malformed_ansys_listings_are_located() {
    let e = |text: &str| read("file.out", text, &ansys_format()).unwrap_err();
    assert_eq!(
        e(&PRVAR.replace("0.12345E-02", "0.12345E-0Z")),
        "file.out:8:14: \"0.12345E-0Z\" is not a number"
    );
    assert_eq!(
        e(&PRVAR.replace("-0.50000E+06    0.50000E-03", "-0.50000E+06")),
        "file.out:14:27: has 3 fields, but the header (line 12) has 4"
    );
    assert_eq!(
        e(&PRVAR.replace("0.20000E-01", "0.50000E-02")),
        "file.out:14:1: TIME: time 0.005 does not increase for \"UX_2\" (its row before, line 8, is at 0.01)"
    );
    assert_eq!(
        e(&PRVAR.replace("3 FX_1", "3 UX_2")),
        "file.out:5:30: variable name \"UX_2\" appears twice in the header: give each variable its own name (the Name argument of NSOL, ESOL, RFORCE)"
    );
    assert!(e("TIME UX\n0 0\n").starts_with("file.out:1:1: has no `***** ANSYS POST26"));
}

/// An Abaqus XY report: a curve name with blanks, `NoValue` in a mapped and an unmapped
/// curve, Abaqus's number forms.
const RPT: &str = "\n\
                X          U:U1 PI: MASS-1 N: 2      RF:RF1 PI: GROUND-1 N: 1             ALLKE\n\
\n\
               0.                        0.                       NoValue                0.\n\
           10.E-03               1.2345E-03               -250.E+03           NoValue\n\
           20.E-03                2.500E-03               -500.E+03                1.\n";

fn abaqus_format() -> ExternalFormat {
    format(
        ExternalLayout::AbaqusReport,
        &[
            ("U:U1 PI: MASS-1 N: 2", "rel_disp [m]", 1.0),
            ("RF:RF1 PI: GROUND-1 N: 1", "resistance [N]", -1.0),
        ],
    )
}

#[test]
fn an_abaqus_report_is_read_with_its_gaps_skipped() {
    let t = read("x.rpt", RPT, &abaqus_format()).unwrap();
    assert_eq!(t.trace.time, [0.01, 0.02]);
    assert_eq!(t.trace.column("rel_disp").unwrap(), [0.0012345, 0.0025]);
    assert_eq!(t.trace.column("resistance").unwrap(), [250e3, 500e3]);
    let notes = t.notes.join("\n");
    assert!(notes.contains("2 `NoValue` entries"), "{notes}");
    assert!(
        notes.contains("1 times skipped where a mapped series has no value (the first at 0)"),
        "{notes}"
    );
}

#[test]
fn malformed_abaqus_reports_are_located() {
    let e = |text: &str| read("x.rpt", text, &abaqus_format()).unwrap_err();
    assert_eq!(
        e(&RPT.replace("-500.E+03", "-500.E+0x")),
        "x.rpt:6:48: \"-500.E+0x\" is not a number (nor `NoValue`)"
    );
    assert_eq!(
        e(&RPT.replace("                1.\n", "\n")),
        "x.rpt:6:48: has 3 fields, but the header (line 2) has 4"
    );
    assert!(e("0. 1.\n").starts_with("x.rpt:1:1: has no `X` header line"));
}

fn opensees_format(recorder: &str) -> ExternalFormat {
    let mut f = format(
        ExternalLayout::OpenSeesRecorder,
        &[("node 2 dof 1 disp", "rel_disp [m]", 1.0)],
    );
    f.recorder = Some(recorder.into());
    f
}

#[test]
fn an_opensees_recorder_file_is_named_by_its_command_or_script() {
    let text = "0 0 0\n0.01 0.0012345 7\n0.02 0.0025 7\n";
    let f = opensees_format("recorder Node -file disp.out -time -node 2 -dof 1 2 disp");
    let t = read("disp.out", text, &f).unwrap();
    assert_eq!(
        t.trace.column("rel_disp").unwrap(),
        [0.0, 0.0012345, 0.0025]
    );
    // from the script's recorder command writing this file
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("model.py");
    std::fs::write(
        &script,
        "ops.recorder('Node', '-file', 'other.out', '-time', '-node', 3, '-dof', 1, 'disp')\n\
         ops.recorder('Node', '-file', 'disp.out', '-time', '-node', 2, '-dof', 1, 2, 'disp')\n",
    )
    .unwrap();
    let data = dir.path().join("disp.out");
    std::fs::write(&data, text).unwrap();
    let mut by_script = opensees_format("");
    by_script.recorder = None;
    by_script.script = Some(script.clone());
    assert_eq!(read_external(&data, &by_script).unwrap().trace, t.trace);
    // without either, by position
    let mut positional = format(
        ExternalLayout::OpenSeesRecorder,
        &[("column 2", "rel_disp [m]", 1.0)],
    );
    positional.recorder = None;
    assert_eq!(read("disp.out", text, &positional).unwrap().trace, t.trace);
    // a script without this file's recorder
    std::fs::write(
        &script,
        "recorder Node -file a.out -time -node 1 -dof 1 disp\n",
    )
    .unwrap();
    let e = read_external(&data, &by_script).unwrap_err().to_string();
    assert!(
        e.contains("model.py: script: has no Node or Element recorder writing \"disp.out\"; its recorders write: a.out (line 1)"),
        "{e}"
    );
}

#[test]
fn malformed_opensees_files_are_located() {
    let f = opensees_format("recorder Node -file disp.out -time -node 2 -dof 1 disp");
    let e = |text: &str| read("disp.out", text, &f).unwrap_err();
    assert_eq!(
        e("0 0\n0.01 0.001 5\n"),
        "disp.out:2:12: has 3 fields, but line 1 of the data has 2"
    );
    assert_eq!(
        e("0 0\n0.01 1e-3q\n"),
        "disp.out:2:6: \"1e-3q\" is not a number"
    );
    assert_eq!(
        e("0 0 1\n"),
        "disp.out:1:1: has 2 values a row, but the recorder (1 nodes × 1 DOFs) writes 1"
    );
    let no_time = opensees_format("recorder Node -file disp.out -node 2 -dof 1 disp");
    assert!(
        read("disp.out", "0\n", &no_time)
            .unwrap_err()
            .ends_with("recorder: the recorder writes no time column: add `-time` to it")
    );
}

#[test]
fn a_csv_with_decimal_commas_and_a_sign_in_the_map() {
    let mut f = format(
        ExternalLayout::Csv,
        &[("t", "time [s]", 1.0), ("P", "normal [kN]", -1.0)],
    );
    f.delimiter = Some(';');
    let t = read("p.csv", "t;P\n0;-1000\n0,5;-999,5\n", &f).unwrap();
    assert_eq!(t.trace.time, [0.0, 0.5]);
    assert_eq!(t.trace.column("normal").unwrap(), [1e6, 999.5e3]);
    assert!(
        t.notes
            .iter()
            .any(|n| n == "sign and scale: \"P\" × -1 → normal")
    );
    assert!(
        t.notes
            .iter()
            .any(|n| n == "decimal commas read as decimal points")
    );
}

#[test]
fn a_program_s_file_without_a_map_is_refused_with_its_series() {
    let e = read("file.out", PRVAR, &format(ExternalLayout::AnsysPrvar, &[])).unwrap_err();
    assert_eq!(
        e,
        "file.out:1:1: needs a column map (`columns`) saying which of its series is which quantity (ANSYS POST26 PRVAR listing); its series: \"UX_2\", \"FX_1\", \"SLIP_1\""
    );
}

/// An OpenSees `-xml` Node and Element recorder file as `XmlFileStream` writes it: the
/// header naming the columns, the rows in `<Data>`, each value followed by a blank.
const OPENSEES_XML: &str = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n \
<OpenSees\n  \
xmlns:xsi = \"http://www.w3.org/2001/XMLSchema-instance\"\n  \
xsi:noNamespaceSchemaLocation = \"http://OpenSees.berkeley.edu/xml-schema/xmlns/OpenSees.xsd\">\n  \
<TimeOutput>\n    <ResponseType>time</ResponseType>\n  </TimeOutput>\n  \
<NodeOutput nodeTag=\"2\" coord1=\"0\" coord2=\"0\" coord3=\"0\">\n    \
<ResponseType>D1</ResponseType>\n  </NodeOutput>\n  \
<ElementOutput eleType=\"flatSliderBearing\" eleTag=\"1\" node1=\"1\" node2=\"2\">\n    \
<ResponseType>Px_1</ResponseType>\n    <ResponseType>Vy_1</ResponseType>\n  </ElementOutput>\n  \
<Data>\n    0 0 0 0 \n    0.01 0.0012345 -1000 -250 \n    0.02 0.0025 -1000 -500 \n  </Data>\n\
</OpenSees>\n";

fn opensees_xml_format() -> ExternalFormat {
    format(
        ExternalLayout::OpenSeesRecorder,
        &[
            ("node 2 D1", "rel_disp [m]", 1.0),
            ("element 1 Px_1", "normal [kN]", -1.0),
            ("element 1 Vy_1", "resistance [kN]", -1.0),
        ],
    )
}

#[test]
fn an_opensees_xml_recorder_file_names_its_own_columns() {
    let t = read("out.xml", OPENSEES_XML, &opensees_xml_format()).unwrap();
    assert_eq!(t.trace.time, [0.0, 0.01, 0.02]);
    assert_eq!(
        t.trace.column("rel_disp").unwrap(),
        [0.0, 0.0012345, 0.0025]
    );
    assert_eq!(t.trace.column("normal").unwrap(), [0.0, 1e6, 1e6]);
    assert_eq!(t.trace.column("resistance").unwrap(), [0.0, 250e3, 500e3]);
    let notes = t.notes.join("\n");
    assert!(
        notes.contains("OpenSees -xml recorder: 3 columns named by the file (\"node 2 D1\", \"element 1 Px_1\", \"element 1 Vy_1\")"),
        "{notes}"
    );
}

#[test]
fn malformed_opensees_xml_files_are_located() {
    let e = |text: &str| read("out.xml", text, &opensees_xml_format()).unwrap_err();
    assert_eq!(
        e(&OPENSEES_XML.replace("0.01 0.0012345 -1000 -250", "0.01 0.0012345 -1000")),
        "out.xml:17:20: has 3 values, but the file names 4 columns"
    );
    assert_eq!(
        e(&OPENSEES_XML.replace("-500 \n", "-5x0 \n")),
        "out.xml:18:23: \"-5x0\" is not a number"
    );
    assert_eq!(
        e(&OPENSEES_XML.replace("  </Data>\n</OpenSees>\n", "")),
        "out.xml:18:1: <Data> is not closed (</Data>): the file ends early (did the analysis stop before the recorder was closed?)"
    );
    assert_eq!(
        e(&OPENSEES_XML.replace(" eleTag=\"1\"", "")),
        "out.xml:11:3: <ElementOutput> has no eleTag attribute"
    );
    assert!(
        e(&OPENSEES_XML.replace("<ResponseType>time</ResponseType>", ""))
            .ends_with("its columns start with no <TimeOutput>: add `-time` to the recorder")
    );
}

/// Rows of an OpenSees `-binary` recorder file: little-endian doubles, a line feed each.
fn binary_rows(rows: &[&[f64]]) -> Vec<u8> {
    let mut out = Vec::new();
    for row in rows {
        for v in *row {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.push(b'\n');
    }
    out
}

fn read_bytes(name: &str, bytes: &[u8], format: &ExternalFormat) -> Result<Vec<f64>, String> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    let prefix = format!("{}:", path.display());
    read_external(&path, format)
        .map(|t| {
            let mut v = t.trace.time.clone();
            v.extend(t.trace.column("rel_disp").unwrap());
            v
        })
        .map_err(|e| e.to_string().replace(&prefix, &format!("{name}:")))
}

#[test]
fn an_opensees_binary_recorder_file_is_read_with_or_without_its_command() {
    // 0.01 s has no zero byte; the zero row makes the file no UTF-8 text
    let bytes = binary_rows(&[&[0.0, 0.0], &[0.01, 0.0012345], &[0.02, 0.0025]]);
    let f = opensees_format("recorder Node -binary d.bin -time -node 2 -dof 1 disp");
    assert_eq!(
        read_bytes("d.bin", &bytes, &f).unwrap(),
        [0.0, 0.01, 0.02, 0.0, 0.0012345, 0.0025]
    );
    // without the command the width is the file's own: "column 2"
    let g = format(
        ExternalLayout::OpenSeesRecorder,
        &[("column 2", "rel_disp [m]", 1.0)],
    );
    assert_eq!(
        read_bytes("d.bin", &bytes, &g).unwrap(),
        [0.0, 0.01, 0.02, 0.0, 0.0012345, 0.0025]
    );
    // located: a file cut inside its last row, a row of another width
    let cut = &bytes[..bytes.len() - 5];
    assert_eq!(
        read_bytes("d.bin", cut, &f).unwrap_err(),
        "d.bin:3:1: row 3: the file ends inside it (46 bytes; a row of 2 values is 17 bytes)"
    );
    let mut wrong = bytes.clone();
    wrong[16] = b' ';
    assert_eq!(
        read_bytes("d.bin", &wrong, &f).unwrap_err(),
        "d.bin:1:3: row 1 (byte 16): does not end in a line feed after its 2 values: not a row of this width"
    );
    assert!(
        read_bytes("d.bin", cut, &g)
            .unwrap_err()
            .contains("is not an OpenSees -binary recorder file: no row width")
    );
}

/// Write `bytes` as `name` in a fresh folder and read it with `format`.
fn read_file_bytes(
    name: &str,
    bytes: &[u8],
    format: &ExternalFormat,
) -> Result<rockslide_core::case::ExternalTrace, String> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    read_external(&path, format).map_err(|e| {
        let prefix = format!("{}:", path.display());
        e.to_string().replace(&prefix, &format!("{name}:"))
    })
}

/// Workbooks written by `tests/data/external/make_sap2000_xlsx.py --malformed` (openpyxl,
/// the layout of SAP2000's "Export to Excel"): the joints and links of three steps.
const SMALL_XLSX: &[u8] = include_bytes!("../../testdata/xlsx/small.xlsx");
const NO_UNITS_XLSX: &[u8] = include_bytes!("../../testdata/xlsx/no-units-row.xlsx");
const TEXT_IN_NUMBER_XLSX: &[u8] = include_bytes!("../../testdata/xlsx/text-in-number.xlsx");
const NO_LINK_SHEET_XLSX: &[u8] = include_bytes!("../../testdata/xlsx/no-link-sheet.xlsx");

/// The small workbook's tables as the TXT export writes them.
const SMALL_TXT: &str = "TABLE:  \"Joint Displacements\"\n\
Joint\tOutputCase\tCaseType\tStepType\tStepNum\tU1\tU2\tU3\n\
Text\tText\tText\tText\tSec\tm\tm\tm\n\
1\tTH\tNonDirHist\tTime\t0\t0\t0\t0\n\
2\tTH\tNonDirHist\tTime\t0\t0\t0\t0\n\
1\tTH\tNonDirHist\tTime\t0.005\t0\t0\t0\n\
2\tTH\tNonDirHist\tTime\t0.005\t0.0003267\t0\t0\n\
1\tTH\tNonDirHist\tTime\t0.01\t0\t0\t0\n\
2\tTH\tNonDirHist\tTime\t0.01\t0.0012\t0\t0\n\
TABLE:  \"Element Forces - Links\"\n\
Link\tLinkElem\tOutputCase\tCaseType\tStepType\tStepNum\tP\tV2\n\
Text\tText\tText\tText\tText\tSec\tKN\tKN\n\
1\t1\tTH\tNonDirHist\tTime\t0\t-1000\t0\n\
1\t1\tTH\tNonDirHist\tTime\t0.005\t-1000\t1.652\n\
1\t1\tTH\tNonDirHist\tTime\t0.01\t-1000\t3.1\n";

#[test]
fn a_sap2000_workbook_reads_like_its_text_export() {
    let t = read_file_bytes("small.xlsx", SMALL_XLSX, &sap_format()).unwrap();
    assert_eq!(t.trace.time, [0.0, 0.005, 0.01]);
    assert_eq!(
        t.trace.column("rel_disp").unwrap(),
        [0.0, 0.0003267, 0.0012]
    );
    assert_eq!(t.trace.column("normal").unwrap(), [1e6, 1e6, 1e6]);
    let kn = |x: f64| x * 1000.0;
    assert_eq!(
        t.trace.column("resistance").unwrap(),
        [0.0, kn(1.652), kn(3.1)]
    );
    // the same tables as text: the same trace, the same notes but the layout's name
    let text = read("small.txt", SMALL_TXT, &sap_format()).unwrap();
    assert_eq!(t.trace, text.trace);
    assert_eq!(
        t.notes[0],
        "SAP2000/ETABS/CSiBridge tables exported to Excel, 3 rows"
    );
    assert_eq!(t.notes[1..], text.notes[1..]);
    // recognised by its extension without `format`, in any case of its letters
    let mut f = sap_format();
    f.layout = None;
    assert_eq!(
        read_file_bytes("SMALL.XLSX", SMALL_XLSX, &f).unwrap().trace,
        t.trace
    );
}

#[test]
fn malformed_sap2000_workbooks_are_located_at_their_sheet_and_cell() {
    let f = sap_format();
    let e = |name: &str, bytes: &[u8]| read_file_bytes(name, bytes, &f).unwrap_err();
    assert_eq!(
        e("no-units.xlsx", NO_UNITS_XLSX),
        "no-units.xlsx:3:1: sheet \"Joint Displacements\", cell A3: table \"Joint \
         Displacements\": the row below the field names is not the units row (`Text, Text, \
         …, Sec, m, …`), which an export writes there"
    );
    assert_eq!(
        e("text.xlsx", TEXT_IN_NUMBER_XLSX),
        "text.xlsx:5:8: sheet \"Element Forces - Links\", cell H5: table \"Element Forces - \
         Links\", field \"V2\": \"1.652 kN\" is not a number"
    );
    assert_eq!(
        e("joints.xlsx", NO_LINK_SHEET_XLSX),
        "joints.xlsx: the column map names \"Link 1: P\", \"Link 1: V2\", but no sheet of the \
         workbook has such a series (export the table that holds it); its sheets: \"Joint \
         Displacements\""
    );
    assert!(
        e("text.xlsx", SAP.as_bytes())
            .starts_with("text.xlsx: is not a readable XLSX workbook: not a zip archive"),
    );
    let mut dead = sap_format();
    dead.output_case = Some("DEAD".into());
    assert_eq!(
        read_file_bytes("small.xlsx", SMALL_XLSX, &dead).unwrap_err(),
        "small.xlsx: has no rows of OutputCase \"DEAD\"; its output cases: TH"
    );
    // cut short: an error, never a panic
    let half = &SMALL_XLSX[..SMALL_XLSX.len() / 2];
    assert!(e("half.xlsx", half).starts_with("half.xlsx: is not a readable XLSX workbook"));
    let ansys = format(ExternalLayout::AnsysPrvar, &[("UX_2", "rel_disp [m]", 1.0)]);
    assert_eq!(
        read_file_bytes("small.xlsx", SMALL_XLSX, &ansys).unwrap_err(),
        "small.xlsx: format: is an Excel workbook: rockslide reads SAP2000/ETABS/CSiBridge \
         tables exported to Excel (`format = \"sap2000\"`, or no format); save another \
         program's results as the text file it writes"
    );
}

#[test]
fn a_workbook_that_unpacks_beyond_the_limit_is_refused_before_it_is_read() {
    // a zip whose one part inflates to 1 GiB + 1 byte of zeros, in 1 MiB of deflate
    let mut zip = Vec::new();
    {
        let mut w = zip::ZipWriter::new(std::io::Cursor::new(&mut zip));
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated)
            .large_file(true);
        w.start_file("xl/sharedStrings.xml", options).unwrap();
        let block = vec![0u8; 1 << 20];
        for _ in 0..(super::MAX_EXTERNAL_BYTES >> 20) {
            std::io::Write::write_all(&mut w, &block).unwrap();
        }
        std::io::Write::write_all(&mut w, &[0]).unwrap();
        w.finish().unwrap();
    }
    let why = read_file_bytes("bomb.xlsx", &zip, &sap_format()).unwrap_err();
    assert_eq!(
        why,
        "bomb.xlsx: is not a readable XLSX workbook: unpacks to more than 256 MiB"
    );
}

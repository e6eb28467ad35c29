//! A record's problems located twice: at the case file's field that names the record
//! (line and column of `excitation.record`, `excitation.y.record`,
//! `excitation.vertical.record`), then inside the record (its own line and column).
//! Requirements checked (the located errors of `cases/README.md`):
//! - rockslide shall report a missing or broken record as
//!   `case:line:col: field: record[:line[:col]]: reason`, exit with code 2 and write nothing;
//! - rockslide shall read a PEER `.AT2` file as the database delivers it and as editors
//!   and mail leave it — byte-order mark, CRLF, trailing spaces, no final newline, tabs,
//!   lowercase `npts=`/`dt=` — to the same samples as the plain file;
//! - rockslide shall refuse a record of 0 points, a NaN or 1e400 value, a DT of 0, negative
//!   or infinite, and NPTS = 10¹² (before allocating), each at the line and column of the
//!   offending value.
//!
//! Expected messages are written out in full: the case's line and column are counted in
//! the case texts below, the record's in the record texts.

use std::path::{Path, PathBuf};

use rockslide::case::parse_case;
use rockslide::case::record::{STANDARD_GRAVITY, parse_at2, read_record};

use crate::common::{repo, rockslide};

/// An oscillator driven by `x.AT2`: `record = "x.AT2"` is line 12, its value at column 10.
const CASE_X: &str = "title = \"t\"\n[model]\nkind = \"oscillator\"\nmass = 1.0e6\n\
gravity = 1.0\n[model.contact]\nkx = 9.8696e8\nkz = 3.94784e9\nmu = 0.5\n[excitation]\n\
kind = \"ground-acceleration\"\nrecord = \"x.AT2\"\n";

/// The second horizontal component: `record = "y.AT2"` on line 14, column 10.
const SECTION_Y: &str = "[excitation.y]\nrecord = \"y.AT2\"\n";

/// The vertical component: `record = "v.AT2"` on line 14, column 10.
const SECTION_V: &str =
    "[excitation.vertical]\nrecord = \"v.AT2\"\nnormal_force = \"quasi-static\"\n";

const RUN: &str = "[run]\nduration = 0.05\ndt = 0.005\n";

/// The four PEER header lines before NPTS and DT.
const HEAD: &str = "PEER NGA STRONG MOTION DATABASE RECORD\nTEST, 1/1/2000, STATION, 90\n\
ACCELERATION TIME SERIES IN UNITS OF G\n";

/// A good record: NPTS (line 4) at column 8, DT at column 17; values on lines 5 and 6, the
/// first at column 3.
fn good_at2() -> String {
    format!("{HEAD}NPTS=  4, DT=   0.005 SEC\n  1.0E-02  2.0E-02 -1.0E-02\n  0.0E+00\n")
}

/// A folder holding `c.toml` (`case`) and the `records`; the case's path.
fn folder(case: &str, records: &[(&str, &str)]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let case_path = dir.path().join("c.toml");
    std::fs::write(&case_path, case).unwrap();
    for (name, text) in records {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    (dir, case_path)
}

/// `rockslide run` on the case: asserts exit code 2, one `error:` line per problem and
/// nothing written (no output folder, no new file beside the case); the error lines.
fn run_refused(dir: &Path, case_path: &Path) -> Vec<String> {
    let before = files(dir);
    let out = dir.join("out");
    let o = rockslide(&[
        "run",
        case_path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(!out.exists(), "nothing written: {stderr}");
    assert_eq!(files(dir), before, "no file beside the case");
    stderr
        .lines()
        .map(|l| {
            l.strip_prefix("error: ")
                .unwrap_or_else(|| panic!("not an error line: {l}"))
                .to_string()
        })
        .collect()
}

fn files(dir: &Path) -> Vec<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    found.sort();
    found
}

/// The message of a missing file, as the operating system words it.
fn not_found(path: &Path) -> String {
    rockslide::error::io_reason(&std::fs::metadata(path).unwrap_err())
}

#[test]
fn a_missing_record_is_located_at_the_case_field_and_names_the_record() {
    let (dir, case_path) = folder(&format!("{CASE_X}{RUN}"), &[]);
    let record = dir.path().join("x.AT2");
    assert_eq!(
        run_refused(dir.path(), &case_path),
        vec![format!(
            "{}:12:10: excitation.record: {}: cannot read the record: {}",
            case_path.display(),
            record.display(),
            not_found(&record)
        )]
    );
    assert!(!not_found(&record).contains("os error"));
}

#[test]
fn a_broken_header_of_the_second_component_is_located_in_both_files() {
    let broken = format!("{HEAD}NPTS=  4, DT=   SEC\n  1.0E-02  2.0E-02 -1.0E-02\n  0.0E+00\n");
    let (dir, case_path) = folder(
        &format!("{CASE_X}{SECTION_Y}{RUN}"),
        &[("x.AT2", &good_at2()), ("y.AT2", &broken)],
    );
    assert_eq!(
        run_refused(dir.path(), &case_path),
        vec![format!(
            "{}:14:10: excitation.y.record: {}:4: cannot read NPTS and DT from \"NPTS=  4, DT=   SEC\" (expected e.g. \"NPTS=  3930, DT= .00500 SEC\")",
            case_path.display(),
            dir.path().join("y.AT2").display(),
        )]
    );
}

#[test]
fn a_value_of_the_vertical_component_that_is_not_a_number_is_located_in_both_files() {
    // "1.0E-O2": the letter O for a zero, as retyped records have it.
    let typo = good_at2().replace("1.0E-02", "1.0E-O2");
    let (dir, case_path) = folder(
        &format!("{CASE_X}{SECTION_V}{RUN}"),
        &[("x.AT2", &good_at2()), ("v.AT2", &typo)],
    );
    assert_eq!(
        run_refused(dir.path(), &case_path),
        vec![format!(
            "{}:14:10: excitation.vertical.record: {}:5:3: \"1.0E-O2\" is not a number",
            case_path.display(),
            dir.path().join("v.AT2").display(),
        )]
    );
}

#[test]
fn an_npts_that_disagrees_with_the_values_is_located_at_npts() {
    let (dir, case_path) = folder(
        &format!("{CASE_X}{RUN}"),
        &[("x.AT2", &good_at2().replace("NPTS=  4", "NPTS=  5"))],
    );
    assert_eq!(
        run_refused(dir.path(), &case_path),
        vec![format!(
            "{}:12:10: excitation.record: {}:4:8: NPTS = 5, but the file has 4 values (the last on line 6)",
            case_path.display(),
            dir.path().join("x.AT2").display(),
        )]
    );
}

#[test]
fn every_component_s_problem_is_reported_together() {
    // x missing, y with a value too many: both lines, in the case's order.
    let extra = good_at2().replace("  0.0E+00\n", "  0.0E+00  3.0E-02\n");
    let (dir, case_path) = folder(&format!("{CASE_X}{SECTION_Y}{RUN}"), &[("y.AT2", &extra)]);
    let x = dir.path().join("x.AT2");
    assert_eq!(
        run_refused(dir.path(), &case_path),
        vec![
            format!(
                "{}:12:10: excitation.record: {}: cannot read the record: {}",
                case_path.display(),
                x.display(),
                not_found(&x)
            ),
            format!(
                "{}:14:10: excitation.y.record: {}:6:12: more values than NPTS = 4 (line 4): value 5 is here",
                case_path.display(),
                dir.path().join("y.AT2").display(),
            ),
        ]
    );
}

#[test]
fn a_record_of_zeros_is_refused_at_the_case_field_naming_the_record() {
    let zeros = good_at2()
        .replace("1.0E-02", "0.0E+00")
        .replace("2.0E-02", "0.0E+00");
    let (dir, case_path) = folder(&format!("{CASE_X}{RUN}"), &[("x.AT2", &zeros)]);
    let e = parse_case(&case_path, &format!("{CASE_X}{RUN}")).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "{}:12:10: excitation.record: {}: every sample is zero: nothing moves the ground",
            case_path.display(),
            dir.path().join("x.AT2").display(),
        )
    );
}

// ── a PEER record straight from the database ────────────────────────────────────────

/// The Chino Hills 090° record as shipped (PEER NGA-West2 RSN8883): NPTS = 16396,
/// DT = 0.005 s, first value 8.6900441E-08 g, the last line one value and trailing spaces.
fn chino_hills() -> String {
    std::fs::read_to_string(repo(
        "cases/records/Chino_Hills_2008_RSN8883_Anaheim-Lakeview-Riverdale_090.AT2",
    ))
    .unwrap()
}

/// A change a file suffers on its way to the user (an editor, a mail client, a platform).
type Dressing = fn(&str) -> String;

/// Each data line's runs of spaces as one tab (the header lines kept).
fn tabs_between_values(text: &str) -> String {
    text.lines()
        .enumerate()
        .map(|(i, l)| {
            if i < 4 {
                l.to_string()
            } else {
                l.split_whitespace().collect::<Vec<_>>().join("\t")
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
        + "\n"
}

#[test]
fn a_peer_record_as_delivered_and_as_editors_leave_it_reads_the_same_samples() {
    let plain_text = chino_hills();
    let plain = parse_at2(Path::new("x.AT2"), &plain_text, None).unwrap();
    assert_eq!(plain.samples.len(), 16396);
    assert_eq!(plain.dt, 0.005);
    assert_eq!(plain.samples[0], 8.6900441E-08 * STANDARD_GRAVITY);
    assert_eq!(plain.samples[16395], 2.3375500E-05 * STANDARD_GRAVITY);
    // In the order they are composed below (tabs rebuild the lines, so they come first).
    let dressings: [(&str, Dressing); 6] = [
        ("tabs", tabs_between_values),
        ("lowercase npts= dt=", |t| {
            t.replace(
                "NPTS=  16396, DT=   0.005 SEC",
                "npts=  16396, dt=   0.005 sec",
            )
        }),
        ("trailing spaces", |t| t.replace('\n', "   \n")),
        ("CRLF", |t| t.replace('\n', "\r\n")),
        ("no final newline", |t| t.trim_end().to_string()),
        ("byte-order mark", |t| format!("\u{feff}{t}")),
    ];
    let mut all = plain_text.clone();
    for (name, dress) in dressings {
        let text = dress(&plain_text);
        assert_ne!(text, plain_text, "{name} changes the text");
        let r =
            parse_at2(Path::new("x.AT2"), &text, None).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((r.dt, &r.samples), (plain.dt, &plain.samples), "{name}");
        all = dress(&all);
    }
    // All at once, read from a file through a case (the reader strips the mark itself).
    let case = CASE_X.replace("x.AT2", "chino.AT2");
    let (_dir, case_path) = folder(&case, &[("chino.AT2", &all)]);
    assert!(
        all.starts_with("\u{feff}PEER")
            && all.contains("dt=   0.005 sec")
            && all.contains("   \r\n")
            && all.contains('\t')
    );
    assert!(all.ends_with("2.3375500E-05"));
    let from_file = read_record(&case_path.with_file_name("chino.AT2"), None).unwrap();
    assert_eq!(from_file.samples, plain.samples);
    let loaded = parse_case(&case_path, &format!("{case}{RUN}")).unwrap();
    let s = loaded.scene.excitation.signal().unwrap();
    assert_eq!(s.peak(), plain.pga());
}

/// A record refused: (what, record text, the record's `line:col: reason` as expected).
fn refused_records() -> Vec<(&'static str, String, String)> {
    let npts_12 = format!(
        "{HEAD}NPTS=  1000000000000, DT=   0.005 SEC\n  1.0E-02  2.0E-02 -1.0E-02\n  0.0E+00\n"
    );
    let room = npts_12.len().div_ceil(2);
    vec![
        (
            "0 points",
            good_at2().replace("NPTS=  4", "NPTS=  0"),
            "4:8: NPTS is 0, but must be a whole number of at least 1".into(),
        ),
        (
            "0 points and no values",
            format!("{HEAD}NPTS=  0, DT=   0.005 SEC\n"),
            "4:8: NPTS is 0, but must be a whole number of at least 1".into(),
        ),
        (
            "NaN",
            good_at2().replace("1.0E-02", "NaN"),
            "5:3: value \"NaN\" is NaN: every sample must be a finite number".into(),
        ),
        (
            "1e400",
            good_at2().replace("2.0E-02", "1e400"),
            "5:12: value \"1e400\" is inf: every sample must be a finite number".into(),
        ),
        (
            "DT of 0",
            good_at2().replace("0.005 SEC", "0 SEC"),
            "4:17: DT is 0 s, but must be a positive finite number".into(),
        ),
        (
            "negative DT",
            good_at2().replace("0.005 SEC", "-0.005 SEC"),
            "4:17: DT is -0.005 s, but must be a positive finite number".into(),
        ),
        (
            "DT of 1e400",
            good_at2().replace("0.005 SEC", "1e400 SEC"),
            "4:17: DT is inf s, but must be a positive finite number".into(),
        ),
        (
            "NPTS = 10¹²",
            npts_12.clone(),
            format!(
                "4:8: NPTS = 1000000000000, but the file ({} bytes) cannot hold more than {room} values",
                npts_12.len()
            ),
        ),
        (
            "old Mac line ends (CR only)",
            good_at2().replace('\n', "\r"),
            "1: the PEER header has four lines (title; event, station; units; NPTS and DT), but the file has only 1".into(),
        ),
    ]
}

#[test]
fn records_of_no_points_non_finite_values_or_steps_and_huge_npts_are_refused_where_they_are() {
    for (what, text, expected) in refused_records() {
        let (dir, case_path) = folder(&format!("{CASE_X}{RUN}"), &[("x.AT2", &text)]);
        let e = parse_case(&case_path, &format!("{CASE_X}{RUN}"))
            .err()
            .unwrap_or_else(|| panic!("{what}: accepted"));
        assert_eq!(
            e.to_string(),
            format!(
                "{}:12:10: excitation.record: {}:{expected}",
                case_path.display(),
                dir.path().join("x.AT2").display()
            ),
            "{what}"
        );
    }
}

#[test]
fn npts_of_ten_to_the_twelve_exits_with_2_not_an_allocation_failure() {
    let (_, text, expected) = refused_records()
        .into_iter()
        .find(|(what, ..)| *what == "NPTS = 10¹²")
        .unwrap();
    let (dir, case_path) = folder(&format!("{CASE_X}{RUN}"), &[("x.AT2", &text)]);
    assert_eq!(
        run_refused(dir.path(), &case_path),
        vec![format!(
            "{}:12:10: excitation.record: {}:{expected}",
            case_path.display(),
            dir.path().join("x.AT2").display()
        )]
    );
}

#[test]
fn a_study_grid_s_records_are_located_at_their_list_item_and_inside_the_record() {
    // `records = [` is 11 characters: the items' values start at columns 12, 21 and 36.
    let grid = "base = \"c.toml\"\n\
                records = [\"x.AT2\", \"missing.AT2\", { path = \"bad.AT2\", unit = \"g\" }]\n";
    let bad = good_at2().replace("-1.0E-02", "-1.0E-02,x");
    let (dir, case_path) = folder(
        &format!("{CASE_X}{RUN}"),
        &[
            ("x.AT2", &good_at2()),
            ("bad.AT2", &bad),
            ("grid.toml", grid),
        ],
    );
    let grid_path = case_path.with_file_name("grid.toml");
    let missing = dir.path().join("missing.AT2");
    let e = rockslide::study::load_grid(&grid_path).unwrap_err();
    let lines: Vec<String> = e.0.iter().map(|e| e.to_string()).collect();
    assert_eq!(
        lines,
        vec![
            format!(
                "{}:2:21: records[1]: {}: cannot read the record: {}",
                grid_path.display(),
                missing.display(),
                not_found(&missing)
            ),
            format!(
                "{}:2:36: records[2]: {}:5:29: \"x\" is not a number",
                grid_path.display(),
                dir.path().join("bad.AT2").display()
            ),
        ]
    );
}

//! Recorded ground motions as input. Requirements checked:
//! - rockslide shall read PEER NGA `.AT2` files (NPTS and DT from the fourth header line,
//!   values in g) and two-column CSV with a stated unit;
//! - rockslide shall reject every malformed record (wrong NPTS, non-numeric values, NaN,
//!   non-increasing time, no samples) with a message naming the file and the line;
//! - scaling to a stated PGA shall be exact.
//!
//! Source of the shipped records: cases/records/SOURCES.md.

use std::path::{Path, PathBuf};

use rockslide::case::record::{AccelUnit, STANDARD_GRAVITY, parse_at2, parse_csv, read_record};
use rockslide::case::{Excitation, Signal, load_case, parse_case};

fn records_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/records")
}

const AT2_HEAD: &str = "PEER TEST\nEVENT, STATION, 000\nACCELERATION TIME HISTORY IN UNITS OF G\n";

#[test]
fn shipped_at2_header_npts_and_dt() {
    let path = records_dir().join("Loma_Prieta_1989_HSP-000.AT2");
    let r = read_record(&path, None).unwrap();
    // Header line 4: "NPTS= 11177, DT= 0.0050 SEC"; first value −4.5853000E-05 g,
    // last −2.5590800E-04 g (read off the file).
    assert_eq!(r.samples.len(), 11177);
    assert_eq!(r.dt, 0.005);
    assert_eq!(r.unit, AccelUnit::G);
    assert_eq!(r.samples[0], -4.5853000E-05 * STANDARD_GRAVITY);
    assert_eq!(r.samples[11176], -2.5590800E-04 * STANDARD_GRAVITY);
    assert!(r.description.starts_with("LOMA PRIETA"));
    // PGA 0.37054 g per SOURCES/the file's largest |value|.
    assert!((r.pga() / STANDARD_GRAVITY - 0.37054).abs() < 1e-12);
}

#[test]
fn shipped_csv_records_are_uniform() {
    let r = read_record(
        &records_dir().join("Imperial_Valley_1979_BCR-230.csv"),
        Some(AccelUnit::G),
    )
    .unwrap();
    assert_eq!(r.samples.len(), 7348);
    assert!((r.dt - 0.005).abs() < 1e-15, "dt = {}", r.dt);
    assert!(r.note.is_empty(), "no resampling: {}", r.note);
    assert!((r.pga() / STANDARD_GRAVITY - 0.774767).abs() < 1e-12);
    let r = read_record(
        &records_dir().join("Northridge_1994_PAC-175.csv"),
        Some(AccelUnit::G),
    )
    .unwrap();
    assert_eq!(r.samples.len(), 1000);
    assert!((r.dt - 0.02).abs() < 1e-15);
}

#[test]
fn at2_fourth_line_older_layout_and_values_per_line() {
    let text = format!("{AT2_HEAD}  7   .0100   NPTS, DT\n 1 2 3\n4 5\n6 7\n");
    let r = parse_at2(Path::new("x.AT2"), &text, None).unwrap();
    assert_eq!(r.samples.len(), 7);
    assert_eq!(r.dt, 0.01);
    assert_eq!(r.samples[6], 7.0 * STANDARD_GRAVITY);
}

/// (text, expected line, words the message must contain)
fn assert_at2_error(text: &str, line: usize, words: &[&str]) {
    let e = parse_at2(Path::new("bad.AT2"), text, None).unwrap_err();
    assert_eq!(e.line, Some(line), "{e}");
    let msg = e.to_string();
    assert!(msg.starts_with(&format!("bad.AT2:{line}")), "{msg}");
    for w in words {
        assert!(msg.contains(w), "\"{msg}\" should mention \"{w}\"");
    }
}

#[test]
fn at2_wrong_npts_too_few() {
    let text = format!("{AT2_HEAD}NPTS=  6, DT= .0100 SEC\n1 2 3\n4 5\n");
    assert_at2_error(&text, 4, &["NPTS = 6", "5 values", "line 6"]);
}

#[test]
fn at2_wrong_npts_too_many() {
    let text = format!("{AT2_HEAD}NPTS=  4, DT= .0100 SEC\n1 2 3\n4 5\n");
    let e = parse_at2(Path::new("bad.AT2"), &text, None).unwrap_err();
    assert_eq!((e.line, e.column), (Some(6), Some(3)), "{e}");
    assert!(e.reason.contains("more values than NPTS = 4"), "{e}");
}

#[test]
fn at2_non_numeric_value() {
    let text = format!("{AT2_HEAD}NPTS=  4, DT= .0100 SEC\n1 2\n3 x4\n");
    let e = parse_at2(Path::new("bad.AT2"), &text, None).unwrap_err();
    assert_eq!((e.line, e.column), (Some(6), Some(3)), "{e}");
    assert!(e.reason.contains("\"x4\" is not a number"), "{e}");
}

#[test]
fn at2_nan_value() {
    let text = format!("{AT2_HEAD}NPTS=  4, DT= .0100 SEC\n1 2\nNaN 4\n");
    assert_at2_error(&text, 6, &["NaN", "finite"]);
}

#[test]
fn at2_unreadable_fourth_line() {
    let text = format!("{AT2_HEAD}POINTS 4 STEP .01\n1 2 3 4\n");
    assert_at2_error(&text, 4, &["cannot read NPTS and DT"]);
}

#[test]
fn at2_empty_file_and_no_values() {
    assert_at2_error("", 1, &["empty"]);
    let text = format!("{AT2_HEAD}NPTS=  4, DT= .0100 SEC\n");
    assert_at2_error(&text, 4, &["no values"]);
}

#[test]
fn at2_unit_disagreeing_with_the_case() {
    let text = format!("{AT2_HEAD}NPTS=  1, DT= .0100 SEC\n1\n");
    let e = parse_at2(
        Path::new("bad.AT2"),
        &text,
        Some(AccelUnit::CentimetrePerSecond2),
    )
    .unwrap_err();
    assert_eq!(e.line, Some(3));
    assert!(e.reason.contains("header says"), "{e}");
}

fn csv_error(text: &str) -> rockslide::error::InputError {
    parse_csv(Path::new("bad.csv"), text, AccelUnit::G).unwrap_err()
}

#[test]
fn csv_non_increasing_time() {
    let e = csv_error("# comment\ntime,acc\n0.0,0.1\n0.01,0.2\n0.01,0.3\n");
    assert_eq!((e.line, e.column), (Some(5), Some(1)), "{e}");
    assert!(e.reason.contains("not after the previous"), "{e}");
    assert!(e.to_string().starts_with("bad.csv:5:1"), "{e}");
    let e = csv_error("0.0,0.1\n0.02,0.2\n0.01,0.3\n");
    assert_eq!(e.line, Some(3), "{e}");
}

#[test]
fn csv_non_numeric_and_nan() {
    let e = csv_error("0.0,0.1\n0.01,abc\n");
    assert_eq!((e.line, e.column), (Some(2), Some(6)), "{e}");
    assert!(e.reason.contains("\"abc\" is not a number"), "{e}");
    let e = csv_error("0.0,0.1\n0.01,nan\n");
    assert_eq!(e.line, Some(2), "{e}");
    assert!(e.reason.contains("finite"), "{e}");
    let e = csv_error("0.0,0.1\n0.01,inf\n");
    assert!(e.reason.contains("finite"), "{e}");
}

#[test]
fn csv_wrong_column_count_and_empty() {
    let e = csv_error("0.0,0.1\n0.01,0.2,0.3\n");
    assert_eq!(e.line, Some(2));
    assert!(e.reason.contains("expected 2 columns"), "{e}");
    let e = csv_error("# only comments\n\n");
    assert!(e.reason.contains("no samples"), "{e}");
    let e = csv_error("");
    assert!(e.reason.contains("no samples"), "{e}");
    assert_eq!(e.line, Some(1));
}

#[test]
fn csv_non_uniform_time_is_resampled_and_said() {
    // Samples of a = t (g) at uneven times: linear data, so resampling is exact.
    let r = parse_csv(
        Path::new("u.csv"),
        "0.0,0.0\n0.01,0.01\n0.03,0.03\n0.04,0.04\n",
        AccelUnit::MetrePerSecond2,
    )
    .unwrap();
    assert!(r.note.contains("resampled"), "{}", r.note);
    assert_eq!(r.samples.len(), 5);
    assert!((r.dt - 0.01).abs() < 1e-15);
    for (i, a) in r.samples.iter().enumerate() {
        assert!((a - 0.01 * i as f64).abs() < 1e-15, "{i}: {a}");
    }
}

fn case_text(record: &str, extra: &str) -> String {
    format!(
        "title = \"t\"\n[model]\nkind = \"oscillator\"\nmass = 1.0e6\ngravity = 1.0\n\
         [model.contact]\nkx = 9.8696e8\nkz = 3.94784e9\nmu = 0.5\n\
         [excitation]\nkind = \"ground-acceleration\"\nrecord = \"{record}\"\n{extra}\n\
         [run]\nduration = 1.0\ndt = 0.005\n"
    )
}

#[test]
fn pga_scaling_is_exact_and_polarity_inverts() {
    let case_path = records_dir().join("virtual.toml");
    for (pga_g, polarity) in [(0.1, 1.0), (0.25, -1.0), (1e-4, 1.0)] {
        let pga = pga_g * STANDARD_GRAVITY;
        let text = case_text(
            "Imperial_Valley_1979_BCR-230.csv",
            &format!("record_unit = \"g\"\nscale_to_pga_g = {pga_g}\npolarity = {polarity}"),
        );
        let case = parse_case(&case_path, &text).unwrap();
        let Excitation::GroundAcceleration(s) = &case.scene.excitation else {
            panic!("ground acceleration expected")
        };
        assert_eq!(
            s.peak(),
            pga,
            "peak equals the stated PGA (g × 9.80665) bit for bit"
        );
        let Signal::Record { samples, .. } = s else {
            panic!()
        };
        // The record's peak is +0.774767 g or −0.774767 g: find its sign after scaling.
        let raw = read_record(
            &records_dir().join("Imperial_Valley_1979_BCR-230.csv"),
            Some(AccelUnit::G),
        )
        .unwrap();
        let i = raw
            .samples
            .iter()
            .position(|a| a.abs() == raw.pga())
            .unwrap();
        assert_eq!(samples[i], polarity * raw.samples[i].signum() * pga);
    }
}

#[test]
fn case_errors_name_the_record_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("r.csv"), "0.0,0.1\n0.01,0.2\n0.01,0.3\n").unwrap();
    let case_path = dir.path().join("c.toml");
    let e = parse_case(&case_path, &case_text("r.csv", "record_unit = \"g\"")).unwrap_err();
    let msg = e.to_string();
    // At the case's `record` (line 12, column 10), then in the record (line 3, column 1).
    let record = dir.path().join("r.csv");
    let want = format!(
        "{}:12:10: excitation.record: {}:3:1: time 0.01 s is not after",
        case_path.display(),
        record.display()
    );
    assert!(msg.starts_with(&want), "{msg}");
    // No unit for a CSV: the message says so.
    let e = parse_case(&case_path, &case_text("r.csv", "")).unwrap_err();
    assert!(e.to_string().contains("record_unit"), "{e}");
    // A missing file.
    let e = parse_case(&case_path, &case_text("nope.AT2", "")).unwrap_err();
    assert!(e.to_string().contains("nope.AT2"), "{e}");
    // Bad unit name and polarity are located in the case file.
    std::fs::write(dir.path().join("ok.csv"), "0.0,0.1\n0.01,0.2\n").unwrap();
    let e = parse_case(
        &case_path,
        &case_text("ok.csv", "record_unit = \"furlong\"\npolarity = 2"),
    )
    .unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("excitation.record_unit: is \"furlong\""),
        "{msg}"
    );
    let e = parse_case(
        &case_path,
        &case_text("ok.csv", "record_unit = \"g\"\npolarity = 2"),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("excitation.polarity: is 2, but must be 1"),
        "{e}"
    );
    assert!(e.contains("c.toml:14:12:"), "located in the case file: {e}");
    // A record is an acceleration: not a ground displacement.
    let text = case_text("ok.csv", "record_unit = \"g\"").replace(
        "kind = \"ground-acceleration\"",
        "kind = \"ground-displacement\"",
    );
    let e = parse_case(&case_path, &text).unwrap_err().to_string();
    assert!(
        e.contains("excitation.kind: a record is an acceleration history"),
        "{e}"
    );
    // Sine-pulse fields alongside a record are rejected.
    let e = parse_case(
        &case_path,
        &case_text("ok.csv", "record_unit = \"g\"\namplitude = 1.0"),
    )
    .unwrap_err();
    assert!(e.to_string().contains("excitation.amplitude"), "{e}");
}

#[test]
fn shipped_record_cases_load() {
    for name in [
        "pepo-loma-prieta.toml",
        "pepo-imperial-valley.toml",
        "pepo-northridge.toml",
        "rpepo-loma-prieta.toml",
    ] {
        let case = load_case(&records_dir().join(name)).unwrap();
        let s = case.scene.excitation.signal().unwrap();
        let pga = if name.starts_with("rpepo") {
            2.941995
        } else {
            0.980665
        };
        assert_eq!(s.peak(), pga, "{name}");
        assert!(
            case.run.duration > s.end(),
            "{name}: runs past the record's end"
        );
    }
}

/// Baseline handling (record/integrate.rs `integrate`): the cubic correction keeps the corrected
/// acceleration, velocity and displacement exact integrals of each other (re-integrating
/// the corrected acceleration reproduces them to < 1e-12), keeps the start at rest, leaves
/// a displacement orthogonal to t² and t³ (the least-squares conditions), and reduces the
/// end drift of this (already processed) record from 13.97 mm to 4.44 mm (measured).
#[test]
fn baseline_correction_is_consistent_and_removes_drift() {
    use rockslide::case::record::{Baseline, integrate};
    let rec = read_record(&records_dir().join("Loma_Prieta_1989_HSP-000.AT2"), None).unwrap();
    let raw = integrate(rec.dt, &rec.samples, Baseline::None);
    let cor = integrate(rec.dt, &rec.samples, Baseline::Cubic);
    let again = integrate(rec.dt, &cor.acc, Baseline::None);
    let dv = cor
        .vel
        .iter()
        .zip(&again.vel)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    let dd = cor
        .disp
        .iter()
        .zip(&again.disp)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(dv < 1e-12 && dd < 1e-12, "{dv} {dd}");
    assert_eq!((cor.vel[0], cor.disp[0]), (0.0, 0.0));
    let end = |d: &[f64]| d.last().unwrap().abs();
    assert!(
        (end(&raw.disp) - 0.013974).abs() < 1e-6,
        "{}",
        end(&raw.disp)
    );
    assert!(
        (end(&cor.disp) - 0.004443).abs() < 1e-6,
        "{}",
        end(&cor.disp)
    );
    for k in [2, 3] {
        let (mut dot, mut norm) = (0.0, 0.0);
        for (i, d) in cor.disp.iter().enumerate() {
            let tk = (i as f64 * rec.dt).powi(k);
            dot += tk * d;
            norm += tk * d.abs();
        }
        assert!(dot.abs() < 1e-9 * norm, "t^{k}: {dot} vs {norm}");
    }
}

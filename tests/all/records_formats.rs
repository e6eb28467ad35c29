//! Records read as engineers receive them, and records that must not exhaust resources.
//! Requirements checked:
//! - a UTF-8 byte-order mark, CRLF line ends, tab or semicolon separators, trailing
//!   separators and blank fields, and Fortran `D` exponents are read as the values they
//!   write (the PEER AT2 as downloaded starts with a BOM on some systems);
//! - an AT2 header whose NPTS the file cannot hold (1e19, 1e12), a DT of 1e-300 s, a device
//!   such as /dev/zero and a file that is not UTF-8 are refused with a located error, before
//!   anything large is allocated.

use std::path::Path;

use rockslide::case::record::{AccelUnit, STANDARD_GRAVITY, parse_at2, parse_csv, read_record};

const AT2_HEAD: &str = "PEER TEST\nEVENT, STATION, 000\nACCELERATION TIME HISTORY IN UNITS OF G\n";

fn shipped_at2() -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/records/Loma_Prieta_1989_HSP-000.AT2"),
    )
    .unwrap()
}

#[test]
fn at2_with_bom_and_crlf_reads_as_the_plain_file() {
    let plain = parse_at2(Path::new("x.AT2"), &shipped_at2(), None).unwrap();
    let dressed = format!("\u{feff}{}", shipped_at2().replace('\n', "\r\n"));
    let r = parse_at2(Path::new("x.AT2"), &dressed, None).unwrap();
    assert_eq!(r.samples, plain.samples);
    assert_eq!(r.dt, plain.dt);
}

#[test]
fn csv_with_bom_crlf_tabs_semicolons_trailing_separators_and_d_exponents() {
    let text = "\u{feff}# a record\r\ntime;acc\r\n0;\t0.1D0;\r\n0.01\t-2.5d-1,,\r\n0.02 ;0.3E0\r\n";
    let r = parse_csv(Path::new("x.csv"), text, AccelUnit::G).unwrap();
    let expect = [0.1, -0.25, 0.3].map(|g| g * STANDARD_GRAVITY);
    assert_eq!(r.samples, expect);
    assert_eq!(r.dt, 0.01);
    assert_eq!(r.description, "a record");
}

#[test]
fn at2_npts_the_file_cannot_hold_is_refused_before_allocating() {
    for npts in ["1e19", "1e12", "1000000000000"] {
        let text = format!("{AT2_HEAD}NPTS= {npts}, DT= .0100 SEC\n1 2 3\n");
        let e = parse_at2(Path::new("bad.AT2"), &text, None).unwrap_err();
        assert_eq!(e.line, Some(4), "{e}");
        assert!(e.reason.contains("cannot hold"), "{e}");
    }
}

#[test]
fn at2_and_csv_time_step_below_a_microsecond_is_refused() {
    let text = format!("{AT2_HEAD}NPTS= 2, DT= 1e-300\n1 2\n");
    let e = parse_at2(Path::new("bad.AT2"), &text, None).unwrap_err();
    assert_eq!(e.line, Some(4), "{e}");
    assert!(e.reason.contains("1e-300"), "{e}");
    let e = parse_csv(Path::new("bad.csv"), "0, 1\n1e-300, 2\n", AccelUnit::G).unwrap_err();
    assert_eq!(e.line, Some(2), "{e}");
    assert!(e.reason.contains("smallest sample interval"), "{e}");
}

#[test]
fn devices_and_non_utf8_files_are_refused_with_a_position() {
    if Path::new("/dev/zero").exists() {
        let e = read_record(Path::new("/dev/zero"), Some(AccelUnit::G)).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("latin1.csv");
    std::fs::write(&path, b"0, 1\n0.01, 2 \xb5\n").unwrap();
    let e = read_record(&path, Some(AccelUnit::G)).unwrap_err();
    let e = &e.0[0];
    assert_eq!((e.line, e.column), (Some(2), Some(9)), "{e}");
    assert!(e.reason.contains("UTF-8"), "{e}");
}

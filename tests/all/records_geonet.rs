//! GeoNet (GNS Science) V1A/V2A volumes: the corrected record of the 2016 Kaikōura
//! M 7.8 earthquake at Hanmer Springs (NZ.HSES) as published, and a V1A written from
//! the documented layout. Requirements checked:
//! - each channel's peak and its time equal what its own text header states (to the
//!   header's digits), its sample count integer 34, its step real 26;
//! - the orientations are the text header's quadrant bearings (N10E, N80W, Up);
//! - the fixture's values are read exactly (mm/s² → m/s²), with a short last line;
//! - every malformed header field is an error at its line and column naming the field.

use std::path::Path;

use rockslide::case::record::{Level, Orientation, parse_station, read_station};

use super::common::repo;

const KAIKOURA: &str = "cases/records/Kaikoura_2016_NZ.HSES.V2A";
const FIXTURE: &str = "tests/data/records/GeoNet_fixture.V1A";

#[test]
fn kaikoura_hanmer_springs_v2a_as_published() {
    let s = read_station(&repo(KAIKOURA)).unwrap();
    assert_eq!(
        (s.format, s.level, s.agency.as_str()),
        ("GeoNet V2A", Level::Corrected, "GNS Science (GeoNet)")
    );
    assert!(
        s.station.starts_with("NZ.HSES Hanmer Springs"),
        "{}",
        s.station
    );
    assert!(s.event.contains("2016 November 13"), "{}", s.event);
    assert!(s.event.contains("Mw 7.82"), "{}", s.event);
    // Text header lines 13–14 of each block: "Component N10E …",
    // "Acceleration:  peak   2364.6 mm/s/s at  48.14 sec" (one decimal: 0.05 mm/s²). The
    // V2A opens with the 5.00 s zero pad of GNS's filter (reals 22 and 23); its header's
    // times count from the V1A's first sample, 5 s into the V2A.
    let stated = [
        (Orientation::Azimuth(10.0), 2364.6, 48.14),
        (Orientation::Azimuth(280.0), 2553.7, 47.82),
        (Orientation::Up, -1571.2, 51.78),
    ];
    assert_eq!(s.channels.len(), 3);
    for (c, (o, peak_mm, at_s)) in s.channels.iter().zip(stated) {
        assert_eq!(c.orientation, o);
        assert_eq!((c.record.samples.len(), c.record.dt), (8192, 0.02));
        let (i, a) = c
            .record
            .samples
            .iter()
            .enumerate()
            .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
            .unwrap();
        assert!((a * 1000.0 - peak_mm).abs() <= 0.05 + 1e-9, "{a} {peak_mm}");
        assert!((i as f64 * 0.02 - 5.0 - at_s).abs() < 1e-9, "{i} {at_s}");
    }
    // Blocks start at lines 1, 2487, 4973 (16 + 10 header lines, 3 × 820 data lines).
    let lines: Vec<usize> = s.channels.iter().map(|c| c.line).collect();
    assert_eq!(lines, [1, 2487, 4973]);
}

#[test]
fn fixture_v1a_read_exactly() {
    let s = read_station(&repo(FIXTURE)).unwrap();
    assert_eq!((s.format, s.level), ("GeoNet V1A", Level::Uncorrected));
    let o: Vec<Orientation> = s.channels.iter().map(|c| c.orientation).collect();
    assert_eq!(
        o,
        [
            Orientation::Azimuth(10.0),
            Orientation::Azimuth(280.0),
            Orientation::Up
        ]
    );
    // The fixture's first channel: 5.0, 34.6, … 36.2 mm/s², 23 values (10 + 10 + 3).
    let c = &s.channels[0];
    assert_eq!((c.record.samples.len(), c.record.dt), (23, 0.005));
    assert_eq!(c.record.samples[0], 5.0 * 0.001);
    assert_eq!(c.record.samples[5], 104.7 * 0.001);
    assert_eq!(c.record.samples[22], 36.2 * 0.001);
    assert_eq!(s.channels[2].record.samples[22], -42.0 * 0.001);
}

/// The fixture with `from` replaced by `to` on 1-based line `line`, parsed: its error.
fn edited(line: usize, from: &str, to: &str) -> rockslide::error::InputError {
    let text = std::fs::read_to_string(repo(FIXTURE)).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    assert!(lines[line - 1].contains(from), "{}", lines[line - 1]);
    lines[line - 1] = lines[line - 1].replacen(from, to, 1);
    parse_station(Path::new("f.V1A"), &lines.join("\n")).unwrap_err()
}

#[test]
fn malformed_header_fields_are_located() {
    let located = |e: rockslide::error::InputError| (e.line, e.column, e.field);
    // The component of channel 2 (its line 13: file line 30 + 13 − 1 = 42).
    assert_eq!(
        located(edited(42, "N80W", "N80Q")),
        (Some(42), Some(11), "component".into())
    );
    assert_eq!(
        located(edited(13, "Component N10E", "Compass N10E")),
        (Some(13), Some(9), "component".into())
    );
    // Integer 34 (the count, line 20, columns 25–32): text, negative, not whole.
    let count = "      23       0       0      23";
    for bad in [
        "      23       0       0     2x3",
        "      23       0       0      -4",
    ] {
        assert_eq!(
            located(edited(20, count, bad)),
            (Some(20), Some(25), "integer header[34]".into())
        );
    }
    assert_eq!(
        located(edited(20, count, "      23       0       0    23.5")),
        (Some(20), Some(25), "integer header[34]".into())
    );
    // Real 26 (the interval, line 23, columns 41–48): zero, then blank.
    assert_eq!(
        located(edited(23, "  0.0050       0", "  0.0000       0")),
        (Some(23), Some(41), "real header[26]".into())
    );
    assert_eq!(
        located(edited(23, "  0.0050       0", "               0")),
        (Some(23), Some(41), "real header[26]".into())
    );
    // A sample (line 27, the second field, columns 9–16).
    assert_eq!(
        located(edited(27, "    34.6", "    3x.6")),
        (Some(27), Some(9), "acceleration values[2]".into())
    );
    // The second block's first line not a GeoNet volume's.
    assert_eq!(
        located(edited(
            30,
            "Uncorrected accelerogram",
            "Corrected accelerogram"
        )),
        (Some(30), Some(1), "text header line 1".into())
    );
    // A file cut inside the second block's header, and one whose count outruns it.
    let text = std::fs::read_to_string(repo(FIXTURE)).unwrap();
    let cut: Vec<&str> = text.lines().take(35).collect();
    let e = parse_station(Path::new("f.V1A"), &cut.join("\n")).unwrap_err();
    assert_eq!(e.line, Some(30));
    let e = edited(
        20,
        "      23       0       0      23",
        "      23       0       0   99999",
    );
    assert!(e.reason.contains("acceleration values"), "{}", e.reason);
}

/// A rigid-block case on the uncorrected Ridgecrest CI.CCC with `keys` in its station.
fn ccc_case(keys: &str) -> String {
    format!(
        "title = \"t\"\n[model]\nkind = \"rigid-block\"\nmass = 1000.0\ngravity = 9.81\nhalf_width = 1.0\nhalf_depth = 1.0\nhalf_height = 0.25\nmu = 0.3\n[excitation]\nkind = \"ground-acceleration\"\n[excitation.station]\nfile = \"../records/Ridgecrest_2019_CI.CCC.RAW\"\n{keys}\n[run]\nduration = 10.0\ndt = 0.001\n[engines.rapier]\n"
    )
}

#[test]
fn the_highpass_of_an_uncorrected_station() {
    use rockslide::case::record::{HighPass, prepare, prepare_window};
    use rockslide::case::{Signal, parse_case};
    let s = read_station(&repo("cases/records/Ridgecrest_2019_CI.CCC.RAW")).unwrap();
    let filter = HighPass {
        corner_hz: 0.1,
        order: 4,
    };
    // Over the whole 354 s record the filter takes every channel's displacement drift
    // down by more than 100× (measured 1.62 → 0.0014 m, 19.6 → 0.0070 m, 0.152 →
    // 0.00047 m; the cubic baseline: 0.31, 3.16, 0.065 m); the final velocity, small as
    // read (1.6e-5, 5.7e-5, 1.0e-4 m/s), stays small (2.1e-4, 1.6e-3, 2.0e-5 m/s: the
    // pads removed keep what the filter spread into them).
    let p = prepare(&s, filter);
    for d in &p.drift {
        assert!(
            d.displacement[1].abs() < 0.01 * d.displacement[0].abs(),
            "{d:?}"
        );
        assert!(d.velocity[1].abs() < 2e-3, "{d:?}");
    }
    assert!(
        p.notes
            .iter()
            .any(|n| n.contains("acausal Butterworth high-pass (order 4")),
        "{:?}",
        p.notes
    );
    // A case asks for it by name; the vertical it drives is the filtered up channel of
    // the window, and the label states the filter and the drift before and after.
    let path = repo("cases/spatial/station-test.toml");
    let keys = "start = 20.0\nbaseline = \"highpass\"\nhighpass_corner_hz = 0.1";
    let case = parse_case(&path, &ccc_case(keys)).unwrap();
    let w = prepare_window(&s, filter, 20.0, 10.0);
    let Some(Signal::Record { samples, label, .. }) =
        case.scene.vertical.as_ref().map(|v| &v.signal)
    else {
        panic!("a vertical record")
    };
    assert_eq!(samples.to_vec(), w.channels[2].record.samples);
    assert!(label.contains("corner 0.1 Hz"), "{label}");
    assert!(label.contains("as read → as used"), "{label}");
    // Its keys are checked and located.
    let errors = |keys: &str| parse_case(&path, &ccc_case(keys)).unwrap_err().to_string();
    for (keys, field) in [
        ("baseline = \"highpass\"", "highpass_corner_hz"),
        (
            "baseline = \"highpass\"\nhighpass_corner_hz = 50.0",
            "highpass_corner_hz",
        ),
        (
            "baseline = \"highpass\"\nhighpass_corner_hz = 0.1\nhighpass_order = 0",
            "highpass_order",
        ),
        ("highpass_corner_hz = 0.1", "highpass_corner_hz"),
    ] {
        let e = errors(keys);
        assert!(
            e.contains(&format!("excitation.station.{field}")),
            "{keys}: {e}"
        );
    }
}

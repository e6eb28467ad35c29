//! Station records as the agencies publish them, read with every channel's orientation:
//! the CSMIP Avol1 V1 of three 2019 Ridgecrest stations (CGS), the CSMIP V2 of the 1983
//! Coalinga record at CDMG 36456, the USGS SMC set of the 1989 Loma Prieta record at
//! San Francisco, 1295 Shafter, and a COSMOS V2 test file. Requirements checked:
//! - each channel's peak equals the peak its own header states (to the header's digits),
//!   its sample count the header's, its step the stated rate;
//! - the orientations are the headers' (90°, 360°, up; 360°, up, 270°);
//! - a malformed header field is an error at its line and column naming the field;
//! - channels of unequal length are trimmed to the shortest with a note, and an
//!   uncorrected record's baseline correction removes the drift of a constant offset.

use std::path::Path;

use rockslide::case::record::{
    Baseline, Level, Orientation, STANDARD_GRAVITY, parse_station, prepare, read_station,
};

use super::common::repo;

/// Peak |a| of each channel, g.
fn peaks_g(file: &str) -> Vec<f64> {
    let s = read_station(&repo(file)).unwrap();
    s.channels
        .iter()
        .map(|c| c.record.pga() / STANDARD_GRAVITY)
        .collect()
}

#[test]
fn ridgecrest_avol1_v1_three_stations() {
    // Header "Max = -.567 g", "-.471 g", "-.361 g" and so on, three digits.
    for (file, stated, counts) in [
        (
            "cases/records/Ridgecrest_2019_CI.CCC.RAW",
            [0.567, 0.471, 0.361],
            [35430, 35402, 35406],
        ),
        (
            "cases/records/Ridgecrest_2019_CI.CLC.v1",
            [0.344, 0.511, 0.347],
            [31932, 32080, 32190],
        ),
        (
            "cases/records/Ridgecrest_2019_CI.TOW2.RAW",
            [0.437, 0.386, 0.360],
            [35562, 35540, 35710],
        ),
    ] {
        let s = read_station(&repo(file)).unwrap();
        assert_eq!(s.format, "CSMIP Avol1 V1");
        assert_eq!(s.level, Level::Uncorrected);
        assert_eq!(s.agency, "CGS");
        assert!(s.event.contains("38457"), "{}", s.event);
        let o: Vec<Orientation> = s.channels.iter().map(|c| c.orientation).collect();
        assert_eq!(
            o,
            [
                Orientation::Azimuth(90.0),
                Orientation::Azimuth(360.0),
                Orientation::Up
            ]
        );
        for ((c, g), n) in s.channels.iter().zip(stated).zip(counts) {
            assert_eq!(c.record.samples.len(), n, "{file}");
            assert_eq!(c.record.dt, 0.01);
            assert!(
                (c.record.pga() / STANDARD_GRAVITY - g).abs() <= 0.0005 + 1e-12,
                "{file}"
            );
        }
    }
}

#[test]
fn coalinga_csmip_v2_and_loma_prieta_smc() {
    // V2 header: PEAK ACCELERATION = -267.957 CM/SEC/SEC (channel 1), 3251 points at .020 s.
    let s = read_station(&repo("cases/records/Coalinga_1983_CE36456.V2")).unwrap();
    assert_eq!(
        (s.format, s.level, s.agency.as_str()),
        ("CSMIP V2", Level::Corrected, "CDMG")
    );
    assert_eq!(s.channels[0].record.samples.len(), 3251);
    assert_eq!(s.channels[0].record.dt, 0.02);
    assert!((s.channels[0].record.pga() - 2.67957).abs() < 0.5e-5);
    let o: Vec<Orientation> = s.channels.iter().map(|c| c.orientation).collect();
    assert_eq!(
        o,
        [
            Orientation::Azimuth(90.0),
            Orientation::Up,
            Orientation::Azimuth(0.0)
        ]
    );
    // SMC: real header peak 104.4078 cm/s² for the 360° channel, the samples written to
    // five digits (1.0441E+2: 0.005 cm/s² half a unit); 200 samples/s.
    let s = read_station(&repo(
        "cases/records/Loma_Prieta_1989_SF-1295-Shafter_0111a.smc",
    ))
    .unwrap();
    assert_eq!((s.format, s.agency.as_str()), ("USGS SMC", "USGS"));
    let c = &s.channels[0];
    assert_eq!(
        (c.orientation, c.record.samples.len(), c.record.dt),
        (Orientation::Azimuth(360.0), 6001, 0.005)
    );
    assert!((c.record.pga() - 1.044078).abs() < 5e-5);
    let up = read_station(&repo(
        "cases/records/Loma_Prieta_1989_SF-1295-Shafter_0111b.smc",
    ))
    .unwrap();
    assert_eq!(up.channels[0].orientation, Orientation::Up);
    assert_eq!(
        peaks_g("cases/records/Loma_Prieta_1989_SF-1295-Shafter_0111c.smc").len(),
        1
    );
}

#[test]
fn cosmos_v2_test_file() {
    // Real header: peak -161.962 cm/sec2 (three decimals) at 27.85 s; integer 54 (the
    // azimuth) 340; real 62 (the interval) 10 ms.
    let s = read_station(&repo("tests/data/records/Cosmos12TimeSeriesTest.v1")).unwrap();
    assert_eq!(s.format, "COSMOS V2");
    let c = &s.channels[0];
    assert_eq!(
        (c.orientation, c.record.samples.len(), c.record.dt),
        (Orientation::Azimuth(340.0), 7000, 0.01)
    );
    assert!((c.record.pga() - 1.61962).abs() <= 0.5e-5);
}

#[test]
fn malformed_header_fields_are_located() {
    let path = Path::new("CCC.RAW");
    let text = std::fs::read_to_string(repo("cases/records/Ridgecrest_2019_CI.CCC.RAW")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let edit = |line: usize, from: &str, to: &str| {
        let mut l = lines.clone();
        let fixed = l[line - 1].replacen(from, to, 1);
        l[line - 1] = &fixed;
        parse_station(path, &l.join("\n")).unwrap_err()
    };
    // The fourth value of the real header (line 21, columns 31–40) made text.
    let e = edit(21, " .0213656", " .02x3656");
    assert_eq!(
        (e.line, e.column, e.field.as_str()),
        (Some(21), Some(31), "real header[4]")
    );
    // An integer header value (line 15, the second field, columns 6–10).
    let e = edit(15, "   19", "   1?");
    assert_eq!(
        (e.line, e.column, e.field.as_str()),
        (Some(15), Some(6), "integer header[18]")
    );
    // The orientation of channel 2 (line 4465).
    let e = edit(4465, "360 Deg", "sideways");
    assert_eq!(
        (e.line, e.field.as_str()),
        (Some(4465), "channel orientation")
    );
    // The count of points of channel 1 (line 28).
    let e = edit(28, " 35430 Accelerogram", " many Accelerogram");
    assert_eq!(
        (e.line, e.column, e.field.as_str()),
        (Some(28), Some(1), "number of points")
    );
    // A sample (line 29, the fourth field, columns 28–36).
    let e = edit(29, "  .000021  .000024", "  .000021  .0000-4");
    assert_eq!((e.line, e.column), (Some(29), Some(28)));
    assert_eq!(e.field, "acceleration values[4]");
    // Not a station file at all.
    let e = parse_station(path, "hello\n").unwrap_err();
    assert_eq!((e.line, e.column), (Some(1), Some(1)));
}

#[test]
fn unequal_channels_trimmed_and_uncorrected_drift_reduced() {
    let s = read_station(&repo("cases/records/Ridgecrest_2019_CI.CCC.RAW")).unwrap();
    let p = prepare(&s, Baseline::Cubic);
    assert!(p.channels.iter().all(|c| c.record.samples.len() == 35402));
    assert!(p.notes[0].contains("35430, 35402, 35406"), "{:?}", p.notes);
    // The cubic baseline takes the displacement drift of every channel down (measured:
    // 1.62 → 0.31 m, 19.6 → 3.2 m, 0.15 → 0.065 m over the 354 s).
    for d in &p.drift {
        assert!(
            d.displacement[1].abs() < 0.45 * d.displacement[0].abs(),
            "{d:?}"
        );
    }
}

/// A station case's text with `keys` in its `[excitation.station]` table.
fn station_case(keys: &str) -> String {
    format!(
        "title = \"t\"\n[model]\nkind = \"rigid-block\"\nmass = 1000.0\ngravity = 9.81\nhalf_width = 1.0\nhalf_depth = 1.0\nhalf_height = 0.25\nmu = 0.3\n[excitation]\nkind = \"ground-acceleration\"\n[excitation.station]\nfile = \"../records/Ridgecrest_2019_CI.CCC.RAW\"\n{keys}\n[run]\nduration = 10.0\ndt = 0.001\n[engines.rapier]\n"
    )
}

/// The x, y and z samples of a station case.
fn xyz(keys: &str) -> [Vec<f64>; 3] {
    use rockslide::case::{Signal, parse_case};
    let path = repo("cases/spatial/station-test.toml");
    let case = parse_case(&path, &station_case(keys)).unwrap();
    let samples = |s: Option<&Signal>| match s {
        Some(Signal::Record { samples, .. }) => samples.to_vec(),
        _ => Vec::new(),
    };
    [
        samples(case.scene.excitation.signal()),
        samples(case.scene.spatial().and_then(|s| s.second.as_ref())),
        samples(case.scene.vertical.as_ref().map(|v| &v.signal)),
    ]
}

#[test]
fn a_station_drives_x_y_and_z_at_any_rotation() {
    // x east, y north: the 90° channel along x, the 360° one along y, the vertical up —
    // each the prepared channel itself (cos 0 = 1, cos 90° = 6e-17 of the other).
    let [x, y, z] = xyz("start = 20.0");
    let s = read_station(&repo("cases/records/Ridgecrest_2019_CI.CCC.RAW")).unwrap();
    let p = rockslide::case::record::prepare_window(&s, Baseline::Cubic, 20.0, 10.0);
    let [e, n, up] = [0, 1, 2].map(|i| p.channels[i].record.samples.clone());
    assert_eq!(
        (x.len(), e.len()),
        (e.len(), (10.0_f64 / 0.01).ceil() as usize + 1)
    );
    for i in 0..x.len() {
        assert!((x[i] - e[i]).abs() <= 1e-15 * (1.0 + n[i].abs()) + 1e-12 * e[i].abs());
        assert!((y[i] - n[i]).abs() <= 1e-15 * (1.0 + e[i].abs()) + 1e-12 * n[i].abs());
        assert_eq!(z[i], up[i]);
    }
    // +x at compass 30°: a_x = e·sin 30° + n·cos 30°, a_y = n·sin 30° − e·cos 30°; the
    // horizontal resultant is the same at every rotation.
    let [x30, y30, _] = xyz("start = 20.0\nx_azimuth_deg = 30.0");
    let (s30, c30) = 30f64.to_radians().sin_cos();
    for i in 0..x.len() {
        assert!((x30[i] - (e[i] * s30 + n[i] * c30)).abs() < 1e-13);
        assert!((y30[i] - (n[i] * s30 - e[i] * c30)).abs() < 1e-13);
        let r0 = x[i].hypot(y[i]);
        assert!((x30[i].hypot(y30[i]) - r0).abs() <= 1e-14 * (1.0 + r0));
    }
    // Scale and polarity on all three; "x" drives x alone (a planar scene).
    let [xs, ys, zs] = xyz("start = 20.0\nscale = 0.5\npolarity = -1");
    assert!(
        (0..x.len()).all(|i| xs[i] == -0.5 * x[i] && ys[i] == -0.5 * y[i] && zs[i] == -0.5 * z[i])
    );
    let [xo, yo, zo] = xyz("start = 20.0\ncomponents = \"x\"");
    assert_eq!((xo, yo.len(), zo.len()), (x, 0, 0));
}

#[test]
fn station_keys_and_files_are_checked_and_located() {
    use rockslide::case::parse_case;
    let path = repo("cases/spatial/station-test.toml");
    let errors = |keys: &str| {
        parse_case(&path, &station_case(keys))
            .unwrap_err()
            .to_string()
    };
    let e = errors("components = \"yz\"");
    assert!(e.contains("excitation.station.components"), "{e}");
    let e = errors("baseline = \"spline\"");
    assert!(e.contains("excitation.station.baseline"), "{e}");
    let e = errors("polarity = 2");
    assert!(e.contains("excitation.station.polarity"), "{e}");
    // A signal key beside the station is refused by name.
    let text = station_case("").replace(
        "kind = \"ground-acceleration\"\n",
        "kind = \"ground-acceleration\"\nrecord = \"x.AT2\"\n",
    );
    let e = parse_case(&path, &text).unwrap_err().to_string();
    assert!(
        e.contains("excitation.record") && e.contains("[excitation.station]"),
        "{e}"
    );
    // A broken file: the error names the case's field and the file's line.
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(repo("cases/records/Ridgecrest_2019_CI.CCC.RAW"))
        .unwrap()
        .replacen("Chan  2: 360 Deg", "Chan  2: 360 Dig", 1);
    let bad = dir.path().join("bad.RAW");
    std::fs::write(&bad, text).unwrap();
    let case = station_case("").replace(
        "../records/Ridgecrest_2019_CI.CCC.RAW",
        &bad.to_string_lossy(),
    );
    let e = parse_case(&path, &case).unwrap_err().to_string();
    assert!(
        e.contains("excitation.station.file") && e.contains("bad.RAW:4465"),
        "{e}"
    );
    // The SMC set, a file a channel, is one station too.
    let smc = station_case("").replace(
        "file = \"../records/Ridgecrest_2019_CI.CCC.RAW\"",
        "files = [\"../records/Loma_Prieta_1989_SF-1295-Shafter_0111a.smc\", \"../records/Loma_Prieta_1989_SF-1295-Shafter_0111b.smc\", \"../records/Loma_Prieta_1989_SF-1295-Shafter_0111c.smc\"]",
    );
    let c = parse_case(&path, &smc).unwrap();
    assert!(c.scene.vertical.is_some() && c.scene.spatial().is_some());
}

#[test]
fn the_station_study_grid_expands_stations_mu_polarity_and_azimuth() {
    use rockslide::study::load_grid;
    let grid = load_grid(&repo("studies/ridgecrest-stations.toml")).unwrap();
    // 3 stations × 3 μ × 2 polarities × 1 scale × 4 azimuths.
    assert_eq!(grid.points.len(), 72);
    let az: Vec<Option<f64>> = grid.points[..4].iter().map(|p| p.x_azimuth_deg).collect();
    assert_eq!(az, [Some(0.0), Some(45.0), Some(90.0), Some(135.0)]);
    // Point 24 is CLC (the second station), at its own window start.
    let p = &grid.points[24];
    assert_eq!((p.record, p.x_azimuth_deg), (1, Some(0.0)));
    let case = grid.point_case(p).unwrap();
    let rockslide::case::Signal::Record { label, .. } = case.scene.excitation.signal().unwrap()
    else {
        panic!("a station drives x by its record");
    };
    assert!(
        label.contains("CLC") && label.contains("t = 0 at 220.00 s"),
        "{label}"
    );
    assert!(label.contains("x (compass 0°)"), "{label}");
    assert_eq!(case.run.duration, 40.0);
}

#[test]
fn summary_statistics_of_a_known_list() {
    use rockslide::study::summary_statistics;
    // 1..5: mean 3, median 3, the 84th percentile at rank 0.84·4 = 3.36 between 4 and 5.
    let [mean, median, p84, max] = summary_statistics(&mut [5.0, 1.0, 4.0, 2.0, 3.0]);
    assert_eq!((mean, median, max), (3.0, 3.0, 5.0));
    assert!((p84 - 4.36).abs() < 1e-12);
    // An even count: the median between the middle two.
    let [_, median, _, _] = summary_statistics(&mut [1.0, 2.0, 3.0, 10.0]);
    assert_eq!(median, 2.5);
}

#[test]
fn the_three_component_study_grid_expands_stations_mu_scale_and_polarity() {
    use rockslide::study::{Amplitude, load_grid};
    let grid = load_grid(&repo("studies/ridgecrest-three-component.toml")).unwrap();
    // 3 stations × 3 μ × 2 scales × 2 polarities, no azimuth axis (the scene is isotropic
    // in plan).
    assert_eq!(grid.points.len(), 36);
    assert!(grid.points.iter().all(|p| p.x_azimuth_deg.is_none()));
    let scales: std::collections::BTreeSet<u64> = grid
        .points
        .iter()
        .map(|p| match p.amplitude {
            Amplitude::Scale(f) => f.to_bits(),
            Amplitude::Pga(_) => panic!("the study scales the records as recorded"),
        })
        .collect();
    assert_eq!(scales, [1.0f64.to_bits(), 1.5f64.to_bits()].into());
    // fe and both rapier routes run every point beside the plan-motion reference.
    assert_eq!(
        grid.plan_signature,
        "fe/single@0.00025,rapier/kinematic-ground@0.00025,rapier/inertial-force@0.00025"
    );
}

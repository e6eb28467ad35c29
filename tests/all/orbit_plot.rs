//! The orbit plot (docs/bidirectional.md): the sliding path in plan, drawn for a spatial scene only,
//! its axes extending to ± the largest peak resultant sliding of any participant.

use std::path::Path;
use std::process::Command;

/// `rockslide run` on the 3D PEPO at azimuth 30° and the planar PEPO into a fresh folder.
fn reports() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "run",
            "cases/spatial/pepo-pulse-azimuth30.toml",
            "cases/pepo-mass-accel.toml",
            "--quiet",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    dir
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The largest `peak_resultant_sliding` of the reference and every run in `result.json`, m.
fn largest_peak_resultant(result: &serde_json::Value) -> f64 {
    let from = |responses: &serde_json::Value| -> Vec<f64> {
        responses
            .as_array()
            .unwrap()
            .iter()
            .filter(|q| q["key"] == "peak_resultant_sliding")
            .map(|q| q["value"].as_f64().unwrap())
            .collect()
    };
    let mut peaks = from(&result["reference"]["Ok"]["responses"]);
    for run in result["runs"].as_array().unwrap() {
        peaks.extend(from(&run["responses"]));
    }
    assert_eq!(
        peaks.len(),
        3,
        "the reference, fe/single and rapier/applied-force"
    );
    peaks.into_iter().fold(0.0, f64::max)
}

#[test]
fn a_spatial_case_has_an_orbit_plot_as_wide_as_its_peak_resultant_and_a_planar_one_none() {
    let dir = reports();
    let planar = dir.path().join("pepo-mass-accel");
    assert!(planar.join("report.md").is_file());
    assert!(!planar.join("plot-orbit.svg").exists());
    assert!(!read(&planar.join("report.md")).contains("plot-orbit"));

    let spatial = dir.path().join("pepo-pulse-azimuth30");
    let svg = read(&spatial.join("plot-orbit.svg"));
    assert!(svg.contains("sliding x [mm]") && svg.contains("sliding y [mm]"));
    // Three paths (reference, fe, rapier) and each one's peak marked.
    assert_eq!(
        svg.matches("<circle").count(),
        3,
        "one peak dot per participant"
    );

    let md = read(&spatial.join("report.md"));
    let caption = md
        .lines()
        .find(|l| l.contains("Sliding path in plan"))
        .expect("the orbit caption");
    let extent: f64 = caption
        .split("axes ±")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no extent in {caption}"));
    let result: serde_json::Value =
        serde_json::from_str(&read(&spatial.join("result.json"))).unwrap();
    let peak_mm = 1e3 * largest_peak_resultant(&result);
    // The caption prints four decimals: equal to within half its last digit.
    assert!(
        (extent - peak_mm).abs() <= 0.5e-4,
        "extent {extent} mm, peak resultant {peak_mm} mm"
    );
    // A one-directional motion at azimuth 30°: the peak's direction is 30°.
    assert!(caption.contains("8.7562 mm at 30.0°"), "{caption}");
}

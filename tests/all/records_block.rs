//! The rigid-block reference on a record case (`reference::for_case` for
//! `kind = "rigid-block"` under a recorded ground acceleration). Requirements checked:
//! - a rectangular record pulse gives Newmark's closed form, at the samples and between
//!   them, with its exact onset, stop, episode count and total slid;
//! - a record strong enough to rock the block has no sliding reference, and says why.

use rockslide::case::{Case, load_case};
use rockslide::reference::for_case;

/// A rigid block (M = 1 t, g = 10 m/s², μ = 0.2: ky = 2 m/s², b/h = 4) under a two-column
/// record in m/s², written beside its case in a temporary folder.
fn block_case(dir: &std::path::Path, samples: &[f64], dt: f64, duration: f64) -> Case {
    let csv: String = samples
        .iter()
        .enumerate()
        .map(|(i, a)| format!("{},{a}\n", i as f64 * dt))
        .collect();
    std::fs::write(dir.join("pulse.csv"), csv).unwrap();
    let toml = format!(
        r#"title = "rigid block under a rectangular record pulse"
source = "Newmark (1965), closed form"
requirement = "the rigid-block record reference matches Newmark's closed form"

[model]
kind = "rigid-block"
mass = 1000.0
gravity = 10.0
half_width = 1.0
half_height = 0.25
mu = 0.2

[excitation]
kind = "ground-acceleration"
record = "pulse.csv"
record_unit = "m/s2"

[run]
duration = {duration}
dt = 0.001
"#
    );
    let path = dir.join("block.toml");
    std::fs::write(&path, toml).unwrap();
    load_case(&path).expect("the block case loads")
}

#[test]
fn a_rectangular_record_pulse_gives_newmarks_closed_form() {
    // ag = −3 m/s² for 1 s (samples every 10 ms), then — the record being linear between
    // samples and zero after — a ramp to zero over the next 10 ms. The drive −ag = 3 m/s²
    // exceeds ky = 2 from t = 0: v = t, u = t²/2; over the ramp v' = 1 − 300τ; then the
    // block decelerates at ky to rest.
    let dir = tempfile::tempdir().unwrap();
    let (dt, a, ky) = (0.01, 3.0, 2.0);
    let case = block_case(dir.path(), &[-a; 101], dt, 2.0);
    let r = for_case(&case).expect("a sliding block has a record reference");
    let (u1, v1) = (0.5, 1.0);
    let v2 = v1 + (a - ky) * dt - a * dt / 2.0; // 0.995
    let u2 = u1 + v1 * dt + (a - ky) * dt * dt / 2.0 - a * dt * dt / 6.0; // 0.51
    let stop = 1.0 + dt + v2 / ky;
    let residual = u2 + v2 * v2 / (2.0 * ky);

    let mut row = vec![0.0; r.channels().len()];
    let mut at = |t: f64| {
        r.eval(t, &mut row);
        (row[3], row[4]) // slide, velocity
    };
    for (t, u, v) in [
        (0.505, 0.505 * 0.505 / 2.0, 0.505), // between samples, in the pulse
        (1.2, u2 + v2 * 0.19 - 0.19 * 0.19, v2 - ky * 0.19),
        (1.9, residual, 0.0),
    ] {
        let (ur, vr) = at(t);
        assert!((ur - u).abs() < 1e-14, "u({t}) = {ur}, closed form {u}");
        assert!((vr - v).abs() < 1e-13, "v({t}) = {vr}, closed form {v}");
    }
    let q: std::collections::BTreeMap<_, _> = r.exact_quantities().into_iter().collect();
    assert_eq!(q["slip_start"], 0.0);
    assert!(
        (q["slip_end"] - stop).abs() < 1e-13,
        "{} vs {stop}",
        q["slip_end"]
    );
    assert_eq!(q["slip_episodes"], 1.0);
    assert!((q["total_slid"] - residual).abs() < 1e-14);
    assert!((q["peak_abs_sliding"] - residual).abs() < 1e-14);
}

#[test]
fn a_record_that_could_rock_the_block_has_no_sliding_reference() {
    // peak 45 m/s² > g·b/h = 40 m/s²: Housner's rocking could start; no record reference
    let dir = tempfile::tempdir().unwrap();
    let case = block_case(dir.path(), &[0.0, 45.0, 0.0], 0.01, 1.0);
    let err = for_case(&case).err().expect("no reference");
    assert!(err.contains("may rock") && err.contains("40.0000"), "{err}");
}

//! Newmark's rigid block on a record (src/reference/newmark_record.rs). Requirements checked:
//! - rockslide shall compute rigid-block sliding on a sampled record that matches a
//!   hand-checkable closed form (Newmark 1965: rectangular pulse of height A and length T,
//!   yield acceleration ky: u = A·T²·(A − ky)/(2·ky));
//! - it shall report both polarities, in cm as well as m (SLAMMER's conventions).

use rockslide::case::record::STANDARD_GRAVITY;
use rockslide::reference::newmark_record::{NewmarkSummary, Sliding, rigid_block};

const G: f64 = STANDARD_GRAVITY;

/// Samples of a rectangular pulse: A at t = i·dt ≤ T, zero after (so linear interpolation
/// ramps down over (T, T + dt)).
fn pulse(a: f64, t_end: f64, dt: f64, total: f64) -> Vec<f64> {
    let n = (total / dt).round() as usize + 1;
    let last = (t_end / dt).round() as usize;
    (0..n).map(|i| if i <= last { a } else { 0.0 }).collect()
}

/// Closed form for the sampled pulse, ramp included: sliding at A − ky until T (V1, D1),
/// a linear ramp of A to 0 over dt (V2, D2), then deceleration at ky to rest.
fn closed_form_sampled(a: f64, ky: f64, t: f64, dt: f64) -> f64 {
    let v1 = (a - ky) * t;
    let d1 = (a - ky) * t * t / 2.0;
    let v2 = v1 + dt * (a / 2.0 - ky);
    let d2 = d1 + v1 * dt + (a - ky) * dt * dt / 2.0 - a * dt * dt / 6.0;
    d2 + v2 * v2 / (2.0 * ky)
}

#[test]
fn rectangular_pulse_matches_the_closed_form() {
    let (a, ky, t) = (0.5 * G, 0.2 * G, 0.4);
    let rect = a * t * t * (a - ky) / (2.0 * ky); // Newmark 1965, exact rectangle
    // Hand check: 0.5g·0.16·0.3g/0.4g = 0.06·g = 0.588399 m = 58.84 cm.
    assert!((rect - 0.06 * G).abs() < 1e-12);
    let mut errors = Vec::new();
    for dt in [0.01, 0.005, 0.0025] {
        let acc = pulse(a, t, dt, 2.0);
        let r = rigid_block(dt, &acc, ky, Sliding::OneWay, 0.0).unwrap();
        // Exact for the piecewise-linear input: measured agreement ~1e-15 relative.
        let exact = closed_form_sampled(a, ky, t, dt);
        assert!(
            (r.residual() - exact).abs() <= 1e-12 * exact,
            "dt {dt}: {} vs {exact}",
            r.residual()
        );
        assert_eq!(r.episodes(), 1);
        errors.push((r.residual() - rect).abs() / rect);
    }
    // The one-sample ramp makes the rectangle error first order in dt: ratio 2 per halving
    // (measured 2.005 and 2.003); at dt = 0.0025 s the error is 6.26e-3 (≈ 2.5·dt/s).
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        assert!((ratio - 2.0).abs() < 0.01, "observed ratio {ratio}");
    }
    assert!(errors[2] < 6.3e-3, "{errors:?}");
}

#[test]
fn both_polarities_and_two_way_sliding() {
    // A symmetric full-sine-like square wave: +A for T, then −A for T, then rest.
    let (a, ky, t, dt): (f64, f64, f64, f64) = (0.5 * G, 0.2 * G, 0.4, 0.001);
    let n_t = (t / dt).round() as usize;
    let acc: Vec<f64> = (0..=4 * n_t)
        .map(|i| {
            if i <= n_t {
                a
            } else if i <= 2 * n_t {
                -a
            } else {
                0.0
            }
        })
        .collect();
    let s = NewmarkSummary::of(dt, &acc, ky, Sliding::OneWay, 2.0).unwrap();
    // One-way, normal polarity: the first half slides +, sliding continues into the
    // negative half and stops; inverted: only the second half drives + sliding.
    assert!(s.normal > 0.0 && s.inverse > 0.0);
    // The inverted record is −A for T (no one-way sliding), then +A for T, then 0: the
    // rectangle case up to the one-step ramps (measured 1.75e-3 relative at dt = 1 ms).
    assert!(
        (s.inverse - 0.06 * G).abs() / (0.06 * G) < 1.8e-3,
        "{}",
        s.inverse
    );
    let table = s.table("square");
    assert!(table.contains("| normal |") && table.contains("| inverse |"));
    assert!(
        table.contains(&format!("{:.3}", s.inverse * 100.0)),
        "cm column"
    );
    // Two-way on the normal record: slides + then − (the negative half exceeds ky the
    // other way once the block has stopped).
    let r = rigid_block(dt, &acc, ky, Sliding::TwoWay, 2.0).unwrap();
    assert!(r.episodes() >= 2, "{}", r.episodes());
    assert!(
        r.residual() < s.normal,
        "two-way gives back some of the slide"
    );
}

/// SLAMMER's rigid-block scheme as Jibson (1993) describes it and pyslammer 0.2 implements
/// it, written here from that description: per sample, relative acceleration a − n·ky
/// (n = 1 while sliding; clipped to zero relative motion while stuck), trapezoidal
/// velocity and displacement, sliding stops when the velocity would turn negative.
fn slammer_trapezoid(acc: &[f64], dt: f64, ky: f64) -> f64 {
    let (mut a0, mut v0, mut d) = (0.0_f64, 0.0_f64, 0.0_f64);
    for &g in acc {
        let n = if v0 < 1e-5 {
            if g.abs() > ky { g.signum() } else { g / ky }
        } else {
            1.0
        };
        let mut a1 = g - n * ky;
        let mut v1 = v0 + dt / 2.0 * (a1 + a0);
        if v1 > 0.0 {
            d += dt / 2.0 * (v1 + v0);
        } else {
            v1 = 0.0;
            a1 = 0.0;
        }
        a0 = a1;
        v0 = v1;
    }
    d
}

#[test]
fn loma_prieta_agrees_with_the_slammer_scheme_both_polarities() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cases/records/Loma_Prieta_1989_HSP-000.AT2");
    let rec = rockslide::case::record::read_record(&path, None).unwrap();
    let inverted: Vec<f64> = rec.samples.iter().map(|a| -a).collect();
    for ky_g in [0.05, 0.1, 0.2] {
        let ky = ky_g * G;
        let s = NewmarkSummary::of(rec.dt, &rec.samples, ky, Sliding::OneWay, 0.0).unwrap();
        let normal = slammer_trapezoid(&rec.samples, rec.dt, ky);
        let inverse = slammer_trapezoid(&inverted, rec.dt, ky);
        // Measured: 79.508/90.335, 24.617/47.422, 3.845/8.115 cm (ours) against
        // 79.511/90.352, 24.619/47.430, 3.843/8.115 cm (SLAMMER's scheme): largest difference 7.2e-4 relative (ky 0.2 g).
        for (ours, theirs) in [(s.normal, normal), (s.inverse, inverse)] {
            assert!(
                (ours - theirs).abs() <= 7.5e-4 * theirs,
                "ky {ky_g} g: {ours} vs {theirs}"
            );
        }
    }
}

#[test]
fn newmark_command_prints_both_polarities_in_mm_block_minus_ground() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args(["newmark", "--ky", "0.1", "--"])
        .arg(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("cases/records/Loma_Prieta_1989_HSP-000.AT2"),
        )
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    // Values of loma_prieta_agrees_with_the_slammer_scheme_both_polarities (ky 0.1 g):
    // SLAMMER's u = 24.617 / 47.422 cm, printed as sliding = −u in mm (the reports' sign).
    assert!(
        text.contains("| 0.1000 | normal | -246.2 | 9 | 246.2 |"),
        "{text}"
    );
    assert!(
        text.contains("| 0.1000 | inverse | -474.2 | 8 | 474.2 |"),
        "{text}"
    );
    assert!(text.contains("| 0.1000 | mean abs | 360.2 |"), "{text}");
    // A CSV without its unit is refused with exit code 2 and says how to fix it.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .args(["newmark", "--ky", "0.1", "--"])
        .arg(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("cases/records/Northridge_1994_PAC-175.csv"),
        )
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--unit"));
}

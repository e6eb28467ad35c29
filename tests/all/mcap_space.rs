//! The 3D view of a bidirectional (3D) scene in the MCAP trace (docs/traces.md): the mass moves
//! in x and y, the body tilts and twists as its rotation vector, the ground moves with both
//! components, every support of an nx × ny grid is drawn, for every run and the reference
//! (a ghost in its own lane). Read back from the file and checked against the trace's
//! values and rigid-body kinematics computed here (Rodrigues' formula), not by the
//! writer's code.
//!
//! rockslide shall show a 3D scene's motion in both horizontal directions in the MCAP
//! trace's 3D view.

use std::path::Path;

use rockslide::analysis::responses;
use rockslide::case::{Case, parse_case};
use rockslide::engine::{Run, RunStatus};
use rockslide::formats::{read_mcap, scene3d};
use rockslide::report::write_case_outputs;
use rockslide::suite::{CaseResult, run_case};
use rockslide::trace::{Trace, q};
use serde_json::Value;

use crate::common::case;

/// The 3D view's and the log's messages of a file as JSON: (topic, log time, message),
/// one entry per transform of a `FrameTransforms` message; the state and contacts are
/// skipped (read back with `read_mcap`).
fn json_messages(path: &Path) -> Vec<(String, u64, Value)> {
    let bytes = std::fs::read(path).unwrap();
    mcap::MessageStream::new(&bytes)
        .unwrap()
        .map(|m| m.unwrap())
        .flat_map(|m| {
            let schema = &m.channel.schema.as_ref().unwrap().name;
            let v: Value = match scene3d::message_type(schema) {
                Some(ty) => scene3d::decode(ty, &m.data).unwrap(),
                None if m.channel.message_encoding == "json" => {
                    serde_json::from_slice(&m.data).unwrap()
                }
                None => return Vec::new(),
            };
            let entries = match v.get("transforms") {
                Some(t) => t.as_array().unwrap().clone(),
                None => vec![v],
            };
            entries
                .into_iter()
                .map(|v| (m.channel.topic.clone(), m.log_time, v))
                .collect()
        })
        .collect()
}

/// The transforms of `topic` whose child frame is `child`.
fn transforms<'a>(
    msgs: &'a [(String, u64, Value)],
    topic: &str,
    child: &str,
) -> Vec<&'a (String, u64, Value)> {
    msgs.iter()
        .filter(|m| m.0 == topic && m.2["child_frame_id"] == child)
        .collect()
}

fn num(v: &Value, k: &str) -> f64 {
    v[k].as_f64().unwrap()
}

/// The row of `trace` at log time `ns` (its time rounded to whole ns).
fn row_at(trace: &Trace, ns: u64) -> usize {
    trace
        .time
        .iter()
        .position(|&t| (t * 1e9).round() as u64 == ns)
        .unwrap()
}

/// Rotation matrix of the rotation vector ψ (Rodrigues: I + sin a K + (1 − cos a) K²).
fn rodrigues(psi: [f64; 3]) -> [[f64; 3]; 3] {
    let a = (psi[0] * psi[0] + psi[1] * psi[1] + psi[2] * psi[2]).sqrt();
    let k = [psi[0] / a, psi[1] / a, psi[2] / a];
    let kx = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let k2: f64 = (0..3).map(|m| kx[i][m] * kx[m][j]).sum();
            r[i][j] = f64::from(u8::from(i == j)) + a.sin() * kx[i][j] + (1.0 - a.cos()) * k2;
        }
    }
    r
}

/// A transform message applied to a point: t + R(q)·p, R from the quaternion by its
/// matrix formula.
fn apply(tf: &Value, p: [f64; 3]) -> [f64; 3] {
    let (t, r) = (&tf["translation"], &tf["rotation"]);
    let (x, y, z, w) = (num(r, "x"), num(r, "y"), num(r, "z"), num(r, "w"));
    let m = [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - z * w),
            2.0 * (x * z + y * w),
        ],
        [
            2.0 * (x * y + z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - x * w),
        ],
        [
            2.0 * (x * z - y * w),
            2.0 * (y * z + x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ];
    let o = [num(t, "x"), num(t, "y"), num(t, "z")];
    std::array::from_fn(|i| o[i] + (0..3).map(|j| m[i][j] * p[j]).sum::<f64>())
}

#[test]
fn the_oscillator_moves_in_x_and_y_in_every_run_and_the_reference() {
    // The paper's PEPO at azimuth 30°: fe's 3D model and the plan reference. The mass is
    // drawn as a cube on its contact; its centre is at the trace's (rel_disp, rel_disp_y)
    // in its ground frame, on the line at 30° from x (the motion is one-directional).
    let result = run_case(case("spatial/pepo-pulse-azimuth30")).unwrap();
    let out = tempfile::tempdir().unwrap();
    let dir = write_case_outputs(&result, out.path()).unwrap();
    let path = dir.join("pepo-pulse-azimuth30.mcap");
    let m = read_mcap(&path).unwrap();
    let msgs = json_messages(&path);
    assert!(m.metadata.contains_key("scene3d"), "a 3D view");
    let tan30 = 30f64.to_radians().tan();
    // measured largest |y − x·tan 30°|: fe 8.8e-15 m, reference 5.1e-17 m of a 9.26 mm
    // peak (round-off of a motion along 30°)
    for (label, limit) in [("fe/single", 1e-14), ("reference", 1e-16)] {
        let trace = m.state(&format!("/{label}/state")).unwrap();
        let bodies = transforms(
            &msgs,
            &format!("/{label}/transform"),
            &format!("{label}/body"),
        );
        assert!(
            bodies.len() > 100,
            "{label}: {} body transforms",
            bodies.len()
        );
        let (x, y) = (
            trace.column("rel_disp").unwrap(),
            trace.column("rel_disp_y").unwrap(),
        );
        let (mut largest, mut off) = (0.0_f64, 0.0_f64);
        for b in &bodies {
            let i = row_at(trace, b.1);
            let t = &b.2["translation"];
            assert_eq!(
                (num(t, "x"), num(t, "y")),
                (x[i], y[i]),
                "{label} row {i} at {} ns: {t}",
                b.1
            );
            off = off.max((num(t, "y") - x[i] * tan30).abs());
            largest = largest.max(x[i].hypot(y[i]));
        }
        println!("{label}: largest |y − x·tan 30°| {off:.3e} m of {largest:.4e} m");
        assert!(largest > 9e-3, "{label}: the mass moves ({largest} m)");
        assert!(off < limit, "{label}: off the 30° line by {off} m");
    }
    // The static scene: the cube (5 × the largest displacement of any run, half-size), its
    // one contact and centre of mass; the reference a translucent ghost.
    let scene = |label: &str| {
        let s = msgs
            .iter()
            .find(|m| m.0 == format!("/{label}/scene"))
            .unwrap();
        s.2["entities"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["id"] == "body")
            .unwrap()
            .clone()
    };
    // every run of the case (fe, rapier) and the reference
    assert!(m.states.len() >= 3, "{} state channels", m.states.len());
    let peak = m
        .states
        .iter()
        .map(|(_, t)| {
            let (x, y) = (
                t.column("rel_disp").unwrap(),
                t.column("rel_disp_y").unwrap(),
            );
            (0..x.len()).map(|i| x[i].hypot(y[i])).fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    let fe = scene("fe/single");
    let size = &fe["cubes"][0]["size"];
    for k in ["x", "y", "z"] {
        assert_eq!(num(size, k), 10.0 * peak, "cube {k}");
    }
    assert_eq!(fe["spheres"].as_array().unwrap().len(), 2, "contact + CM");
    assert!(num(&fe["cubes"][0]["color"], "a") > 0.5);
    assert_eq!(num(&scene("reference")["cubes"][0]["color"], "a"), 0.25);
}

const GRID_CASE: &str = r#"
# Test-only RPEPO-like body on a 4 × 3 grid of supports in a 3D scene, for the 3D view.
title = "Rocking body on a grid, 3D view test"
source = "AL-Shawaf & Rahman, Fig. 7: RPEPO geometry, extended to a grid"
requirement = "rockslide shall draw a 3D scene's body, supports and ground in Foxglove's 3D panel"
[model]
kind = "rocking-body"
mass = 1.0e6          # kg
gravity = 9.81        # m/s²
cm_height = 0.625     # m
half_width = 0.5      # m
half_depth = 0.3      # m
supports = 4
support_rows = 3
[model.contact]
kx = 2.4e9            # N/m
kz = 3.94784e8        # N/m
mu = 0.5
[excitation]
kind = "ground-displacement"
shape = "sine-pulse"
amplitude = 0.001     # m
omega = 31.41592653589793
cycles = 1
[excitation.y]
shape = "sine-pulse"
amplitude = 0.002     # m
omega = 31.41592653589793
cycles = 1
[run]
duration = 0.05
dt = 0.0005
"#;

/// A trace of a body that slides, tilts about x and y and twists about z, on a ground
/// moving in x and y, with forces along x and y (values made up, smooth in t).
fn grid_trace() -> Trace {
    let chans = [
        &q::CM_X,
        &q::CM_Y,
        &q::CM_Z,
        &q::ROTATION,
        &q::ROTATION_X,
        &q::ROTATION_Z,
        &q::GROUND_DISP,
        &q::GROUND_DISP_Y,
        &q::RESISTANCE,
        &q::RESISTANCE_Y,
        &q::NORMAL,
    ];
    let mut trace = Trace::with_channels(&chans, 101);
    for i in 0..=100 {
        let t = i as f64 * 0.0005;
        let s = (40.0 * t).sin();
        trace.push(
            t,
            &[
                0.003 * s,
                -0.002 * s,
                0.0005 * s * s,
                0.04 * s,
                -0.03 * s,
                0.02 * (25.0 * t).sin(),
                0.001 * (31.4 * t).sin(),
                0.002 * (31.4 * t).sin(),
                2.0e6 * (9.0 * t).cos(),
                -1.0e6 * (9.0 * t).cos(),
                9.81e6,
            ],
        );
    }
    trace
}

fn grid_result(trace: Trace) -> CaseResult {
    let c: Case = parse_case(Path::new("grid-3d.toml"), GRID_CASE).unwrap();
    let run = Run {
        engine: "fe",
        variant: "exact".into(),
        arrangement: Default::default(),
        dt: 0.0005,
        settings: Vec::new(),
        stats: rockslide::engine::SolverStats::steps(trace.len() as u64),
        findings: Vec::new(),
        trace,
        status: RunStatus::Completed,
        wall_seconds: 0.0,
    };
    CaseResult {
        run_responses: vec![responses(&run.trace)],
        invariants: Vec::new(),
        envelopes: Vec::new(),
        azimuths: None,
        history_errors: vec![None],
        runs: vec![run],
        case: c,
        not_applicable: Vec::new(),
        reference: Err("none in this test".into()),
        checks: Vec::new(),
    }
}

#[test]
fn a_body_on_a_grid_tilts_twists_and_slides_with_its_ground_in_both_directions() {
    let (b, d, h) = (0.5, 0.3, 0.625);
    let trace = grid_trace();
    let out = tempfile::tempdir().unwrap();
    let dir = write_case_outputs(&grid_result(trace.clone()), out.path()).unwrap();
    let path = dir.join("grid-3d.mcap");
    let msgs = json_messages(&path);
    // Every support of the 4 × 3 grid at (x_i, y_j, −h) in the body frame, and the CM.
    let scene = msgs.iter().find(|m| m.0 == "/fe/exact/scene").unwrap();
    let ents = scene.2["entities"].as_array().unwrap();
    let body = ents.iter().find(|e| e["id"] == "body").unwrap();
    let size = &body["cubes"][0]["size"];
    assert_eq!(
        (num(size, "x"), num(size, "y"), num(size, "z")),
        (2.0 * b, 2.0 * d, 2.0 * h)
    );
    let spheres = body["spheres"].as_array().unwrap();
    assert_eq!(spheres.len(), 4 * 3 + 1);
    let mut drawn: Vec<(f64, f64, f64)> = spheres[..12]
        .iter()
        .map(|s| {
            let p = &s["pose"]["position"];
            (num(p, "x"), num(p, "y"), num(p, "z"))
        })
        .collect();
    drawn.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let mut grid = Vec::new();
    for i in 0..4 {
        for j in 0..3 {
            let x = -b + 2.0 * b * i as f64 / 3.0;
            let y = -d + 2.0 * d * j as f64 / 2.0;
            grid.push((x, y, -h));
        }
    }
    grid.sort_by(|a, b| a.partial_cmp(b).unwrap());
    for (p, g) in drawn.iter().zip(&grid) {
        assert!(
            (p.0 - g.0).abs() < 1e-15 && (p.1 - g.1).abs() < 1e-15 && p.2 == g.2,
            "{p:?} vs {g:?}"
        );
    }
    // The ground's ticks run across x and across y (a grid).
    let ground = ents.iter().find(|e| e["id"] == "ground").unwrap();
    let along_y = ground["cubes"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| num(&c["pose"]["orientation"], "z") != 0.0)
        .count();
    assert!(along_y >= 3, "{along_y} ticks along y");

    let bodies = transforms(&msgs, "/fe/exact/transform", "fe/exact/body");
    let grounds = transforms(&msgs, "/fe/exact/transform", "fe/exact/ground");
    let forces: Vec<_> = msgs.iter().filter(|m| m.0 == "/fe/exact/forces").collect();
    assert_eq!(bodies.len(), 51);
    assert_eq!(grounds.len(), 51);
    let col = |k: &str| trace.column(k).unwrap();
    let mut largest_twist = 0.0_f64;
    for ((bt, gt), f) in bodies.iter().zip(&grounds).zip(&forces) {
        let i = row_at(&trace, bt.1);
        // ground: (ground_disp, lane 0 + ground_disp_y, 0)
        let g = &gt.2["translation"];
        assert_eq!(
            (num(g, "x"), num(g, "y"), num(g, "z")),
            (col("ground_disp")[i], col("ground_disp_y")[i], 0.0)
        );
        // body: a support corner p goes to CM + R(ψ)·p, ψ = (rotation_x, −rotation, rotation_z)
        let psi = [
            col("rotation_x")[i],
            -col("rotation")[i],
            col("rotation_z")[i],
        ];
        let cm = [col("cm_x")[i], col("cm_y")[i], h + col("cm_z")[i]];
        for p in [[b, d, -h], [-b, d, -h], [-b, -d, -h], [0.0, 0.0, 0.0]] {
            let expected: [f64; 3] = if psi == [0.0; 3] {
                std::array::from_fn(|k| cm[k] + p[k])
            } else {
                let r = rodrigues(psi);
                std::array::from_fn(|k| cm[k] + (0..3).map(|j| r[k][j] * p[j]).sum::<f64>())
            };
            let got = apply(&bt.2, p);
            // measured: ≤ 2.3e-16 m (rounding of the quaternion and matrix products)
            for k in 0..3 {
                assert!(
                    (got[k] - expected[k]).abs() < 1e-14,
                    "row {i}: {got:?} vs {expected:?}"
                );
            }
        }
        largest_twist = largest_twist.max(psi[2].abs());
        // the tangential arrow points along the force on the body, (−R_x, −R_y)
        let arrows = f.2["entities"][0]["arrows"].as_array().unwrap();
        let (fx, fy) = (-col("resistance")[i], -col("resistance_y")[i]);
        let shear = &arrows[1];
        let dir = apply(
            &serde_json::json!({
                "translation": { "x": 0.0, "y": 0.0, "z": 0.0 },
                "rotation": shear["pose"]["orientation"]
            }),
            [1.0, 0.0, 0.0],
        );
        let norm = fx.hypot(fy);
        assert!(
            (dir[0] - fx / norm).abs() < 1e-12 && (dir[1] - fy / norm).abs() < 1e-12,
            "row {i}: arrow {dir:?}, force ({fx}, {fy})"
        );
    }
    assert!(largest_twist > 0.01, "the body twists");
}

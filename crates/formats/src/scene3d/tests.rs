//! The 3D view's messages: CDR round trips, the direct encodings against the JSON ones,
//! the definitions.

use serde_json::json;

use rockslide_core::trace::Trace;

use super::*;

#[test]
fn a_frame_transform_reads_back_bit_for_bit_and_aligned() {
    let tf = json!({ "transforms": [transform(
        1_500_000_001,
        "world",
        "fe/single/ground",
        (0.1 + 0.2, -3.0, f64::MIN_POSITIVE),
        [0.0, -0.25f64.sin(), 0.0, 0.25f64.cos()],
    )] });
    let mut buf = Vec::new();
    encode(&FRAME_TRANSFORMS, &tf, &mut buf);
    // header 4, count 4, time 8, "world\0" 4 + 6 → pad 2, "fe/single/ground\0"
    // 4 + 17 → at 49, pad to 56 (8-aligned past the header: 52), 7 float64
    assert_eq!(buf.len(), 4 + 4 + 8 + 4 + 6 + 2 + 4 + 17 + 3 + 7 * 8);
    assert_eq!(decode(&FRAME_TRANSFORMS, &buf).unwrap(), tf);
    assert!(decode(&FRAME_TRANSFORMS, &buf[..buf.len() - 1]).is_err());
    let mut longer = buf.clone();
    longer.push(0);
    assert!(decode(&FRAME_TRANSFORMS, &longer).is_err());
}

/// A trace of `keys` with rows from `rows` (time = row index · 0.01 s).
fn trace_of(keys: &[&str], rows: &[&[f64]]) -> Trace {
    let channels: Vec<_> = keys
        .iter()
        .map(|k| rockslide_core::trace::q::by_key(k).unwrap())
        .collect();
    let mut t = Trace::with_channels(&channels, rows.len());
    for (i, r) in rows.iter().enumerate() {
        t.push(i as f64 * 0.01, r);
    }
    t
}

#[test]
fn direct_encodings_equal_the_json_messages() {
    let planar = Geometry {
        kind: "rocking-body",
        cm_height: 1.25,
        half_width: 0.3,
        half_height: 1.25,
        half_depth: None,
        supports: vec![[-0.3, 0.0], [0.3, 0.0]],
        weight: 9810.0,
    };
    let spatial = Geometry {
        kind: "rigid-block",
        half_depth: Some(0.2),
        ..planar.clone()
    };
    let (nan, inf) = (f64::NAN, f64::INFINITY);
    // rel_disp, rotation, ground_disp, normal, base_shear: both signs of each force,
    // forces too small to draw, a ground displacement that is not finite
    let rocking = trace_of(
        &[
            "rel_disp",
            "rotation",
            "ground_disp",
            "normal",
            "base_shear",
        ],
        &[
            &[0.0, 0.0, 0.0, 9810.0, 0.0],
            &[0.1 + 0.2, -0.013, 0.02, 9000.5, 123.25],
            &[-0.7, 0.25, nan, -5.0, -4000.0],
            &[1e-3, 1e-7, inf, 1e-12, 1e-13],
            &[2.5, -0.4, -1.5, nan, inf],
        ],
    );
    // a sliding block without base shear: −resistance along x
    let sliding = trace_of(
        &["rel_disp", "ground_disp", "normal", "resistance"],
        &[&[0.0, 0.0, 9810.0, 0.0], &[0.5, -0.25, 9810.0, -3000.0]],
    );
    // a 3D scene: the resultant of base shear and −resistance_y, a rotation vector
    let plan = trace_of(
        &[
            "rel_disp",
            "rel_disp_y",
            "cm_z",
            "rotation_x",
            "rotation",
            "rotation_z",
            "ground_disp",
            "ground_disp_y",
            "normal",
            "base_shear",
            "resistance_y",
        ],
        &[
            &[0.0; 11],
            &[
                0.1, -0.2, 1e-3, 0.01, 0.02, -0.03, 0.4, -0.5, 9000.0, 100.0, 200.0,
            ],
            &[
                -0.3, 0.6, 0.0, 1e-6, 0.0, 2e-5, nan, 0.1, 9810.0, -700.0, 0.0,
            ],
            &[0.2, 0.1, 0.0, 0.0, 0.3, 0.0, 0.0, 0.0, 9810.0, 0.0, -50.0],
        ],
    );
    let cases = [
        (&rocking, &planar, "fe/double"),
        (&sliding, &planar, "predictor-corrector/default"),
        (&plan, &spatial, "rapier/plan"),
    ];
    let (mut json_bytes, mut direct) = (Vec::new(), Vec::new());
    let mut compared = 0;
    for (trace, g, label) in cases {
        let (ground, body) = frames(label);
        for i in 0..trace.len() {
            let Some(p) = Pose::at(trace, i, g) else {
                continue;
            };
            let ns = 1_000_000_000 * i as u64 + 7;
            let lane_y = 0.75 * i as f64;
            let tfs = frame_transforms(ns, trace, i, lane_y, &p, label);
            encode(&FRAME_TRANSFORMS, &tfs, &mut json_bytes);
            encode_frame_transforms(ns, trace, i, lane_y, &p, (&ground, &body), &mut direct);
            assert_eq!(direct, json_bytes, "{label} row {i}: transforms");
            encode(
                &SCENE_UPDATE,
                &forces(trace, i, ns, g, &p, label),
                &mut json_bytes,
            );
            encode_forces(trace, i, ns, g, &p, &ground, &mut direct);
            assert_eq!(direct, json_bytes, "{label} row {i}: forces");
            compared += 1;
        }
    }
    assert_eq!(compared, 5 + 2 + 4);
}

#[test]
fn definitions_name_each_dependency_once() {
    let d = definition(&SCENE_UPDATE);
    assert!(d.starts_with(
        "foxglove_msgs/SceneEntityDeletion[] deletions\nfoxglove_msgs/SceneEntity[] entities\n"
    ));
    assert_eq!(d.matches("\nMSG: geometry_msgs/Pose\n").count(), 1);
    assert_eq!(d.matches("MSG: ").count(), 18);
    assert_eq!(SCENE_UPDATE.schema_name(), "foxglove_msgs/msg/SceneUpdate");
    assert_eq!(
        message_type("foxglove_msgs/msg/FrameTransforms").map(|m| m.name),
        Some("foxglove_msgs/FrameTransforms")
    );
}

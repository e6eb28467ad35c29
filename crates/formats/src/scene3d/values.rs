//! The JSON building blocks of the messages: times, vectors, poses, colours (one lane
//! colour per run), entities and a run's frame names.

use serde_json::{Value, json};

/// The label of the reference's run, drawn as a ghost.
use rockslide_core::case::REFERENCE_LABEL;

/// Foxglove time `{sec, nsec}` from nanoseconds (the JSON `foxglove.Log`).
pub fn time_json(ns: u64) -> Value {
    json!({ "sec": ns / 1_000_000_000, "nsec": ns % 1_000_000_000 })
}

/// ROS 2 time `{sec, nanosec}` (`builtin_interfaces/Time`) from nanoseconds: the 3D view's
/// CDR messages.
pub fn ros_time(ns: u64) -> Value {
    json!({ "sec": ns / 1_000_000_000, "nanosec": ns % 1_000_000_000 })
}

pub(super) fn vec3(x: f64, y: f64, z: f64) -> Value {
    json!({ "x": x, "y": y, "z": z })
}

pub(super) fn quat(q: [f64; 4]) -> Value {
    json!({ "x": q[0], "y": q[1], "z": q[2], "w": q[3] })
}

pub(super) fn pose(p: (f64, f64, f64), q: [f64; 4]) -> Value {
    json!({ "position": vec3(p.0, p.1, p.2), "orientation": quat(q) })
}

pub(super) fn color(c: [f64; 4]) -> Value {
    json!({ "r": c[0], "g": c[1], "b": c[2], "a": c[3] })
}

pub(super) const IDENTITY: [f64; 4] = [0.0, 0.0, 0.0, 1.0];
/// Arrow pointing +z (rotation −90° about +y maps +x to +z).
pub(super) const UP: [f64; 4] = [
    0.0,
    -std::f64::consts::FRAC_1_SQRT_2,
    0.0,
    std::f64::consts::FRAC_1_SQRT_2,
];
/// Arrow pointing −x (180° about +z).
pub(super) const LEFT: [f64; 4] = [0.0, 0.0, 1.0, 0.0];
/// Arrow pointing +y (90° about +z): the ground's ticks along y.
pub(super) const ALONG_Y: [f64; 4] = [
    0.0,
    0.0,
    std::f64::consts::FRAC_1_SQRT_2,
    std::f64::consts::FRAC_1_SQRT_2,
];

/// Lane colours, one per run (colour-blind-safe Okabe–Ito palette).
const PALETTE: [[f64; 3]; 7] = [
    [0.0, 0.447, 0.698],
    [0.835, 0.369, 0.0],
    [0.0, 0.620, 0.451],
    [0.800, 0.475, 0.655],
    [0.902, 0.624, 0.0],
    [0.337, 0.706, 0.914],
    [0.941, 0.894, 0.259],
];

/// The colour of lane `i`, with alpha `a`.
pub fn lane_color(i: usize, a: f64) -> [f64; 4] {
    let c = PALETTE[i % PALETTE.len()];
    [c[0], c[1], c[2], a]
}

/// The body's colour: its lane's, translucent (a ghost) for the reference.
pub(super) fn body_color(lane: usize, label: &str) -> [f64; 4] {
    if label == REFERENCE_LABEL {
        [0.3, 0.3, 0.3, 0.25]
    } else {
        lane_color(lane, 0.55)
    }
}

/// One scene entity: the primitive lists `prims` gives (the others are empty in the CDR
/// message), living until replaced.
pub(super) fn entity(ns: u64, frame: &str, id: &str, frame_locked: bool, prims: Value) -> Value {
    let mut e = json!({
        "timestamp": ros_time(ns),
        "frame_id": frame,
        "id": id,
        "frame_locked": frame_locked,
    });
    if let (Some(e), Value::Object(p)) = (e.as_object_mut(), prims) {
        e.extend(p);
    }
    e
}

/// The frame names of a run label.
pub fn frames(label: &str) -> (String, String) {
    (format!("{label}/ground"), format!("{label}/body"))
}

//! A run's frames at one row: the ground's and the body's transforms, as a JSON
//! `FrameTransforms`, and the same message written straight in CDR.

use serde_json::{Value, json};

use rockslide_core::trace::Trace;

use super::Pose;
use super::codec::CdrOut;
use super::values::{IDENTITY, frames, quat, ros_time, vec3};

/// One `FrameTransform` (an element of a `FrameTransforms` message).
pub fn transform(ns: u64, parent: &str, child: &str, t: (f64, f64, f64), q: [f64; 4]) -> Value {
    json!({
        "timestamp": ros_time(ns),
        "parent_frame_id": parent,
        "child_frame_id": child,
        "translation": vec3(t.0, t.1, t.2),
        "rotation": quat(q)
    })
}

/// The body's transform from its pose.
pub fn body_transform(ns: u64, p: &Pose, label: &str) -> Value {
    let (ground, body) = frames(label);
    transform(ns, &ground, &body, (p.x, p.y, p.z), p.quaternion())
}

/// The ground's translation at row `i`: its displacement (`ground_disp`,
/// `ground_disp_y`; 0 where the trace has none or it is not finite) and the lane.
fn ground_translation(trace: &Trace, i: usize, lane_y: f64) -> (f64, f64, f64) {
    let disp = |key: &str| {
        trace
            .column(key)
            .map(|c| c[i])
            .filter(|x| x.is_finite())
            .unwrap_or(0.0)
    };
    let (xg, yg) = (disp("ground_disp"), disp("ground_disp_y"));
    (xg, lane_y + yg, 0.0)
}

/// The ground's transform: its displacement (`ground_disp`, `ground_disp_y`; 0 where
/// the trace has none) and the lane.
pub fn ground_transform(ns: u64, trace: &Trace, i: usize, lane_y: f64, label: &str) -> Value {
    let (ground, _) = frames(label);
    transform(
        ns,
        "world",
        &ground,
        ground_translation(trace, i, lane_y),
        IDENTITY,
    )
}

/// One frame of a run's transforms at row `i`, as one `FrameTransforms` message: the
/// ground's, then the body's.
pub fn frame_transforms(
    ns: u64,
    trace: &Trace,
    i: usize,
    lane_y: f64,
    p: &Pose,
    label: &str,
) -> Value {
    json!({ "transforms": [
        ground_transform(ns, trace, i, lane_y, label),
        body_transform(ns, p, label),
    ] })
}

/// The CDR bytes of [`frame_transforms`] (`foxglove_msgs/msg/FrameTransforms`) into
/// `buf`, built without a JSON value; `(ground, body)` are the run's frames
/// ([`frames`]). The same bytes as [`encode`](super::encode) of the JSON message.
pub fn encode_frame_transforms(
    ns: u64,
    trace: &Trace,
    i: usize,
    lane_y: f64,
    p: &Pose,
    (ground, body): (&str, &str),
    buf: &mut Vec<u8>,
) {
    let mut out = CdrOut::start(buf);
    out.u32(2);
    let mut one = |parent: &str, child: &str, t: (f64, f64, f64), q: [f64; 4]| {
        out.time(ns);
        out.str(parent);
        out.str(child);
        out.xyz(t);
        out.four(q);
    };
    one(
        "world",
        ground,
        ground_translation(trace, i, lane_y),
        IDENTITY,
    );
    one(ground, body, (p.x, p.y, p.z), p.quaternion());
}

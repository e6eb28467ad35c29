//! The static scene of a run, published once: ground slab and ticks, body, supports,
//! label, and the world's datum post.

use serde_json::{Value, json};

use super::Geometry;
use super::values::{ALONG_Y, IDENTITY, body_color, color, entity, frames, pose, vec3};

/// The ground's tick marks every `tick` from −8 to 8 ticks: across x (a planar scene),
/// and across y too in a 3D scene (a grid, so that the ground's motion shows both ways).
fn ground_ticks(g: &Geometry, tick: f64, lane_w: f64) -> Vec<Value> {
    let mark = |p: (f64, f64, f64), q: [f64; 4], len: f64| {
        json!({
            "pose": pose(p, q),
            "size": vec3(0.02 * g.half_width, len, 0.001),
            "color": color([0.15, 0.15, 0.15, 1.0])
        })
    };
    let mut ticks: Vec<Value> = (-8..=8)
        .map(|k| mark((k as f64 * tick, 0.0, 0.0005), IDENTITY, lane_w))
        .collect();
    if g.is_spatial() {
        let n = (0.5 * lane_w / tick).floor() as i32;
        let len = 16.0 * tick;
        ticks.extend((-n..=n).map(|k| mark((0.0, k as f64 * tick, 0.0005), ALONG_Y, len)));
    }
    ticks
}

/// The static scene of one run (published once at t = 0, on its own topic so that a
/// viewer seeking anywhere still has it): ground slab with ticks every max(b, h) (so the
/// ground's motion shows; a grid in a 3D scene), the body, its centre of mass, its
/// supports (every support of a 3D grid), a label.
pub fn static_scene(g: &Geometry, lane: usize, label: &str) -> Value {
    let (ground, body) = frames(label);
    let c = body_color(lane, label);
    let h_body = 2.0 * g.half_height;
    let slab_len = 16.0 * g.half_width.max(g.half_height) + g.half_width;
    let slab_t = 0.04 * h_body;
    let lane_w = 0.8 * g.lane_spacing();
    let tick = g.half_width.max(g.half_height);
    let mut ground_cubes = vec![json!({
        "pose": pose((0.0, 0.0, -0.5 * slab_t), IDENTITY),
        "size": vec3(slab_len, lane_w, slab_t),
        "color": color([0.62, 0.62, 0.62, 1.0])
    })];
    ground_cubes.extend(ground_ticks(g, tick, lane_w));
    let supports: Vec<Value> = g
        .supports
        .iter()
        .map(|&[x, y]| {
            json!({
                "pose": pose((x, y, -g.cm_height), IDENTITY),
                "size": vec3(0.08 * g.half_width, 0.08 * g.half_width, 0.08 * g.half_width),
                "color": color([0.1, 0.1, 0.1, 1.0])
            })
        })
        .collect();
    let cm = 0.12 * g.half_width.min(g.half_height);
    let entities = vec![
        entity(0, &ground, "ground", true, json!({ "cubes": ground_cubes })),
        entity(
            0,
            &ground,
            "label",
            true,
            json!({ "texts": [{
                "pose": pose((0.0, 0.0, g.cm_height + 1.3 * g.half_height), IDENTITY),
                "billboard": true, "font_size": 14.0, "scale_invariant": true,
                "color": color([0.0, 0.0, 0.0, 1.0]), "text": label
            }] }),
        ),
        entity(
            0,
            &body,
            "body",
            true,
            json!({
                "cubes": [{
                    "pose": pose((0.0, 0.0, 0.0), IDENTITY),
                    "size": vec3(2.0 * g.half_width, g.depth(), h_body),
                    "color": color(c)
                }],
                "spheres": supports.into_iter().chain(std::iter::once(json!({
                    "pose": pose((0.0, 0.0, 0.0), IDENTITY),
                    "size": vec3(cm, cm, cm),
                    "color": color([0.0, 0.0, 0.0, 1.0])
                }))).collect::<Vec<_>>()
            }),
        ),
    ];
    json!({ "deletions": [], "entities": entities })
}

/// A fixed datum post in the world frame at x = 0 (against which the ground's motion
/// shows), on the scene topic of the first run.
pub fn datum(g: &Geometry) -> Value {
    let h = 2.0 * g.half_height;
    entity(
        0,
        "world",
        "datum",
        false,
        json!({ "cubes": [{
            "pose": pose((0.0, -0.6 * g.lane_spacing(), 0.5 * h), IDENTITY),
            "size": vec3(0.02 * g.half_width, 0.02 * g.half_width, h),
            "color": color([0.8, 0.1, 0.1, 1.0])
        }] }),
    )
}

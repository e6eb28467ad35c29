//! The 3D view of a trace for Foxglove's 3D panel: the scene's geometry (ground, block,
//! supports), the block's pose rebuilt from the trace's `cm_x`/`cm_z`/`rotation` channels,
//! and the total support forces as arrows — encoded as the well-known Foxglove schemas
//! `foxglove.SceneUpdate`, `foxglove.FrameTransform` and `foxglove.Log` in JSON.
//!
//! Conventions (Foxglove's: x right, y into the screen, z up). The motion is in the x–z
//! plane; a counter-clockwise rotation θ as seen with x right and z up (the trace's sign
//! convention) is a rotation by −θ about +y. Each run gets its own lane along y so that
//! engines can be compared side by side. Frames, per run label `L`:
//!
//! ```text
//! world ─▶ L/ground   translation (ground_disp, lane y, 0): the moving ground
//!          └▶ L/body  translation (x_cm, 0, z_cm0 + cm_z), rotation θ: origin at the centre of mass
//! ```
//!
//! The JSON schemas below are written here from the field lists of Foxglove's message
//! schema documentation (only the fields this module emits are described in detail); the
//! 3D panel recognises the messages by schema *name*. They stay inside the JSON-schema
//! subset Foxglove's reader turns into message definitions: every field has one concrete
//! `type`, every object its `properties`, no `$ref`.

use serde_json::{Value, json};

use crate::case::Model;

use super::Trace;

/// The geometry of a scene that has one, in metres, with the static pose of its body.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// `rocking-body` or `rigid-block`.
    pub kind: &'static str,
    /// Height of the centre of mass above the base when the body rests on the ground, m.
    pub cm_height: f64,
    /// Half-width of the base, m.
    pub half_width: f64,
    /// Half of the drawn body's height, m (the body is drawn centred on its centre of mass).
    pub half_height: f64,
    /// Support abscissae relative to the base centre O, m (empty: a rigid base).
    pub supports: Vec<f64>,
    /// Weight M·g (or M where g = 0), N: sets the force-arrow scale.
    pub weight: f64,
}

impl Geometry {
    /// The geometry of a model, or `None` for a scene without one (`Model::has_geometry`).
    pub fn of(model: &Model) -> Option<Self> {
        if !model.has_geometry() {
            return None;
        }
        let weight = |m: f64, g: f64| if g > 0.0 { m * g } else { m };
        match model {
            Model::Oscillator(_) => None,
            Model::RockingBody(r) => Some(Self {
                kind: "rocking-body",
                cm_height: r.cm_height,
                half_width: r.half_width,
                half_height: r.cm_height,
                supports: r.support_positions(),
                weight: weight(r.mass, r.gravity),
            }),
            Model::RigidBlock(b) => Some(Self {
                kind: "rigid-block",
                cm_height: b.half_height,
                half_width: b.half_width,
                half_height: b.half_height,
                supports: Vec::new(),
                weight: weight(b.mass, b.gravity),
            }),
        }
    }

    /// Depth of the drawn body along y, m.
    pub fn depth(&self) -> f64 {
        self.half_width
    }

    /// Distance between the lanes of successive runs along y, m.
    pub fn lane_spacing(&self) -> f64 {
        3.0 * self.depth()
    }

    /// Length of a force arrow per newton, m/N: the weight is drawn as long as the
    /// centre of mass is high.
    pub fn arrow_scale(&self) -> f64 {
        self.cm_height / self.weight
    }
}

/// The pose of a body in its ground frame at one row of a trace.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Horizontal position of the centre of mass relative to the ground, m.
    pub x: f64,
    /// Height of the centre of mass above the ground surface, m.
    pub z: f64,
    /// Rotation, rad, counter-clockwise positive (x right, z up).
    pub theta: f64,
}

impl Pose {
    /// Rebuild the pose at row `i` from the channels the trace has: `cm_x` (else the base
    /// point's `rel_disp` moved to the centre of mass through the rotation), `cm_z`
    /// (else 0) and `rotation` (else 0). `None` when the trace has no horizontal position
    /// or a value is not finite (a diverged run's last rows).
    pub fn at(trace: &Trace, i: usize, g: &Geometry) -> Option<Self> {
        let get = |key: &str| trace.column(key).map(|c| c[i]);
        let theta = get("rotation").unwrap_or(0.0);
        let x = match (get("cm_x"), get("rel_disp")) {
            (Some(x), _) => x,
            // O = CM + R(θ)·(0, −h): x_O = x_cm + h·sin θ
            (None, Some(x_o)) => x_o - g.cm_height * theta.sin(),
            (None, None) => return None,
        };
        let z = g.cm_height + get("cm_z").unwrap_or(0.0);
        let p = Self { x, z, theta };
        [x, z, theta].iter().all(|v| v.is_finite()).then_some(p)
    }

    /// Base centre O in the ground frame: CM + R(θ)·(0, −h) = (x + h sin θ, z − h cos θ).
    pub fn base_point(&self, g: &Geometry) -> (f64, f64) {
        (
            self.x + g.cm_height * self.theta.sin(),
            self.z - g.cm_height * self.theta.cos(),
        )
    }

    /// Orientation as a quaternion (x, y, z, w): rotation −θ about +y.
    pub fn quaternion(&self) -> [f64; 4] {
        let h = 0.5 * self.theta;
        [0.0, -h.sin(), 0.0, h.cos()]
    }
}

/// Whether a trace carries enough to draw its body (a horizontal position).
pub fn drawable(trace: &Trace) -> bool {
    trace.has("cm_x") || trace.has("rel_disp")
}

/// Foxglove time `{sec, nsec}` from nanoseconds.
pub fn time_json(ns: u64) -> Value {
    json!({ "sec": ns / 1_000_000_000, "nsec": ns % 1_000_000_000 })
}

fn vec3(x: f64, y: f64, z: f64) -> Value {
    json!({ "x": x, "y": y, "z": z })
}

fn quat(q: [f64; 4]) -> Value {
    json!({ "x": q[0], "y": q[1], "z": q[2], "w": q[3] })
}

fn pose(p: (f64, f64, f64), q: [f64; 4]) -> Value {
    json!({ "position": vec3(p.0, p.1, p.2), "orientation": quat(q) })
}

fn color(c: [f64; 4]) -> Value {
    json!({ "r": c[0], "g": c[1], "b": c[2], "a": c[3] })
}

const IDENTITY: [f64; 4] = [0.0, 0.0, 0.0, 1.0];
/// Arrow pointing +z (rotation −90° about +y maps +x to +z).
const UP: [f64; 4] = [
    0.0,
    -std::f64::consts::FRAC_1_SQRT_2,
    0.0,
    std::f64::consts::FRAC_1_SQRT_2,
];
/// Arrow pointing −x (180° about +z).
const LEFT: [f64; 4] = [0.0, 0.0, 1.0, 0.0];

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

/// One scene entity with every primitive list present (empty where unused), as the
/// Foxglove JSON readers expect.
fn entity(ns: u64, frame: &str, id: &str, frame_locked: bool, prims: Value) -> Value {
    let mut e = json!({
        "timestamp": time_json(ns),
        "frame_id": frame,
        "id": id,
        "lifetime": { "sec": 0, "nsec": 0 },
        "frame_locked": frame_locked,
        "metadata": [],
        "arrows": [], "cubes": [], "spheres": [], "cylinders": [],
        "lines": [], "triangles": [], "texts": [], "models": []
    });
    if let (Some(e), Some(p)) = (e.as_object_mut(), prims.as_object()) {
        for (k, v) in p {
            e.insert(k.clone(), v.clone());
        }
    }
    e
}

/// The frame names of a run label.
pub fn frames(label: &str) -> (String, String) {
    (format!("{label}/ground"), format!("{label}/body"))
}

/// The static scene of one run (published once at t = 0, on its own topic so that a
/// viewer seeking anywhere still has it): ground slab with ticks every max(b, h) (so the
/// ground's motion shows), the body, its centre of mass, its supports, a label.
pub fn static_scene(g: &Geometry, lane: usize, label: &str) -> Value {
    let (ground, body) = frames(label);
    let c = lane_color(lane, 0.55);
    let h_body = 2.0 * g.half_height;
    let slab_len = 16.0 * g.half_width.max(g.half_height) + g.half_width;
    let slab_t = 0.04 * h_body;
    let lane_w = 0.8 * g.lane_spacing();
    let tick = g.half_width.max(g.half_height);
    let ticks: Vec<Value> = (-8..=8)
        .map(|k| {
            json!({
                "pose": pose((k as f64 * tick, 0.0, 0.0005), IDENTITY),
                "size": vec3(0.02 * g.half_width, lane_w, 0.001),
                "color": color([0.15, 0.15, 0.15, 1.0])
            })
        })
        .collect();
    let mut ground_cubes = vec![json!({
        "pose": pose((0.0, 0.0, -0.5 * slab_t), IDENTITY),
        "size": vec3(slab_len, lane_w, slab_t),
        "color": color([0.62, 0.62, 0.62, 1.0])
    })];
    ground_cubes.extend(ticks);
    let supports: Vec<Value> = g
        .supports
        .iter()
        .map(|&x| {
            json!({
                "pose": pose((x, 0.0, -g.cm_height), IDENTITY),
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

/// The support-force arrows at one row, in the ground frame, drawn ending at the base
/// centre O: the total normal force (`normal`) upward and the total tangential force
/// on the body (`base_shear`, else −`resistance`) along x, length |F|·`arrow_scale`.
pub fn forces(trace: &Trace, i: usize, ns: u64, g: &Geometry, p: &Pose, label: &str) -> Value {
    let (ground, _) = frames(label);
    let (ox, oz) = p.base_point(g);
    let s = g.arrow_scale();
    let mut arrows = Vec::new();
    let mut arrow = |tail: (f64, f64), q: [f64; 4], len: f64, c: [f64; 4]| {
        if len.is_finite() && len > 1e-9 * g.cm_height {
            arrows.push(json!({
                "pose": pose((tail.0, 0.0, tail.1), q),
                "shaft_length": 0.8 * len,
                "shaft_diameter": 0.04 * g.half_width,
                "head_length": 0.2 * len,
                "head_diameter": 0.1 * g.half_width,
                "color": color(c)
            }));
        }
    };
    if let Some(n) = trace.column("normal").map(|c| c[i]) {
        let len = n.abs() * s;
        let (tail, q) = if n >= 0.0 {
            ((ox, oz - len), UP)
        } else {
            ((ox, oz), UP) // a tensile total cannot happen on compression-only supports
        };
        arrow(tail, q, len, [0.2, 0.6, 0.2, 1.0]);
    }
    let shear = trace
        .column("base_shear")
        .map(|c| c[i])
        .or_else(|| trace.column("resistance").map(|c| -c[i]));
    if let Some(f) = shear {
        let len = f.abs() * s;
        let (tail, q) = if f >= 0.0 {
            ((ox - len, oz), IDENTITY)
        } else {
            ((ox + len, oz), LEFT)
        };
        arrow(tail, q, len, [0.85, 0.1, 0.1, 1.0]);
    }
    json!({
        "deletions": [],
        "entities": [entity(ns, &ground, "forces", false, json!({ "arrows": arrows }))]
    })
}

/// A `foxglove.FrameTransform` message.
pub fn transform(ns: u64, parent: &str, child: &str, t: (f64, f64, f64), q: [f64; 4]) -> Value {
    json!({
        "timestamp": time_json(ns),
        "parent_frame_id": parent,
        "child_frame_id": child,
        "translation": vec3(t.0, t.1, t.2),
        "rotation": quat(q)
    })
}

/// The body's transform from its pose.
pub fn body_transform(ns: u64, p: &Pose, label: &str) -> Value {
    let (ground, body) = frames(label);
    transform(ns, &ground, &body, (p.x, 0.0, p.z), p.quaternion())
}

/// The ground's transform: its displacement (0 when the trace has none) and the lane.
pub fn ground_transform(ns: u64, trace: &Trace, i: usize, lane_y: f64, label: &str) -> Value {
    let (ground, _) = frames(label);
    let xg = trace
        .column("ground_disp")
        .map(|c| c[i])
        .filter(|x| x.is_finite())
        .unwrap_or(0.0);
    transform(ns, "world", &ground, (xg, lane_y, 0.0), IDENTITY)
}

/// A `foxglove.Log` message (levels: 2 info, 3 warning, 4 error).
pub fn log(ns: u64, level: u8, name: &str, message: &str) -> Value {
    json!({
        "timestamp": time_json(ns),
        "level": level,
        "message": message,
        "name": name,
        "file": "",
        "line": 0
    })
}

// The schemas are inline (no `$ref`), every object has `properties` and every field one
// concrete `type`: the subset Foxglove's JSON-schema reader accepts.

fn num(d: &str) -> Value {
    json!({ "type": "number", "description": d })
}

fn object(title: &str, props: Value) -> Value {
    json!({ "type": "object", "title": title, "properties": props })
}

fn array_of(item: Value) -> Value {
    json!({ "type": "array", "items": item })
}

fn time_schema(d: &str) -> Value {
    json!({
        "type": "object", "title": "time", "description": d,
        "properties": {
            "sec": { "type": "integer", "minimum": 0 },
            "nsec": { "type": "integer", "minimum": 0, "maximum": 999_999_999 }
        }
    })
}

fn vector3_schema() -> Value {
    object(
        "foxglove.Vector3",
        json!({ "x": num("x, m"), "y": num("y, m"), "z": num("z, m") }),
    )
}

fn quaternion_schema() -> Value {
    object(
        "foxglove.Quaternion",
        json!({ "x": num("x"), "y": num("y"), "z": num("z"), "w": num("w") }),
    )
}

fn pose_schema() -> Value {
    object(
        "foxglove.Pose",
        json!({ "position": vector3_schema(), "orientation": quaternion_schema() }),
    )
}

fn color_schema() -> Value {
    object(
        "foxglove.Color",
        json!({ "r": num("red, 0–1"), "g": num("green, 0–1"), "b": num("blue, 0–1"), "a": num("alpha, 0–1") }),
    )
}

fn shape_schema(title: &str) -> Value {
    object(
        title,
        json!({ "pose": pose_schema(), "size": vector3_schema(), "color": color_schema() }),
    )
}

fn entity_schema() -> Value {
    let unused = |title: &str| array_of(object(title, json!({})));
    object(
        "foxglove.SceneEntity",
        json!({
            "timestamp": time_schema("Timestamp of the entity (simulation time)"),
            "frame_id": { "type": "string" },
            "id": { "type": "string" },
            "lifetime": time_schema("0: until replaced"),
            "frame_locked": { "type": "boolean" },
            "metadata": array_of(object("foxglove.KeyValuePair", json!({
                "key": { "type": "string" }, "value": { "type": "string" }
            }))),
            "arrows": array_of(object("foxglove.ArrowPrimitive", json!({
                "pose": pose_schema(),
                "shaft_length": num("m"), "shaft_diameter": num("m"),
                "head_length": num("m"), "head_diameter": num("m"),
                "color": color_schema()
            }))),
            "cubes": array_of(shape_schema("foxglove.CubePrimitive")),
            "spheres": array_of(shape_schema("foxglove.SpherePrimitive")),
            "cylinders": unused("foxglove.CylinderPrimitive"),
            "lines": unused("foxglove.LinePrimitive"),
            "triangles": unused("foxglove.TriangleListPrimitive"),
            "texts": array_of(object("foxglove.TextPrimitive", json!({
                "pose": pose_schema(),
                "billboard": { "type": "boolean" },
                "font_size": num("px when scale_invariant"),
                "scale_invariant": { "type": "boolean" },
                "color": color_schema(),
                "text": { "type": "string" }
            }))),
            "models": unused("foxglove.ModelPrimitive")
        }),
    )
}

/// JSON schema of `foxglove.SceneUpdate` (the fields emitted here).
pub fn scene_update_schema() -> Value {
    json!({
        "title": "foxglove.SceneUpdate",
        "description": "An update to the entities displayed in a 3D scene",
        "type": "object",
        "properties": {
            "deletions": array_of(object("foxglove.SceneEntityDeletion", json!({
                "timestamp": time_schema("Timestamp of the deletion"),
                "type": { "type": "integer", "description": "0 matching id, 1 all" },
                "id": { "type": "string" }
            }))),
            "entities": array_of(entity_schema())
        }
    })
}

/// JSON schema of `foxglove.FrameTransform`.
pub fn frame_transform_schema() -> Value {
    json!({
        "title": "foxglove.FrameTransform",
        "description": "A transform between two reference frames in 3D space",
        "type": "object",
        "properties": {
            "timestamp": time_schema("Timestamp of the transform (simulation time)"),
            "parent_frame_id": { "type": "string" },
            "child_frame_id": { "type": "string" },
            "translation": vector3_schema(),
            "rotation": quaternion_schema()
        },
        "required": ["timestamp", "parent_frame_id", "child_frame_id", "translation", "rotation"]
    })
}

/// JSON schema of `foxglove.Log`.
pub fn log_schema() -> Value {
    json!({
        "title": "foxglove.Log",
        "description": "A log message",
        "type": "object",
        "properties": {
            "timestamp": time_schema("Timestamp of the log message (simulation time)"),
            "level": { "type": "integer", "description": "0 unknown, 1 debug, 2 info, 3 warning, 4 error, 5 fatal" },
            "message": { "type": "string" },
            "name": { "type": "string" },
            "file": { "type": "string" },
            "line": { "type": "integer", "minimum": 0 }
        },
        "required": ["timestamp", "level", "message", "name", "file", "line"]
    })
}

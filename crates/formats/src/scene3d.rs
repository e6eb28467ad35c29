//! The 3D view of a trace for Foxglove's 3D panel: the scene's geometry (ground, body,
//! supports), the body's pose rebuilt from the trace's channels, and the total support
//! forces as arrows — encoded as the well-known Foxglove schemas in their ROS 2 form,
//! `foxglove_msgs/msg/SceneUpdate` and `foxglove_msgs/msg/FrameTransforms` in CDR (a
//! third of the JSON bytes, compressed: docs/performance.md §2), and `foxglove.Log` in JSON.
//!
//! Conventions (Foxglove's: x right, y into the screen, z up). A planar scene moves in the
//! x–z plane; a counter-clockwise rotation θ as seen with x right and z up (the trace's
//! sign convention) is a rotation by −θ about +y. A bidirectional (3D) scene moves in x
//! and y: the centre of mass from `cm_x`/`cm_y` (else the base point's `rel_disp`/
//! `rel_disp_y`), the orientation from the rotation vector (`rotation_x`, −`rotation`,
//! `rotation_z`), the ground from `ground_disp`/`ground_disp_y`, its supports on the
//! `supports` × `support_rows` grid; the oscillator, which has no geometry, is drawn as a
//! cube on its one contact, sized from the largest displacement of the runs so that the
//! motion shows. Each run gets its own lane along y so that engines can be compared side
//! by side; the reference is drawn as a translucent ghost. Frames, per run label `L`:
//!
//! ```text
//! world ─▶ L/ground   translation (ground_disp, lane y + ground_disp_y, 0): the moving ground
//!          └▶ L/body  translation (x_cm, y_cm, z_cm0 + cm_z), rotation: origin at the centre of mass
//! ```
//!
//! The ROS 2 definitions below are written here from the field lists of Foxglove's message
//! schemas (foxglove_msgs); the 3D panel recognises the messages by schema *name*
//! (`foxglove_msgs/msg/…`, as it does `foxglove.…`) and decodes them with the definition
//! the file carries. The messages are built as JSON values with the definitions' field
//! names ([`encode`] writes them in CDR, [`decode`] reads them back); the two written at
//! every frame, the transforms and the force arrows, are also written straight in CDR
//! ([`encode_frame_transforms`], [`encode_forces`]: the same bytes without a JSON value
//! between, which cost most of the trace files' time).

use serde_json::{Value, json};

use rockslide_core::case::{Model, Scene};

use rockslide_core::trace::Trace;

use crate::cdr::CDR_LE_HEADER;

/// The label of the reference's run, drawn as a ghost.
const REFERENCE_LABEL: &str = "reference";

/// The geometry of a scene that has one, in metres, with the static pose of its body.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// `rocking-body`, `rigid-block` or `oscillator` (a 3D scene's mass, drawn as a cube).
    pub kind: &'static str,
    /// Height of the centre of mass above the base when the body rests on the ground, m.
    pub cm_height: f64,
    /// Half-width of the base along x, m.
    pub half_width: f64,
    /// Half of the drawn body's height, m (the body is drawn centred on its centre of mass).
    pub half_height: f64,
    /// Half-depth of the base along y in a 3D scene, m (`None`: a planar scene, drawn
    /// `half_width` deep).
    pub half_depth: Option<f64>,
    /// Support positions (x, y) relative to the base centre O, m (empty: a rigid base).
    pub supports: Vec<[f64; 2]>,
    /// Weight M·g (or M where g = 0), N: sets the force-arrow scale.
    pub weight: f64,
}

fn weight(m: f64, g: f64) -> f64 {
    if g > 0.0 { m * g } else { m }
}

impl Geometry {
    /// The geometry of a planar model, or `None` for a scene without one
    /// (`Model::has_geometry`).
    pub fn of(model: &Model) -> Option<Self> {
        if !model.has_geometry() {
            return None;
        }
        match model {
            Model::Oscillator(_) => None,
            Model::RockingBody(r) => Some(Self {
                kind: "rocking-body",
                cm_height: r.cm_height,
                half_width: r.half_width,
                half_height: r.cm_height,
                half_depth: None,
                supports: r.support_positions().iter().map(|&x| [x, 0.0]).collect(),
                weight: weight(r.mass, r.gravity),
            }),
            Model::RigidBlock(b) => Some(Self {
                kind: "rigid-block",
                cm_height: b.half_height,
                half_width: b.half_width,
                half_height: b.half_height,
                half_depth: None,
                supports: Vec::new(),
                weight: weight(b.mass, b.gravity),
            }),
        }
    }

    /// The geometry of a scene: [`Geometry::of`] for a planar one; for a 3D one the body
    /// with its depth and its grid of supports (`supports` × `support_rows`, rows from −d
    /// to +d), and the oscillator as a cube of half-size 5 × the largest resultant
    /// displacement of `traces` (`rel_disp`, `rel_disp_y`; 1 m when none moves), resting
    /// on its one contact.
    pub fn of_scene(scene: &Scene, traces: &[&Trace]) -> Option<Self> {
        let Some(spatial) = scene.spatial() else {
            return Self::of(&scene.model);
        };
        let half_depth = spatial.depth.map(|d| d.half_depth);
        let rows = spatial.depth.map_or(1, |d| d.support_rows.max(1));
        match &scene.model {
            Model::Oscillator(o) => {
                let s = oscillator_half_size(traces);
                Some(Self {
                    kind: "oscillator",
                    cm_height: s,
                    half_width: s,
                    half_height: s,
                    half_depth: Some(s),
                    supports: vec![[0.0, 0.0]],
                    weight: weight(o.mass, o.gravity),
                })
            }
            Model::RockingBody(_) | Model::RigidBlock(_) => {
                let mut g = Self::of(&scene.model)?;
                let d = half_depth.unwrap_or(g.half_width);
                g.half_depth = Some(d);
                g.supports = grid(&g.supports, d, rows);
                Some(g)
            }
        }
    }

    /// Whether the scene is bidirectional (drawn with its depth, moving in y too).
    pub fn is_spatial(&self) -> bool {
        self.half_depth.is_some()
    }

    /// Depth of the drawn body along y, m.
    pub fn depth(&self) -> f64 {
        self.half_depth.map_or(self.half_width, |d| 2.0 * d)
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

/// The planar supports `row` (x, 0) repeated on `rows` rows from y = −d to +d (one row: y = 0).
fn grid(row: &[[f64; 2]], d: f64, rows: usize) -> Vec<[f64; 2]> {
    let ys: Vec<f64> = if rows <= 1 {
        vec![0.0]
    } else {
        (0..rows)
            .map(|j| -d + 2.0 * d * j as f64 / (rows - 1) as f64)
            .collect()
    };
    ys.iter()
        .flat_map(|&y| row.iter().map(move |p| [p[0], y]))
        .collect()
}

/// Half-size of the cube drawn for a 3D oscillator: 5 × the largest finite resultant
/// relative displacement of the traces, 1 m when none moves.
fn oscillator_half_size(traces: &[&Trace]) -> f64 {
    let peak = traces
        .iter()
        .filter_map(|t| {
            let x = t.column("rel_disp")?;
            let y = t.column("rel_disp_y");
            Some(
                (0..x.len())
                    .map(|i| x[i].hypot(y.map_or(0.0, |y| y[i])))
                    .filter(|r| r.is_finite())
                    .fold(0.0, f64::max),
            )
        })
        .fold(0.0, f64::max);
    if peak > 0.0 { 5.0 * peak } else { 1.0 }
}

/// The pose of a body in its ground frame at one row of a trace.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Position of the centre of mass along x relative to the ground, m.
    pub x: f64,
    /// Position of the centre of mass along y relative to the ground, m (0 in a planar scene).
    pub y: f64,
    /// Height of the centre of mass above the ground surface, m.
    pub z: f64,
    /// Rotation vector (axis × angle, rad) about x, y, z; a planar rotation θ
    /// (counter-clockwise with x right and z up) is (0, −θ, 0).
    pub rotation: [f64; 3],
}

impl Pose {
    /// Rebuild the pose at row `i` from the channels the trace has: `cm_x`, `cm_y` (else
    /// the base point's `rel_disp`, `rel_disp_y` moved to the centre of mass through the
    /// rotation; y 0 when the trace has neither), `cm_z` (else 0) and the rotation vector
    /// (`rotation_x`, −`rotation`, `rotation_z`, each 0 when absent). `None` when the trace
    /// has no horizontal position or a value is not finite (a diverged run's last rows).
    pub fn at(trace: &Trace, i: usize, g: &Geometry) -> Option<Self> {
        let get = |key: &str| trace.column(key).map(|c| c[i]);
        let rotation = [
            get("rotation_x").unwrap_or(0.0),
            -get("rotation").unwrap_or(0.0),
            get("rotation_z").unwrap_or(0.0),
        ];
        let mut p = Self {
            x: 0.0,
            y: 0.0,
            z: g.cm_height + get("cm_z").unwrap_or(0.0),
            rotation,
        };
        // O = CM + R·(0, 0, −h), so CM = O + R·(0, 0, h)
        let up = p.apply([0.0, 0.0, g.cm_height]);
        p.x = match (get("cm_x"), get("rel_disp")) {
            (Some(x), _) => x,
            (None, Some(x_o)) => x_o + up[0],
            (None, None) => return None,
        };
        p.y = match (get("cm_y"), get("rel_disp_y")) {
            (Some(y), _) => y,
            (None, Some(y_o)) => y_o + up[1],
            (None, None) => 0.0,
        };
        let finite = [p.x, p.y, p.z]
            .iter()
            .chain(&p.rotation)
            .all(|v| v.is_finite());
        finite.then_some(p)
    }

    /// The planar rotation θ when the rotation vector is (0, −θ, 0).
    fn planar_theta(&self) -> Option<f64> {
        (self.rotation[0] == 0.0 && self.rotation[2] == 0.0).then_some(-self.rotation[1])
    }

    /// Base centre O in the ground frame: CM + R·(0, 0, −h) (planar: (x + h sin θ, z − h cos θ)).
    pub fn base_point(&self, g: &Geometry) -> [f64; 3] {
        let d = self.apply([0.0, 0.0, -g.cm_height]);
        [self.x + d[0], self.y + d[1], self.z + d[2]]
    }

    /// A body-frame vector turned by the body's rotation R (not moved).
    pub fn apply(&self, v: [f64; 3]) -> [f64; 3] {
        if let Some(th) = self.planar_theta() {
            // rotation −θ about +y
            let (s, c) = th.sin_cos();
            return [c * v[0] - s * v[2], v[1], s * v[0] + c * v[2]];
        }
        rotate(self.quaternion(), v)
    }

    /// Orientation as a quaternion (x, y, z, w) of the rotation vector (planar: rotation
    /// −θ about +y).
    pub fn quaternion(&self) -> [f64; 4] {
        if let Some(th) = self.planar_theta() {
            let h = 0.5 * th;
            return [0.0, -h.sin(), 0.0, h.cos()];
        }
        let [a, b, c] = self.rotation;
        let angle = (a * a + b * b + c * c).sqrt();
        let half = 0.5 * angle;
        // sin(|ψ|/2)/|ψ|, its series below 1e-4 rad (error < 1e-18)
        let k = if angle < 1e-4 {
            0.5 - angle * angle / 48.0
        } else {
            half.sin() / angle
        };
        [k * a, k * b, k * c, half.cos()]
    }
}

/// v turned by the unit quaternion q = (x, y, z, w): v + 2w(q⃗ × v) + 2 q⃗ × (q⃗ × v).
pub fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let u = [q[0], q[1], q[2]];
    let t = cross(u, v);
    let tt = cross(u, t);
    [
        v[0] + 2.0 * (q[3] * t[0] + tt[0]),
        v[1] + 2.0 * (q[3] * t[1] + tt[1]),
        v[2] + 2.0 * (q[3] * t[2] + tt[2]),
    ]
}

/// Whether a trace carries enough to draw its body (a horizontal position).
pub fn drawable(trace: &Trace) -> bool {
    trace.has("cm_x") || trace.has("rel_disp")
}

/// Foxglove time `{sec, nsec}` from nanoseconds (the JSON `foxglove.Log`).
pub fn time_json(ns: u64) -> Value {
    json!({ "sec": ns / 1_000_000_000, "nsec": ns % 1_000_000_000 })
}

/// ROS 2 time `{sec, nanosec}` (`builtin_interfaces/Time`) from nanoseconds: the 3D view's
/// CDR messages.
pub fn ros_time(ns: u64) -> Value {
    json!({ "sec": ns / 1_000_000_000, "nanosec": ns % 1_000_000_000 })
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
/// Arrow pointing +y (90° about +z): the ground's ticks along y.
const ALONG_Y: [f64; 4] = [
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
fn body_color(lane: usize, label: &str) -> [f64; 4] {
    if label == REFERENCE_LABEL {
        [0.3, 0.3, 0.3, 0.25]
    } else {
        lane_color(lane, 0.55)
    }
}

/// One scene entity: the primitive lists `prims` gives (the others are empty in the CDR
/// message), living until replaced.
fn entity(ns: u64, frame: &str, id: &str, frame_locked: bool, prims: Value) -> Value {
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

/// The total tangential force on the body at row `i`, (x, y) N: `base_shear` (else
/// −`resistance`) along x and −`resistance_y` along y (`None` in a planar trace).
fn tangential_force(trace: &Trace, i: usize) -> (Option<f64>, Option<f64>) {
    let fx = trace
        .column("base_shear")
        .map(|c| c[i])
        .or_else(|| trace.column("resistance").map(|c| -c[i]));
    let fy = trace.column("resistance_y").map(|c| -c[i]);
    (fx, fy)
}

/// One force arrow: its tail in the ground frame, its orientation, its length and colour.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Arrow {
    tail: (f64, f64, f64),
    q: [f64; 4],
    len: f64,
    color: [f64; 4],
}

/// The support-force arrows at row `i` (at most two: normal, then tangential), as
/// [`forces`] describes them; an arrow too short to see is left out.
fn force_arrows(trace: &Trace, i: usize, g: &Geometry, p: &Pose) -> ([Arrow; 2], usize) {
    let [ox, oy, oz] = p.base_point(g);
    let s = g.arrow_scale();
    let none = Arrow {
        tail: (0.0, 0.0, 0.0),
        q: IDENTITY,
        len: 0.0,
        color: [0.0; 4],
    };
    let mut arrows = [none; 2];
    let mut n_arrows = 0;
    let mut arrow = |tail: (f64, f64, f64), q: [f64; 4], len: f64, color: [f64; 4]| {
        if len.is_finite() && len > 1e-9 * g.cm_height {
            arrows[n_arrows] = Arrow {
                tail,
                q,
                len,
                color,
            };
            n_arrows += 1;
        }
    };
    if let Some(n) = trace.column("normal").map(|c| c[i]) {
        let len = n.abs() * s;
        let tail = if n >= 0.0 {
            (ox, oy, oz - len)
        } else {
            (ox, oy, oz) // a tensile total cannot happen on compression-only supports
        };
        arrow(tail, UP, len, [0.2, 0.6, 0.2, 1.0]);
    }
    let red = [0.85, 0.1, 0.1, 1.0];
    match tangential_force(trace, i) {
        (Some(f), None) => {
            let len = f.abs() * s;
            let (tail, q) = if f >= 0.0 {
                ((ox - len, oy, oz), IDENTITY)
            } else {
                ((ox + len, oy, oz), LEFT)
            };
            arrow(tail, q, len, red);
        }
        (fx, Some(fy)) => {
            let fx = fx.unwrap_or(0.0);
            let len = fx.hypot(fy) * s;
            let phi = fy.atan2(fx);
            let (sin, cos) = phi.sin_cos();
            let half = 0.5 * phi;
            let q = [0.0, 0.0, half.sin(), half.cos()];
            arrow((ox - len * cos, oy - len * sin, oz), q, len, red);
        }
        (None, None) => {}
    }
    (arrows, n_arrows)
}

/// The support-force arrows at one row, in the ground frame, drawn ending at the base
/// centre O: the total normal force (`normal`) upward and the total tangential force
/// on the body (`base_shear`, else −`resistance`, along x; −`resistance_y` along y in a
/// 3D scene: one arrow along the horizontal resultant), length |F|·`arrow_scale`. As a
/// JSON value; [`encode_forces`] writes the same message's CDR bytes directly.
pub fn forces(trace: &Trace, i: usize, ns: u64, g: &Geometry, p: &Pose, label: &str) -> Value {
    let (ground, _) = frames(label);
    let (arrows, n) = force_arrows(trace, i, g, p);
    let arrows: Vec<Value> = arrows[..n]
        .iter()
        .map(|a| {
            json!({
                "pose": pose(a.tail, a.q),
                "shaft_length": 0.8 * a.len,
                "shaft_diameter": 0.04 * g.half_width,
                "head_length": 0.2 * a.len,
                "head_diameter": 0.1 * g.half_width,
                "color": color(a.color)
            })
        })
        .collect();
    json!({
        "deletions": [],
        "entities": [entity(ns, &ground, "forces", false, json!({ "arrows": arrows }))]
    })
}

/// A CDR message written field by field into a buffer, each type at its alignment
/// (counted past the 4-byte encapsulation header): the primitives of [`encode`], and of
/// the per-frame messages of the 3D view written without a JSON value first.
struct CdrOut<'a>(&'a mut Vec<u8>);

impl CdrOut<'_> {
    /// Start a message: clear the buffer, write the little-endian header.
    fn start(buf: &mut Vec<u8>) -> CdrOut<'_> {
        buf.clear();
        buf.extend_from_slice(&CDR_LE_HEADER);
        CdrOut(buf)
    }

    fn align(&mut self, n: usize) {
        align(self.0, n);
    }

    /// A `float64`; a value that is not finite is written as NaN, as a JSON `null` is.
    fn f64(&mut self, x: f64) {
        self.align(8);
        let x = if x.is_finite() { x } else { f64::NAN };
        self.0.extend_from_slice(&x.to_le_bytes());
    }

    fn u32(&mut self, x: u32) {
        self.align(4);
        self.0.extend_from_slice(&x.to_le_bytes());
    }

    fn str(&mut self, text: &str) {
        self.u32(text.len() as u32 + 1);
        self.0.extend_from_slice(text.as_bytes());
        self.0.push(0);
    }

    /// A `builtin_interfaces/Time` of `ns` (as [`ros_time`]).
    fn time(&mut self, ns: u64) {
        self.u32((ns / 1_000_000_000) as i64 as i32 as u32);
        self.u32((ns % 1_000_000_000) as u32);
    }

    fn xyz(&mut self, (x, y, z): (f64, f64, f64)) {
        self.f64(x);
        self.f64(y);
        self.f64(z);
    }

    fn four(&mut self, v: [f64; 4]) {
        for x in v {
            self.f64(x);
        }
    }
}

/// The CDR bytes of [`forces`] (`foxglove_msgs/msg/SceneUpdate`) into `buf`, built
/// without a JSON value; `ground` is the run's ground frame ([`frames`]). The same bytes
/// as [`encode`] of the JSON message (test `direct_encodings_equal_the_json_messages`).
pub fn encode_forces(
    trace: &Trace,
    i: usize,
    ns: u64,
    g: &Geometry,
    p: &Pose,
    ground: &str,
    buf: &mut Vec<u8>,
) {
    let (arrows, n) = force_arrows(trace, i, g, p);
    let mut out = CdrOut::start(buf);
    out.u32(0); // deletions
    out.u32(1); // entities
    out.time(ns);
    out.str(ground);
    out.str("forces");
    out.time(0); // lifetime
    out.0.push(0); // frame_locked
    out.u32(0); // metadata
    out.u32(n as u32);
    for a in &arrows[..n] {
        out.xyz(a.tail);
        out.four(a.q);
        out.f64(0.8 * a.len);
        out.f64(0.04 * g.half_width);
        out.f64(0.2 * a.len);
        out.f64(0.1 * g.half_width);
        out.four(a.color);
    }
    for _ in [
        "cubes",
        "spheres",
        "cylinders",
        "lines",
        "triangles",
        "texts",
        "models",
    ] {
        out.u32(0);
    }
}

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
/// ([`frames`]). The same bytes as [`encode`] of the JSON message.
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

// The log's JSON schema is inline (no `$ref`), every object has `properties` and every
// field one concrete `type`: the subset Foxglove's JSON-schema reader accepts.

fn time_schema(d: &str) -> Value {
    json!({
        "type": "object", "title": "time", "description": d,
        "properties": {
            "sec": { "type": "integer", "minimum": 0 },
            "nsec": { "type": "integer", "minimum": 0, "maximum": 999_999_999 }
        }
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

// ---------------------------------------------------------------------------------------
// The 3D view's messages in CDR: `foxglove_msgs/msg/SceneUpdate` and
// `foxglove_msgs/msg/FrameTransforms`, the ROS 2 forms of Foxglove's well-known schemas
// (foxglove_msgs 3.x field lists, without the later `uuid`/`lineage` additions: a
// reader decodes with the definition the file carries). One table of types below gives
// the definition text, the encoder and the decoder, so the three cannot disagree.

/// A field type of a ROS 2 message definition.
#[derive(Debug)]
pub enum Ty {
    /// `float64`, 8-byte aligned.
    F64,
    /// `uint8`.
    U8,
    /// `bool` (one byte).
    Bool,
    /// `int32`, 4-byte aligned.
    I32,
    /// `uint32`, 4-byte aligned.
    U32,
    /// `string`: a `uint32` length (NUL included), the bytes, a NUL.
    Str,
    /// A nested message.
    Msg(&'static Msg),
    /// An unbounded sequence: a `uint32` count, then the elements.
    Seq(&'static Ty),
}

/// A ROS 2 message type: `package/Type` and its fields in order.
#[derive(Debug)]
pub struct Msg {
    /// `package/Type`, as dependencies are named in a definition.
    pub name: &'static str,
    /// (field name, type), in wire order.
    pub fields: &'static [(&'static str, Ty)],
}

impl Msg {
    /// The schema name Foxglove's 3D panel recognises: `package/msg/Type`.
    pub fn schema_name(&self) -> String {
        self.name.replacen('/', "/msg/", 1)
    }
}

const TIME: Msg = Msg {
    name: "builtin_interfaces/Time",
    fields: &[("sec", Ty::I32), ("nanosec", Ty::U32)],
};
const DURATION: Msg = Msg {
    name: "builtin_interfaces/Duration",
    fields: &[("sec", Ty::I32), ("nanosec", Ty::U32)],
};
const XYZ: &[(&str, Ty)] = &[("x", Ty::F64), ("y", Ty::F64), ("z", Ty::F64)];
const VECTOR3: Msg = Msg {
    name: "geometry_msgs/Vector3",
    fields: XYZ,
};
const POINT: Msg = Msg {
    name: "geometry_msgs/Point",
    fields: XYZ,
};
const QUATERNION: Msg = Msg {
    name: "geometry_msgs/Quaternion",
    fields: &[
        ("x", Ty::F64),
        ("y", Ty::F64),
        ("z", Ty::F64),
        ("w", Ty::F64),
    ],
};
const POSE: Msg = Msg {
    name: "geometry_msgs/Pose",
    fields: &[
        ("position", Ty::Msg(&POINT)),
        ("orientation", Ty::Msg(&QUATERNION)),
    ],
};
const COLOR: Msg = Msg {
    name: "foxglove_msgs/Color",
    fields: &[
        ("r", Ty::F64),
        ("g", Ty::F64),
        ("b", Ty::F64),
        ("a", Ty::F64),
    ],
};
const KEY_VALUE: Msg = Msg {
    name: "foxglove_msgs/KeyValuePair",
    fields: &[("key", Ty::Str), ("value", Ty::Str)],
};
const ARROW: Msg = Msg {
    name: "foxglove_msgs/ArrowPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("shaft_length", Ty::F64),
        ("shaft_diameter", Ty::F64),
        ("head_length", Ty::F64),
        ("head_diameter", Ty::F64),
        ("color", Ty::Msg(&COLOR)),
    ],
};
const SHAPE: &[(&str, Ty)] = &[
    ("pose", Ty::Msg(&POSE)),
    ("size", Ty::Msg(&VECTOR3)),
    ("color", Ty::Msg(&COLOR)),
];
const CUBE: Msg = Msg {
    name: "foxglove_msgs/CubePrimitive",
    fields: SHAPE,
};
const SPHERE: Msg = Msg {
    name: "foxglove_msgs/SpherePrimitive",
    fields: SHAPE,
};
const CYLINDER: Msg = Msg {
    name: "foxglove_msgs/CylinderPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("size", Ty::Msg(&VECTOR3)),
        ("bottom_scale", Ty::F64),
        ("top_scale", Ty::F64),
        ("color", Ty::Msg(&COLOR)),
    ],
};
const LINE: Msg = Msg {
    name: "foxglove_msgs/LinePrimitive",
    fields: &[
        ("type", Ty::U8),
        ("pose", Ty::Msg(&POSE)),
        ("thickness", Ty::F64),
        ("scale_invariant", Ty::Bool),
        ("points", Ty::Seq(&Ty::Msg(&POINT))),
        ("color", Ty::Msg(&COLOR)),
        ("colors", Ty::Seq(&Ty::Msg(&COLOR))),
        ("indices", Ty::Seq(&Ty::U32)),
    ],
};
const TRIANGLES: Msg = Msg {
    name: "foxglove_msgs/TriangleListPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("points", Ty::Seq(&Ty::Msg(&POINT))),
        ("color", Ty::Msg(&COLOR)),
        ("colors", Ty::Seq(&Ty::Msg(&COLOR))),
        ("indices", Ty::Seq(&Ty::U32)),
    ],
};
const TEXT: Msg = Msg {
    name: "foxglove_msgs/TextPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("billboard", Ty::Bool),
        ("font_size", Ty::F64),
        ("scale_invariant", Ty::Bool),
        ("color", Ty::Msg(&COLOR)),
        ("text", Ty::Str),
    ],
};
const MODEL: Msg = Msg {
    name: "foxglove_msgs/ModelPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("scale", Ty::Msg(&VECTOR3)),
        ("color", Ty::Msg(&COLOR)),
        ("override_color", Ty::Bool),
        ("url", Ty::Str),
        ("media_type", Ty::Str),
        ("data", Ty::Seq(&Ty::U8)),
    ],
};
const ENTITY: Msg = Msg {
    name: "foxglove_msgs/SceneEntity",
    fields: &[
        ("timestamp", Ty::Msg(&TIME)),
        ("frame_id", Ty::Str),
        ("id", Ty::Str),
        ("lifetime", Ty::Msg(&DURATION)),
        ("frame_locked", Ty::Bool),
        ("metadata", Ty::Seq(&Ty::Msg(&KEY_VALUE))),
        ("arrows", Ty::Seq(&Ty::Msg(&ARROW))),
        ("cubes", Ty::Seq(&Ty::Msg(&CUBE))),
        ("spheres", Ty::Seq(&Ty::Msg(&SPHERE))),
        ("cylinders", Ty::Seq(&Ty::Msg(&CYLINDER))),
        ("lines", Ty::Seq(&Ty::Msg(&LINE))),
        ("triangles", Ty::Seq(&Ty::Msg(&TRIANGLES))),
        ("texts", Ty::Seq(&Ty::Msg(&TEXT))),
        ("models", Ty::Seq(&Ty::Msg(&MODEL))),
    ],
};
const DELETION: Msg = Msg {
    name: "foxglove_msgs/SceneEntityDeletion",
    fields: &[
        ("timestamp", Ty::Msg(&TIME)),
        ("type", Ty::U8),
        ("id", Ty::Str),
    ],
};
/// `foxglove_msgs/msg/SceneUpdate`: the static scene and the force arrows.
pub const SCENE_UPDATE: Msg = Msg {
    name: "foxglove_msgs/SceneUpdate",
    fields: &[
        ("deletions", Ty::Seq(&Ty::Msg(&DELETION))),
        ("entities", Ty::Seq(&Ty::Msg(&ENTITY))),
    ],
};
const FRAME_TRANSFORM: Msg = Msg {
    name: "foxglove_msgs/FrameTransform",
    fields: &[
        ("timestamp", Ty::Msg(&TIME)),
        ("parent_frame_id", Ty::Str),
        ("child_frame_id", Ty::Str),
        ("translation", Ty::Msg(&VECTOR3)),
        ("rotation", Ty::Msg(&QUATERNION)),
    ],
};
/// `foxglove_msgs/msg/FrameTransforms`: a run's ground and body transforms of one frame.
pub const FRAME_TRANSFORMS: Msg = Msg {
    name: "foxglove_msgs/FrameTransforms",
    fields: &[("transforms", Ty::Seq(&Ty::Msg(&FRAME_TRANSFORM)))],
};

/// The 3D view's message type of a schema name (`None`: not one of them).
pub fn message_type(schema_name: &str) -> Option<&'static Msg> {
    [&SCENE_UPDATE, &FRAME_TRANSFORMS]
        .into_iter()
        .find(|m| m.schema_name() == schema_name)
}

/// A type's name in a definition (`float64`, `foxglove_msgs/Color[]`, ...).
fn type_name(ty: &Ty) -> String {
    match ty {
        Ty::F64 => "float64".into(),
        Ty::U8 => "uint8".into(),
        Ty::Bool => "bool".into(),
        Ty::I32 => "int32".into(),
        Ty::U32 => "uint32".into(),
        Ty::Str => "string".into(),
        Ty::Msg(m) => m.name.into(),
        Ty::Seq(t) => format!("{}[]", type_name(t)),
    }
}

/// The message types `m` uses, depth first, each once.
fn dependencies(m: &'static Msg, out: &mut Vec<&'static Msg>) {
    for (_, ty) in m.fields {
        let mut ty = ty;
        while let Ty::Seq(t) = ty {
            ty = t;
        }
        if let Ty::Msg(d) = ty
            && !out.iter().any(|o| o.name == d.name)
        {
            out.push(d);
            dependencies(d, out);
        }
    }
}

/// The ROS 2 definition of `m` (schema encoding `ros2msg`): its fields, then each type
/// it uses after the 80-`=` separator and `MSG: package/Type`, as ROS 2 bundles them.
pub fn definition(m: &'static Msg) -> String {
    let fields = |m: &Msg| {
        m.fields
            .iter()
            .map(|(n, t)| format!("{} {n}\n", type_name(t)))
            .collect::<String>()
    };
    let mut deps = Vec::new();
    dependencies(m, &mut deps);
    let mut s = fields(m);
    for d in deps {
        s.push_str(&format!(
            "{}\nMSG: {}\n{}",
            "=".repeat(80),
            d.name,
            fields(d)
        ));
    }
    s
}

/// Pad `buf` with zeros to a multiple of `n` past the 4-byte encapsulation header.
fn align(buf: &mut Vec<u8>, n: usize) {
    while (buf.len() - 4) % n != 0 {
        buf.push(0);
    }
}

/// `v` (a JSON object with `m`'s field names) as a CDR message of type `m`, into `buf`:
/// the little-endian header, then every field in definition order; a field `v` lacks is
/// zero, false, empty (a JSON `null` number is NaN).
pub fn encode(m: &Msg, v: &Value, buf: &mut Vec<u8>) {
    buf.clear();
    buf.extend_from_slice(&CDR_LE_HEADER);
    put_msg(m, v, buf);
}

fn put_msg(m: &Msg, v: &Value, buf: &mut Vec<u8>) {
    for (name, ty) in m.fields {
        put_field(ty, v.get(name), buf);
    }
}

fn put_field(ty: &Ty, v: Option<&Value>, buf: &mut Vec<u8>) {
    let int = |v: Option<&Value>| v.and_then(Value::as_i64).unwrap_or(0);
    let mut out = CdrOut(buf);
    match ty {
        // a JSON number is finite, and `null` is NaN: what `CdrOut::f64` writes
        Ty::F64 => out.f64(match v {
            Some(Value::Null) => f64::NAN,
            v => v.and_then(Value::as_f64).unwrap_or(0.0),
        }),
        Ty::U8 => out.0.push(int(v) as u8),
        Ty::Bool => out
            .0
            .push(u8::from(v.and_then(Value::as_bool).unwrap_or(false))),
        Ty::I32 => out.u32(int(v) as i32 as u32),
        Ty::U32 => out.u32(int(v) as u32),
        Ty::Str => out.str(v.and_then(Value::as_str).unwrap_or("")),
        Ty::Msg(m) => put_msg(m, v.unwrap_or(&Value::Null), buf),
        Ty::Seq(t) => {
            let items = v.and_then(Value::as_array).map_or(&[][..], Vec::as_slice);
            out.u32(items.len() as u32);
            for item in items {
                put_field(t, Some(item), buf);
            }
        }
    }
}

/// A CDR message of type `m` read back as JSON (field names as in the definition;
/// NaN as `null`); an error says where the bytes end or what is wrong.
pub fn decode(m: &Msg, data: &[u8]) -> Result<Value, String> {
    let Some(header) = data.get(..4) else {
        return Err(format!("{} bytes, shorter than the CDR header", data.len()));
    };
    if header[..2] != CDR_LE_HEADER[..2] {
        return Err("not little-endian plain CDR".into());
    }
    let mut r = Reader { data, at: 4 };
    let v = r.msg(m)?;
    match data.len() - r.at {
        0 => Ok(v),
        n => Err(format!("{n} bytes after the last field of {}", m.name)),
    }
}

struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, align: usize, n: usize) -> Result<&[u8], String> {
        let start = 4 + (self.at - 4).next_multiple_of(align);
        let bytes = self
            .data
            .get(start..start + n)
            .ok_or_else(|| format!("message ends at byte {} inside a field", self.data.len()))?;
        self.at = start + n;
        Ok(bytes)
    }

    fn u32(&mut self) -> Result<u32, String> {
        let b = self.take(4, 4)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn msg(&mut self, m: &Msg) -> Result<Value, String> {
        let mut obj = serde_json::Map::with_capacity(m.fields.len());
        for (name, ty) in m.fields {
            obj.insert((*name).to_string(), self.field(ty)?);
        }
        Ok(Value::Object(obj))
    }

    fn field(&mut self, ty: &Ty) -> Result<Value, String> {
        Ok(match ty {
            Ty::F64 => {
                let b = self.take(8, 8)?;
                json!(f64::from_le_bytes(b.try_into().unwrap_or([0; 8])))
            }
            Ty::U8 => json!(self.take(1, 1)?[0]),
            Ty::Bool => match self.take(1, 1)?[0] {
                0 => json!(false),
                1 => json!(true),
                b => return Err(format!("bool byte {b}")),
            },
            Ty::I32 => json!(self.u32()? as i32),
            Ty::U32 => json!(self.u32()?),
            Ty::Str => {
                let n = self.u32()? as usize;
                let bytes = self.take(1, n)?;
                let (nul, text) = bytes.split_last().ok_or("a string of length 0")?;
                if *nul != 0 {
                    return Err("a string without its NUL".into());
                }
                json!(std::str::from_utf8(text).map_err(|e| e.to_string())?)
            }
            Ty::Msg(m) => self.msg(m)?,
            Ty::Seq(t) => {
                let n = self.u32()? as usize;
                // every element takes at least one byte: a count beyond the bytes left is damage
                if n > self.data.len() - self.at {
                    return Err(format!("a sequence of {n} in {} bytes", self.data.len()));
                }
                let mut items = Vec::with_capacity(n);
                for _ in 0..n {
                    items.push(self.field(t)?);
                }
                Value::Array(items)
            }
        })
    }
}

#[cfg(test)]
mod tests {
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
}

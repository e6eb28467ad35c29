//! The support forces at one row as arrows: a JSON `SceneUpdate`, and the same message
//! written straight in CDR.

use serde_json::{Value, json};

use rockslide_core::trace::Trace;

use super::codec::CdrOut;
use super::values::{IDENTITY, LEFT, UP, color, entity, frames, pose};
use super::{Geometry, Pose};

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

/// The CDR bytes of [`forces`] (`foxglove_msgs/msg/SceneUpdate`) into `buf`, built
/// without a JSON value; `ground` is the run's ground frame ([`frames`]). The same bytes
/// as [`encode`](super::encode) of the JSON message (test `direct_encodings_equal_the_json_messages`).
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

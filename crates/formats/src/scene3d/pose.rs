//! The body's pose in its ground frame, rebuilt from a trace's channels at one row.

use rockslide_core::trace::Trace;

use super::Geometry;

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

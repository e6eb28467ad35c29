//! Plan motion in rapier's axes: scene (x, y, z up) is rapier's (X, −Z, Y), so the frame
//! stays right-handed; plan vectors as `[x, y]`; the radial return of a spring in series
//! with a slider on the circular friction cone; the row every 3D run of a block or an
//! oscillator records ([`plan_channels`]).

use rapier3d_f64::prelude::*;

use rockslide_core::trace::{Quantity, q};

/// A plan vector (x, y) as a rapier vector at height `up`.
pub(crate) fn to_world(p: [f64; 2], up: f64) -> Vector {
    Vector::new(p[0], up, -p[1])
}

/// The plan part (x, y) of a rapier vector.
pub(crate) fn plan(v: Vector) -> [f64; 2] {
    [v.x, -v.z]
}

pub(crate) fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

pub(crate) fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

/// Azimuth of a plan vector, degrees from +x toward +y (0 for the zero vector).
pub(crate) fn azimuth_deg(a: [f64; 2]) -> f64 {
    if a == [0.0, 0.0] {
        0.0
    } else {
        a[1].atan2(a[0]).to_degrees()
    }
}

/// |F|²/limit² below which a spring is inside its circle whatever the round-off of |F|²
/// (a few ulps) and of `hypot` (one): [`radial_return`] then skips the `hypot`.
const INSIDE: f64 = 1.0 - 1e-9;

/// The radial return of a spring `k` in series with a slider `p` on the circle of radius
/// `limit` (the circular friction cone), after a step that left the spring's end at `u`:
/// where k·|u − p| > limit the slider follows along u − p so that |F| = limit. Returns the
/// spring force on the ground side, F = k·(u − p), |F| ≤ limit.
pub(crate) fn radial_return(k: f64, limit: f64, p: &mut [f64; 2], u: [f64; 2]) -> [f64; 2] {
    let e = sub(u, *p);
    let f = [k * e[0], k * e[1]];
    // Well inside the circle (|F|² below limit² by far more than its round-off) the spring
    // holds: the answer `norm` would give, without its cost.
    if f[0] * f[0] + f[1] * f[1] < limit * limit * INSIDE {
        return f;
    }
    let size = norm(f);
    if size > limit {
        let scale = limit / size;
        *p = [u[0] - e[0] * scale, u[1] - e[1] * scale];
        [f[0] * scale, f[1] * scale]
    } else {
        f
    }
}

/// The channels every 3D run of a block or an oscillator records (the x channels keep
/// the planar keys); `lifts`: under a vertical component, the body's uplift above the
/// ground and its contacts (points pressed), so that a lift-off shows.
pub(crate) fn plan_channels(moves: bool, lifts: bool) -> Vec<&'static Quantity> {
    let mut c = vec![
        &q::FORCE,
        &q::RESISTANCE,
        &q::REL_DISP,
        &q::REL_DISP_Y,
        &q::SLIDE,
        &q::SLIDE_Y,
        &q::VEL,
        &q::VEL_Y,
        &q::ACC,
        &q::SLIDE_RESULTANT,
        &q::SLIDE_AZIMUTH,
        &q::NORMAL,
    ];
    if lifts {
        c.extend([&q::UPLIFT, &q::CONTACTS]);
    }
    if moves {
        c.push(&q::GROUND_DISP);
    }
    c
}

/// One output row of a 3D run, in [`plan_channels`] order.
pub(crate) struct PlanRow {
    pub(crate) force: [f64; 2],
    pub(crate) resistance: f64,
    pub(crate) rel_disp: [f64; 2],
    pub(crate) slide: [f64; 2],
    pub(crate) vel: [f64; 2],
    pub(crate) acc: f64,
    pub(crate) normal: f64,
    /// Under a vertical component: the uplift above the ground (m, ≥ 0) and the
    /// contacts pressed.
    pub(crate) lift: Option<(f64, f64)>,
    pub(crate) ground: f64,
}

impl PlanRow {
    /// The row into `out`, laid out as [`plan_channels`] (`out` as long as its channels).
    pub(crate) fn write(&self, out: &mut [f64]) {
        let head = [
            self.force[0],
            self.resistance,
            self.rel_disp[0],
            self.rel_disp[1],
            self.slide[0],
            self.slide[1],
            self.vel[0],
            self.vel[1],
            self.acc,
            norm(self.slide),
            azimuth_deg(self.slide),
            self.normal,
        ];
        let (first, rest) = out.split_at_mut(head.len());
        first.copy_from_slice(&head);
        let rest = match self.lift {
            Some((uplift, contacts)) => {
                rest[0] = uplift;
                rest[1] = contacts;
                &mut rest[2..]
            }
            None => rest,
        };
        if let Some(ground) = rest.first_mut() {
            *ground = self.ground;
        }
    }
}

//! One run of the 3D model: drive it and record, at every converged step, the motion in
//! both horizontal directions and the contacts' state (preallocated rows, nothing
//! allocated in the loop).

use nalgebra::{Vector2, Vector3};

use super::body::SpaceBody;
use crate::element::Status;
use crate::model::{Drive, Model, Snapshot, Space};
use crate::options::FeOptions;
use crate::stepper::{Counters as SpaceCounters, integrate};
use rockslide_core::case::{Excitation, Signal};
use rockslide_engine_api::{RunStatus, step_count};

/// The recorded state at one instant. Horizontal quantities are (x, y) pairs, relative
/// to the ground where a ground moves.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SpaceRow {
    /// Time, s.
    pub t: f64,
    /// Horizontal force on the mass in relative coordinates, N.
    pub force: Vector2<f64>,
    /// Base shear: the sum of the ground elements' tangential forces, N.
    pub resistance: Vector2<f64>,
    /// Displacement of the base centre O (of the mass, for the oscillator) relative to
    /// the ground, m.
    pub rel_disp: Vector2<f64>,
    /// Sliding: the mean accumulated slip of the ground elements, m.
    pub slide: Vector2<f64>,
    /// Velocity of the centre of mass relative to the ground, m/s.
    pub vel: Vector2<f64>,
    /// Acceleration of the centre of mass relative to the ground, m/s².
    pub acc: Vector2<f64>,
    /// Centre-of-mass displacement relative to the ground (x, y) and from its static
    /// position (z), m.
    pub cm: Vector3<f64>,
    /// Rotation vector of the body, rad.
    pub rotation: Vector3<f64>,
    /// Largest gap of a ground element, m (0 when all are closed).
    pub uplift: f64,
    /// Ground elements in compression.
    pub contacts: usize,
    /// Total normal force, N.
    pub normal: f64,
    /// Largest |T|/(μ·N) of a compressed ground element (1 on the cone).
    pub cone_ratio: f64,
    /// Mean node displacement relative to the ground (double arrangement), m.
    pub node_disp: Vector2<f64>,
}

/// A run of the 3D model.
#[derive(Debug, Clone)]
pub struct SpaceRun {
    /// Rows at t = 0 and after every step.
    pub rows: Vec<SpaceRow>,
    /// How the run ended.
    pub status: RunStatus,
    /// Deterministic counters.
    pub counters: SpaceCounters,
}

/// Run `body` under `excitation` along `azimuth` (rad from x towards y), with an optional
/// `second` signal of the same kind at right angles, for `duration` at step `dt` with the
/// 2D engine's options (integrator, Newton).
pub fn run_space(
    body: &SpaceBody,
    excitation: &Excitation,
    second: Option<&Signal>,
    azimuth: f64,
    duration: f64,
    dt: f64,
    opts: &FeOptions,
) -> SpaceRun {
    let mut model = Model::space(body);
    let drive = Drive::new(excitation, body.mass).along(azimuth, second);
    let steps = step_count(duration, dt);
    let mut rows = Vec::with_capacity(steps + 1);
    // The reference point: the base centre O below the centre of mass (a rocking body),
    // the mass itself (the oscillator).
    let o_offset = if body.rotation {
        body.supports
            .first()
            .map_or(Vector3::zeros(), |d| Vector3::new(0.0, 0.0, d.z))
    } else {
        Vector3::zeros()
    };
    let (status, counters) = integrate(&mut model, &drive, opts, dt, steps, |m, s| {
        rows.push(record(m, s, &drive, &o_offset));
    });
    SpaceRun {
        rows,
        status,
        counters,
    }
}

/// The row of one snapshot.
pub(super) fn record(
    m: &Model<Space>,
    s: &Snapshot<Space>,
    drive: &Drive,
    o_offset: &Vector3<f64>,
) -> SpaceRow {
    let xg = s.ground[0].xy();
    let mut row = SpaceRow {
        t: s.t,
        force: drive.equivalent_force::<Space>(s.t, s.force).xy(),
        ..SpaceRow::default()
    };
    let mut node_sum = Vector2::zeros();
    for (k, sup) in m.supports.iter().enumerate() {
        let e = &sup.lower;
        let st = e.state();
        let t = e.tangential();
        row.resistance += t;
        row.normal += e.normal();
        row.slide += st.slip;
        row.uplift = row.uplift.max(st.delta.z);
        if st.status != Status::Open && e.normal() > 0.0 {
            row.contacts += 1;
            row.cone_ratio = row.cone_ratio.max(t.norm() / (e.mu * e.normal()));
        }
        if sup.upper.is_some() {
            node_sum += s.un[k].xy() - xg;
        }
    }
    let n = m.supports.len() as f64;
    row.slide /= n;
    row.uplift = row.uplift.max(0.0);
    if m.nodes > 0 {
        row.node_disp = node_sum / n;
    }
    let x = &s.pose.x;
    row.rel_disp = Model::<Space>::displacement_of(x, &s.pose.r, o_offset).xy() - xg;
    row.vel = s.v.fixed_rows::<2>(0).into_owned() - s.ground[1].xy();
    row.acc = s.a.fixed_rows::<2>(0).into_owned() - s.ground[2].xy();
    let cz = x.z - s.statics.x.z;
    row.cm = Vector3::new(x.x - xg.x, x.y - xg.y, cz);
    // The rotation vector of the step's accepted pose, log(R).
    row.rotation = s.pose.psi;
    row
}

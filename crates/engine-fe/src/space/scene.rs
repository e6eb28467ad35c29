//! The fe engine on a bidirectional (3D) scene (`Scene::spatial`): the 3D model built from
//! the scene (the oscillator on one isotropic contact; the rocking body on its
//! `supports` × `support_rows` grid), driven by the excitation pair, recorded as a trace
//! whose x channels keep the 2D keys and whose y channels are added (`*_y`), with the
//! per-contact block giving |T|, the slip accumulated along the friction force (Σ T̂·Δs) and the gap.
//! The rows go to a [`StepSink`] as they are recorded (a whole run: a `WholeRun` sized up
//! front; a streamed run: the caller's sink, no rows held).

use nalgebra::{Matrix3, Vector2, Vector3};

use super::body::{BlockGrid, SpaceBody};
use super::run::{SpaceRow, record};
use crate::model::{Drive, Model, Snapshot, Space, default_rotational_inertia};
use crate::options::FeOptions;
use crate::run_parts::{integrator_settings, is_double, no_double, rigid_block, solver_stats};
use crate::stepper::integrate;
use crate::variant;
use rockslide_core::case::{Case, Excitation, Model as SceneModel, Scene, Spatial};
use rockslide_core::error::InputError;
use rockslide_core::trace::{ContactBlock, ContactState, Quantity, Trace, plan_slip_increment, q};
use rockslide_engine_api::{NotApplicable, Run, Setting, StepSink, step_count};

/// The variants of a 3D scene, or why fe does not run it.
pub fn variants(scene: &Scene, spatial: &Spatial) -> Result<Vec<&'static str>, NotApplicable> {
    let double = match &scene.model {
        SceneModel::Oscillator(o) => o.double.is_some(),
        SceneModel::RockingBody(r) => {
            if spatial.depth.is_some_and(|d| d.support_rows < 2) {
                return Err(NotApplicable(
                    "one row of supports is a knife edge along x: in 3D the body has no stiffness against tipping about it (give support_rows ≥ 2)".into(),
                ));
            }
            r.double.is_some()
        }
        SceneModel::RigidBlock(_) => {
            return Err(NotApplicable(
                "the penalty FE model needs contact stiffnesses, and a rigid block on a rigid ground has none".into(),
            ));
        }
    };
    Ok(if double {
        vec![variant::SINGLE, variant::DOUBLE]
    } else {
        vec![variant::SINGLE]
    })
}

/// The 3D body of the scene and where its inertia came from.
fn body(case: &Case, spatial: &Spatial, double: bool) -> Result<(SpaceBody, String), InputError> {
    match &case.scene.model {
        SceneModel::Oscillator(o) => Ok((SpaceBody::oscillator(o, double), String::new())),
        SceneModel::RockingBody(r) => {
            let depth = spatial.depth.ok_or_else(|| {
                case.field_error(
                    "model.half_depth",
                    "is required for a rocking body in a 3D scene",
                )
            })?;
            let (inertia, note) = match spatial.inertia {
                Some([ix, iy, iz]) => (
                    Matrix3::from_diagonal(&Vector3::new(ix, iy, iz)),
                    format!(
                        "{ix}, {iy}, {iz} kg·m² about x, y, z (model.rotational_inertia_x, _y, _z)"
                    ),
                ),
                None => {
                    let i = if r.rotational_inertia > 0.0 {
                        r.rotational_inertia
                    } else {
                        default_rotational_inertia(r)
                    };
                    (
                        Matrix3::identity() * i,
                        format!("{i} kg·m² about every axis (the planar value, isotropic)"),
                    )
                }
            };
            let grid = BlockGrid {
                mass: r.mass,
                gravity: r.gravity,
                cm_height: r.cm_height,
                half_length: r.half_width,
                half_width: depth.half_depth,
                nx: r.supports,
                ny: depth.support_rows,
                inertia,
                contact: r.contact,
                double: r.double,
            };
            Ok((SpaceBody::block(&grid, double), note))
        }
        SceneModel::RigidBlock(_) => Err(rigid_block(case)),
    }
}

/// The channels of a 3D run: the catalogue's plan-motion set, the double support's node
/// displacement, and an oscillator's contact uplift under a vertical component (`vertical`).
fn channels(
    rocking: bool,
    moves_ground: bool,
    double: bool,
    vertical: bool,
) -> Vec<&'static Quantity> {
    let mut c = q::plan_motion(moves_ground, rocking);
    if double {
        c.push(&q::NODE_DISP);
    }
    if vertical && !rocking {
        c.push(&q::UPLIFT);
    }
    c
}

/// The layout of a 3D run of `body`: its channels and one contact per support (its lower
/// element), without rows.
fn layout(body: &SpaceBody, moves_ground: bool, double: bool, vertical: bool) -> Trace {
    let mut layout =
        Trace::with_channels(&channels(body.rotation, moves_ground, double, vertical), 0);
    let kz = body.double.map_or(body.contact.kz, |d| d.lower.kz);
    layout.contacts = ContactBlock::for_supports(body.supports.len(), 1.0 / kz, 0);
    layout
}

/// Values one row of `variant` of a 3D scene records (time, channels, the contacts'
/// fields), or `None` when the variant does not build.
pub fn recorded_values_space(case: &Case, spatial: &Spatial, variant: &str) -> Option<usize> {
    let double = variant == variant::DOUBLE;
    let (body, _) = body(case, spatial, double).ok()?;
    let moves_ground = matches!(case.scene.excitation, Excitation::GroundDisplacement(_));
    let vertical = case.scene.vertical().is_some();
    Some(crate::recording::values_per_row(&layout(
        &body,
        moves_ground,
        double,
        vertical,
    )))
}

/// Run `variant` of a 3D scene at step `dt`, handing the layout and every recorded row to
/// `sink`: the returned run's trace is the layout without rows.
pub fn simulate_space_into<S: StepSink + ?Sized>(
    case: &Case,
    spatial: &Spatial,
    variant: &str,
    dt: f64,
    opts: &FeOptions,
    sink: &mut S,
) -> Result<Run, InputError> {
    let double = is_double(case, variant)?;
    let (body, inertia_note) = body(case, spatial, double)?;
    if double && body.double.is_none() {
        return Err(no_double(case));
    }
    let excitation = &case.scene.excitation;
    let moves_ground = matches!(excitation, Excitation::GroundDisplacement(_));
    let rocking = body.rotation;
    let steps = step_count(case.run.duration, dt);
    let vertical = case.scene.vertical().is_some();
    let layout = layout(&body, moves_ground, double, vertical);
    sink.begin(&layout);
    let mut states = vec![ContactState::default(); body.supports.len()];
    // each support's last slip vector and its slip accumulated along the friction force
    let mut slid = vec![(Vector2::zeros(), 0.0_f64); body.supports.len()];
    let drive = Drive::new(excitation, body.mass)
        .along(spatial.azimuth(), spatial.second.as_ref())
        .with_vertical(case.scene.vertical().map(|v| &v.signal));
    let o_offset = if rocking {
        Vector3::new(0.0, 0.0, body.supports[0].z)
    } else {
        Vector3::zeros()
    };
    let mut model = Model::space(&body);
    let mut values = [0.0_f64; 32];
    let (status, counters) = integrate(&mut model, &drive, opts, dt, steps, |m, s| {
        let r = record(m, s, &drive, &o_offset);
        let i = row_values(
            &r,
            s,
            (moves_ground, rocking, double, vertical),
            &mut values,
        );
        contact_states(m, &mut states, &mut slid);
        sink.row(s.t, &values[..i], &states);
    });
    Ok(Run {
        engine: crate::options::ID,
        variant: variant.to_string(),
        arrangement: crate::arrangement(variant),
        dt,
        settings: {
            let mut s = settings(spatial, dt, opts, &body, inertia_note);
            s.extend(crate::vertical::describe(&case.scene));
            s
        },
        stats: solver_stats(&counters),
        findings: Vec::new(),
        trace: layout,
        status,
        wall_seconds: 0.0,
    })
}

/// The channel values of row `r` (snapshot `s`) in the layout's order, written into
/// `values`; returns how many.
fn row_values(
    r: &SpaceRow,
    s: &Snapshot<Space>,
    (moves_ground, rocking, double, vertical): (bool, bool, bool, bool),
    values: &mut [f64; 32],
) -> usize {
    let mut i = 0;
    let mut put = |v: f64| {
        values[i] = v;
        i += 1;
    };
    for v in [r.force, r.resistance, r.rel_disp, r.slide, r.vel, r.acc] {
        put(v.x);
        put(v.y);
    }
    put(r.slide.norm());
    put(if r.slide == nalgebra::Vector2::zeros() {
        0.0
    } else {
        r.slide.y.atan2(r.slide.x).to_degrees()
    });
    if moves_ground {
        put(s.ground[0].x);
        put(s.ground[0].y);
    }
    if rocking {
        put(r.cm.x);
        put(r.cm.y);
        put(r.cm.z);
        put(-r.rotation.y);
        put(r.rotation.x);
        put(r.rotation.z);
        put(r.uplift);
        put(r.contacts as f64);
    }
    put(r.normal);
    if double {
        put(r.node_disp.x);
    }
    if vertical && !rocking {
        put(r.uplift);
    }
    i
}

/// Each support's contact state (its lower element's) into `states`, with the slip
/// accumulated along the friction force (Σ T̂·Δs; `slid`: each support's last slip vector
/// and that sum).
fn contact_states(m: &Model<Space>, states: &mut [ContactState], slid: &mut [(Vector2<f64>, f64)]) {
    for ((c, sup), (last, along)) in states.iter_mut().zip(&m.supports).zip(slid) {
        let st = sup.lower.state();
        let tangential = sup.lower.tangential();
        let ds = st.slip - *last;
        *along += plan_slip_increment([tangential.x, tangential.y], [ds.x, ds.y]);
        *last = st.slip;
        *c = ContactState {
            normal: sup.lower.normal(),
            tangential: tangential.norm(),
            slip: *along,
            gap: st.delta.z,
        };
    }
}

/// What shaped a 3D run, as (name, value).
fn settings(
    spatial: &Spatial,
    dt: f64,
    opts: &FeOptions,
    body: &SpaceBody,
    inertia_note: String,
) -> Vec<Setting> {
    let mut s = integrator_settings(dt, opts);
    s.extend([
        Setting::text(
            "model",
            "3D: six degrees of freedom, exact finite rotations (Simo–Vu Quoc incremental rotation vector, right-Jacobian tangent); cone contacts with radial return",
        ),
        Setting::text(
            "excitation",
            format!(
                "azimuth {}°{}",
                spatial.azimuth_deg,
                if spatial.second.is_some() {
                    ", second component at right angles"
                } else {
                    ""
                }
            ),
        ),
        Setting::count("supports", body.supports.len() as u64),
        Setting::text(
            "gravity",
            "static preload: the run starts from equilibrium under M·g",
        ),
    ]);
    if body.rotation {
        s.push(Setting::text("rotational inertia", inertia_note));
    }
    s
}

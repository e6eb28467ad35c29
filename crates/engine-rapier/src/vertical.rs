//! Vertical ground motion (issue 15) in the rigid-body engine, by both routes the
//! horizontal motion takes:
//!
//! - *kinematic ground*: the ground body is moved to (xg, yg)(t_{n+1}) each step, yg the
//!   vertical ground acceleration integrated twice exactly (the same tables as the
//!   horizontal one, `ground`); the recorder measures heights from the moving ground;
//! - *inertial force*: the ground stays fixed and every dynamic body of mass m gets the
//!   vertical force −m·(vg_y(n+1) − vg_y(n))/Δt over the step (a_v positive upward: an
//!   upward ground acceleration presses the body down). A mass-acceleration scene (fixed
//!   ground, applied force) takes its vertical component this way too.
//!
//! What then carries the normal force is the model's own: the rigid block's rapier contact
//! (restitution 0: a landing block loses its vertical velocity, and Coulomb friction acts
//! through the landing, as the exact reference's plastic impact), and the supports'
//! compression-only springs Kz (the rocking body's, applied-force or joint-limit, their
//! gaps measured from the moving ground; [`oscillator_with_supports`] for the oscillator:
//! one joint-limit support under a mass free in X and Z), whose friction cap is
//! μ times the support's own N after every step and whose slider follows an open support
//! (CONTA178's reset at re-closure). A rigid vertical contact (`normal_force =
//! "quasi-static"`) is not a rapier model of the oscillator (its springs have Kz), and the
//! feet models (`contact_model = "foot"`) do not take vertical motion: "not applicable"
//! and a located error.

use rapier3d_f64::prelude::*;

use super::ground::{GroundAt, GroundTable};
use super::settings::{OscillatorContact, OscillatorSteps, RapierSettings};
use super::simulate::{Drive, Outcome, force_at, ground_frame, start_in_ground_frame, time_loop};
use super::world::{self, GroundKind, Rig, Support};
use rockslide_core::case::{Case, Excitation, Model, NormalForce, Oscillator, Scene, Vertical};
use rockslide_core::error::InputError;
use rockslide_core::trace::{ContactState, Quantity, q};
use rockslide_engine_api::{NotApplicable, StepSink, step_count};

/// The vertical ground motion at the step times: yg(t_n) and vg_y(t_n⁺), from rest,
/// evaluated when asked for (the horizontal ground's integration, `ground::GroundAt`).
#[derive(Debug, Clone)]
pub struct VerticalTable(GroundAt);

impl VerticalTable {
    /// The motion at step times `t_k = k·dt`.
    pub fn new(vertical: &Vertical, dt: f64) -> Self {
        Self(GroundAt::new(
            &Excitation::GroundAcceleration(vertical.signal.clone()),
            dt,
        ))
    }

    /// yg(t_k), m (positive upward).
    #[inline]
    pub fn disp(&self, k: usize) -> f64 {
        self.0.disp(k)
    }

    /// vg_y(t_k⁺), m/s.
    #[inline]
    pub fn vel(&self, k: usize) -> f64 {
        self.0.vel(k)
    }
}

/// Whether rapier runs the scene's vertical component (if any).
pub(crate) fn check(scene: &Scene) -> Result<(), NotApplicable> {
    let Some(v) = scene.vertical() else {
        return Ok(());
    };
    match &scene.model {
        Model::Oscillator(_) if v.normal_force == NormalForce::QuasiStatic => Err(NotApplicable(
            "rapier's oscillator under vertical motion has a support with its vertical stiffness Kz: a rigid vertical contact (normal_force = \"quasi-static\") is not its model".into(),
        )),
        Model::Oscillator(o) if o.double.is_some() => Err(NotApplicable(
            "rapier models vertical motion on the single contact, not the double arrangement".into(),
        )),
        _ => Ok(()),
    }
}

/// The feet models (`contact_model = "foot"`) do not take vertical motion: a located error
/// for a case that asks for them with a vertical component.
pub(crate) fn check_settings(case: &Case, settings: &RapierSettings) -> Result<(), InputError> {
    let feet = settings.oscillator_contact == OscillatorContact::Foot;
    if case.scene.vertical().is_some() && feet && !matches!(case.scene.model, Model::RigidBlock(_))
    {
        return Err(case.field_error(
            "engines.rapier.contact_model",
            "\"foot\" does not take vertical ground motion; the joint-limit supports (the default) do",
        ));
    }
    Ok(())
}

/// The vertical route in words, for the run's settings table.
pub(crate) fn describe(case: &Case, drive: Drive) -> Option<(String, String)> {
    case.scene.vertical().map(|_| {
        let route = match drive {
            Drive::KinematicGround => "kinematic ground moved to yg(t_{n+1}) each step (a_v integrated twice, exactly between samples); heights measured from the moving ground",
            _ => "fixed ground; −m·(vg_y(n+1) − vg_y(n))/Δt on every dynamic body (a_v positive upward)",
        };
        let model = match case.scene.model {
            Model::RigidBlock(_) => "N from rapier's contact (restitution 0: a landing block loses its vertical velocity)",
            _ => "N from each support's compression-only spring Kz after every step; friction cap μ·N; an open support's slider follows its anchor",
        };
        ("vertical ground motion".into(), format!("{route}; {model}"))
    })
}

/// Height of the ground at step `k` in the frame the recorder measures from: the moving
/// ground's yg for a kinematic ground, 0 for a fixed one.
pub(crate) fn ground_height(drive: Drive, g: &GroundTable, k: usize) -> f64 {
    match (&g.vertical, drive) {
        (Some(v), Drive::KinematicGround) => v.disp(k),
        _ => 0.0,
    }
}

/// The vertical ground acceleration a body feels as a force over the output step ending
/// at `k` (`stride` rapier steps of `dt_out`/stride), m/s²: its mean on the fixed-ground
/// routes, 0 on the kinematic one (there the body's own acceleration is absolute).
pub(crate) fn inertial_acceleration(
    drive: Drive,
    g: &GroundTable,
    k: usize,
    stride: usize,
    dt_out: f64,
) -> f64 {
    match (&g.vertical, drive) {
        (Some(_), Drive::KinematicGround) | (None, _) => 0.0,
        (Some(v), _) if k >= stride => (v.vel(k) - v.vel(k - stride)) / dt_out,
        _ => 0.0,
    }
}

/// The step's vertical drive, after the horizontal one: the kinematic ground's next
/// height, or −m·a_v on every dynamic body.
pub(crate) fn drive_step(rig: &mut Rig, drive: Drive, g: &GroundTable, k: usize, dt: f64) {
    let Some(v) = &g.vertical else { return };
    if drive == Drive::KinematicGround {
        // from where the ground started (the rigs place it differently), to yg(t_{n+1})
        let ground = &mut rig.world.bodies[rig.ground];
        let y = ground.translation().y - v.disp(k) + v.disp(k + 1);
        ground.set_next_kinematic_translation(Vector::new(g.disp(k + 1), y, 0.0));
    } else {
        let av = (v.vel(k + 1) - v.vel(k)) / dt;
        for &(h, m) in &rig.inertial_masses {
            rig.world.bodies[h].add_force(Vector::new(0.0, -m * av, 0.0), false);
        }
    }
}

/// rapier's step for the oscillator on a support: the horizontal rule
/// ([`OscillatorSteps`]) with its period scaled to the vertical mode √(Kz/M) when that is
/// faster, and no longer than a vertical record's sample step. Returns (stride, rapier step).
pub(crate) fn oscillator_steps(
    osc: &Oscillator,
    ex: &Excitation,
    vertical: &Vertical,
    dt: f64,
    accuracy: f64,
) -> (usize, f64, OscillatorSteps) {
    let steps = OscillatorSteps::for_scene(osc, ex, dt, accuracy);
    let omega_z = (osc.contact.kz / osc.mass).sqrt();
    let mut dt_max = steps.dt_max * (osc.omega() / omega_z).min(1.0);
    if let rockslide_core::case::Signal::Record { dt: rdt, .. } = &vertical.signal {
        dt_max = dt_max.min(*rdt);
    }
    let stride = ((dt / dt_max * (1.0 - 1e-12)).ceil() as usize).clamp(1, super::MAX_STRIDE);
    (stride, dt / stride as f64, steps)
}

/// The oscillator as a mass free in X and Z (no rotation) on one joint-limit support
/// ([`Support`], as the rocking body's): a compression-only spring Kz on Y and the spring
/// Kx on X capped at μ·N after every step, in series with its slider. The mass carries its
/// weight through the support and starts in static equilibrium, compressed by M·g/Kz.
pub(crate) fn oscillator_with_supports(
    osc: &Oscillator,
    s: &RapierSettings,
    dt: f64,
    kind: GroundKind,
) -> Rig {
    let mut w = world::new_world(s, dt, osc.gravity);
    let ground = world::add_ground(&mut w, kind, 0.0);
    let m = osc.mass;
    let (kx, kz, mu) = (osc.contact.kx, osc.contact.kz, osc.contact.mu);
    let preload = m * osc.gravity / kz;
    let body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, -preload, 0.0))
        .additional_mass_properties(MassProperties::new(Vector::ZERO, m, Vector::splat(m)))
        .enabled_translations(true, true, false)
        .lock_rotations()
        .can_sleep(false);
    let structure = w.insert_body(body);
    let h = dt / s.substeps as f64;
    let share = 1.0 - world::SUPPORT_DAMPING_SHARE;
    let damping = (osc.damping() - share * h * kx, -share * h * kz);
    let normal = m * osc.gravity;
    let cap = world::friction_cap(mu, normal);
    let spring = |axis: JointAxis, k: f64, c: f64, max: f64| {
        GenericJointBuilder::new(JointAxesMask::empty())
            .local_anchor1(Vector::new(0.0, world::GROUND_HALF.1, 0.0))
            .local_anchor2(Vector::ZERO)
            .motor_model(axis, MotorModel::ForceBased)
            .motor_position(axis, 0.0, k, c)
            .motor_max_force(axis, max)
            .contacts_enabled(false)
            .build()
    };
    let joint = w.insert_impulse_joint(
        ground,
        structure,
        spring(JointAxis::LinX, kx, damping.0, cap),
    );
    let vertical = w.insert_impulse_joint(
        ground,
        structure,
        spring(JointAxis::LinY, kz, damping.1, f64::INFINITY),
    );
    Rig {
        supports: vec![Support {
            joint,
            vertical,
            x: 0.0,
            cm_height: 0.0,
            kx,
            kz,
            mu,
            damping,
            s: 0.0,
            normal,
            delta: (0.0, -preload),
            anchor: (0.0, 0.0),
        }],
        ..Rig::single(w, ground, structure, m)
    }
}

/// Run the oscillator on its support ([`oscillator_with_supports`]) and record the
/// oscillator's channels (and N(t)) every `stride` rapier steps of dt/stride: the
/// resistance and the contact are the support's spring force Kx·(δx − s) within its cap
/// μ·N, N = Kz·compression after the step, the slide its slider.
pub(crate) fn run_oscillator(
    mut rig: Rig,
    drive: Drive,
    (ex, vertical): (&Excitation, &Vertical),
    (dt, stride): (f64, usize),
    duration: f64,
    sink: &mut dyn StepSink,
) -> Outcome {
    let n = step_count(duration, dt);
    let dt_in = dt / stride as f64;
    let g = GroundTable::new(ex, dt_in).with_vertical(Some(vertical), dt_in);
    let moves = ex.moves_ground();
    let mut channels: Vec<&'static Quantity> = q::sliding(moves);
    channels.push(&q::NORMAL);
    let kz = rig.supports[0].kz;
    let trace = super::rows::layout(&channels, 1, 1.0 / kz);
    let mut row = vec![0.0; channels.len()];
    let m = rig.mass;
    start_in_ground_frame(&mut rig, drive, &g);
    let record = |out: &mut dyn StepSink, rig: &Rig, k: usize, v_prev: &mut f64| {
        let t = (k / stride) as f64 * dt;
        let (x_g, v_g) = ground_frame(drive, &g, k);
        let body = &rig.world.bodies[rig.structure];
        let x = body.translation().x - x_g;
        let v = body.linvel().x - v_g;
        let a = if k == 0 { 0.0 } else { (v - *v_prev) / dt };
        *v_prev = v;
        let sup = &rig.supports[0];
        let state = ContactState {
            normal: sup.normal,
            tangential: sup.shear(),
            slip: sup.s,
            gap: sup.delta.1,
        };
        let vals = [force_at(ex, m, t), sup.shear(), x, sup.s, v, a];
        row[..6].copy_from_slice(&vals);
        if moves {
            row[6] = g.disp(k);
        }
        let last = row.len() - 1;
        row[last] = sup.normal;
        out.row(t, &row, &[state]);
    };
    time_loop(
        &mut rig,
        (drive, ex, &g),
        (n * stride, dt_in, stride),
        (trace, sink),
        0.0,
        record,
    )
}

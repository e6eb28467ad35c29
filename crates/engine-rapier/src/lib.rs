//! Engine 3: sliding and rocking bodies as rigid bodies in rapier (rapier3d-f64,
//! parry3d-f64 shapes), with Coulomb friction at exactly the scene's μ and ground motion
//! as a moving kinematic ground or as an inertial force on a fixed-ground model.
//! Shares nothing with the other engines but the scene and the trace.
//!
//! Each model's contact, by default (`contact_model` names the others):
//! - the rigid block: rapier's own contact between the block's collider and the ground;
//! - the oscillator (PEPO): joint-limit, the mass joined to the ground by one joint whose
//!   spring Kx rapier caps at μ·N, in series with a massless slider; under a vertical
//!   component one joint-limit support (Kz compression only); `"foot"`: a spring joint
//!   to a light foot body that slides on the ground;
//! - the rocking body (RPEPO): computed supports, each support's springs and Coulomb
//!   law computed by the engine from the body's pose after every step and applied to the
//!   body as one force and torque (no joints, no colliders); `"joint-limit"`: each
//!   support as two capped motor joints to the ground; `"foot"`: spring joints to light
//!   foot bodies on the ground;
//! - in a 3D scene: the block on a ground slab, the oscillator with its plan contact as an
//!   applied force, the rocking body on an nx × ny grid of computed supports.
//!
//! Every scene runs through one time loop (`time_loop`: a rig, a drive and a recorder;
//! only the feet models settle under gravity before t = 0):
//! - `planar_scene`, `space`: what a planar or a 3D scene runs (rig, drive, stride,
//!   statement); `describe`: the run's settings and findings; `step_rule`: strides and
//!   their bounds; `settings`: the `[engines.rapier]` options and rapier's integration
//!   parameters;
//! - `world`, `planar`: the planar rigs, built and driven; `record`: their recorders;
//! - `space_rigs`, `space_rocking`: the 3D rigs with their recorders; `space_axes`: the
//!   3D scenes' axes, plan vectors and row;
//! - `drive`, `ground`: the routes over the ground's tables (horizontal and vertical);
//! - `rows`: where the rows go (a trace for a whole run, the caller's sink for a streamed
//!   one: the engine streams natively), and the pilot run's path length;
//! - `contact_forces`: the ground's force on a body from rapier's contact impulses;
//! - `vertical`: which scenes take vertical ground motion, and its settings.

#![warn(missing_docs)]

mod budget;
mod contact_forces;
mod describe;
mod drive;
mod ground;
mod ladder;
mod planar;
mod planar_scene;
mod record;
mod rows;
mod settings;
mod space;
mod space_axes;
mod space_rigs;
mod space_rocking;
mod step_rule;
mod time_loop;
mod vertical;
mod world;

pub use drive::Drive;
pub use settings::{
    ACCURACY_MAX, ACCURACY_MIN, KEYS, MAX_STRIDE, OscillatorContact, OscillatorSteps,
    RapierOptions, RapierSettings, StepRule,
};
pub use space_rocking::RockingGrid;
pub use step_rule::{
    COMPUTED_SUPPORTS_OMEGA_H, KINEMATIC_BLOCK_K, MAX_BLOCK_STEPS, ROCKING_OMEGA_H,
};
pub use world::{SUPPORT_DAMPING_SHARE, Support};

use std::sync::Arc;

use rockslide_core::case::{Case, EngineOptions, Excitation, Invariant, Model, Scene};
use rockslide_core::error::InputError;
use rockslide_engine_api::{Engine, NotApplicable, Run, StepSink, Variant, step_count};

/// The rapier rigid-body engine.
pub struct Rapier;

/// The variants, each a constant the engine matches on.
pub mod variant {
    use rockslide_engine_api::Variant;

    /// Mass acceleration as a force M·a(t) on the structure.
    pub const APPLIED_FORCE: Variant = Variant::single("applied-force");
    /// Free response on a fixed ground.
    pub const FIXED_GROUND: Variant = Variant::single("fixed-ground");
    /// Ground motion by a kinematic (position-driven) ground body.
    pub const KINEMATIC_GROUND: Variant = Variant::single("kinematic-ground");
    /// Ground motion as the inertial force −m·ag on every body over a fixed ground.
    pub const INERTIAL_FORCE: Variant = Variant::single("inertial-force");
}

impl Engine for Rapier {
    fn id(&self) -> &'static str {
        settings::ID
    }

    fn description(&self) -> &'static str {
        "rigid bodies with Coulomb contact (rapier3d-f64); elastic-plastic supports as capped spring joints (oscillator) or engine-computed support forces (rocking body)"
    }

    fn variants(&self, scene: &Scene) -> Result<Vec<Variant>, NotApplicable> {
        if scene.spatial().is_some() {
            space::check(scene)?;
        } else {
            vertical::check(scene)?;
        }
        match &scene.model {
            Model::Oscillator(o) => {
                if o.double.is_some() {
                    // Not an error: the foot *is* the double element's intermediate node.
                }
            }
            Model::RigidBlock(_) => {}
            Model::RockingBody(_) => {}
        }
        Ok(match scene.excitation {
            Excitation::None => vec![variant::FIXED_GROUND],
            Excitation::MassAcceleration(_) => vec![variant::APPLIED_FORCE],
            Excitation::GroundDisplacement(_) | Excitation::GroundAcceleration(_) => {
                vec![variant::KINEMATIC_GROUND, variant::INERTIAL_FORCE]
            }
        })
    }

    fn invariant_limit(&self, invariant: Invariant) -> f64 {
        ladder::invariant_limit(invariant)
    }

    fn step_cost(&self, scene: &Scene, variant: Variant) -> f64 {
        ladder::step_cost(scene, variant)
    }

    fn for_sweep(&self, case: &mut Case) -> Vec<String> {
        ladder::sweep_notes(case)
    }

    fn at_rung(&self, case: &Case, dt: f64) -> Option<Case> {
        ladder::at_rung(case, dt)
    }

    fn for_stability(&self, case: &mut Case) {
        ladder::at_own_step(case)
    }

    fn parse_options(&self, case: &Case) -> Result<Option<EngineOptions>, Vec<InputError>> {
        RapierOptions::parse(case).map(|o| Some(Arc::new(o) as EngineOptions))
    }

    fn models_plan_motion(&self) -> bool {
        true
    }

    fn run(&self, case: &Case, variant: Variant, dt: f64) -> Result<Run, InputError> {
        let mut rows = rows::TraceSink::sized(step_count(case.run.duration, dt) + 1);
        let mut run = self.run_into(case, variant, dt, &mut rows)?;
        run.trace = rows.trace;
        Ok(run)
    }

    fn run_streaming(
        &self,
        case: &Case,
        variant: Variant,
        dt: f64,
        sink: &mut dyn StepSink,
    ) -> Result<Run, InputError> {
        self.run_into(case, variant, dt, sink)
    }

    fn streams_natively(&self) -> bool {
        true
    }

    fn recorded_values(&self, case: &Case, _variant: Variant) -> Option<usize> {
        let (channels, contacts) = recorded_layout(case)?;
        Some(1 + channels + contacts * rockslide_core::trace::CONTACT_FIELDS.len())
    }
}

impl Rapier {
    /// Run one variant at time step `dt`, handing every row to `sink` as it is recorded
    /// (the rapier world holds no trace); the returned run's trace is the layout only.
    fn run_into(
        &self,
        case: &Case,
        variant: Variant,
        dt: f64,
        sink: &mut dyn StepSink,
    ) -> Result<Run, InputError> {
        let drive = drive_of(variant);
        let settings = RapierOptions::of(case)?.of_run(drive == Drive::KinematicGround);
        budget::check(case, drive, dt, &settings)?;
        match case.scene.spatial() {
            Some(spatial) => space::run(case, spatial, drive, (variant, dt), settings, None, sink),
            None => planar_scene::run(case, (variant, drive), dt, settings, sink),
        }
    }
}

/// The route a variant names.
fn drive_of(variant: Variant) -> Drive {
    match variant {
        variant::KINEMATIC_GROUND => Drive::KinematicGround,
        variant::INERTIAL_FORCE => Drive::InertialForce,
        _ => Drive::AppliedForce,
    }
}

/// Run `variant` of a 3D rocking-body scene on `grid` instead of the scene's own
/// ([`RockingGrid::from_scene`]): e.g. the grid turned about the vertical.
pub fn run_on_grid(
    case: &Case,
    grid: &RockingGrid,
    variant: Variant,
    dt: f64,
) -> Result<Run, InputError> {
    let settings = RapierOptions::of(case)?.other;
    let drive = drive_of(variant);
    let spatial = case
        .scene
        .spatial()
        .ok_or_else(|| case.field_error("model.kind", "is not a 3D scene"))?;
    let mut rows = rows::TraceSink::sized(step_count(case.run.duration, dt) + 1);
    let mut run = space::run(
        case,
        spatial,
        drive,
        (variant, dt),
        settings,
        Some(grid),
        &mut rows,
    )?;
    run.trace = rows.trace;
    Ok(run)
}

/// The channels and the contacts one row of a run of `case` records (every variant of a
/// scene records the same), or `None` for a 3D body without its depth (the run refuses it).
fn recorded_layout(case: &Case) -> Option<(usize, usize)> {
    let moves = case.scene.excitation.moves_ground();
    let model = &case.scene.model;
    if let Some(spatial) = case.scene.spatial() {
        return Some(match model {
            Model::RockingBody(r) => {
                let grid = RockingGrid::from_scene(r, spatial.depth?, spatial.inertia);
                (space_rocking::channels(moves).len(), grid.points.len())
            }
            _ => (
                space_axes::plan_channels(moves, case.scene.vertical().is_some()).len(),
                1,
            ),
        });
    }
    Some(match model {
        // the sliding channels and N(t)
        Model::Oscillator(_) => (rockslide_core::trace::q::sliding(moves).len() + 1, 1),
        Model::RigidBlock(_) => (record::block_channels(moves).len(), 1),
        Model::RockingBody(r) => (record::rocking_channels(moves).len(), r.supports),
    })
}

//! The run's cost estimated from the scene before any work: rapier steps (output steps ×
//! the stride of the scene's step rule) times the solver's substeps, refused above the
//! step limit (`rockslide_core::case::limits::max_steps`) with the reason — as the other
//! engines' steps are refused at load. A scene whose stiffest mode asks a step rule for
//! its largest stride ([`MAX_STRIDE`] rapier steps an output step) is refused too: the
//! rule can no longer follow the scene (a stiff contact Kx = 1e300 N/m or a mass of
//! 1e-300 kg), and such runs once took minutes without a word (10⁷ rapier steps for a
//! 1 s pulse at 1 ms).

use super::drive::Drive;
use super::settings::{MAX_STRIDE, OscillatorContact, OscillatorSteps, RapierSettings, StepRule};
use super::space_rocking::{self, RockingGrid};
use super::step_rule::{
    MAX_BLOCK_STEPS, SETTLE_STEPS, oscillator_on_support_steps, plan_oscillator_steps,
    plan_vertical_steps, rocking_mode, rocking_stride,
};
use rockslide_core::case::limits::{MAX_STEPS_VARIABLE, max_steps};
use rockslide_core::case::{Case, Excitation, Model, Signal};
use rockslide_core::error::InputError;
use rockslide_engine_api::step_count;

/// Solver steps (rapier steps × substeps) a run of `case` at output step `dt` takes, and
/// the stride (rapier steps per output step) its step rule picks.
pub(crate) fn planned_steps(
    case: &Case,
    drive: Drive,
    dt: f64,
    settings: &RapierSettings,
) -> (f64, usize) {
    let n = step_count(case.run.duration, dt) as f64;
    let (stride, extra, _) = stride_of(case, drive, dt, settings);
    let rapier_steps = n * stride as f64 + extra;
    (rapier_steps * settings.substeps.max(1) as f64, stride)
}

/// The stride of the scene's step rule, rapier steps taken outside the output steps (a
/// pilot run, a settling phase), and whether the stride follows a mode of the scene (a
/// rule capped at [`MAX_STRIDE`]).
fn stride_of(case: &Case, drive: Drive, dt: f64, settings: &RapierSettings) -> (usize, f64, bool) {
    let scene = &case.scene;
    let ex = &scene.excitation;
    let n = step_count(case.run.duration, dt) as f64;
    let ruled = settings.step_rule == StepRule::Scene;
    match &scene.model {
        Model::Oscillator(osc) if scene.spatial().is_some() => {
            let steps = match scene.vertical() {
                Some(v) => plan_vertical_steps(osc, ex, v, settings, dt),
                None => plan_oscillator_steps(osc, ex, settings, dt),
            };
            (steps.stride, 0.0, true)
        }
        Model::Oscillator(osc) => match scene.vertical() {
            Some(v) => (
                oscillator_on_support_steps(osc, ex, v, dt, settings.accuracy).0,
                0.0,
                true,
            ),
            None if settings.oscillator_contact == OscillatorContact::Foot || !ruled => {
                (1, 0.0, false)
            }
            None => (
                OscillatorSteps::for_scene(osc, ex, dt, settings.accuracy).stride,
                0.0,
                true,
            ),
        },
        Model::RigidBlock(_) => {
            let on_record = matches!(ex, Excitation::GroundAcceleration(Signal::Record { .. }));
            if drive == Drive::KinematicGround && ruled && on_record {
                // a pilot run at the output step, then at most MAX_BLOCK_STEPS rapier steps
                let stride = (MAX_BLOCK_STEPS as f64 / n.max(1.0)).floor().max(1.0);
                (stride as usize, n, false)
            } else {
                (1, 0.0, false)
            }
        }
        Model::RockingBody(_) if settings.oscillator_contact == OscillatorContact::Foot => {
            (1, SETTLE_STEPS as f64, false)
        }
        Model::RockingBody(r) => match scene.spatial() {
            Some(spatial) => match spatial.depth {
                Some(depth) => {
                    let grid = RockingGrid::from_scene(r, depth, spatial.inertia);
                    let stride = space_rocking::stride(grid.stiffest_mode(), dt, settings);
                    (stride, 0.0, true)
                }
                None => (1, 0.0, false),
            },
            None if ruled => (rocking_stride(rocking_mode(r), dt, settings), 0.0, true),
            None => (1, 0.0, false),
        },
    }
}

/// `Err` (located at `run.dt`) when the run of `case` would take more solver steps than
/// the step limit, or when its step rule is capped at [`MAX_STRIDE`]: the estimate, the
/// stride behind it and how to raise the limit.
pub(crate) fn check(
    case: &Case,
    drive: Drive,
    dt: f64,
    settings: &RapierSettings,
) -> Result<(), InputError> {
    let (_, _, modal) = stride_of(case, drive, dt, settings);
    let (steps, stride) = planned_steps(case, drive, dt, settings);
    let n = step_count(case.run.duration, dt);
    if modal && stride >= MAX_STRIDE {
        return Err(case.field_error(
            "run.dt",
            format!(
                "is {dt} s, but the scene's stiffest mode asks rapier's step rule for at least \
                 {MAX_STRIDE} rapier steps an output step (its largest): {n} output steps would \
                 take {steps:.3e} solver steps and the rule could not follow the scene; the \
                 contact's stiffness or the mass is outside the engine's validity"
            ),
        ));
    }
    let limit = max_steps();
    if steps > limit as f64 || steps.is_nan() {
        return Err(case.field_error(
            "run.dt",
            format!(
                "is {dt} s, but rapier would take {steps:.3e} solver steps ({n} output steps × \
                 {stride} rapier steps × {} substeps); the limit is {limit} (set \
                 {MAX_STEPS_VARIABLE} to raise it)",
                settings.substeps.max(1)
            ),
        ));
    }
    Ok(())
}

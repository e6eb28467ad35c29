//! rapier on a bidirectional (3D) scene (`Scene::spatial`), its native setting: the
//! excitation pair drives the bodies in both horizontal directions at once.
//!
//! - the rigid block on a ground slab and the oscillator (PEPO) in plan, with its plan
//!   contact as an applied force: `space_rigs` (their rigs and recorders);
//! - the rocking body on its nx × ny grid of supports: `space_rocking`.
//!
//! Here: whether rapier runs a 3D scene, each model's step rule and what its run states.
//! rapier's 3D friction is a circular cone per friction constraint (the tangential
//! impulse is solved as a coupled 2 × 2 system, Δλ = −K⁻¹·Δv, and capped in magnitude,
//! `simd_cap_magnitude`, in `contact_constraint_element.rs` of rapier 0.36); with the
//! block's tipping locked K = I/m, so the capped impulse opposes the slip in every
//! direction (free to tip, K holds h²/I about each horizontal axis and a slab slid 6.6°
//! off its drive).
//!
//! Axes: scene (x, y, z up) is rapier's (X, −Z, Y), so the frame stays right-handed.
//! The ground moves by either route of the planar engine (`Drive`): a kinematic ground
//! moved to x_g(t_{n+1}) in plan each step, or a fixed ground with the inertial force
//! −m·(v_g(n+1) − v_g(n))/Δt on the body. Traces keep the planar keys for x and add the
//! catalogue's y channels, the resultant sliding and its azimuth. A vertical component
//! moves the block's ground by the planar routes (the kinematic ground to y_g(t_{n+1}),
//! or −m·a_v on the block over a fixed ground): rapier's contact carries N(t), its cone
//! μ·N(t), and the block flies when the ground drops faster than g; the oscillator and
//! the rocking body stand on their springs Kz (their own rigs).

use rapier3d_f64::prelude::FrictionModel;

use super::describe::Statement;
use super::drive::{Drive, PlanDrive};
use super::rows::PathLength;
use super::settings::{RapierSettings, StepRule};
use super::space_rigs::{PlanVertical, run_block, run_oscillator};
use super::space_rocking::{self, RockingGrid};
use super::step_rule::{
    MAX_BLOCK_STEPS, block_stride, block_substeps, plan_oscillator_steps, plan_vertical_steps,
};
use super::time_loop::Outcome;
use rockslide_core::case::{
    Case, Excitation, Model, NormalForce, Oscillator, RigidBlock, Scene, Signal, Spatial,
};
use rockslide_core::error::InputError;
use rockslide_core::trace::q;
use rockslide_engine_api::{NotApplicable, Run, Setting, StepSink, Variant, step_count};

/// Why rapier does not run a 3D scene, if it does not. Under a vertical component the
/// oscillator and the rocking body stand on their supports' Kz ([`PlanVertical`]: as in
/// 2D), the block on rapier's contact.
pub fn check(scene: &Scene) -> Result<(), NotApplicable> {
    if let Some(v) = scene.vertical() {
        match &scene.model {
            Model::Oscillator(_) if v.normal_force == NormalForce::QuasiStatic => return Err(NotApplicable(
                "rapier's oscillator in plan under vertical motion stands on its vertical stiffness Kz: a rigid vertical contact (normal_force = \"quasi-static\") is not its model".into(),
            )),
            Model::RockingBody(_) if v.normal_force == NormalForce::QuasiStatic => return Err(NotApplicable(
                "rapier's rocking body in plan stands on its supports' Kz: a rigid vertical contact (normal_force = \"quasi-static\") is not its model".into(),
            )),
            Model::Oscillator(o) if o.double.is_some() => return Err(NotApplicable(
                "rapier models vertical motion in plan on the single contact, not the double arrangement".into(),
            )),
            _ => {}
        }
    }
    match &scene.model {
        Model::RigidBlock(b) if b.initial_tilt != 0.0 => Err(NotApplicable(
            "an initially tilted rigid block in a bidirectional (3D) scene is not yet modelled in rapier (3D rocking is not built)".into(),
        )),
        _ => Ok(()),
    }
}

/// rapier steps per output step for the block on a moving kinematic ground under a
/// recorded pair: the planar rule (`planar_scene::block_kinematic_stride`) with the plan
/// ground's ∫|a_g|dt (vector norm) and the total distance slid along the path S of a
/// pilot run (inertial force at the output step): Δt ≤ 2·ε·S/∫|a_g|dt, at most
/// [`MAX_BLOCK_STEPS`] steps. Returns (stride, S, ∫|a_g|dt, Δt bound).
pub fn block_kinematic_stride(
    case: &Case,
    spatial: &Spatial,
    b: &RigidBlock,
    half_depth: f64,
    settings: &RapierSettings,
    dt: f64,
) -> (usize, f64, f64, f64) {
    let ex = &case.scene.excitation;
    let n = step_count(case.run.duration, dt);
    let pilot_drive = PlanDrive::new(Drive::InertialForce, ex, spatial, dt, n)
        .with_vertical(case.scene.vertical());
    let abs_ag = pilot_drive.abs_acceleration_integral();
    let mut path = PathLength::of(q::SLIDE.key, Some(q::SLIDE_Y.key));
    run_block(b, half_depth, settings, &pilot_drive, (dt, 1), n, &mut path);
    let slid = path.sum;
    let dt_max = 2.0 * settings.accuracy * slid / abs_ag;
    (block_stride(dt, dt_max, n), slid, abs_ag, dt_max)
}

/// Run `drive` on the 3D scene of `case` at output step `dt`: the block or the
/// oscillator in plan, with the settings and findings the run states.
pub fn run(
    case: &Case,
    spatial: &Spatial,
    drive: Drive,
    (variant, dt): (Variant, f64),
    mut settings: RapierSettings,
    grid: Option<&RockingGrid>,
    sink: &mut dyn StepSink,
) -> Result<Run, InputError> {
    check(&case.scene).map_err(|e| case.field_error("model.kind", e.0))?;
    let mut said = Statement {
        described: settings.describe(dt),
        findings: Vec::new(),
    };
    let outcome = match &case.scene.model {
        Model::Oscillator(osc) => {
            oscillator_case(case, spatial, osc, drive, dt, &settings, (&mut said, sink))
        }
        Model::RigidBlock(b) => block_case(
            case,
            spatial,
            b,
            drive,
            dt,
            &mut settings,
            (&mut said, sink),
        )?,
        Model::RockingBody(r) => {
            let depth = spatial.depth.ok_or_else(|| {
                case.field_error(
                    "model.half_depth",
                    "is required for a rocking body in a 3D scene",
                )
            })?;
            let ex = &case.scene.excitation;
            let n = step_count(case.run.duration, dt);
            let pd_for =
                |dt_in: f64, steps: usize| PlanDrive::new(drive, ex, spatial, dt_in, steps);
            let grid = grid
                .cloned()
                .unwrap_or_else(|| RockingGrid::from_scene(r, depth, spatial.inertia));
            space_rocking::case(
                &grid,
                spatial,
                depth,
                (pd_for, case.scene.vertical()),
                (dt, n),
                &settings,
                (&mut said, sink),
            )
        }
    };
    said.described.push(Setting::text("ground motion", match drive {
            Drive::AppliedForce => "fixed ground; mass acceleration pair as force M·a (Simpson mean over the step), in plan",
            Drive::KinematicGround => "kinematic position-based ground moved in plan to x_g(t_{n+1}) each step",
            Drive::InertialForce => "fixed ground; −m·(v_g(n+1) − v_g(n))/Δt in plan on the body, −v_g(0⁺) initial velocity",
        }
        ));
    said.described.push(Setting::text(
        "excitation",
        format!(
            "azimuth {}°{}; scene (x, y, z up) is rapier's (X, −Z, Y)",
            spatial.azimuth_deg,
            if spatial.second.is_some() {
                ", second component at right angles"
            } else {
                ""
            }
        ),
    ));
    Ok(said.into_run(variant, dt, settings.substeps, outcome))
}

/// The oscillator in plan at the planar step rule, with what it states.
fn oscillator_case(
    case: &Case,
    spatial: &Spatial,
    osc: &Oscillator,
    drive: Drive,
    dt: f64,
    settings: &RapierSettings,
    (said, sink): (&mut Statement, &mut dyn StepSink),
) -> Outcome {
    let ex = &case.scene.excitation;
    let n = step_count(case.run.duration, dt);
    let vertical = case.scene.vertical();
    let steps = match vertical {
        Some(v) => plan_vertical_steps(osc, ex, v, settings, dt),
        None => plan_oscillator_steps(osc, ex, settings, dt),
    };
    let pd = PlanDrive::new(drive, ex, spatial, steps.dt_inner, n * steps.stride);
    let pv = vertical.map(|v| PlanVertical::new(osc, v, steps.dt_inner));
    said.described
        .retain(|s| !s.name.starts_with("contact softness") && !s.name.starts_with("friction"));
    said.described.push(Setting::text("contact model", if pv.is_some() {
            "applied force in plan: one body free in x, y and z (no collider, rotations locked); the engine computes Kx·(u − p) − C·u̇ after every rapier step, the slider p returned radially onto |F| ≤ μ·N (circular cone, N from the vertical spring), and applies it over the next step (the only model in plan: contact_model is not read)"
        } else {
            "applied force in plan: one body free in x and y (no collider, rotations and the vertical locked); the engine computes Kx·(u − p) − C·u̇ after every rapier step, the slider p returned radially onto |F| ≤ μ·M·g (circular cone), and applies it over the next step (the only model in plan: contact_model is not read)"
        }
        ));
    if pv.is_some() {
        said.described.push(Setting::text("vertical ground motion", "the body free vertically too, on a compression-only spring Kz from static rest (an applied force, world gravity 0): N − M·g − M·a_v over each step, a_v the step's mean −(vg_y(n+1) − vg_y(n))/Δt on every route (the vertical in the ground's frame), N = Kz·δ after the step, the slider's circle μ·N"));
    }
    said.described.push(Setting::text(
        "rapier step [s] (output step / stride)",
        format!("{} (stride {})", steps.dt_inner, steps.stride),
    ));
    said.findings.push(format!(
        "{} the engine's validity: rapier step {:.3e} s, the planar oscillator's step rule asks ≤ {:.3e} s for accuracy {}{}; |F| ≤ μ·N by construction; measured against the plan-motion reference (docs/rapier-engine.md, \"Plan motion\"): {OSCILLATOR_MEASURED}{}",
        if steps.within_target() { "within" } else { "outside" },
        steps.dt_inner,
        steps.dt_max,
        settings.accuracy,
        if pv.is_some() { " (its period scaled to the vertical mode √(Kz/M) when faster)" } else { "" },
        if pv.is_some() { VERTICAL_MEASURED } else { "" },
    ));
    run_oscillator(
        osc,
        settings,
        (&pd, pv.as_ref()),
        (dt, steps.stride),
        n,
        sink,
    )
}

/// The block on the ground slab (the kinematic ground at its step rule under a record),
/// with what it states.
fn block_case(
    case: &Case,
    spatial: &Spatial,
    b: &RigidBlock,
    drive: Drive,
    dt: f64,
    settings: &mut RapierSettings,
    (said, sink): (&mut Statement, &mut dyn StepSink),
) -> Result<Outcome, InputError> {
    let ex = &case.scene.excitation;
    let n = step_count(case.run.duration, dt);
    let depth = spatial.depth.map(|d| d.half_depth).ok_or_else(|| {
        case.field_error(
            "model.half_depth",
            "is required for a rigid block in a 3D scene",
        )
    })?;
    let ruled = drive == Drive::KinematicGround
        && settings.step_rule == StepRule::Scene
        && matches!(ex, Excitation::GroundAcceleration(Signal::Record { .. }));
    let stride = if ruled {
        kinematic_rule(case, spatial, b, depth, dt, settings, said)
    } else {
        1
    };
    let dt_in = dt / stride as f64;
    let vertical = case.scene.vertical();
    let pd = PlanDrive::new(drive, ex, spatial, dt_in, n * stride).with_vertical(vertical);
    said.described.push(Setting::text("block", format!(
            "uniform cuboid 2b × 2h × 2d = {} × {} × {} m (x, z, y), mass {} kg, on the ground slab, free in x, y, z and yaw, its tipping rotations locked (the friction's tangent effective mass isotropic: free to tip, a 2 × 1 m slab slid 6.6° off its drive)",
            2.0 * b.half_width,
            2.0 * b.half_height,
            2.0 * depth,
            b.mass
        )));
    said.described.push(Setting::text(
        "rapier step [s] (output step / stride)",
        format!("{dt_in} (stride {stride}, {} substeps)", settings.substeps),
    ));
    said.described.push(Setting::text("friction cone", "circular: rapier 0.36 solves each friction constraint's two tangential impulses together and caps their magnitude at μ·N"));
    if vertical.is_some() {
        said.described.push(Setting::text("vertical ground motion", match drive {
            Drive::KinematicGround => "kinematic ground moved to y_g(t_{n+1}) each step with its plan motion (a_v integrated twice, exactly between samples); uplift measured from the moving ground; N from rapier's contact (restitution 0: a landing block loses its vertical velocity), the cone's radius μ·N",
            _ => "fixed ground; −m·(vg_y(n+1) − vg_y(n))/Δt on the block over each step (a_v positive upward); N from rapier's contact (restitution 0: a landing block loses its vertical velocity), the cone's radius μ·N",
        }));
    }
    said.findings.push(format!(
        "measured against the plan-motion block reference with the Simplified friction model (docs/rapier-engine.md, \"Plan motion\"): {BLOCK_MEASURED}{}",
        if settings.friction == FrictionModel::Coulomb {
            "; outside the engine's validity with friction_model = \"coulomb\": one record along x slid 59 % too far (+16 % at 30°, within 0.01 % at 45° and 135°)"
        } else {
            ""
        }
    ));
    if vertical.is_some() {
        said.findings.push(format!(
            "under a vertical component, measured (docs/rapier-engine.md, \"Plan motion\"): {BLOCK_VERTICAL_MEASURED}"
        ));
    }
    said.findings.push(tipping_finding(b, depth));
    Ok(run_block(b, depth, settings, &pd, (dt, stride), n, sink))
}

/// Whether the block's locked tipping is its physics: friction, at most μ·M·g at the
/// base, cannot tip a block with μ < min(b, d)/h about an edge of its footprint.
fn tipping_finding(b: &RigidBlock, depth: f64) -> String {
    let limit = b.half_width.min(depth) / b.half_height;
    if b.mu < limit {
        format!(
            "within the engine's validity for its locked tipping: μ = {} < min(b, d)/h = {limit:.4}, so friction cannot tip the block",
            b.mu
        )
    } else {
        format!(
            "outside the engine's validity: the block's tipping rotations are locked (a sliding block), but μ = {} ≥ min(b, d)/h = {limit:.4}: a drive above g·min(b, d)/h would tip it",
            b.mu
        )
    }
}

/// The block's kinematic-ground step rule ([`block_kinematic_stride`]) with what it
/// states; the output step's substeps shared among its rapier steps. Returns the stride.
fn kinematic_rule(
    case: &Case,
    spatial: &Spatial,
    b: &RigidBlock,
    depth: f64,
    dt: f64,
    settings: &mut RapierSettings,
    said: &mut Statement,
) -> usize {
    let (stride, slid, abs_ag, dt_max) =
        block_kinematic_stride(case, spatial, b, depth, settings, dt);
    let dt_in = dt / stride as f64;
    let estimate = 0.5 * dt_in * abs_ag;
    said.described.push(Setting::text("step rule", format!(
            "Δt ≤ 2·accuracy·S/∫|a_g|dt = {dt_max:.4e} s (S = {slid:.4e} m slid along the path in a pilot run on the inertial-force route at the output step, ∫|a_g|dt = {abs_ag:.4} m/s of the plan ground acceleration); at most {MAX_BLOCK_STEPS} rapier steps"
        )));
    said.findings.push(format!(
        "{} the engine's validity for the distance slid: the kinematic ground's slip estimate ½·Δt·∫|a_g|dt = {estimate:.3e} m is {:.2} % of S (target {} %)",
        if dt_in <= dt_max * (1.0 + 1e-12) {
            "within"
        } else {
            "outside"
        },
        100.0 * estimate / slid,
        100.0 * settings.accuracy
    ));
    if stride > 1 {
        settings.substeps = block_substeps(settings.substeps, stride);
    }
    stride
}

/// The oscillator's measured agreement, stated in its runs' findings
/// (tests/all/rapier_space.rs).
const OSCILLATOR_MEASURED: &str = "peaks and residual +0.003 %, slip start −0.8 ms; under the shipped record pair (T = 0.5 s, μ = 0.05) peak relative displacement +0.82 %, residual resultant sliding +0.66 %, first order in the step (the radial return moves the slider along the step's last direction)";

/// The vertical component's measured agreement, stated in its runs' findings
/// (tests/all/vertical_plan.rs).
const VERTICAL_MEASURED: &str = "; with a vertical pulse at 2/3 on its spring Kz (pepo-pulse-azimuth30-vertical) peaks and residual within 0.00003 %, slip start −0.8 ms";

/// The block's measured agreement under a vertical component, stated in its runs'
/// findings (tests/all/rapier_block_vertical_plan.rs, the case's own gates).
const BLOCK_VERTICAL_MEASURED: &str = "three components of one station without lift-off (block-ridgecrest-ccc-xyz, against the plan-motion reference with μ·(g + a_v)): peak / residual resultant sliding +0.025 / +0.024 % (inertial force), +0.008 / +0.008 % (kinematic ground), 16 slip episodes as the reference's; lifting off (block-liftoff at 30°, against the exact planar block with its flight along the drive): residual +0.018 % (inertial force) / −0.11 % (kinematic ground), peak uplift −0.003 / +0.45 %, first full lift-off +0.86 ms on the inertial route (the kinematic ground's contact chatters before it), the slide along the drive to 6e-15 m";

/// The block's measured agreement, stated in its runs' findings
/// (tests/all/rapier_space.rs).
const BLOCK_MEASURED: &str = "record pair (block-record-pair), peak / residual resultant sliding −0.11 / −0.09 % on both routes; one record at five azimuths, residual +0.028 % at each, to 5e-14 of each other (inertial force; +0.001 % at 0° and 135° on the kinematic ground); a 2 × 1 m slab under a pulse at 30° (block-pulse-azimuth30) slides along its drive to 2e-13°: isotropic, |T| ≤ μ·N on every step to round-off";

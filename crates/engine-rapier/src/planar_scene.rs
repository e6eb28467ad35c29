//! What a planar scene runs: from the case and the route, the rig (`world`: the
//! oscillator on its joint-limit contact, on a support under a vertical component or on a
//! foot; the rigid block; the rocking body on computed or joint-limit supports or on
//! feet), the stride of its step rule (`step_rule`), and what the run states
//! (`describe`); then the run, through the one time loop (`record`).

use super::describe::{self, Statement};
use super::drive::Drive;
use super::record;
use super::rows::PathLength;
use super::settings::{
    self, KINEMATIC_BLOCK_CONTACT_HZ, OscillatorContact, OscillatorSteps, RapierOptions,
    RapierSettings, StepRule,
};
use super::step_rule::{
    KINEMATIC_BLOCK_K, MAX_BLOCK_STEPS, SETTLE_STEPS, block_stride, oscillator_on_support_steps,
    peak_ground_acceleration, rocking_mode, rocking_stride,
};
use super::time_loop::Outcome;
use super::vertical;
use super::world::{self, GroundKind};
use rockslide_core::case::{Case, Model, Oscillator, RigidBlock, RockingBody, Vertical};
use rockslide_core::error::InputError;
use rockslide_engine_api::{Run, Setting, StepSink, Variant, step_count};

/// Run route `drive` of the planar scene of `case` at output step `dt` with `settings`,
/// handing every row to `sink`; the run's trace is the layout only.
pub(crate) fn run(
    case: &Case,
    (variant, drive): (Variant, Drive),
    dt: f64,
    settings: RapierSettings,
    sink: &mut dyn StepSink,
) -> Result<Run, InputError> {
    vertical::check_settings(case, &settings)?;
    let ex = &case.scene.excitation;
    let mut said = Statement {
        described: settings.describe(dt),
        findings: settings::former_contact_model_name(case)
            .into_iter()
            .collect(),
    };
    let run = (drive, dt, &settings);
    let outcome = match &case.scene.model {
        Model::Oscillator(osc) if let Some(v) = case.scene.vertical() => {
            oscillator_on_support(case, osc, v, run, (&mut said, sink))
        }
        Model::Oscillator(osc) => oscillator(case, osc, run, (&mut said, sink)),
        Model::RigidBlock(b) => block(case, b, run, (&mut said, sink))?,
        Model::RockingBody(r) if settings.oscillator_contact != OscillatorContact::Foot => {
            rocking_on_supports(case, r, run, (&mut said, sink))
        }
        Model::RockingBody(r) => rocking_on_feet(case, r, run, (&mut said, sink)),
    };
    describe::ground_motion(drive, &mut said.described);
    said.described.extend(vertical::describe(case, drive));
    describe::record_baseline(ex, drive, &mut said.described);
    Ok(said.into_run(variant, dt, settings.substeps, outcome))
}

/// The route, the output step and the settings of a run.
type RunOf<'s> = (Drive, f64, &'s RapierSettings);

/// Where a run states what it did and sends its rows.
type Out<'o> = (&'o mut Statement, &'o mut dyn StepSink);

/// The oscillator on one joint-limit support under a vertical component.
fn oscillator_on_support(
    case: &Case,
    osc: &Oscillator,
    v: &Vertical,
    (drive, dt, settings): RunOf,
    (said, sink): Out,
) -> Outcome {
    let ex = &case.scene.excitation;
    let (stride, dt_in, steps) = oscillator_on_support_steps(osc, ex, v, dt, settings.accuracy);
    let rig = world::oscillator_with_supports(osc, settings, dt_in, drive.ground_kind());
    let described = &mut said.described;
    describe::describe_joint_limit(osc, settings, &steps, ex, described, &mut said.findings);
    described.retain(|s| {
        !s.name.starts_with("contact model")
            && !s.name.starts_with("rapier step")
            && !s.name.starts_with("friction limit")
    });
    described.push(Setting::text("contact model", "joint-limit support: mass free in X and Z on two joints ground → mass: Kz as a ForceBased motor on Y, compression only, and Kx on X capped at μ·N(t) after every step, in series with a massless slider"));
    described.push(Setting::text("rapier step [s] (output step / stride)", format!("{dt_in} (stride {stride}; the step rule's period scaled to the vertical mode √(Kz/M) when faster)")));
    let duration = case.run.duration;
    record::run_oscillator_on_support(rig, drive, (ex, v), (dt, stride), duration, sink)
}

/// The oscillator on its joint-limit contact (the default) or on a foot.
fn oscillator(
    case: &Case,
    osc: &Oscillator,
    (drive, dt, settings): RunOf,
    (said, sink): Out,
) -> Outcome {
    let ex = &case.scene.excitation;
    let (described, findings) = (&mut said.described, &mut said.findings);
    let (rig, stride) = match settings.oscillator_contact {
        OscillatorContact::Foot => {
            let rig = world::oscillator(osc, settings, dt, drive.ground_kind());
            describe::describe_foot(osc, &rig, dt, described, findings);
            (rig, 1)
        }
        OscillatorContact::JointLimit | OscillatorContact::ComputedSupports => {
            let mut steps = OscillatorSteps::for_scene(osc, ex, dt, settings.accuracy);
            if settings.step_rule == StepRule::None {
                steps = steps.at_output_step(dt);
            }
            let rig =
                world::oscillator_joint_limit(osc, settings, steps.dt_inner, drive.ground_kind());
            describe::describe_joint_limit(osc, settings, &steps, ex, described, findings);
            (rig, steps.stride)
        }
    };
    let duration = case.run.duration;
    record::run_oscillator(rig, osc.contact.kx, drive, ex, (dt, stride), duration, sink)
}

/// The rigid block; on a kinematic ground under a record at its own step rule.
fn block(
    case: &Case,
    b: &RigidBlock,
    (drive, dt, settings): RunOf,
    (said, sink): Out,
) -> Result<Outcome, InputError> {
    // On a kinematic ground under a record the solver is the block's own
    // (`RapierSettings::for_run`, also with `step_rule = "none"`, so a sweep's
    // rungs converge as the case's run does); the step rule only with
    // `step_rule = "scene"`.
    let kinematic = drive == Drive::KinematicGround;
    let on_record = settings::kinematic_block_on_record(case, kinematic);
    let stride = if on_record && settings.step_rule == StepRule::Scene {
        // the pilot runs on the inertial-force route, with that route's settings
        let pilot = RapierOptions::of(case)?.other;
        block_kinematic_stride(case, b, (settings, &pilot), dt, said)
    } else {
        1
    };
    let dt_in = dt / stride as f64;
    if on_record {
        said.described.push(Setting::text("solver (block on a kinematic ground under a record)", format!(
                "{} substep(s) per rapier step, contacts at {} Hz unless the case sets them: the ground's velocity changes once a step and friction takes only μ·N·Δt/substeps of it in the first substep, so more substeps let the stuck block slip; a stiffer contact than rapier's 30 Hz keeps the block from tilting under the friction's moment (docs/rapier-engine.md)",
                settings.substeps,
                settings.contact_hz.unwrap_or(KINEMATIC_BLOCK_CONTACT_HZ)
            )));
    }
    let rig = world::rigid_block(b, settings, dt_in, drive.ground_kind());
    describe::block(b, &mut said.described);
    let (ex, vert, duration) = (
        &case.scene.excitation,
        case.scene.vertical(),
        case.run.duration,
    );
    Ok(record::run_block(
        rig,
        b,
        drive,
        (ex, vert),
        (dt, stride),
        duration,
        sink,
    ))
}

/// The rocking body on computed supports (the default) or joint-limit ones.
fn rocking_on_supports(
    case: &Case,
    r: &RockingBody,
    (drive, dt, settings): RunOf,
    (said, sink): Out,
) -> Outcome {
    let omega_r = rocking_mode(r);
    let stride = match settings.step_rule {
        StepRule::Scene => rocking_stride(omega_r, dt, settings),
        StepRule::None => 1,
    };
    let dt_in = dt / stride as f64;
    let rig = if settings.oscillator_contact == OscillatorContact::ComputedSupports {
        world::rocking_body_applied_force(r, settings, dt_in, drive.ground_kind())
    } else {
        world::rocking_body_joint_limit(r, settings, dt_in, drive.ground_kind())
    };
    describe::describe_rocking_joint_limit(
        r,
        omega_r,
        dt_in,
        stride,
        settings,
        &mut said.described,
    );
    said.findings
        .push(describe::rocking_validity(omega_r, dt_in, settings));
    let (ex, vert, duration) = (
        &case.scene.excitation,
        case.scene.vertical(),
        case.run.duration,
    );
    record::run_rocking_joint_limit(rig, r, drive, (ex, vert), (dt, stride), duration, sink)
}

/// The rocking body on feet (`contact_model = "foot"`), settled before t = 0.
fn rocking_on_feet(
    case: &Case,
    r: &RockingBody,
    (drive, dt, settings): RunOf,
    (said, sink): Out,
) -> Outcome {
    let rig = world::rocking_body(r, settings, dt, drive.ground_kind());
    let out = (&mut said.described, &mut said.findings);
    describe::describe_rocking_feet(r, &rig, dt, settings, out);
    let (ex, duration) = (&case.scene.excitation, case.run.duration);
    record::run_rocking(rig, r, drive, ex, dt, (duration, SETTLE_STEPS), sink)
}

/// The rigid block's step rule on a moving kinematic ground under a recorded ground
/// acceleration: at one substep and a stiff contact ([`RapierSettings::for_run`]) the
/// total distance slid is off by about K·PGA·Δt² ([`KINEMATIC_BLOCK_K`]), so Δt is
/// chosen with that estimate within the accuracy target of the total slid S,
/// Δt ≤ √(ε·S/(K·PGA)). S is measured by a pilot run on the inertial-force route at the
/// output step, with that route's settings (`pilot`; +0.17 % on the Northridge block at
/// 1 ms). Returns rapier steps per output
/// step, capped so that the run takes at most [`MAX_BLOCK_STEPS`]; beyond it the run says
/// it is outside the engine's validity, with the estimate.
fn block_kinematic_stride(
    case: &Case,
    b: &rockslide_core::case::RigidBlock,
    (settings, pilot): (&RapierSettings, &RapierSettings),
    dt: f64,
    said: &mut Statement,
) -> usize {
    let (described, findings) = (&mut said.described, &mut said.findings);
    let ex = &case.scene.excitation;
    let duration = case.run.duration;
    let pilot_rig = world::rigid_block(b, pilot, dt, GroundKind::Fixed);
    let mut path = PathLength::of(rockslide_core::trace::q::SLIDE.key, None);
    record::run_block(
        pilot_rig,
        b,
        Drive::InertialForce,
        (ex, case.scene.vertical()),
        (dt, 1),
        duration,
        &mut path,
    );
    let slid = path.sum;
    let pga = peak_ground_acceleration(ex);
    let eps = settings.accuracy;
    let dt_max = (eps * slid / (KINEMATIC_BLOCK_K * pga)).sqrt();
    let n = step_count(duration, dt);
    let stride = block_stride(dt, dt_max, n);
    let dt_in = dt / stride as f64;
    let estimate = KINEMATIC_BLOCK_K * pga * dt_in * dt_in;
    described.push(Setting::text(
        "accuracy target (relative)",
        format!("{eps}"),
    ));
    described.push(Setting::text(
        "rapier step [s] (output step / stride)",
        format!("{dt_in} (stride {stride})"),
    ));
    described.push(Setting::text("step rule", format!(
            "Δt ≤ √(accuracy·S/(K·PGA)) = {dt_max:.4e} s: the kinematic ground's error of the total slid K·PGA·Δt² (K = {KINEMATIC_BLOCK_K}, measured) within the accuracy of the total slid S = {slid:.4e} m (pilot run: inertial force at the output step), PGA = {pga:.4} m/s²; at most {MAX_BLOCK_STEPS} rapier steps"
        )));
    if dt_in <= dt_max * (1.0 + 1e-12) {
        findings.push(format!(
            "within the engine's validity for the total distance slid: the kinematic ground's error estimate K·PGA·Δt² = {estimate:.3e} m is {:.3} % of the total slid {slid:.4e} m (target {} %; measured on the five shipped records, μ 0.08–0.185, against the exact reference at 0.5 ms: total slid within 0.50 %, residual within 0.34 % for slides ≥ 1 cm; docs/rapier-engine.md)",
            100.0 * estimate / slid,
            100.0 * eps
        ));
    } else {
        findings.push(format!(
            "outside the engine's validity for the total distance slid: the moving kinematic ground's error of the total slid, about K·PGA·Δt² = {estimate:.3e} m at the largest run of {MAX_BLOCK_STEPS} rapier steps (Δt = {dt_in:.3e} s), against a total slid of {slid:.3e} m and an accuracy target of {} %; the inertial-force route has no such error (docs/rapier-engine.md)",
            100.0 * eps
        ));
    }
    stride
}

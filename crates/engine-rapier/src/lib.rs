//! Engine 3: the block as a rigid body on a ground body, simulated with rapier
//! (rapier3d-f64, parry3d-f64 shapes): Coulomb friction with exactly the scene's μ,
//! elasticity as spring joints to light foot bodies that touch the ground, ground motion
//! as a moving kinematic ground or as an inertial force on a fixed-ground model
//! (SPEC §2, engine 3). Shares nothing with the other engines but the scene and the trace.
//!
//! - `settings`: the `[engines.rapier]` options and rapier's integration parameters;
//! - `world`: building the world (ground, structure, feet, joints);
//! - `ground`: ground displacement and velocity tables for both ground-motion routes;
//! - `simulate`: the time loop and the recorded channels;
//! - `rows`: where the rows go (a trace for a whole run, the caller's sink for a streamed
//!   one: the engine streams natively), and the pilot run's path length;
//! - `contact_forces`: the ground's force on a body from rapier's contact impulses;
//! - `vertical`: vertical ground motion by both routes, the oscillator on a support.

#![warn(missing_docs)]

mod contact_forces;
mod ground;
mod ladder;
mod rows;
mod settings;
mod simulate;
mod space;
mod space_rocking;
mod vertical;
mod world;

pub use settings::{
    ACCURACY_MAX, ACCURACY_MIN, KEYS, MAX_STRIDE, OscillatorContact, OscillatorSteps,
    RapierSettings, StepRule,
};
pub use simulate::Drive;
pub use space_rocking::RockingGrid;
pub use world::{SUPPORT_DAMPING_SHARE, Support};

use rockslide_core::case::{Case, Excitation, Invariant, Model, Scene};
use rockslide_core::error::InputError;
use rockslide_engine_api::{
    Arrangement, Engine, NotApplicable, Run, SolverStats, StepSink, Variant, step_count,
};

/// The rapier rigid-body engine.
pub struct Rapier;

/// Variant names.
pub mod variant {
    /// Mass acceleration as a force M·a(t) on the structure.
    pub const APPLIED_FORCE: &str = "applied-force";
    /// Free response on a fixed ground.
    pub const FIXED_GROUND: &str = "fixed-ground";
    /// Ground motion by a kinematic (position-driven) ground body.
    pub const KINEMATIC_GROUND: &str = "kinematic-ground";
    /// Ground motion as the inertial force −m·ag on every body over a fixed ground.
    pub const INERTIAL_FORCE: &str = "inertial-force";
}

impl Engine for Rapier {
    fn id(&self) -> &'static str {
        "rapier"
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
        }
        .into_iter()
        .map(Variant::single)
        .collect())
    }

    fn invariant_limit(&self, invariant: Invariant) -> f64 {
        ladder::invariant_limit(invariant)
    }

    fn step_cost(&self, scene: &Scene, variant: &str) -> f64 {
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

    fn check_options(&self, case: &Case) -> Vec<InputError> {
        RapierSettings::from_case(case).err().unwrap_or_default()
    }

    fn models_plan_motion(&self) -> bool {
        true
    }

    fn run(&self, case: &Case, variant: &str, dt: f64) -> Result<Run, InputError> {
        let mut rows = rows::TraceSink::sized(step_count(case.run.duration, dt) + 1);
        let mut run = self.run_into(case, variant, dt, &mut rows)?;
        run.trace = rows.trace;
        Ok(run)
    }

    fn run_streaming(
        &self,
        case: &Case,
        variant: &str,
        dt: f64,
        sink: &mut dyn StepSink,
    ) -> Result<Run, InputError> {
        self.run_into(case, variant, dt, sink)
    }

    fn streams_natively(&self) -> bool {
        true
    }

    fn recorded_values(&self, case: &Case, _variant: &str) -> Option<usize> {
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
        variant: &str,
        dt: f64,
        sink: &mut dyn StepSink,
    ) -> Result<Run, InputError> {
        let drive = match variant {
            variant::KINEMATIC_GROUND => Drive::KinematicGround,
            variant::INERTIAL_FORCE => Drive::InertialForce,
            _ => Drive::AppliedForce,
        };
        let kinematic = drive == Drive::KinematicGround;
        let settings = RapierSettings::for_run(case, kinematic).map_err(|mut e| e.remove(0))?;
        if let Some(spatial) = case.scene.spatial() {
            return space::run(case, spatial, drive, (variant, dt), settings, None, sink);
        }
        vertical::check_settings(case, &settings)?;
        let vert = case.scene.vertical();
        let ex = &case.scene.excitation;
        let duration = case.run.duration;
        let mut described = settings.describe(dt);
        let mut findings = Vec::new();
        let outcome = match &case.scene.model {
            Model::Oscillator(osc) if let Some(v) = vert => {
                let (stride, dt_in, steps) =
                    vertical::oscillator_steps(osc, ex, v, dt, settings.accuracy);
                let rig =
                    vertical::oscillator_with_supports(osc, &settings, dt_in, drive.ground_kind());
                describe_joint_limit(osc, &settings, &steps, ex, &mut described, &mut findings);
                described.retain(|(k, _)| {
                    !k.starts_with("contact model")
                        && !k.starts_with("rapier step")
                        && !k.starts_with("friction limit")
                });
                described.push((
                    "contact model".into(),
                    "joint-limit support: mass free in X and Z on two joints ground → mass: Kz as a ForceBased motor on Y, compression only, and Kx on X capped at μ·N(t) after every step, in series with a massless slider".into(),
                ));
                described.push((
                    "rapier step [s] (output step / stride)".into(),
                    format!("{dt_in} (stride {stride}; the step rule's period scaled to the vertical mode √(Kz/M) when faster)"),
                ));
                vertical::run_oscillator(rig, drive, (ex, v), (dt, stride), duration, sink)
            }
            Model::Oscillator(osc) => {
                let (rig, stride) = match settings.oscillator_contact {
                    OscillatorContact::Foot => {
                        let rig = world::oscillator(osc, &settings, dt, drive.ground_kind());
                        describe_foot(osc, &rig, dt, &mut described, &mut findings);
                        (rig, 1)
                    }
                    OscillatorContact::JointLimit | OscillatorContact::AppliedForce => {
                        let mut steps = OscillatorSteps::for_scene(osc, ex, dt, settings.accuracy);
                        if settings.step_rule == StepRule::None {
                            steps = steps.at_output_step(dt);
                        }
                        let rig = world::oscillator_joint_limit(
                            osc,
                            &settings,
                            steps.dt_inner,
                            drive.ground_kind(),
                        );
                        describe_joint_limit(
                            osc,
                            &settings,
                            &steps,
                            ex,
                            &mut described,
                            &mut findings,
                        );
                        (rig, steps.stride)
                    }
                };
                simulate::run_oscillator(
                    rig,
                    osc.contact.kx,
                    drive,
                    ex,
                    (dt, stride),
                    duration,
                    sink,
                )
            }
            Model::RigidBlock(b) => {
                // On a kinematic ground under a record the solver is the block's own
                // (`RapierSettings::for_run`, also with `step_rule = "none"`, so a sweep's
                // rungs converge as the case's run does); the step rule only with
                // `step_rule = "scene"`.
                let on_record = settings::kinematic_block_on_record(case, kinematic);
                let stride = if on_record && settings.step_rule == StepRule::Scene {
                    // the pilot runs on the inertial-force route, with that route's settings
                    let pilot =
                        RapierSettings::for_run(case, false).map_err(|mut e| e.remove(0))?;
                    let ruled = (&settings, &pilot);
                    block_kinematic_stride(case, b, ruled, dt, &mut described, &mut findings)
                } else {
                    1
                };
                let dt_in = dt / stride as f64;
                if on_record {
                    described.push((
                        "solver (block on a kinematic ground under a record)".into(),
                        format!(
                            "{} substep(s) per rapier step, contacts at {} Hz unless the case sets them: the ground's velocity changes once a step and friction takes only μ·N·Δt/substeps of it in the first substep, so more substeps let the stuck block slip; a stiffer contact than rapier's 30 Hz keeps the block from tilting under the friction's moment (docs/rapier-engine.md)",
                            settings.substeps,
                            settings.contact_hz.unwrap_or(settings::KINEMATIC_BLOCK_CONTACT_HZ)
                        ),
                    ));
                }
                let rig = world::rigid_block(b, &settings, dt_in, drive.ground_kind());
                described.push((
                    "block".into(),
                    format!(
                        "uniform cuboid 2b × 2h × 2b = {} × {} × {} m, mass {} kg",
                        2.0 * b.half_width,
                        2.0 * b.half_height,
                        2.0 * b.half_width,
                        b.mass
                    ),
                ));
                simulate::run_block(rig, b, drive, (ex, vert), (dt, stride), duration, sink)
            }
            Model::RockingBody(r) if settings.oscillator_contact != OscillatorContact::Foot => {
                let omega_r = rocking_mode(r);
                let stride = match settings.step_rule {
                    StepRule::Scene => rocking_stride(omega_r, dt, &settings),
                    StepRule::None => 1,
                };
                let dt_in = dt / stride as f64;
                let rig = if settings.oscillator_contact == OscillatorContact::AppliedForce {
                    world::rocking_body_applied_force(r, &settings, dt_in, drive.ground_kind())
                } else {
                    world::rocking_body_joint_limit(r, &settings, dt_in, drive.ground_kind())
                };
                describe_rocking_joint_limit(r, omega_r, dt_in, stride, &settings, &mut described);
                findings.push(rocking_validity(omega_r, dt_in, &settings));
                simulate::run_rocking_joint_limit(
                    rig,
                    r,
                    drive,
                    (ex, vert),
                    (dt, stride),
                    duration,
                    sink,
                )
            }
            Model::RockingBody(r) => {
                let rig = world::rocking_body(r, &settings, dt, drive.ground_kind());
                let inertia = world::rocking_inertia(r);
                let omega_f = (r.contact.kz / rig.foot_mass).sqrt();
                described.push(("foot mass (each) [kg]".into(), format!("{}", rig.foot_mass)));
                described.push((
                    "feet".into(),
                    format!(
                        "{} feet; joint per foot: springs Kx (X) and Kz (Z) as ForceBased motors in the foot's (ground) axes, rotation free; springs start with the static preload",
                        r.supports
                    ),
                ));
                described.push((
                    "rotational inertia [kg·m²]".into(),
                    format!(
                        "{inertia}{}",
                        if r.rotational_inertia > 0.0 {
                            " (scene)"
                        } else {
                            " (scene has none: 0.01 % of a uniform block 2b × 2h, 1e-4·M(b² + h²)/3, as the fe engine)"
                        }
                    ),
                ));
                described.push((
                    "gravity through rotation (P-Delta)".into(),
                    "included (exact rigid-body kinematics)".into(),
                ));
                described.push((
                    "settling steps before t = 0".into(),
                    format!("{SETTLE_STEPS}"),
                ));
                described.push((
                    "contact model".into(),
                    "feet (contact_model = \"foot\")".into(),
                ));
                findings.push(
                    "outside the engine's validity: the feet model's lifted feet (1 % of M) add rotating inertia the scene does not have (first full lift-off −93 ms, peak sliding +13 to +23 % against the FE engine); the default contact_model = \"joint-limit\" agrees with it within 5 % (docs/rapier-engine.md)".into(),
                );
                findings.push(format!(
                    "foot vertical mode √(Kz/m_f) = {omega_f:.0} rad/s, ω·h = {:.3} per substep",
                    omega_f * dt / settings.substeps as f64
                ));
                // The stated inertia on the supports: the body's own rocking mode about the
                // CM, √((n·Kx·h² + Kz·Σx_i²)/I); rapier resolves it only for ω·h ≲ 2
                // (docs/rapier-engine.md, "Rotational inertia").
                let sum_x2: f64 = (0..r.supports)
                    .map(|i| {
                        let x =
                            -r.half_width + 2.0 * r.half_width * i as f64 / (r.supports - 1) as f64;
                        x * x
                    })
                    .sum();
                let omega_r = ((r.supports as f64 * r.contact.kx * r.cm_height.powi(2)
                    + r.contact.kz * sum_x2)
                    / inertia)
                    .sqrt();
                findings.push(format!(
                    "rocking mode of the rotational inertia on the supports √((n·Kx·h² + Kz·Σx²)/I) = {omega_r:.0} rad/s, ω·h = {:.2} per substep",
                    omega_r * dt / settings.substeps as f64
                ));
                simulate::run_rocking(rig, r, drive, ex, dt, (duration, SETTLE_STEPS), sink)
            }
        };
        let ground = match drive {
            Drive::AppliedForce => "fixed ground; mass acceleration as force M·a (step mean)",
            Drive::KinematicGround => {
                "kinematic position-based ground moved to xg(t_{n+1}) each step"
            }
            Drive::InertialForce => {
                "fixed ground; −m·(vg(n+1) − vg(n))/Δt on every dynamic body, −vg(0⁺) initial velocity"
            }
        };
        described.push(("ground motion".into(), ground.into()));
        described.extend(vertical::describe(case, drive));
        if matches!(
            ex,
            Excitation::GroundAcceleration(rockslide_core::case::Signal::Record { .. })
        ) && drive != Drive::AppliedForce
        {
            described.push((
                "record baseline".into(),
                match ground::RECORD_BASELINE {
                    rockslide_core::case::record::Baseline::None => "none: the record integrated as given (piecewise-linear acceleration, exactly between samples; its displacement may drift), as the exact references; both routes use this ground",
                    rockslide_core::case::record::Baseline::Cubic => "cubic: least-squares c2·t² + c3·t³ removed from the integrated displacement (and its derivatives from v and a); both routes use this corrected ground",
                }
                .into(),
            ));
        }
        Ok(Run {
            engine: "rapier",
            variant: variant.to_string(),
            arrangement: Arrangement::Single,
            dt,
            settings: described.into_iter().map(Into::into).collect(),
            stats: SolverStats {
                substeps_per_step: Some(settings.substeps as u64),
                ..SolverStats::steps(outcome.steps)
            },
            findings,
            trace: outcome.trace,
            status: outcome.status,
            wall_seconds: 0.0,
        })
    }
}

/// The largest ω·h (h = rapier step / substeps) the rocking body's joint-limit supports
/// run at, for the rocking mode of the rotational inertia on the supports. Symplectic
/// Euler is stable for ω·h < 2; measured on both RPEPO cases (docs/rapier-engine.md,
/// one Gauss–Seidel sweep, 1 ms output): ω·h = 1.07 (5 rapier steps of 0.2 ms × 4
/// substeps) agrees with the FE engine before the first full lift-off within 2.9 % and
/// on the lift-off within 2 ms; ω·h = 1.34 moves the ground-displacement case's first
/// full lift-off by −11 %, and 1.78 the mass-acceleration case's by −11 %.
pub const ROCKING_OMEGA_H: f64 = 1.1;

/// The largest ω·h (h = the rapier step) the rocking body's applied-force supports
/// (the default, `contact_model = "applied-force"`) run at: the supports' forces are
/// held over each step, so the scheme is symplectic Euler on the support springs,
/// stable for ω·h < 2. Measured on both RPEPO cases (docs/rapier-engine.md): ω·h from
/// 1.07 to 1.93 changes every peak before the first full lift-off by less than 0.6 %
/// of it and the lift-off by less than 1 ms; 1.5 keeps a margin of 25 % to the limit.
pub const APPLIED_FORCE_OMEGA_H: f64 = 1.5;

/// The rocking mode of a rocking body's rotational inertia on its supports,
/// √((n·Kx·h² + Kz·Σx_i²)/I), rad/s: the stiffest mode of the scene.
fn rocking_mode(r: &rockslide_core::case::RockingBody) -> f64 {
    let sum_x2: f64 = r.support_positions().iter().map(|x| x * x).sum();
    ((r.supports as f64 * r.contact.kx * r.cm_height.powi(2) + r.contact.kz * sum_x2)
        / world::rocking_inertia(r))
    .sqrt()
}

/// The rocking body's validity finding: within while ω_r·h meets the rule (it does
/// unless `step_rule = "none"` or the stride cap stopped it), else outside, with ω_r·h.
fn rocking_validity(omega_r: f64, dt_in: f64, settings: &RapierSettings) -> String {
    let omega_h = omega_r * dt_in / settings.substeps as f64;
    let bound = rocking_omega_h(settings);
    if omega_h <= bound * (1.0 + 1e-9) {
        let measured = if settings.oscillator_contact == OscillatorContact::AppliedForce {
            "applied-force supports, measured on the shipped RPEPO cases against the FE engine: peaks before the first full lift-off within 3.4 %, lift-off within 2 ms, at 31–35 ms of CPU per simulated second"
        } else {
            "joint-limit supports, measured on the shipped RPEPO cases against the FE engine: peaks before the first full lift-off within 2.9 %, lift-off within 2 ms, at 99–110 ms of CPU per simulated second"
        };
        format!(
            "within the engine's validity for the rocking body before the first full lift-off (docs/rapier-engine.md): rocking mode of the rotational inertia on the supports √((n·Kx·h² + Kz·Σx²)/I) = {omega_r:.0} rad/s, ω·h = {omega_h:.3} per substep (rule ≤ {bound}); {measured}"
        )
    } else {
        format!(
            "outside the engine's validity: the rocking mode of the rotational inertia on the supports, {omega_r:.0} rad/s, has ω·h = {omega_h:.3} per substep (rule ≤ {bound}; symplectic Euler is unstable beyond 2){}",
            if settings.step_rule == StepRule::None {
                " — step_rule = \"none\": one rapier step per output step"
            } else {
                ""
            }
        )
    }
}

/// The ω_r·h bound of the rocking body's model: [`APPLIED_FORCE_OMEGA_H`] for the
/// applied-force supports, [`ROCKING_OMEGA_H`] for the joint-limit ones.
fn rocking_omega_h(settings: &RapierSettings) -> f64 {
    if settings.oscillator_contact == OscillatorContact::AppliedForce {
        APPLIED_FORCE_OMEGA_H
    } else {
        ROCKING_OMEGA_H
    }
}

/// rapier steps per output step for the rocking body without feet: the fewest with
/// ω_r·h within the model's bound ([`rocking_omega_h`]), h = dt/(stride·substeps).
fn rocking_stride(omega_r: f64, dt: f64, settings: &RapierSettings) -> usize {
    let h_max = rocking_omega_h(settings) / omega_r;
    ((dt / (h_max * settings.substeps as f64) * (1.0 - 1e-12)).ceil() as usize).clamp(1, MAX_STRIDE)
}

/// Settings of the joint-limit rocking body (the default).
fn describe_rocking_joint_limit(
    r: &rockslide_core::case::RockingBody,
    omega_r: f64,
    dt_in: f64,
    stride: usize,
    settings: &RapierSettings,
    described: &mut Vec<(String, String)>,
) {
    let model = if settings.oscillator_contact == OscillatorContact::AppliedForce {
        format!(
            "applied-force: {} supports computed by the engine from the body's pose after each rapier step (Kz compression only, Kx capped at μ·N_i in series with a massless slider) and applied to the rapier body as one force and torque over the next step; no joints, no colliders",
            r.supports
        )
    } else {
        format!(
            "joint-limit: {} supports, each two joints ground → body (no feet): Kz as a ForceBased motor on Y, compression only (force capped at 0 while the anchor is above the ground), Kx as a motor on X capped at μ·N_i in series with a massless slider (moved after each step)",
            r.supports
        )
    };
    described.push(("contact model".into(), model));
    described.push((
        "rapier step [s] (output step / stride)".into(),
        format!("{dt_in} (stride {stride})"),
    ));
    described.push((
        "step rule".into(),
        match settings.step_rule {
            StepRule::Scene => format!(
                "ω_r·h ≤ {}, ω_r = {omega_r:.0} rad/s (rocking mode of the rotational inertia on the supports), h = rapier step / {} substeps",
                rocking_omega_h(settings),
                settings.substeps
            ),
            StepRule::None => "none (step_rule = \"none\"): one rapier step per output step".into(),
        },
    ));
    if settings.oscillator_contact == OscillatorContact::JointLimit {
        described.push((
            "spring damping passed to rapier".into(),
            format!(
                "−(1 − {})·h·K on each motor (cancels the motor's implicit damping; the scene has none)",
                world::SUPPORT_DAMPING_SHARE
            ),
        ));
    }
    described.push((
        "rotational inertia [kg·m²]".into(),
        format!("{}", world::rocking_inertia(r)),
    ));
}

/// Settings and findings of the foot oscillator (`contact_model = "foot"`).
fn describe_foot(
    osc: &rockslide_core::case::Oscillator,
    rig: &world::Rig,
    dt: f64,
    described: &mut Vec<(String, String)>,
    findings: &mut Vec<String>,
) {
    let mf = rig.foot_mass;
    let omega_f = (osc.contact.kx / mf).sqrt();
    described.push((
        "contact model".into(),
        "foot (contact_model = \"foot\")".into(),
    ));
    described.push(("foot mass [kg]".into(), format!("{mf}")));
    described.push((
        "foot".into(),
        "one foot; gravity scale M/m_f (normal force M·g); joint: spring Kx on X (ForceBased motor), other axes locked".into(),
    ));
    described.push((
        "spring damping C [N·s/m]".into(),
        format!("{}", osc.damping()),
    ));
    if osc.contact.mu.is_infinite() {
        described.push(("μ = ∞ as".into(), format!("μ = {:e}", world::MU_INFINITE)));
    }
    findings.push(format!(
        "foot mode √(Kx/m_f) = {omega_f:.1} rad/s, ω_f·Δt = {:.3}; structure ω·Δt = {:.4}",
        omega_f * dt,
        osc.omega() * dt
    ));
    findings.push(
        "outside the engine's validity: the foot model's inertia (1 % of M by default) adds to the friction force (|R| up to 1.2–1.4 μN) and its errors are not bounded by an accuracy target (docs/rapier-engine.md); the default contact_model = \"joint-limit\" is".into(),
    );
}

/// Settings and findings of the joint-limit oscillator (the default).
fn describe_joint_limit(
    osc: &rockslide_core::case::Oscillator,
    settings: &RapierSettings,
    steps: &OscillatorSteps,
    ex: &Excitation,
    described: &mut Vec<(String, String)>,
    findings: &mut Vec<String>,
) {
    let h = steps.dt_inner / settings.substeps as f64;
    described.push((
        "contact model".into(),
        "joint-limit: mass joined to the ground by a spring Kx (ForceBased motor on X, other axes locked) whose force rapier caps at Ru = μ·M·g, in series with a massless slider (the motor's target, moved after each step); no foot body".into(),
    ));
    described.push((
        "accuracy target (relative)".into(),
        format!("{}", settings.accuracy),
    ));
    described.push((
        "rapier step [s] (output step / stride)".into(),
        format!("{} (stride {})", steps.dt_inner, steps.stride),
    ));
    described.push((
        "step rule".into(),
        format!(
            "Δt ≤ {:.4e} s: T_min·√(accuracy/300), T_min = {:.4} s, and ≤ a record's sample step ({})",
            steps.dt_max,
            steps.period,
            if steps.excitation_limits {
                "set by the excitation: sine-pulse period or record step"
            } else {
                "set by the structure's period 2π/ω"
            }
        ),
    ));
    described.push((
        "spring damping passed to rapier [N·s/m]".into(),
        format!(
            "C − (1 − {})·h·Kx = {} (C = {}; cancels the motor's implicit damping)",
            world::MOTOR_DAMPING_MARGIN,
            osc.damping() - (1.0 - world::MOTOR_DAMPING_MARGIN) * h * osc.contact.kx,
            osc.damping()
        ),
    ));
    described.push((
        "friction limit Ru = μ·M·g [N]".into(),
        format!("{}", osc.friction_limit()),
    ));
    let pga = peak_ground_acceleration(ex);
    if steps.within_target() {
        findings.push(format!(
            "within the engine's validity: rapier step {:.3e} s ≤ {:.3e} s for accuracy {} (ω·Δt = {:.4}); |R| ≤ μ·N by construction; a stick–slip transition lags at most ½(PGA + μg)·Δt² = {:.2e} m; measured at accuracy 0.01 on the shipped records against the exact reference: residual sliding within 0.021 %, max |u| within 0.032 %, at 3–6 ms of CPU per simulated second (docs/rapier-engine.md)",
            steps.dt_inner,
            steps.dt_max,
            settings.accuracy,
            osc.omega() * steps.dt_inner,
            0.5 * (pga + osc.contact.mu.min(1e6) * osc.gravity) * steps.dt_inner.powi(2)
        ));
    } else {
        findings.push(format!(
            "outside the engine's validity: the accuracy target {} needs a rapier step ≤ {:.3e} s, {}; ran at {:.3e} s",
            settings.accuracy,
            steps.dt_max,
            if settings.step_rule == StepRule::None {
                "but step_rule = \"none\" runs one rapier step per output step"
            } else {
                "more than the cap of steps per output step"
            },
            steps.dt_inner
        ));
    }
}

/// Most rapier steps a rigid block on a kinematic ground runs: the block's step rule
/// ([`block_kinematic_stride`]) stops here (about 10 s of CPU at ≈ 10 µs a step); a
/// finer step than this allows is outside the engine's validity.
pub const MAX_BLOCK_STEPS: usize = 1_000_000;

/// Error constant of the rigid block on a moving kinematic ground under a record, at one
/// substep per rapier step and a [`KINEMATIC_BLOCK_CONTACT_HZ`] contact: the total
/// distance slid is off by E ≈ K·PGA·Δt² (second order in Δt). Measured against the
/// exact block reference on the five shipped records (Northridge, Loma Prieta, Imperial
/// Valley, Chino Hills 090° and 360°), μ = 0.08, 0.12 and 0.185 at PGA 0.3 g and three of
/// them at 0.15 and 0.6 g, at Δt = 0.25, 0.5 and 1 ms: E/(PGA·Δt²) from 0.8 to 90.4
/// (docs/rapier-engine.md, "Rigid block on a kinematic ground"); K is the largest with
/// a margin.
pub const KINEMATIC_BLOCK_K: f64 = 100.0;

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
    described: &mut Vec<(String, String)>,
    findings: &mut Vec<String>,
) -> usize {
    let ex = &case.scene.excitation;
    let duration = case.run.duration;
    let pilot_rig = world::rigid_block(b, pilot, dt, world::GroundKind::Fixed);
    let mut path = rows::PathLength::of(rockslide_core::trace::q::SLIDE.key, None);
    simulate::run_block(
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
    let n = rockslide_engine_api::step_count(duration, dt);
    let stride = block_stride(dt, dt_max, n);
    let dt_in = dt / stride as f64;
    let estimate = KINEMATIC_BLOCK_K * pga * dt_in * dt_in;
    described.push(("accuracy target (relative)".into(), format!("{eps}")));
    described.push((
        "rapier step [s] (output step / stride)".into(),
        format!("{dt_in} (stride {stride})"),
    ));
    described.push((
        "step rule".into(),
        format!(
            "Δt ≤ √(accuracy·S/(K·PGA)) = {dt_max:.4e} s: the kinematic ground's error of the total slid K·PGA·Δt² (K = {KINEMATIC_BLOCK_K}, measured) within the accuracy of the total slid S = {slid:.4e} m (pilot run: inertial force at the output step), PGA = {pga:.4} m/s²; at most {MAX_BLOCK_STEPS} rapier steps"
        ),
    ));
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

/// Substeps of each rapier step when the 3D block's step rule (`space.rs`, the plane
/// block's first-order rule kept in plan) splits the output step into `stride` rapier
/// steps: the output step's substeps shared among them, at least 1 (the solver's substep
/// no coarser than at the output step). Measured in the plane, before the plane block took
/// its own solver ([`RapierSettings::for_run`]), on
/// `cases/records/block-northridge.toml` (13 steps of 76.9 µs, kinematic ground, against
/// the exact block reference): 1 substep gives total slid +0.39 %, residual −0.76 %, peak
/// |sliding| −0.76 %, stop −0.25 ms, 2 episodes as the reference, in 1.49 s of CPU; 4
/// substeps +0.45 %, −0.76 %, −0.52 %, −0.25 ms, 2 episodes, in 2.74 s (docs/rapier-engine.md).
fn block_substeps(substeps: usize, stride: usize) -> usize {
    substeps.div_ceil(stride).max(1)
}

/// Peak |acceleration| of the excitation (ground or mass), m/s²; 0 without one.
fn peak_ground_acceleration(ex: &Excitation) -> f64 {
    use rockslide_core::case::Signal;
    let sig = match ex {
        Excitation::None => return 0.0,
        Excitation::MassAcceleration(s)
        | Excitation::GroundDisplacement(s)
        | Excitation::GroundAcceleration(s) => s,
    };
    match (ex, sig) {
        (
            Excitation::GroundDisplacement(_),
            Signal::SinePulse {
                amplitude, omega, ..
            },
        ) => amplitude.abs() * omega * omega,
        (_, Signal::SinePulse { amplitude, .. }) => amplitude.abs(),
        (_, Signal::Record { samples, .. }) => samples.iter().fold(0.0_f64, |m, a| m.max(a.abs())),
    }
}

/// Quasi-static settling steps of a rocking body before t = 0 (static preload).
const SETTLE_STEPS: usize = 400;

/// Run `variant` of a 3D rocking-body scene on `grid` instead of the scene's own
/// ([`RockingGrid::from_scene`]): e.g. the grid turned about the vertical.
pub fn run_on_grid(
    case: &Case,
    grid: &RockingGrid,
    variant: &str,
    dt: f64,
) -> Result<Run, InputError> {
    let settings = RapierSettings::from_case(case).map_err(|mut e| e.remove(0))?;
    let drive = match variant {
        variant::KINEMATIC_GROUND => Drive::KinematicGround,
        variant::INERTIAL_FORCE => Drive::InertialForce,
        _ => Drive::AppliedForce,
    };
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
            _ => (space::plan_channels(moves).len(), 1),
        });
    }
    Some(match model {
        // the sliding channels and N(t)
        Model::Oscillator(_) => (rockslide_core::trace::q::sliding(moves).len() + 1, 1),
        Model::RigidBlock(_) => (simulate::block_channels(moves).len(), 1),
        Model::RockingBody(r) => (simulate::rocking_channels(moves).len(), r.supports),
    })
}

/// rapier steps per output step `dt` of the kinematic-ground block so that each is at most
/// `dt_max` (none needed: one), capped so that a run of `steps` output steps takes at most
/// [`MAX_BLOCK_STEPS`] rapier steps.
pub(crate) fn block_stride(dt: f64, dt_max: f64, steps: usize) -> usize {
    let max_stride = (MAX_BLOCK_STEPS / steps.max(1)).max(1);
    let wanted = if dt_max > 0.0 {
        (dt / dt_max * (1.0 - 1e-12)).ceil()
    } else {
        f64::INFINITY
    };
    if wanted <= max_stride as f64 {
        (wanted as usize).max(1)
    } else {
        max_stride
    }
}

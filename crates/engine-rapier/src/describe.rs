//! What a run states besides its trace: its settings as (name, value) and its findings
//! (within or outside the engine's validity, with what was measured), per model and
//! route, in the words of the run's settings table.

use super::drive::Drive;
use super::ground::RECORD_BASELINE;
use super::settings::{OscillatorContact, OscillatorSteps, RapierSettings, StepRule};
use super::step_rule::{SETTLE_STEPS, peak_ground_acceleration, rocking_omega_h};
use super::time_loop::Outcome;
use super::world::{
    MOTOR_DAMPING_MARGIN, MU_INFINITE, Rig, SUPPORT_DAMPING_SHARE, rocking_inertia,
};
use rockslide_core::case::record::Baseline;
use rockslide_core::case::{Excitation, RigidBlock, RockingBody, Signal};
use rockslide_engine_api::{Arrangement, Run, Setting, SolverStats, Variant};

/// What a run states besides its trace: settings and findings, as (name, value) and text.
pub(crate) struct Statement {
    pub(crate) described: Vec<Setting>,
    pub(crate) findings: Vec<String>,
}

impl Statement {
    /// The run this statement describes: `variant` at output step `dt`, `substeps` solver
    /// substeps per rapier step, ended as `outcome` says (rapier's supports are single).
    pub(crate) fn into_run(
        self,
        variant: Variant,
        dt: f64,
        substeps: usize,
        outcome: Outcome,
    ) -> Run {
        Run {
            engine: crate::settings::ID,
            variant: variant.name.to_string(),
            arrangement: Arrangement::Single,
            dt,
            settings: self.described,
            stats: SolverStats {
                substeps_per_step: Some(substeps as u64),
                ..SolverStats::steps(outcome.steps)
            },
            findings: self.findings,
            trace: outcome.trace,
            status: outcome.status,
            wall_seconds: 0.0,
        }
    }
}

/// The planar ground route.
pub(crate) fn ground_motion(drive: Drive, described: &mut Vec<Setting>) {
    let ground = match drive {
        Drive::AppliedForce => "fixed ground; mass acceleration as force M·a (step mean)",
        Drive::KinematicGround => "kinematic position-based ground moved to xg(t_{n+1}) each step",
        Drive::InertialForce => {
            "fixed ground; −m·(vg(n+1) − vg(n))/Δt on every dynamic body, −vg(0⁺) initial velocity"
        }
    };
    described.push(Setting::text("ground motion", ground));
}

/// The record's baseline, under a recorded ground acceleration that moves the ground.
pub(crate) fn record_baseline(ex: &Excitation, drive: Drive, described: &mut Vec<Setting>) {
    if matches!(ex, Excitation::GroundAcceleration(Signal::Record { .. }))
        && drive != Drive::AppliedForce
    {
        described.push(Setting::text("record baseline", match RECORD_BASELINE {
                Baseline::None => "none: the record integrated as given (piecewise-linear acceleration, exactly between samples; its displacement may drift), as the exact references; both routes use this ground",
                Baseline::Cubic => "cubic: least-squares c2·t² + c3·t³ removed from the integrated displacement (and its derivatives from v and a); both routes use this corrected ground",
            }
            ));
    }
}

/// The rigid block's size and mass.
pub(crate) fn block(b: &RigidBlock, described: &mut Vec<Setting>) {
    described.push(Setting::text(
        "block",
        format!(
            "uniform cuboid 2b × 2h × 2b = {} × {} × {} m, mass {} kg",
            2.0 * b.half_width,
            2.0 * b.half_height,
            2.0 * b.half_width,
            b.mass
        ),
    ));
}

/// The rocking body's validity finding: within while ω_r·h meets the rule (it does
/// unless `step_rule = "none"` or the stride cap stopped it), else outside, with ω_r·h.
pub(crate) fn rocking_validity(omega_r: f64, dt_in: f64, settings: &RapierSettings) -> String {
    let omega_h = omega_r * dt_in / settings.substeps as f64;
    let bound = rocking_omega_h(settings);
    if omega_h <= bound * (1.0 + 1e-9) {
        let measured = if settings.oscillator_contact == OscillatorContact::ComputedSupports {
            "computed supports, measured on the shipped RPEPO cases against the FE engine: peaks before the first full lift-off within 3.4 %, lift-off within 2 ms"
        } else {
            "joint-limit supports, measured on the shipped RPEPO cases against the FE engine: peaks before the first full lift-off within 2.9 %, lift-off within 2 ms"
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

/// Settings of the joint-limit rocking body (the default).
pub(crate) fn describe_rocking_joint_limit(
    r: &rockslide_core::case::RockingBody,
    omega_r: f64,
    dt_in: f64,
    stride: usize,
    settings: &RapierSettings,
    described: &mut Vec<Setting>,
) {
    let model = if settings.oscillator_contact == OscillatorContact::ComputedSupports {
        format!(
            "computed-supports: {} supports computed by the engine from the body's pose after each rapier step (Kz compression only, Kx capped at μ·N_i in series with a massless slider) and applied to the rapier body as one force and torque over the next step; no joints, no colliders",
            r.supports
        )
    } else {
        format!(
            "joint-limit: {} supports, each two joints ground → body (no feet): Kz as a ForceBased motor on Y, compression only (force capped at 0 while the anchor is above the ground), Kx as a motor on X capped at μ·N_i in series with a massless slider (moved after each step)",
            r.supports
        )
    };
    described.push(Setting::text("contact model", model));
    described.push(Setting::text(
        "rapier step [s] (output step / stride)",
        format!("{dt_in} (stride {stride})"),
    ));
    described.push(Setting::text("step rule", match settings.step_rule {
            StepRule::Scene => format!(
                "ω_r·h ≤ {}, ω_r = {omega_r:.0} rad/s (rocking mode of the rotational inertia on the supports), h = rapier step / {} substeps",
                rocking_omega_h(settings),
                settings.substeps
            ),
            StepRule::None => "none (step_rule = \"none\"): one rapier step per output step".into(),
        }));
    if settings.oscillator_contact == OscillatorContact::JointLimit {
        described.push(Setting::text("spring damping passed to rapier", format!(
                "−(1 − {})·h·K on each motor (cancels the motor's implicit damping; the scene has none)",
                SUPPORT_DAMPING_SHARE
            )));
    }
    described.push(Setting::text(
        "rotational inertia [kg·m²]",
        format!("{}", rocking_inertia(r)),
    ));
}

/// Settings and findings of the foot oscillator (`contact_model = "foot"`).
pub(crate) fn describe_foot(
    osc: &rockslide_core::case::Oscillator,
    rig: &Rig,
    dt: f64,
    described: &mut Vec<Setting>,
    findings: &mut Vec<String>,
) {
    let mf = rig.foot_mass;
    let omega_f = (osc.contact.kx / mf).sqrt();
    described.push(Setting::text(
        "contact model",
        "foot (contact_model = \"foot\")",
    ));
    described.push(Setting::text("foot mass [kg]", format!("{mf}")));
    described.push(Setting::text("foot", "one foot; gravity scale M/m_f (normal force M·g); joint: spring Kx on X (ForceBased motor), other axes locked"));
    described.push(Setting::text(
        "spring damping C [N·s/m]",
        format!("{}", osc.damping()),
    ));
    if osc.contact.mu.is_infinite() {
        described.push(Setting::text("μ = ∞ as", format!("μ = {:e}", MU_INFINITE)));
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
pub(crate) fn describe_joint_limit(
    osc: &rockslide_core::case::Oscillator,
    settings: &RapierSettings,
    steps: &OscillatorSteps,
    ex: &Excitation,
    described: &mut Vec<Setting>,
    findings: &mut Vec<String>,
) {
    let h = steps.dt_inner / settings.substeps as f64;
    described.push(Setting::text("contact model", "joint-limit: mass joined to the ground by a spring Kx (ForceBased motor on X, other axes locked) whose force rapier caps at Ru = μ·M·g, in series with a massless slider (the motor's target, moved after each step); no foot body"));
    described.push(Setting::text(
        "accuracy target (relative)",
        format!("{}", settings.accuracy),
    ));
    described.push(Setting::text(
        "rapier step [s] (output step / stride)",
        format!("{} (stride {})", steps.dt_inner, steps.stride),
    ));
    described.push(Setting::text("step rule", format!(
            "Δt ≤ {:.4e} s: T_min·√(accuracy/300), T_min = {:.4} s, and ≤ a record's sample step ({})",
            steps.dt_max,
            steps.period,
            if steps.excitation_limits {
                "set by the excitation: sine-pulse period or record step"
            } else {
                "set by the structure's period 2π/ω"
            }
        )));
    described.push(Setting::text(
        "spring damping passed to rapier [N·s/m]",
        format!(
            "C − (1 − {})·h·Kx = {} (C = {}; cancels the motor's implicit damping)",
            MOTOR_DAMPING_MARGIN,
            osc.damping() - (1.0 - MOTOR_DAMPING_MARGIN) * h * osc.contact.kx,
            osc.damping()
        ),
    ));
    described.push(Setting::text(
        "friction limit Ru = μ·M·g [N]",
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

/// Settings and findings of the rocking body on feet (`contact_model = "foot"`), on `rig`
/// at output step `dt`.
pub(crate) fn describe_rocking_feet(
    r: &RockingBody,
    rig: &Rig,
    dt: f64,
    settings: &RapierSettings,
    (described, findings): (&mut Vec<Setting>, &mut Vec<String>),
) {
    let inertia = rocking_inertia(r);
    let omega_f = (r.contact.kz / rig.foot_mass).sqrt();
    described.push(Setting::text(
        "foot mass (each) [kg]",
        format!("{}", rig.foot_mass),
    ));
    described.push(Setting::text("feet", format!(
            "{} feet; joint per foot: springs Kx (X) and Kz (Z) as ForceBased motors in the foot's (ground) axes, rotation free; springs start with the static preload",
            r.supports
        )));
    described.push(Setting::text("rotational inertia [kg·m²]", format!(
            "{inertia}{}",
            if r.rotational_inertia > 0.0 {
                " (scene)"
            } else {
                " (scene has none: 0.01 % of a uniform block 2b × 2h, 1e-4·M(b² + h²)/3, as the fe engine)"
            }
        )));
    described.push(Setting::text(
        "gravity through rotation (P-Delta)",
        "included (exact rigid-body kinematics)",
    ));
    described.push(Setting::text(
        "settling steps before t = 0",
        format!("{SETTLE_STEPS}"),
    ));
    described.push(Setting::text(
        "contact model",
        "feet (contact_model = \"foot\")",
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
            let x = -r.half_width + 2.0 * r.half_width * i as f64 / (r.supports - 1) as f64;
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
}

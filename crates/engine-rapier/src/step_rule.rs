//! Step rules: how many rapier steps each output step takes for a scene (the stride),
//! and the bounds they keep — the oscillator's accuracy rule (`settings`'
//! [`OscillatorSteps`]) with its vertical mode, the rocking body's ω_r·h bound per
//! support model, the rigid block's kinematic-ground rule with its cap of rapier steps.

use super::settings::{MAX_STRIDE, OscillatorContact, OscillatorSteps, RapierSettings, StepRule};
use super::world;
use rockslide_core::case::{Excitation, Oscillator, Vertical};

/// The largest ω·h (h = rapier step / substeps) the rocking body's joint-limit supports
/// run at, for the rocking mode of the rotational inertia on the supports. Symplectic
/// Euler is stable for ω·h < 2; measured on both RPEPO cases (docs/rapier-engine.md,
/// one Gauss–Seidel sweep, 1 ms output): ω·h = 1.07 (5 rapier steps of 0.2 ms × 4
/// substeps) agrees with the FE engine before the first full lift-off within 2.9 % and
/// on the lift-off within 2 ms; ω·h = 1.34 moves the ground-displacement case's first
/// full lift-off by −11 %, and 1.78 the mass-acceleration case's by −11 %.
pub const ROCKING_OMEGA_H: f64 = 1.1;

/// The largest ω·h (h = the rapier step) the rocking body's computed supports
/// (the default, `contact_model = "computed-supports"`) run at: the supports' forces are
/// held over each step, so the scheme is symplectic Euler on the support springs,
/// stable for ω·h < 2. Measured on both RPEPO cases (docs/rapier-engine.md): ω·h from
/// 1.07 to 1.93 changes every peak before the first full lift-off by less than 0.6 %
/// of it and the lift-off by less than 1 ms; 1.5 keeps a margin of 25 % to the limit.
pub const COMPUTED_SUPPORTS_OMEGA_H: f64 = 1.5;

/// The rocking mode of a rocking body's rotational inertia on its supports,
/// √((n·Kx·h² + Kz·Σx_i²)/I), rad/s: the stiffest mode of the scene.
pub(crate) fn rocking_mode(r: &rockslide_core::case::RockingBody) -> f64 {
    let sum_x2: f64 = r.support_positions().iter().map(|x| x * x).sum();
    ((r.supports as f64 * r.contact.kx * r.cm_height.powi(2) + r.contact.kz * sum_x2)
        / world::rocking_inertia(r))
    .sqrt()
}

/// The ω_r·h bound of the rocking body's model: [`COMPUTED_SUPPORTS_OMEGA_H`] for the
/// computed supports, [`ROCKING_OMEGA_H`] for the joint-limit ones.
pub(crate) fn rocking_omega_h(settings: &RapierSettings) -> f64 {
    if settings.oscillator_contact == OscillatorContact::ComputedSupports {
        COMPUTED_SUPPORTS_OMEGA_H
    } else {
        ROCKING_OMEGA_H
    }
}

/// rapier steps per output step for the rocking body without feet: the fewest with
/// ω_r·h within the model's bound ([`rocking_omega_h`]), h = dt/(stride·substeps).
pub(crate) fn rocking_stride(omega_r: f64, dt: f64, settings: &RapierSettings) -> usize {
    let h_max = rocking_omega_h(settings) / omega_r;
    ((dt / (h_max * settings.substeps as f64) * (1.0 - 1e-12)).ceil() as usize).clamp(1, MAX_STRIDE)
}

/// Most rapier steps a rigid block on a kinematic ground runs: the block's step rule
/// (`planar_scene::block_kinematic_stride`) stops here (about 10 s of CPU at ≈ 10 µs a step); a
/// finer step than this allows is outside the engine's validity.
pub const MAX_BLOCK_STEPS: usize = 1_000_000;

/// Error constant of the rigid block on a moving kinematic ground under a record, at one
/// substep per rapier step and a `settings::KINEMATIC_BLOCK_CONTACT_HZ` contact: the total
/// distance slid is off by E ≈ K·PGA·Δt² (second order in Δt). Measured against the
/// exact block reference on the five shipped records (Northridge, Loma Prieta, Imperial
/// Valley, Chino Hills 090° and 360°), μ = 0.08, 0.12 and 0.185 at PGA 0.3 g and three of
/// them at 0.15 and 0.6 g, at Δt = 0.25, 0.5 and 1 ms: E/(PGA·Δt²) from 0.8 to 90.4
/// (docs/rapier-engine.md, "Rigid block on a kinematic ground"); K is the largest with
/// a margin.
pub const KINEMATIC_BLOCK_K: f64 = 100.0;

/// Substeps of each rapier step when the 3D block's step rule (`space.rs`, the plane
/// block's first-order rule kept in plan) splits the output step into `stride` rapier
/// steps: the output step's substeps shared among them, at least 1 (the solver's substep
/// no coarser than at the output step). Measured in the plane, before the plane block took
/// its own solver ([`RapierSettings::for_run`]), on
/// `cases/records/block-northridge.toml` (13 steps of 76.9 µs, kinematic ground, against
/// the exact block reference): 1 substep gives total slid +0.39 %, residual −0.76 %, peak
/// |sliding| −0.76 %, stop −0.25 ms, 2 episodes as the reference, in 1.49 s of CPU; 4
/// substeps +0.45 %, −0.76 %, −0.52 %, −0.25 ms, 2 episodes, in 2.74 s (docs/rapier-engine.md).
pub(crate) fn block_substeps(substeps: usize, stride: usize) -> usize {
    substeps.div_ceil(stride).max(1)
}

/// Peak |acceleration| of the excitation (ground or mass), m/s²; 0 without one.
pub(crate) fn peak_ground_acceleration(ex: &Excitation) -> f64 {
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
pub(crate) const SETTLE_STEPS: usize = 400;

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

/// rapier's step for the oscillator on a support: the horizontal rule
/// ([`OscillatorSteps`]) with its period scaled to the vertical mode √(Kz/M) when that is
/// faster, and no longer than a vertical record's sample step. Returns (stride, rapier step).
pub(crate) fn oscillator_on_support_steps(
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
    let stride = ((dt / dt_max * (1.0 - 1e-12)).ceil() as usize).clamp(1, MAX_STRIDE);
    (stride, dt / stride as f64, steps)
}

/// The oscillator's steps in plan: the planar rule, or one rapier step per output step
/// with `step_rule = "none"`.
pub(crate) fn plan_oscillator_steps(
    osc: &Oscillator,
    ex: &Excitation,
    settings: &RapierSettings,
    dt: f64,
) -> OscillatorSteps {
    let steps = OscillatorSteps::for_scene(osc, ex, dt, settings.accuracy);
    if settings.step_rule == StepRule::None {
        steps.at_output_step(dt)
    } else {
        steps
    }
}

/// The oscillator's steps in plan under a vertical component: the planar rule with its
/// period scaled to the vertical mode √(Kz/M) when that is faster, and no longer than a
/// vertical record's sample step (the 2D rule, [`oscillator_on_support_steps`]).
pub(crate) fn plan_vertical_steps(
    osc: &Oscillator,
    ex: &Excitation,
    vertical: &Vertical,
    settings: &RapierSettings,
    dt: f64,
) -> OscillatorSteps {
    let (stride, dt_inner, steps) =
        oscillator_on_support_steps(osc, ex, vertical, dt, settings.accuracy);
    let scale = (osc.omega() / (osc.contact.kz / osc.mass).sqrt()).min(1.0);
    OscillatorSteps {
        stride,
        dt_inner,
        dt_max: steps.dt_max * scale,
        ..steps
    }
}

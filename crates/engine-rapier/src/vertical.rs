//! Vertical ground motion in the rigid-body engine, by both routes the
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
//! compression-only springs Kz (the rocking body's, computed or joint-limit, their
//! gaps measured from the moving ground; `world::oscillator_with_supports` for the oscillator:
//! one joint-limit support under a mass free in X and Z), whose friction cap is
//! μ times the support's own N after every step and whose slider follows an open support
//! (CONTA178's reset at re-closure). A rigid vertical contact (`normal_force =
//! "quasi-static"`) is not a rapier model of the oscillator (its springs have Kz), and the
//! feet models (`contact_model = "foot"`) do not take vertical motion: "not applicable"
//! and a located error.

use super::drive::Drive;
use super::settings::{OscillatorContact, RapierSettings};
use rockslide_core::case::{Case, Model, NormalForce, Scene};
use rockslide_core::error::InputError;
use rockslide_engine_api::{NotApplicable, Setting};

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
pub(crate) fn describe(case: &Case, drive: Drive) -> Option<Setting> {
    case.scene.vertical().map(|_| {
        let route = match drive {
            Drive::KinematicGround => "kinematic ground moved to yg(t_{n+1}) each step (a_v integrated twice, exactly between samples); heights measured from the moving ground",
            _ => "fixed ground; −m·(vg_y(n+1) − vg_y(n))/Δt on every dynamic body (a_v positive upward)",
        };
        let model = match case.scene.model {
            Model::RigidBlock(_) => "N from rapier's contact (restitution 0: a landing block loses its vertical velocity)",
            _ => "N from each support's compression-only spring Kz after every step; friction cap μ·N; an open support's slider follows its anchor",
        };
        Setting::text("vertical ground motion", format!("{route}; {model}"))
    })
}

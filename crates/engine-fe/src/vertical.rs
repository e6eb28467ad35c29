//! Vertical ground motion: the ground's vertical acceleration a_v(t) (positive
//! upward) enters as an inertial load in relative coordinates, −M·a_v(t) on the body's Z at
//! its centre of mass, beside the static preload −M·g — the same route as the horizontal
//! ground-acceleration record (force −M·a_g, ground fixed). Chosen over imposing the
//! ground's vertical displacement on the contacts because a record gives acceleration:
//! integrating it twice to a displacement drifts (baseline correction would be a modelling
//! choice of its own), while the contact elements only ever see the relative displacement,
//! which is the same either way.
//!
//! Everything else is the model as it is: the CONTA178-like elements are compression-only,
//! so N(t) = Kz·compression follows the body's vertical oscillation on the contacts' Kz
//! (the dynamic normal force), contacts open when it reaches zero and close again — the
//! tangential origin follows an open contact, so a contact that closes again starts
//! unstressed (CONTA178 re-establishes sticking at contact) — and the rocking body's
//! supports open and close as they do for rocking. The friction limit of each element is
//! μ times its own normal force, so |T| ≤ μ·N(t) holds by construction.
//!
//! A rigid vertical contact (`normal_force = "quasi-static"`, N = M·(g + a_v) at every
//! instant) is not this model: the penalty contact has its stiffness Kz, so fe says "not
//! applicable" for it rather than run a different scene.

use rockslide_core::case::{NormalForce, Scene, Signal};
use rockslide_engine_api::{NotApplicable, Setting};

/// Whether fe runs the scene's vertical component (if any).
pub(crate) fn check(scene: &Scene) -> Result<(), NotApplicable> {
    match scene.vertical() {
        Some(v) if v.normal_force == NormalForce::QuasiStatic => Err(NotApplicable(
            "fe's contacts have their vertical stiffness Kz: a rigid vertical contact (normal_force = \"quasi-static\") is not its model".into(),
        )),
        _ => Ok(()),
    }
}

/// The vertical inertial load −M·a_v(t) on the body in relative coordinates, N (0 without
/// a vertical component).
#[inline]
pub(crate) fn load(signal: Option<&Signal>, mass: f64, t: f64) -> f64 {
    signal.map_or(0.0, |s| -mass * s.value(t))
}

/// The setting in words, for the run's settings table.
pub(crate) fn describe(scene: &Scene) -> Option<Setting> {
    scene.vertical().map(|_| {
        Setting::text(
            "vertical ground motion",
            "relative coordinates: load −M·a_v(t) on the body's centre of mass beside the preload −M·g; N(t) from the contacts' Kz (compression only: contacts open and close, the tangential origin follows an open contact)",
        )
    })
}

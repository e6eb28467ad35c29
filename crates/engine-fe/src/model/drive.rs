//! How an excitation drives the model, in either dimension — a force on the body (a mass
//! acceleration, or a ground acceleration in relative coordinates) or a prescribed ground
//! displacement, along the excitation's direction and, in space, a second signal at right
//! angles; the vertical ground motion as a load — and what an observer of the time loop
//! is shown at each output instant.

use nalgebra::Vector3;

use super::dimension::{Dimension, Vector};
use rockslide_core::case::{Excitation, Signal};

/// How the excitation drives the model.
#[derive(Debug, Clone, Copy)]
pub struct Drive<'a> {
    excitation: &'a Excitation,
    /// A second signal of the same kind at right angles (space only).
    second: Option<&'a Signal>,
    /// The vertical ground acceleration a_v(t), if any (`vertical`).
    vertical: Option<&'a Signal>,
    mass: f64,
    /// The excitation's horizontal direction e₁ and e₂ at right angles.
    directions: [Vector3<f64>; 2],
}

impl<'a> Drive<'a> {
    /// The drive of an excitation along x on a body of mass `mass`.
    pub fn new(excitation: &'a Excitation, mass: f64) -> Self {
        Self {
            excitation,
            second: None,
            vertical: None,
            mass,
            directions: [Vector3::x(), Vector3::y()],
        }
    }
    /// The same drive along the horizontal direction at `azimuth` (radians from x towards
    /// y), with an optional `second` signal of the same kind at right angles.
    pub fn along(self, azimuth: f64, second: Option<&'a Signal>) -> Self {
        let (s, c) = azimuth.sin_cos();
        Self {
            second,
            directions: [Vector3::new(c, s, 0.0), Vector3::new(-s, c, 0.0)],
            ..self
        }
    }
    /// The same drive with a vertical ground acceleration a_v(t) (positive upward).
    pub fn with_vertical(self, vertical: Option<&'a Signal>) -> Self {
        Self { vertical, ..self }
    }
    /// Vertical force on the body at `t` beyond the preload, N: −M·a_v(t) (`vertical`).
    pub fn vertical_force(&self, t: f64) -> f64 {
        crate::vertical::load(self.vertical, self.mass, t)
    }
    /// The horizontal quantity of `value`, one of a signal's derivatives.
    #[inline]
    fn horizontal<D: Dimension>(
        &self,
        first: &Signal,
        value: impl Fn(&Signal) -> f64,
    ) -> D::Horizontal {
        D::horizontal(value(first), self.second.map(&value), &self.directions)
    }
    /// Horizontal force applied to the body at `t`, N. A ground acceleration record is
    /// run in relative coordinates (force −M·ag, ground fixed).
    #[inline]
    pub fn force<D: Dimension>(&self, t: f64) -> D::Horizontal {
        match self.excitation {
            Excitation::MassAcceleration(s) => self.horizontal::<D>(s, |s| self.mass * s.value(t)),
            Excitation::GroundAcceleration(s) => {
                self.horizontal::<D>(s, |s| -self.mass * s.value(t))
            }
            _ => D::no_horizontal(),
        }
    }
    /// Prescribed ground (displacement, velocity, acceleration) at `t`, in the model.
    #[inline]
    pub fn ground<D: Dimension>(&self, t: f64) -> D::Ground {
        match self.excitation {
            Excitation::GroundDisplacement(s) => D::ground(
                self.horizontal::<D>(s, |s| s.value(t)),
                self.horizontal::<D>(s, |s| s.derivative(t)),
                self.horizontal::<D>(s, |s| s.second_derivative(t)),
            ),
            _ => D::rest_ground(),
        }
    }
    /// The horizontal force on the mass in relative coordinates (output channel `force`).
    /// `force` is `self.force(t)`, as a snapshot holds it (no second evaluation).
    pub fn equivalent_force<D: Dimension>(&self, t: f64, force: D::Horizontal) -> D::Horizontal {
        match self.excitation {
            Excitation::GroundDisplacement(s) => {
                self.horizontal::<D>(s, |s| -self.mass * s.second_derivative(t))
            }
            _ => force,
        }
    }
}

/// The model's state at one output instant.
#[derive(Debug, Clone, Copy)]
pub struct Snapshot<'a, D: Dimension> {
    /// Time, s.
    pub t: f64,
    /// Where the body is.
    pub pose: D::Pose,
    /// Velocity of the body's unknowns.
    pub v: D::Unknowns,
    /// Acceleration of the body's unknowns.
    pub a: D::Unknowns,
    /// Node displacements.
    pub un: &'a [Vector<D>],
    /// Ground (displacement, velocity, acceleration).
    pub ground: D::Ground,
    /// Where the body is at static equilibrium.
    pub statics: &'a D::Pose,
    /// Applied horizontal force at `t` (`Drive::force`), N.
    pub force: D::Horizontal,
    /// Vertical load at `t` beyond the preload (`Drive::vertical_force`), N.
    pub vertical_force: f64,
    /// The iterate of the last assembly (the plane's (cos θ, sin θ) at `pose`).
    pub at: &'a D::Iterate,
}

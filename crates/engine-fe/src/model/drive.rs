//! How an excitation drives the plane model (a horizontal force or a prescribed ground
//! displacement, and the vertical ground motion as a load), and what an observer of the
//! time loop is shown at each output instant.

use nalgebra::{Vector2, Vector3};

use rockslide_core::case::{Excitation, Signal};

/// How the excitation drives the model.
#[derive(Debug, Clone, Copy)]
pub struct Drive<'a> {
    excitation: &'a Excitation,
    mass: f64,
    /// The vertical ground acceleration a_v(t), if any (`vertical`).
    vertical: Option<&'a Signal>,
}

impl<'a> Drive<'a> {
    /// The drive of an excitation on a body of mass `mass`.
    pub fn new(excitation: &'a Excitation, mass: f64) -> Self {
        Self {
            excitation,
            mass,
            vertical: None,
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
    /// Horizontal force applied to the body at `t`, N. A ground acceleration record is
    /// run in relative coordinates (force −M·ag, ground fixed).
    pub fn force(&self, t: f64) -> f64 {
        match self.excitation {
            Excitation::MassAcceleration(s) => self.mass * s.value(t),
            Excitation::GroundAcceleration(s) => -self.mass * s.value(t),
            _ => 0.0,
        }
    }
    /// Prescribed ground (displacement, velocity, acceleration) at `t`, in the model.
    pub fn ground(&self, t: f64) -> (f64, f64, f64) {
        match self.excitation {
            Excitation::GroundDisplacement(s) => {
                (s.value(t), s.derivative(t), s.second_derivative(t))
            }
            _ => (0.0, 0.0, 0.0),
        }
    }
    /// The horizontal force on the mass in relative coordinates (output channel `force`).
    /// `force` is `self.force(t)`, as a snapshot holds it (no second evaluation).
    pub fn equivalent_force(&self, t: f64, force: f64) -> f64 {
        match self.excitation {
            Excitation::GroundDisplacement(s) => -self.mass * s.second_derivative(t),
            _ => force,
        }
    }
}

/// The model's state at one output instant.
#[derive(Debug, Clone, Copy)]
pub struct Snapshot<'a> {
    /// Time, s.
    pub t: f64,
    /// Body displacement (X, Z, θ) from the unloaded position.
    pub q: Vector3<f64>,
    /// Body velocity.
    pub v: Vector3<f64>,
    /// Body acceleration.
    pub a: Vector3<f64>,
    /// Node displacements.
    pub un: &'a [Vector2<f64>],
    /// Ground (displacement, velocity, acceleration).
    pub ground: (f64, f64, f64),
    /// Body displacement at static equilibrium.
    pub q_static: Vector3<f64>,
    /// Applied horizontal force at `t` (`Drive::force`), N.
    pub force: f64,
    /// Vertical load at `t` beyond the preload (`Drive::vertical_force`), N.
    pub vertical_force: f64,
    /// (cos θ, sin θ) of `q` as the model's kinematics use them (`Assembly::rotation`).
    pub rotation: (f64, f64),
}

//! Newmark's relations and the HHT-α weights of one step (Newmark 1959; Hilber, Hughes &
//! Taylor 1977), with q the body's unknowns:
//!   a₊ = (q₊ − qₙ − Δt·vₙ)/(βΔt²) − (1/(2β) − 1)·aₙ,   v₊ = vₙ + Δt·((1 − γ)aₙ + γa₊)
//! and the HHT equilibrium at t_{n+1+α}:
//!   M·a₊ + (1 + α)(p₊ + C·v₊ − f₊) − α(pₙ + C·vₙ − fₙ) = 0.

use nalgebra::SVector;

use crate::options::FeOptions;

/// The Newmark/HHT-α coefficients of one step of length `h`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Newmark {
    /// HHT's α (0 for Newmark).
    pub alpha: f64,
    /// Newmark's γ (β enters through `c0`, `c1` and the weight of aₙ).
    pub gamma: f64,
    /// 1 + α, the weight of the end-of-step forces.
    pub s: f64,
    /// ∂a/∂q = 1/(β·h²) and ∂v/∂q = γ/(β·h).
    pub c0: f64,
    pub c1: f64,
    /// Step, s.
    pub h: f64,
    /// 1/(2β) − 1 and 1 − γ, the weights of aₙ in `kinematics` (computed once).
    a_weight: f64,
    v_weight: f64,
}

impl Newmark {
    pub(crate) fn new(opts: &FeOptions, h: f64) -> Self {
        let (alpha, beta, gamma) = opts.integrator.parameters();
        Self {
            alpha,
            gamma,
            s: 1.0 + alpha,
            c0: 1.0 / (beta * h * h),
            c1: gamma / (beta * h),
            h,
            a_weight: 0.5 / beta - 1.0,
            v_weight: 1.0 - gamma,
        }
    }

    /// Acceleration and velocity at the end of the step from the displacement increment
    /// `dq` = q − qₙ and the start's velocity and acceleration (Newmark's relations).
    #[inline]
    pub(crate) fn kinematics<const D: usize>(
        &self,
        dq: SVector<f64, D>,
        vn: &SVector<f64, D>,
        an: &SVector<f64, D>,
    ) -> (SVector<f64, D>, SVector<f64, D>) {
        let a = (dq - vn * self.h) * self.c0 - an * self.a_weight;
        let v = vn + (an * self.v_weight + a * self.gamma) * self.h;
        (a, v)
    }
}

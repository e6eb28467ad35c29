//! The closed-form Duhamel solution of a linear viscously damped oscillator under a sine
//! pulse `p0·sin θt` on [0, td] (Chopra, Dynamics of Structures, §3.2 and §4.8): transient
//! plus steady state during the pulse, free damped vibration after it. Anchors the linear
//! (no-slip) scene and, through it, the elastic-plastic reference.

use super::{ExactSolution, SineForcing};
use rockslide_core::case::Oscillator;
use rockslide_core::trace::{Quantity, q};

/// Linear oscillator under a sine pulse, in closed form.
#[derive(Debug, Clone)]
pub struct Duhamel {
    m: f64,
    k: f64,
    c: f64,
    zeta: f64,
    omega: f64,
    omega_d: f64,
    forcing: SineForcing,
    /// Displacement and velocity just after td (jump included).
    after_pulse: (f64, f64),
}

impl Duhamel {
    /// The closed form for `osc` (friction ignored: linear) under `forcing`.
    pub fn new(osc: &Oscillator, forcing: SineForcing, _duration: f64) -> Result<Self, String> {
        let (m, k) = (osc.mass, osc.contact.kx);
        let omega = (k / m).sqrt();
        let zeta = osc.damping_ratio;
        if zeta >= 1.0 {
            return Err("the Duhamel closed form here is for under-damped oscillators".into());
        }
        let r = forcing.theta / omega;
        if zeta == 0.0 && forcing.p0 != 0.0 && (r - 1.0).abs() < 1e-9 {
            return Err(
                "the undamped resonant case (θ = ω) is not covered by this closed form".into(),
            );
        }
        let mut d = Duhamel {
            m,
            k,
            c: 2.0 * zeta * m * omega,
            zeta,
            omega,
            omega_d: omega * (1.0 - zeta * zeta).sqrt(),
            forcing,
            after_pulse: (0.0, 0.0),
        };
        let td = d.forcing.td;
        let (x, v) = d.during_pulse(td);
        let jump: f64 = d
            .forcing
            .velocity_jumps
            .iter()
            .filter(|(t, _)| *t == td && td > 0.0)
            .map(|j| j.1)
            .sum();
        d.after_pulse = (x, v + jump);
        Ok(d)
    }

    /// Steady-state coefficients (C, D) of x = C sin θt + D cos θt (Chopra Eq. 3.2.3).
    fn steady(&self) -> (f64, f64) {
        let r = self.forcing.theta / self.omega;
        let den = (1.0 - r * r).powi(2) + (2.0 * self.zeta * r).powi(2);
        let xst = self.forcing.p0 / self.k;
        (
            xst * (1.0 - r * r) / den,
            xst * (-2.0 * self.zeta * r) / den,
        )
    }

    /// (x, v) for 0 ≤ t ≤ td, from rest with the initial velocity jump.
    fn during_pulse(&self, t: f64) -> (f64, f64) {
        let v0: f64 = self
            .forcing
            .velocity_jumps
            .iter()
            .filter(|(tj, _)| *tj == 0.0)
            .map(|j| j.1)
            .sum();
        let (cs, ds) = self.steady();
        let th = self.forcing.theta;
        let (w, wd, z) = (self.omega, self.omega_d, self.zeta);
        // x(0) = 0: A + D = 0; v(0) = v0: −ζωA + ωd·B + θC = v0
        let a = -ds;
        let b = (v0 + z * w * a - th * cs) / wd;
        let decay = (-z * w * t).exp();
        let (s, c) = (wd * t).sin_cos();
        let x = decay * (a * c + b * s) + cs * (th * t).sin() + ds * (th * t).cos();
        let v = decay * ((-z * w) * (a * c + b * s) + wd * (-a * s + b * c))
            + th * (cs * (th * t).cos() - ds * (th * t).sin());
        (x, v)
    }

    /// (x, v) after the pulse: free damped vibration (Chopra Eq. 2.2.4).
    fn after(&self, t: f64) -> (f64, f64) {
        let (x0, v0) = self.after_pulse;
        let tau = t - self.forcing.td;
        let (w, wd, z) = (self.omega, self.omega_d, self.zeta);
        let decay = (-z * w * tau).exp();
        let (s, c) = (wd * tau).sin_cos();
        let b = (v0 + z * w * x0) / wd;
        let x = decay * (x0 * c + b * s);
        let v = decay * (-z * w * (x0 * c + b * s) + wd * (-x0 * s + b * c));
        (x, v)
    }

    /// (x, v) at t.
    pub fn state(&self, t: f64) -> (f64, f64) {
        if t < self.forcing.td {
            self.during_pulse(t)
        } else {
            self.after(t)
        }
    }
}

impl ExactSolution for Duhamel {
    fn name(&self) -> &'static str {
        "duhamel"
    }

    fn method(&self) -> String {
        "closed-form Duhamel solution of the linear oscillator (Chopra §3.2, §4.8)".into()
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        q::sliding(self.forcing.ground_amplitude.is_some())
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        let (x, v) = self.state(t);
        let p = self.forcing.at(t);
        let r = self.k * x;
        out[0] = p;
        out[1] = r;
        out[2] = x;
        out[3] = 0.0;
        out[4] = v;
        out[5] = (p - r - self.c * v) / self.m;
        if let Some(g) = self.forcing.ground(t) {
            out[6] = g;
        }
    }
}

//! Ground motion as the rigid-body engine feeds it to rapier: the ground's displacement
//! and velocity at every step time, precomputed before the time loop so the loop does not
//! allocate. The two routes read the same tables:
//!
//! - *kinematic ground*: the ground body is moved to xg(t_{n+1}) each step, so the
//!   velocity the contact sees over the step is (xg(n+1) − xg(n))/Δt;
//! - *inertial force*: the ground stays fixed and every dynamic body of mass m gets the
//!   force −m·(vg(n+1) − vg(n))/Δt over the step — the exact change of the ground
//!   velocity, jumps included — and at t = 0 the relative velocity −vg(0⁺).

use crate::case::{Excitation, Signal};

/// Ground displacement and (right-continuous) ground velocity at the step times.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundTable {
    /// xg(t_n), m.
    pub disp: Vec<f64>,
    /// vg(t_n⁺), m/s.
    pub vel: Vec<f64>,
}

impl GroundTable {
    /// Tables for `n + 1` step times `t_k = k·dt`.
    pub fn new(excitation: &Excitation, dt: f64, n: usize) -> Self {
        let mut disp = Vec::with_capacity(n + 1);
        let mut vel = Vec::with_capacity(n + 1);
        for k in 0..=n {
            let t = k as f64 * dt;
            let (x, v) = match excitation {
                Excitation::GroundDisplacement(s) => (s.value(t), s.derivative(t)),
                Excitation::GroundAcceleration(s) => integrated(s, t, dt),
                Excitation::None | Excitation::MassAcceleration(_) => (0.0, 0.0),
            };
            disp.push(x);
            vel.push(v);
        }
        Self { disp, vel }
    }

    /// Mean ground acceleration over step `k → k+1`, m/s² (velocity jumps included).
    pub fn mean_acceleration(&self, k: usize, dt: f64) -> f64 {
        (self.vel[k + 1] - self.vel[k]) / dt
    }
}

/// (xg, vg) at `t` for a ground *acceleration* signal starting from rest at the origin.
fn integrated(s: &Signal, t: f64, dt: f64) -> (f64, f64) {
    match s {
        Signal::SinePulse {
            amplitude, omega, ..
        } => {
            // ag = a·sin θt on [0, te]: vg = (a/θ)(1 − cos θt), xg = (a/θ)(t − sin θt / θ);
            // after te the ground coasts at vg(te).
            let (a, w) = (*amplitude, *omega);
            let te = s.end();
            let tt = t.min(te);
            let v = a / w * (1.0 - (w * tt).cos());
            let x = a / w * (tt - (w * tt).sin() / w);
            (x + v * (t - tt), v)
        }
        Signal::Record { .. } => {
            // Piecewise-linear acceleration: integrate on a grid 32 times finer than the step
            // (trapezoid for v, the exact quadratic for x on each piece).
            let m = (t / dt * 32.0).round().max(1.0) as usize;
            let h = t / m as f64;
            let (mut x, mut v) = (0.0, 0.0);
            for i in 0..m {
                let (a0, a1) = (s.value(i as f64 * h), s.value((i + 1) as f64 * h));
                x += v * h + h * h * (2.0 * a0 + a1) / 6.0;
                v += 0.5 * h * (a0 + a1);
            }
            (x, v)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sine_acceleration_integrates_to_the_closed_form_velocity() {
        // ag = 2 sin(πt) over one half cycle (te = 1 s): vg(te) = 2·2/π.
        let s = Signal::SinePulse {
            amplitude: 2.0,
            omega: std::f64::consts::PI,
            cycles: 0.5,
        };
        let g = GroundTable::new(&Excitation::GroundAcceleration(s), 0.5, 4);
        let v_end = 4.0 / std::f64::consts::PI;
        assert!((g.vel[2] - v_end).abs() < 1e-12);
        assert!((g.vel[4] - v_end).abs() < 1e-12);
        assert!((g.disp[4] - g.disp[2] - v_end).abs() < 1e-12);
    }

    #[test]
    fn displacement_pulse_velocity_is_right_continuous() {
        let s = Signal::SinePulse {
            amplitude: 1.0,
            omega: std::f64::consts::PI,
            cycles: 0.5,
        };
        let g = GroundTable::new(&Excitation::GroundDisplacement(s), 0.5, 3);
        assert!(
            (g.vel[0] - std::f64::consts::PI).abs() < 1e-12,
            "vg(0+) = Aθ"
        );
        assert_eq!(g.vel[2], 0.0, "vg(td+) = 0");
    }
}

//! Housner's rocking block (Housner 1963, "The behavior of inverted pendulum structures
//! during earthquakes"): a rigid block of half-width b and half-height h rocking on a
//! rigid ground without sliding or bouncing, about one base corner at a time. Between
//! impacts the exact nonlinear equation of motion is integrated by RK4 with a fine step
//! (the step is cut at the pulse end); each impact (rotation crossing zero) is located by
//! bisection on the step length, and the angular velocity is multiplied by Housner's
//! coefficient of restitution r = 1 − 1.5·sin²α (conservation of angular momentum about
//! the new corner). Written from the equations of motion alone — it shares nothing with
//! the engines.
//!
//! Rotation φ is counter-clockwise positive (X right, Z up): φ > 0 pivots on the left
//! corner. With R = √(b² + h²), tan α = b/h, I₀ = (4/3)·M·R² about a corner and p(t) the
//! horizontal driving acceleration (−ag, or a for a force on the block), s = sign φ:
//!
//! I₀·φ'' = −s·M·g·R·sin(α − s·φ) − M·p(t)·R·cos(α − s·φ)      (Housner 1963, Eq. 1)

use super::{ExactSolution, SineForcing};
use rockslide_core::case::{RigidBlock, limits};
use rockslide_core::trace::{Quantity, q};

/// Integration step of the reference, s (RK4: local error ~ (p·Δt)⁵, negligible).
const STEP: f64 = 2e-5;

/// The event-driven rocking history, stored densely.
#[derive(Debug, Clone)]
pub struct HousnerRocking {
    m: f64,
    g: f64,
    b: f64,
    hh: f64,
    big_r: f64,
    alpha: f64,
    forcing: SineForcing,
    /// Coefficient of restitution r = 1 − 1.5 sin²α.
    pub restitution: f64,
    /// Times of impacts, s.
    pub impacts: Vec<f64>,
    /// Time, rotation and angular velocity samples (impacts included, twice).
    samples: Vec<(f64, f64, f64)>,
}

impl HousnerRocking {
    /// Solve the rocking of `block` (from its initial tilt, or from rest) under `forcing`.
    pub fn new(block: &RigidBlock, forcing: SineForcing, duration: f64) -> Result<Self, String> {
        if forcing.velocity_jumps.iter().any(|j| j.1 != 0.0) {
            return Err(
                "Housner's rocking reference does not take ground-velocity jumps (use a ground-acceleration pulse)".into(),
            );
        }
        // a sample is kept every STEP: their count is held to the step limit
        let steps = duration / STEP;
        if !(duration >= 0.0 && steps <= limits::max_steps() as f64) {
            return Err(format!(
                "Housner's rocking reference over {duration:e} s keeps a sample every {STEP:e} s: \
                 {steps:.3e} samples, more than the limit of {} (set {} to raise it)",
                limits::max_steps(),
                limits::MAX_STEPS_VARIABLE
            ));
        }
        let (b, hh) = (block.half_width, block.half_height);
        let alpha = (b / hh).atan();
        let mut sol = HousnerRocking {
            m: block.mass,
            g: block.gravity,
            b,
            hh,
            big_r: b.hypot(hh),
            alpha,
            restitution: 1.0 - 1.5 * alpha.sin().powi(2),
            forcing,
            impacts: Vec::new(),
            samples: Vec::new(),
        };
        sol.solve(-block.initial_tilt, duration);
        Ok(sol)
    }

    fn p(&self, t: f64) -> f64 {
        self.forcing.at(t) / self.m
    }

    /// φ'' for a pivot side `s` (Housner 1963, Eq. 1, divided by I₀ = 4/3·M·R²).
    fn accel(&self, t: f64, phi: f64, s: f64) -> f64 {
        let c = 3.0 / (4.0 * self.big_r);
        c * (-s * self.g * (self.alpha - s * phi).sin() - self.p(t) * (self.alpha - s * phi).cos())
    }

    fn rk4(&self, t: f64, phi: f64, w: f64, s: f64, h: f64) -> (f64, f64) {
        let k1 = (w, self.accel(t, phi, s));
        let k2 = (
            w + 0.5 * h * k1.1,
            self.accel(t + 0.5 * h, phi + 0.5 * h * k1.0, s),
        );
        let k3 = (
            w + 0.5 * h * k2.1,
            self.accel(t + 0.5 * h, phi + 0.5 * h * k2.0, s),
        );
        let k4 = (w + h * k3.1, self.accel(t + h, phi + h * k3.0, s));
        (
            phi + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
            w + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
        )
    }

    fn solve(&mut self, phi0: f64, duration: f64) {
        let (mut t, mut phi, mut w) = (0.0, phi0, 0.0);
        self.samples.push((t, phi, w));
        let td = self.forcing.td;
        let at_rest_limit = self.g * self.alpha.tan();
        while t < duration {
            let mut h = STEP.min(duration - t);
            if t < td && t + h > td {
                h = td - t; // cut the step at the pulse end (p has a kink there)
            }
            if phi == 0.0 && w == 0.0 {
                // Resting flat: rocking starts when |p| exceeds g·tan α (Housner 1963).
                if self.p(t).abs() <= at_rest_limit || self.p(t + h).abs() <= at_rest_limit {
                    t += h;
                    self.samples.push((t, 0.0, 0.0));
                    continue;
                }
            }
            let s = if phi != 0.0 {
                phi.signum()
            } else if w != 0.0 {
                w.signum()
            } else {
                -self.p(t).signum()
            };
            let (phi1, w1) = self.rk4(t, phi, w, s, h);
            if s * phi1 < 0.0 {
                // Impact inside the step: bisect on the step length.
                let (mut lo, mut hi) = (0.0, h);
                for _ in 0..crate::root::BISECTION_LIMIT {
                    let mid = 0.5 * (lo + hi);
                    if mid <= lo || mid >= hi {
                        break;
                    }
                    if s * self.rk4(t, phi, w, s, mid).0 > 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let (_, w_imp) = self.rk4(t, phi, w, s, hi);
                t += hi;
                self.samples.push((t, 0.0, w_imp));
                self.impacts.push(t);
                // Housner's restitution: angular momentum about the new corner is conserved.
                w = self.restitution * w_imp;
                phi = 0.0;
                if w.abs() < 1e-12 {
                    w = 0.0;
                }
                self.samples.push((t, 0.0, w));
            } else {
                t += h;
                phi = phi1;
                w = w1;
                self.samples.push((t, phi, w));
            }
        }
    }

    /// (φ, φ') at `t` (cubic Hermite between stored samples; right-continuous at impacts).
    pub fn state(&self, t: f64) -> (f64, f64) {
        self.state_at(self.samples.partition_point(|s| s.0 <= t), t)
    }

    /// [`Self::state`] with the samples' partition point at `t` already found.
    fn state_at(&self, i: usize, t: f64) -> (f64, f64) {
        if i == 0 {
            return (self.samples[0].1, self.samples[0].2);
        }
        if i >= self.samples.len() {
            let s = self.samples[self.samples.len() - 1];
            return (s.1, s.2);
        }
        let (t0, p0, w0) = self.samples[i - 1];
        let (t1, p1, w1) = self.samples[i];
        let h = t1 - t0;
        if h <= 0.0 {
            return (p1, w1);
        }
        let x = (t - t0) / h;
        let (h00, h10, h01, h11) = (
            2.0 * x.powi(3) - 3.0 * x * x + 1.0,
            x.powi(3) - 2.0 * x * x + x,
            -2.0 * x.powi(3) + 3.0 * x * x,
            x.powi(3) - x * x,
        );
        let phi = h00 * p0 + h10 * h * w0 + h01 * p1 + h11 * h * w1;
        (phi, w0 + x * (w1 - w0))
    }

    /// The channels at rotation φ (pivot, centre of mass, uplift, base centre), in
    /// [`ExactSolution::channels`] order.
    fn write(&self, phi: f64, out: &mut [f64]) {
        let (b, h) = (self.b, self.hh);
        let s = if phi >= 0.0 { 1.0 } else { -1.0 };
        // Pivot corner at (−s·b, 0); CM = pivot + R(φ)·(s·b, h); base centre O likewise.
        let (sn, cs) = phi.sin_cos();
        let pivot = -s * b;
        let cm_x = pivot + cs * s * b - sn * h;
        let cm_z = sn * s * b + cs * h;
        let o_x = pivot + cs * s * b;
        out[0] = phi;
        out[1] = cm_x;
        out[2] = cm_z - h;
        out[3] = 2.0 * b * sn.abs();
        out[4] = o_x;
    }

    /// Largest |φ| between consecutive impacts: [before the first, after the first, …].
    pub fn half_cycle_peaks(&self) -> Vec<f64> {
        let mut peaks = vec![0.0_f64];
        let mut k = 0;
        for &(t, phi, _) in &self.samples {
            if k < self.impacts.len() && t >= self.impacts[k] {
                k += 1;
                peaks.push(0.0);
            }
            let last = peaks.len() - 1;
            peaks[last] = peaks[last].max(phi.abs());
        }
        peaks
    }
}

impl ExactSolution for HousnerRocking {
    fn name(&self) -> &'static str {
        "Housner"
    }

    fn method(&self) -> String {
        format!(
            "Housner (1963) rocking block: exact nonlinear equation by RK4 (Δt = {STEP} s) between {} impacts located by bisection, r = 1 − 1.5 sin²α = {:.5}",
            self.impacts.len(),
            self.restitution
        )
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        vec![&q::ROTATION, &q::CM_X, &q::CM_Z, &q::UPLIFT, &q::REL_DISP]
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        self.write(self.state(t).0, out);
    }

    fn sample_into(&self, times: &[f64], trace: &mut rockslide_core::trace::Trace) {
        crate::each_row_by_piece(
            trace,
            times,
            &self.samples,
            |s, t| s.0 <= t,
            |i, t, out| {
                self.write(self.state_at(i, t).0, out);
            },
        );
    }

    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        let mut v = Vec::new();
        if let Some(&t) = self.impacts.first() {
            v.push(("first_impact", t));
        }
        if let Some(&t) = self.impacts.get(1) {
            v.push(("second_impact", t));
        }
        if let Some(&p) = self.half_cycle_peaks().get(1) {
            v.push(("peak_tilt_after_impact", p));
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn free(b: f64, h: f64, tilt: f64) -> HousnerRocking {
        let block = RigidBlock {
            mass: 1.0,
            gravity: 9.81,
            half_width: b,
            half_height: h,
            mu: 10.0,
            initial_tilt: tilt,
        };
        let none = SineForcing {
            p0: 0.0,
            theta: 1.0,
            td: 0.0,
            velocity_jumps: vec![],
            ground_amplitude: None,
        };
        HousnerRocking::new(&block, none, 3.0).unwrap()
    }

    /// A duration of 1e15 s (from a script) grew memory until the system killed the
    /// process: the samples are now counted against the step limit first.
    #[test]
    fn a_duration_beyond_the_step_limit_is_refused_before_solving() {
        let block = RigidBlock {
            mass: 1.0,
            gravity: 9.81,
            half_width: 0.2,
            half_height: 1.0,
            mu: f64::INFINITY,
            initial_tilt: 0.0,
        };
        let pulse = SineForcing {
            p0: -5.0,
            theta: 10.0,
            td: 0.1 * std::f64::consts::PI,
            velocity_jumps: vec![],
            ground_amplitude: None,
        };
        let why = HousnerRocking::new(&block, pulse.clone(), 1e15)
            .err()
            .unwrap();
        assert!(
            why.contains("5.000e19 samples, more than the limit"),
            "{why}"
        );
        assert!(HousnerRocking::new(&block, pulse, f64::NAN).is_err());
    }

    #[test]
    fn first_impact_matches_the_energy_quadrature() {
        // Free rocking from rest at tilt θ0: (3g/2R)(cos(α − θ0) − cos(α − θ)) = θ'²
        // (energy), so t_impact = ∫₀^θ0 dθ / θ'(θ). Substituting θ = θ0·(1 − u²) removes
        // the endpoint singularity; integrate with Simpson's rule (independent of RK4).
        let (b, h, th0) = (0.2, 1.0, 0.1);
        let sol = free(b, h, th0);
        let (r, alpha) = (b.hypot(h), (b / h).atan());
        let k = 3.0 * 9.81 / (2.0 * r);
        let f = |u: f64| {
            if u == 0.0 {
                // θ'² ≈ k·sin(α − θ0)·θ0·u² near u = 0, so the integrand tends to
                // 2θ0 / √(k·θ0·sin(α − θ0)).
                return 2.0 * th0 / (k * th0 * (alpha - th0).sin()).sqrt();
            }
            let th = th0 * (1.0 - u * u);
            let w2 = k * ((alpha - th0).cos() - (alpha - th).cos());
            2.0 * th0 * u / w2.sqrt()
        };
        let n = 20_000;
        let dh = 1.0 / n as f64;
        let mut sum = f(0.0) + f(1.0);
        for i in 1..n {
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * dh);
        }
        let t_quad = sum * dh / 3.0;
        let t_ref = sol.impacts[0];
        assert!(
            (t_ref - t_quad).abs() < 1e-7,
            "RK4 + bisection {t_ref} s, quadrature {t_quad} s"
        );
    }

    #[test]
    fn restitution_scales_the_energy_by_r_squared() {
        // The impact keeps r² of the kinetic energy, so the block rises after it to θ1
        // with cos(α − θ1) − cos α = r²·(cos(α − θ0) − cos α) (energy, per unit M·g·R).
        let (b, h, th0) = (0.2, 1.0, 0.1);
        let sol = free(b, h, th0);
        let alpha = (b / h).atan();
        let r = 1.0 - 1.5 * alpha.sin().powi(2);
        let e1 = r * r * ((alpha - th0).cos() - alpha.cos());
        let th1 = alpha - (alpha.cos() + e1).acos();
        let peaks = sol.half_cycle_peaks();
        assert!((peaks[0] - th0).abs() < 1e-12);
        assert!(
            (peaks[1] - th1).abs() < 1e-6 * th1,
            "peak after impact {} rad, energy balance {th1} rad",
            peaks[1]
        );
    }
}

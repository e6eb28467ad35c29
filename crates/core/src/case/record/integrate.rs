//! Ground velocity and displacement integrated from a record's acceleration, with a
//! stated baseline correction.

/// How the drift of integrated ground displacement is removed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Baseline {
    /// Integrate the acceleration as given (displacement may drift).
    None,
    /// Subtract the least-squares fit c2·t² + c3·t³ of the uncorrected displacement (and
    /// its derivatives from velocity and acceleration). The fit has no constant or linear
    /// term, so the corrected motion still starts from rest at zero, and the corrected
    /// acceleration, velocity and displacement remain exact integrals of each other.
    Cubic,
}

/// Ground motion obtained from an acceleration record: velocity and displacement at the
/// samples, for engines that need the ground's displacement (a moving kinematic ground).
#[derive(Debug, Clone, PartialEq)]
pub struct GroundMotion {
    /// Acceleration after baseline correction, m/s².
    pub acc: Vec<f64>,
    /// Velocity, m/s.
    pub vel: Vec<f64>,
    /// Displacement, m.
    pub disp: Vec<f64>,
}

/// Integrate a uniformly sampled acceleration (linear between samples, from rest) to
/// velocity and displacement, exactly for that piecewise-linear acceleration:
/// v(i+1) = v(i) + Δt·(a(i) + a(i+1))/2, d(i+1) = d(i) + Δt·v(i) + Δt²·(2a(i) + a(i+1))/6;
/// then apply `baseline`.
pub fn integrate(dt: f64, acc: &[f64], baseline: Baseline) -> GroundMotion {
    let n = acc.len();
    let mut vel = vec![0.0; n];
    let mut disp = vec![0.0; n];
    for i in 1..n {
        vel[i] = vel[i - 1] + dt * (acc[i - 1] + acc[i]) / 2.0;
        disp[i] = disp[i - 1] + dt * vel[i - 1] + dt * dt * (2.0 * acc[i - 1] + acc[i]) / 6.0;
    }
    let mut acc = acc.to_vec();
    if baseline == Baseline::Cubic && n >= 3 {
        // Least squares for d ≈ c2 t² + c3 t³: normal equations in (c2, c3).
        let (mut s44, mut s45, mut s46, mut r2, mut r3) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for (i, d) in disp.iter().enumerate() {
            let t = i as f64 * dt;
            let (t2, t3) = (t * t, t * t * t);
            s44 += t2 * t2;
            s45 += t2 * t3;
            s46 += t3 * t3;
            r2 += t2 * d;
            r3 += t3 * d;
        }
        let det = s44 * s46 - s45 * s45;
        if det != 0.0 {
            let c2 = (r2 * s46 - r3 * s45) / det;
            let c3 = (s44 * r3 - s45 * r2) / det;
            for i in 0..n {
                let t = i as f64 * dt;
                acc[i] -= 2.0 * c2 + 6.0 * c3 * t;
                vel[i] -= 2.0 * c2 * t + 3.0 * c3 * t * t;
                disp[i] -= c2 * t * t + c3 * t * t * t;
            }
        }
    }
    GroundMotion { acc, vel, disp }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integration_is_exact_for_constant_acceleration() {
        // a = 2 m/s² from rest: v = 2t, d = t² exactly (piecewise-linear input).
        let m = integrate(0.1, &[2.0; 11], Baseline::None);
        assert!((m.vel[10] - 2.0).abs() < 1e-12);
        assert!((m.disp[10] - 1.0).abs() < 1e-12);
        // The cubic baseline removes a t² drift entirely.
        let m = integrate(0.1, &[2.0; 11], Baseline::Cubic);
        assert!(m.disp.iter().all(|d| d.abs() < 1e-12));
    }
}

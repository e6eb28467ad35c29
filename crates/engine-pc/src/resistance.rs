//! The resistance law of the paper, Eqs 7–8: elastic-perfectly-plastic, the origin of the
//! curve shifted by the accumulated plastic (sliding) displacement xp.

/// Resistance R at displacement `x` given the previous step's slip `xp_prev`, and the
/// updated slip. Paper Eq 7 (loading, x − xp > 0): R = min(K(x − xp), Ru);
/// Eq 8 (unloading): R = max(K(x − xp), −Ru). The slip is the shift of the origin:
/// xp = x − R/K, unchanged while elastic.
pub fn resistance(x: f64, xp_prev: f64, k: f64, ru: f64) -> (f64, f64) {
    let trial = k * (x - xp_prev);
    let r = if x - xp_prev > 0.0 {
        trial.min(ru) // Eq 7
    } else {
        trial.max(-ru) // Eq 8
    };
    let xp = if r == trial { xp_prev } else { x - r / k };
    (r, xp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elastic_below_the_limit_plastic_above() {
        assert_eq!(resistance(0.001, 0.0, 1000.0, 5.0), (1.0, 0.0));
        let (r, xp) = resistance(0.01, 0.0, 1000.0, 5.0);
        assert_eq!(r, 5.0);
        assert!((xp - 0.005).abs() < 1e-15);
        let (r, xp) = resistance(-0.02, 0.005, 1000.0, 5.0);
        assert_eq!(r, -5.0);
        assert!((xp + 0.015).abs() < 1e-15);
    }

    #[test]
    fn infinite_friction_is_linear() {
        assert_eq!(resistance(3.0, 0.0, 2.0, f64::INFINITY), (6.0, 0.0));
    }
}

//! Time signals that drive a scene: an analytic sine pulse (the paper's half-sine and
//! five-cycle inputs) or a sampled record. A signal knows its value and derivatives and
//! the jumps of its first derivative, which the exact references must apply as impulses.

use std::f64::consts::PI;
use std::sync::Arc;

/// A jump of the first derivative of a signal at a given time (e.g. the ground velocity
/// jumping from 0 to A·θ when a displacement pulse `A·sin θt` starts).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jump {
    /// When it happens, s.
    pub time: f64,
    /// Derivative after minus derivative before.
    pub size: f64,
}

/// A scalar function of time, zero before 0 and after its end.
#[derive(Debug, Clone, PartialEq)]
pub enum Signal {
    /// `amplitude · sin(omega · t)` for `0 ≤ t ≤ cycles · 2π / omega`, zero after.
    SinePulse {
        /// Peak value, in the unit of the excitation.
        amplitude: f64,
        /// Circular frequency θ, rad/s.
        omega: f64,
        /// Number of full cycles (0.5 is a half-sine).
        cycles: f64,
    },
    /// Samples at a fixed interval, linear in between, zero after the last sample.
    Record {
        /// Sample interval, s.
        dt: f64,
        /// Values, already scaled to the excitation's SI unit.
        samples: Arc<[f64]>,
        /// Where the record came from (file and scaling), for reports.
        label: String,
    },
}

impl Signal {
    /// Time at which the signal ends, s.
    pub fn end(&self) -> f64 {
        match self {
            Signal::SinePulse { omega, cycles, .. } => cycles * 2.0 * PI / omega,
            Signal::Record { dt, samples, .. } => dt * (samples.len().saturating_sub(1)) as f64,
        }
    }

    /// Value at `t`.
    pub fn value(&self, t: f64) -> f64 {
        match self {
            Signal::SinePulse {
                amplitude, omega, ..
            } => {
                if (0.0..=self.end()).contains(&t) {
                    amplitude * (omega * t).sin()
                } else {
                    0.0
                }
            }
            Signal::Record { dt, samples, .. } => {
                if t < 0.0 || samples.is_empty() {
                    return 0.0;
                }
                let x = t / dt;
                // beyond the last sample (or past usize's range, where `as` saturates)
                if x >= samples.len() as f64 {
                    return 0.0;
                }
                let i = x.floor() as usize;
                if i + 1 >= samples.len() {
                    return if i + 1 == samples.len() && x == i as f64 {
                        samples[i]
                    } else {
                        0.0
                    };
                }
                let f = x - i as f64;
                samples[i] * (1.0 - f) + samples[i + 1] * f
            }
        }
    }

    /// First derivative at `t` (for a record: the slope of the segment containing `t`).
    pub fn derivative(&self, t: f64) -> f64 {
        match self {
            Signal::SinePulse {
                amplitude, omega, ..
            } => {
                if (0.0..self.end()).contains(&t) {
                    amplitude * omega * (omega * t).cos()
                } else {
                    0.0
                }
            }
            Signal::Record { dt, samples, .. } => {
                let i = (t / dt).floor();
                if i < 0.0 || i as usize + 1 >= samples.len() {
                    return 0.0;
                }
                let i = i as usize;
                (samples[i + 1] - samples[i]) / dt
            }
        }
    }

    /// Second derivative at `t`, away from jumps (zero for a record: linear segments).
    pub fn second_derivative(&self, t: f64) -> f64 {
        match self {
            Signal::SinePulse {
                amplitude, omega, ..
            } => {
                if (0.0..self.end()).contains(&t) {
                    -amplitude * omega * omega * (omega * t).sin()
                } else {
                    0.0
                }
            }
            Signal::Record { .. } => 0.0,
        }
    }

    /// Jumps of the first derivative (start and end of a sine pulse).
    pub fn derivative_jumps(&self) -> Vec<Jump> {
        match self {
            Signal::SinePulse {
                amplitude, omega, ..
            } => {
                let end = self.end();
                vec![
                    Jump {
                        time: 0.0,
                        size: amplitude * omega,
                    },
                    Jump {
                        time: end,
                        size: -amplitude * omega * (omega * end).cos(),
                    },
                ]
            }
            Signal::Record { .. } => Vec::new(),
        }
    }

    /// Largest absolute value (peak of the signal).
    pub fn peak(&self) -> f64 {
        match self {
            Signal::SinePulse {
                amplitude, cycles, ..
            } => {
                if *cycles >= 0.25 {
                    amplitude.abs()
                } else {
                    (amplitude * (2.0 * PI * cycles).sin()).abs()
                }
            }
            Signal::Record { samples, .. } => samples.iter().fold(0.0, |m, v| m.max(v.abs())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_sine_pulse_of_the_paper() {
        let theta = 31.415_926_535_897_93 / 2.0;
        let s = Signal::SinePulse {
            amplitude: 1.0,
            omega: theta,
            cycles: 0.5,
        };
        assert!((s.end() - 0.2).abs() < 1e-15);
        assert!((s.value(0.1) - 1.0).abs() < 1e-12);
        assert_eq!(s.value(0.3), 0.0);
        let jumps = s.derivative_jumps();
        assert!((jumps[0].size - theta).abs() < 1e-12);
        assert!(
            (jumps[1].size - theta).abs() < 1e-12,
            "cos π = −1: velocity −Aθ jumps to 0"
        );
    }

    #[test]
    fn record_is_linear_between_samples() {
        let s = Signal::Record {
            dt: 0.01,
            samples: Arc::from(vec![0.0, 1.0, -1.0]),
            label: String::new(),
        };
        assert!((s.value(0.005) - 0.5).abs() < 1e-12);
        assert!((s.value(0.015) - 0.0).abs() < 1e-12);
        assert!((s.value(0.02) + 1.0).abs() < 1e-12);
        assert_eq!(s.value(0.03), 0.0);
        assert!((s.derivative(0.012) + 200.0).abs() < 1e-9);
    }
}

//! The acausal (zero-phase) Butterworth high-pass filter of an uncorrected record, as in
//! the strong-motion processing of Boore & Bommer (2005, "Processing of strong-motion
//! accelerograms: needs, options and consequences", Soil Dyn. Earthq. Eng. 25) and Boore
//! (2005, "On pads and filters", BSSA 95(2)): the acceleration padded with zeros at both
//! ends, filtered forward and then backward by a digital Butterworth high-pass of the
//! stated order and corner, and the pads removed.
//!
//! The digital filter is the analogue Butterworth high-pass of order n, |H(f)|² =
//! 1 / (1 + (f_c/f)²ⁿ), through the bilinear transform with the corner pre-warped
//! (K = tan(π·f_c·Δt)), as second-order sections (and one first-order section for an odd
//! order): one pass has the gain 1/√2 at f_c exactly, the forward-backward pair 1/2 and
//! no phase shift. Each pad is 1.5·n/f_c / 2 long (Boore's total pad 1.5·n/f_c split over
//! the two ends), so the filter's transients die out in the pads.

/// A Butterworth high-pass: corner frequency and order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HighPass {
    /// Corner frequency f_c, Hz (each pass's gain there is 1/√2).
    pub corner_hz: f64,
    /// Order n of each pass (1 to [`HighPass::MAX_ORDER`]).
    pub order: usize,
}

/// One section y = (b₀ + b₁z⁻¹ + b₂z⁻²) / (1 + a₁z⁻¹ + a₂z⁻²) x.
#[derive(Debug, Clone, Copy)]
struct Section {
    b: [f64; 3],
    a: [f64; 2],
}

impl Section {
    /// Run the section over `x` in place (transposed direct form II, from rest).
    fn run(&self, x: &mut [f64]) {
        let (mut s1, mut s2) = (0.0, 0.0);
        for v in x.iter_mut() {
            let input = *v;
            let y = self.b[0] * input + s1;
            s1 = self.b[1] * input - self.a[0] * y + s2;
            s2 = self.b[2] * input - self.a[1] * y;
            *v = y;
        }
    }
}

impl HighPass {
    /// Largest order accepted.
    pub const MAX_ORDER: usize = 8;

    /// The second-order sections (and a first-order one for an odd order) of one pass at
    /// sample interval `dt`.
    fn sections(&self, dt: f64) -> Vec<Section> {
        let k = (std::f64::consts::PI * self.corner_hz * dt).tan();
        let n = self.order;
        let mut out = Vec::with_capacity(n.div_ceil(2));
        for j in 1..=n / 2 {
            // The conjugate pole pair at θ = (2j − 1)π/(2n): s² + 2 sin θ·s + 1.
            let theta = (2 * j - 1) as f64 * std::f64::consts::PI / (2 * n) as f64;
            let damping = 2.0 * theta.sin();
            let a0 = 1.0 + damping * k + k * k;
            out.push(Section {
                b: [1.0 / a0, -2.0 / a0, 1.0 / a0],
                a: [(2.0 * k * k - 2.0) / a0, (1.0 - damping * k + k * k) / a0],
            });
        }
        if n % 2 == 1 {
            // The real pole s = −1: s/(s + 1).
            let a0 = 1.0 + k;
            out.push(Section {
                b: [1.0 / a0, -1.0 / a0, 0.0],
                a: [(k - 1.0) / a0, 0.0],
            });
        }
        out
    }

    /// Samples of the zero pad at each end: 1.5·n/f_c / 2 seconds.
    pub fn pad_samples(&self, dt: f64) -> usize {
        (0.75 * self.order as f64 / self.corner_hz / dt).ceil() as usize
    }

    /// One forward pass over `x` (from rest, no pads): causal, gain 1/√2 at f_c.
    pub fn causal(&self, dt: f64, x: &[f64]) -> Vec<f64> {
        let mut y = x.to_vec();
        for s in self.sections(dt) {
            s.run(&mut y);
        }
        y
    }

    /// The acausal filter: `x` padded with zeros at both ends, filtered forward then
    /// backward, the pads removed. Zero phase; gain 1/2 at f_c.
    pub fn acausal(&self, dt: f64, x: &[f64]) -> Vec<f64> {
        let pad = self.pad_samples(dt);
        let mut y = vec![0.0; x.len() + 2 * pad];
        y[pad..pad + x.len()].copy_from_slice(x);
        let sections = self.sections(dt);
        for s in &sections {
            s.run(&mut y);
        }
        y.reverse();
        for s in &sections {
            s.run(&mut y);
        }
        y.reverse();
        y[pad..pad + x.len()].to_vec()
    }

    /// "acausal Butterworth high-pass, order 4, corner 0.1 Hz".
    pub fn describe(&self) -> String {
        format!(
            "the acausal Butterworth high-pass (order {} forward and backward, corner {} Hz, zero pads of {:.1} s at each end; Boore & Bommer 2005)",
            self.order,
            self.corner_hz,
            0.75 * self.order as f64 / self.corner_hz
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Amplitude of a unit sine at `f` after `filter`, over the middle half of 200 cycles.
    fn gain(f: f64, dt: f64, filter: impl Fn(&[f64]) -> Vec<f64>) -> f64 {
        let n = (200.0 / f / dt) as usize;
        let x: Vec<f64> = (0..n)
            .map(|i| (2.0 * std::f64::consts::PI * f * i as f64 * dt).sin())
            .collect();
        let y = filter(&x);
        let mid = &y[n / 4..3 * n / 4];
        (2.0 * mid.iter().map(|v| v * v).sum::<f64>() / mid.len() as f64).sqrt()
    }

    #[test]
    fn gain_at_the_corner_is_one_over_root_two_a_pass() {
        for order in [1, 2, 4, 5] {
            let hp = HighPass {
                corner_hz: 0.5,
                order,
            };
            let dt = 0.01;
            let one = gain(0.5, dt, |x| hp.causal(dt, x));
            assert!((one - 0.5_f64.sqrt()).abs() < 2e-3, "order {order}: {one}");
            let two = gain(0.5, dt, |x| hp.acausal(dt, x));
            assert!((two - 0.5).abs() < 2e-3, "order {order}: {two}");
            // Elsewhere the closed form of the bilinear Butterworth: |H|² = 1/(1 + Ω^−2n) a
            // pass, Ω = tan(π·f·Δt)/tan(π·f_c·Δt); forward and backward: |H|².
            for f in [0.25, 1.0, 5.0] {
                let omega = (PI * f * dt).tan() / (PI * 0.5 * dt).tan();
                let expected = 1.0 / (1.0 + omega.powi(-2 * order as i32));
                let both = gain(f, dt, |x| hp.acausal(dt, x));
                assert!(
                    (both - expected).abs() < 2e-3,
                    "order {order}, {f} Hz: {both}"
                );
            }
        }
    }

    #[test]
    fn a_pure_drift_is_removed() {
        // An offset and a linear drift of the acceleration (a quadratic and cubic drift of
        // the displacement): a high-pass of order n ≥ 2 has n zeros at f = 0, so once its
        // transient has decayed the output is zero.
        let dt = 0.01;
        let x: Vec<f64> = (0..6000).map(|i| 0.02 + 0.003 * i as f64 * dt).collect();
        for order in [2, 4] {
            let hp = HighPass {
                corner_hz: 0.5,
                order,
            };
            let y = hp.causal(dt, &x);
            let tail = y[5000..].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            assert!(tail < 1e-12, "order {order}: {tail}");
        }
    }
}

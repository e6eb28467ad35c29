//! Bidirectional (3D) scenes: the excitation's azimuth in the horizontal plane, a second
//! horizontal component, and the bodies' depth along y. A scene without any of these keys
//! is today's planar scene (`Scene::spatial` is `None`) and every 2D engine runs it as
//! before; a spatial scene is run only by an engine that models plan motion
//! (`Engine::models_plan_motion`), the others report it not applicable.
//!
//! Axes: x and y horizontal, z up. The `[excitation]` signal acts along the unit vector
//! e₁ = (cos θ, sin θ) at the azimuth θ (`azimuth_deg`, from +x toward +y), the optional
//! `[excitation.y]` signal along e₂ = (−sin θ, cos θ) — along +y when θ = 0 — so one key
//! rotates the whole excitation pair. The oscillator's contact is isotropic (the same Kx
//! in every horizontal direction) with a circular friction cone |T| ≤ μ·N.

use super::signal::Signal;

/// The plan-motion part of a scene (`Scene::spatial`).
#[derive(Debug, Clone, PartialEq)]
pub struct Spatial {
    /// Azimuth θ of the `[excitation]` signal in the horizontal plane, degrees, from +x
    /// toward +y (0: along +x, as a planar scene).
    pub azimuth_deg: f64,
    /// The second horizontal component `[excitation.y]`, of the same kind as the first
    /// (m/s² or m), acting along e₂ = (−sin θ, cos θ).
    pub second: Option<Signal>,
    /// The depth of a rocking body or rigid block along y (`None` for the oscillator).
    pub depth: Option<Depth>,
    /// Rotational inertias about axes x, y, z through the centre of mass, kg·m², when
    /// given (`rotational_inertia_x`, `_y`, `_z`).
    pub inertia: Option<[f64; 3]>,
}

/// A body's extent along y and, for a rocking body, its rows of supports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Depth {
    /// Half-depth d of the base along y, m.
    pub half_depth: f64,
    /// Rows of supports along y, equally spaced from −d to +d (1: one row at y = 0); a
    /// rocking body has `supports` × `support_rows` supports. 1 for a rigid block.
    pub support_rows: usize,
}

impl Spatial {
    /// The azimuth θ in radians.
    pub fn azimuth(&self) -> f64 {
        self.azimuth_deg.to_radians()
    }

    /// Unit vector e₁ = (cos θ, sin θ) of the `[excitation]` signal.
    pub fn first_direction(&self) -> [f64; 2] {
        let (s, c) = self.azimuth().sin_cos();
        [c, s]
    }

    /// Unit vector e₂ = (−sin θ, cos θ) of the `[excitation.y]` signal.
    pub fn second_direction(&self) -> [f64; 2] {
        let (s, c) = self.azimuth().sin_cos();
        [-s, c]
    }

    /// The horizontal excitation vector at `t` in (x, y), given the `[excitation]` signal:
    /// first(t)·e₁ + second(t)·e₂.
    pub fn horizontal(&self, first: Option<&Signal>, t: f64) -> [f64; 2] {
        let a = first.map_or(0.0, |s| s.value(t));
        let b = self.second.as_ref().map_or(0.0, |s| s.value(t));
        let [c1, s1] = self.first_direction();
        let [c2, s2] = self.second_direction();
        [a * c1 + b * c2, a * s1 + b * s2]
    }

    /// End of the later of the two horizontal signals, s.
    pub fn end(&self, first: Option<&Signal>) -> f64 {
        let a = first.map_or(0.0, Signal::end);
        let b = self.second.as_ref().map_or(0.0, Signal::end);
        a.max(b)
    }
}

impl Depth {
    /// Support ordinates along y, equally spaced from −d to +d (one row: y = 0), m.
    pub fn row_positions(&self) -> Vec<f64> {
        let n = self.support_rows;
        if n <= 1 {
            return vec![0.0];
        }
        (0..n)
            .map(|j| -self.half_depth + 2.0 * self.half_depth * j as f64 / (n - 1) as f64)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_azimuth_rotates_both_components() {
        let s = Spatial {
            azimuth_deg: 30.0,
            second: Some(Signal::SinePulse {
                amplitude: 2.0,
                omega: 1.0,
                cycles: 10.0,
            }),
            depth: None,
            inertia: None,
        };
        let first = Signal::SinePulse {
            amplitude: 1.0,
            omega: 1.0,
            cycles: 10.0,
        };
        let t = 1.0;
        let [x, y] = s.horizontal(Some(&first), t);
        let (a, b) = (t.sin(), 2.0 * t.sin());
        let th = 30f64.to_radians();
        assert!((x - (a * th.cos() - b * th.sin())).abs() < 1e-15);
        assert!((y - (a * th.sin() + b * th.cos())).abs() < 1e-15);
        assert!(((x * x + y * y).sqrt() - (a * a + b * b).sqrt()).abs() < 1e-15);
    }

    #[test]
    fn rows_span_the_depth() {
        let d = Depth {
            half_depth: 0.5,
            support_rows: 3,
        };
        assert_eq!(d.row_positions(), vec![-0.5, 0.0, 0.5]);
        let one = Depth {
            half_depth: 0.5,
            support_rows: 1,
        };
        assert_eq!(one.row_positions(), vec![0.0]);
    }
}

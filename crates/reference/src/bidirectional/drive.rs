//! The horizontal drive of a 3D scene as a 2-vector function of time, with its kinks.

use std::cell::Cell;

use rockslide_core::case::{Excitation, NormalForce, Scene, Signal};

/// The force per unit mass d(t) on the body (relative coordinates), in (x, y), and the
/// vertical ground acceleration a_v(t) when the scene has one, with how the normal force
/// follows it.
#[derive(Debug, Clone)]
pub struct PlanDrive {
    first: Option<Signal>,
    second: Option<Signal>,
    /// e₁ and e₂ times the sign (+1 mass acceleration, −1 ground acceleration).
    e1: [f64; 2],
    e2: [f64; 2],
    vertical: Option<Signal>,
    normal_force: NormalForce,
}

impl PlanDrive {
    /// The drive of `first` along unit vector `e1` and `second` along `e2`, times `sign`.
    pub fn new(
        first: Option<Signal>,
        e1: [f64; 2],
        second: Option<Signal>,
        e2: [f64; 2],
        sign: f64,
    ) -> Self {
        PlanDrive {
            first,
            second,
            e1: [sign * e1[0], sign * e1[1]],
            e2: [sign * e2[0], sign * e2[1]],
            vertical: None,
            normal_force: NormalForce::QuasiStatic,
        }
    }

    /// With a vertical ground acceleration a_v(t) (positive upward), the normal force
    /// rigid (N = M·(g + a_v)) unless [`PlanDrive::with_normal_force`] says otherwise.
    pub fn with_vertical(mut self, vertical: Signal) -> Self {
        self.vertical = Some(vertical);
        self
    }

    /// How the normal force follows a_v (the oscillator's reference reads it; the block
    /// is rigid-plastic, N = M·(g + a_v) whatever it says).
    pub fn with_normal_force(mut self, normal_force: NormalForce) -> Self {
        self.normal_force = normal_force;
        self
    }

    /// How the normal force follows a_v.
    pub fn normal_force(&self) -> NormalForce {
        self.normal_force
    }

    /// Whether the drive has a vertical component.
    pub fn has_vertical(&self) -> bool {
        self.vertical.is_some()
    }

    /// The drive of a scene: its `[excitation]` along e₁, `[excitation.y]` along e₂ (a
    /// planar scene: along +x), a mass or ground acceleration.
    pub fn of_scene(scene: &Scene) -> Result<Self, String> {
        let (sign, first) = match &scene.excitation {
            Excitation::None => (1.0, None),
            Excitation::MassAcceleration(s) => (1.0, Some(s.clone())),
            Excitation::GroundAcceleration(s) => (-1.0, Some(s.clone())),
            Excitation::GroundDisplacement(_) => {
                return Err("the plan-motion references take a mass or ground acceleration, not a ground displacement".into());
            }
        };
        let (e1, e2, second) = match scene.spatial() {
            Some(s) => (s.first_direction(), s.second_direction(), s.second.clone()),
            None => ([1.0, 0.0], [0.0, 1.0], None),
        };
        let drive = PlanDrive::new(first, e1, second, e2, sign);
        Ok(match scene.vertical() {
            Some(v) => drive
                .with_vertical(v.signal.clone())
                .with_normal_force(v.normal_force),
            None => drive,
        })
    }

    /// d(t), m/s².
    pub fn at(&self, t: f64) -> [f64; 2] {
        let a = self.first.as_ref().map_or(0.0, |s| s.value(t));
        let b = self.second.as_ref().map_or(0.0, |s| s.value(t));
        [
            a * self.e1[0] + b * self.e2[0],
            a * self.e1[1] + b * self.e2[1],
        ]
    }

    /// d(t) remembered at two times ([`DriveAt`]), for one integration step's stages.
    pub(crate) fn remembered(&self) -> DriveAt<'_> {
        DriveAt {
            drive: self,
            first: Cell::new(None),
            last: Cell::new(None),
        }
    }

    /// The vertical ground acceleration a_v(t), m/s² (0 without one).
    pub fn vertical(&self, t: f64) -> f64 {
        self.vertical.as_ref().map_or(0.0, |s| s.value(t))
    }

    /// da_v/dt at `t` on the smooth piece of a_v that holds `inside` (a time strictly
    /// inside the integration step, whose ends are at kinks or inside one piece): the
    /// one-sided rate at a kink, as the step's stages need it, m/s³.
    pub fn vertical_rate(&self, t: f64, inside: f64) -> f64 {
        match &self.vertical {
            None => 0.0,
            Some(s @ Signal::Record { .. }) => s.derivative(inside),
            Some(
                s @ Signal::SinePulse {
                    amplitude, omega, ..
                },
            ) if inside > 0.0 && inside < s.end() => amplitude * omega * (omega * t).cos(),
            Some(Signal::SinePulse { .. }) => 0.0,
        }
    }

    /// The times in (0, end) where the drive is not smooth: record samples, pulse ends.
    pub fn kinks(&self, end: f64) -> Vec<f64> {
        let mut k = Vec::new();
        for s in [&self.first, &self.second, &self.vertical]
            .into_iter()
            .flatten()
        {
            match s {
                Signal::SinePulse { .. } => k.push(s.end()),
                Signal::Record { dt, samples, .. } => {
                    k.extend((1..samples.len()).map(|i| i as f64 * dt));
                }
            }
        }
        k.retain(|&t| t > 0.0 && t < end);
        k.sort_by(f64::total_cmp);
        k.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * end);
        k
    }
}

/// [`PlanDrive::at`] remembered at the first time asked and at the last one: a
/// Runge–Kutta step asks twice at its midpoint, and the bisection of an event asks at the
/// step's start once per trial length. The values are those of [`PlanDrive::at`] (a
/// function of the time's bits alone), only not evaluated again.
pub(crate) struct DriveAt<'a> {
    drive: &'a PlanDrive,
    /// (time's bits, d) of the first time asked.
    first: Cell<Option<(u64, [f64; 2])>>,
    /// (time's bits, d) of the last time asked that was not the first.
    last: Cell<Option<(u64, [f64; 2])>>,
}

impl DriveAt<'_> {
    /// d(t), m/s².
    pub(crate) fn at(&self, t: f64) -> [f64; 2] {
        let bits = t.to_bits();
        for kept in [&self.first, &self.last] {
            if let Some((b, d)) = kept.get()
                && b == bits
            {
                return d;
            }
        }
        let d = self.drive.at(t);
        let slot = if self.first.get().is_none() {
            &self.first
        } else {
            &self.last
        };
        slot.set(Some((bits, d)));
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_remembered_drive_is_the_drive_bit_for_bit() {
        let record = |samples: Vec<f64>| Signal::Record {
            dt: 0.01,
            samples: samples.into(),
            label: String::new(),
        };
        let drive = PlanDrive::new(
            Some(record(vec![0.0, 1.0, -2.0, 0.5, 3.0])),
            [0.6, 0.8],
            Some(record(vec![0.3, -0.1, 0.7, 0.0, -1.0])),
            [-0.8, 0.6],
            -1.0,
        );
        let memo = drive.remembered();
        // a step's stages, a bisection's repeated start, -0.0 beside 0.0, past the end
        for t in [
            0.0, 0.005, 0.005, 0.01, 0.0, 0.0025, 0.0, -0.0, 0.013, 0.0, 0.07, 0.013,
        ] {
            let (a, b) = (memo.at(t), drive.at(t));
            assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "t = {t}");
        }
    }
}

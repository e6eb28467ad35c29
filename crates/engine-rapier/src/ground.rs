//! Ground motion as the rigid-body engine feeds it to rapier: the ground's displacement
//! and velocity at every step time, evaluated when the time loop asks for it (the same
//! function of the step time, so the same bits, as the tables of one entry per step it
//! replaces), so that a run holds no memory in proportion to its length and its loop does
//! not allocate. The two routes read the same ground:
//!
//! - *kinematic ground*: the ground body is moved to xg(t_{n+1}) each step, so the
//!   velocity the contact sees over the step is (xg(n+1) − xg(n))/Δt;
//! - *inertial force*: the ground stays fixed and every dynamic body of mass m gets the
//!   force −m·(vg(n+1) − vg(n))/Δt over the step — the exact change of the ground
//!   velocity, jumps included — and at t = 0 the relative velocity −vg(0⁺).
//!
//! A recorded ground *acceleration* is integrated once, at the record's own samples, by
//! `case::record::integrate` as given, without baseline correction ([`RECORD_BASELINE`]:
//! the exact references integrate the same record), and the tables are evaluated exactly
//! between samples (the acceleration is piecewise linear). Both routes read that one
//! ground, so they can be compared with each other; the run's settings name it.

use std::cell::Cell;

use rockslide_core::case::record::{Baseline, GroundMotion, integrate};
use rockslide_core::case::{Excitation, Signal, Vertical};

/// Baseline correction of a recorded ground acceleration before it moves the ground:
/// none, the record as given (its displacement may drift; the exact references and the
/// other engines see the same acceleration), docs/records-and-studies.md.
pub const RECORD_BASELINE: Baseline = Baseline::None;

/// One horizontal (or vertical) ground motion at the step times `t_k = k·dt`:
/// displacement and right-continuous velocity computed at each step time asked for. A
/// recorded acceleration is integrated once, at its own samples (memory in proportion to
/// the record, not to the run). The loop asks for each step time a few times (a step
/// drives with k and k + 1, the recorder reads k): the last two are kept.
#[derive(Debug, Clone)]
pub struct GroundAt {
    /// The excitation the ground follows.
    excitation: Excitation,
    /// A recorded acceleration integrated at its samples: (sample step, motion).
    record: Option<(f64, GroundMotion)>,
    /// Step, s.
    dt: f64,
    /// The last step times evaluated: (k, xg, vg), the older first (`usize::MAX`: none).
    recent: Cell<[(usize, f64, f64); 2]>,
}

impl GroundAt {
    /// The motion of `excitation` at step times `k·dt`.
    pub fn new(excitation: &Excitation, dt: f64) -> Self {
        // A record is integrated once, at its samples (O(samples), not per step time).
        let record = match excitation {
            Excitation::GroundAcceleration(Signal::Record {
                dt: rdt, samples, ..
            }) => Some((*rdt, integrate(*rdt, samples, RECORD_BASELINE))),
            _ => None,
        };
        Self {
            excitation: excitation.clone(),
            record,
            dt,
            recent: Cell::new([(usize::MAX, 0.0, 0.0); 2]),
        }
    }

    /// (xg(t_k), vg(t_k⁺)).
    #[inline]
    pub fn at(&self, k: usize) -> (f64, f64) {
        let recent = self.recent.get();
        for &(j, x, v) in recent.iter().rev() {
            if j == k {
                return (x, v);
            }
        }
        let (x, v) = self.evaluate(k);
        self.recent.set([recent[1], (k, x, v)]);
        (x, v)
    }

    /// xg(t_k), m.
    #[inline]
    pub fn disp(&self, k: usize) -> f64 {
        self.at(k).0
    }

    /// vg(t_k⁺), m/s.
    #[inline]
    pub fn vel(&self, k: usize) -> f64 {
        self.at(k).1
    }

    /// The motion at step time `k·dt`, computed.
    fn evaluate(&self, k: usize) -> (f64, f64) {
        let t = k as f64 * self.dt;
        match (&self.excitation, &self.record) {
            (_, Some((rdt, m))) => record_at(m, *rdt, t),
            (Excitation::GroundDisplacement(s), _) => (s.value(t), s.derivative(t)),
            (Excitation::GroundAcceleration(s), _) => integrated(s, t),
            (Excitation::None | Excitation::MassAcceleration(_), _) => (0.0, 0.0),
        }
    }
}

/// Ground displacement and (right-continuous) ground velocity at the step times, and the
/// vertical ground motion at the same times if the scene has one.
#[derive(Debug, Clone)]
pub struct GroundTable {
    /// The horizontal motion.
    horizontal: GroundAt,
    /// The vertical ground motion at the same times, if the scene has one (`vertical`).
    pub vertical: Option<VerticalTable>,
}

impl GroundTable {
    /// The ground at step times `t_k = k·dt`.
    pub fn new(excitation: &Excitation, dt: f64) -> Self {
        Self {
            horizontal: GroundAt::new(excitation, dt),
            vertical: None,
        }
    }

    /// The same ground with the scene's vertical ground motion (if any) at the same times.
    pub fn with_vertical(self, vertical: Option<&Vertical>, dt: f64) -> Self {
        Self {
            vertical: vertical.map(|v| VerticalTable::new(v, dt)),
            ..self
        }
    }

    /// xg(t_k), m.
    #[inline]
    pub fn disp(&self, k: usize) -> f64 {
        self.horizontal.disp(k)
    }

    /// vg(t_k⁺), m/s.
    #[inline]
    pub fn vel(&self, k: usize) -> f64 {
        self.horizontal.vel(k)
    }

    /// Mean ground acceleration over step `k → k+1`, m/s² (velocity jumps included).
    pub fn mean_acceleration(&self, k: usize, dt: f64) -> f64 {
        (self.vel(k + 1) - self.vel(k)) / dt
    }
}

/// The vertical ground motion at the step times: yg(t_n) and vg_y(t_n⁺), from rest,
/// evaluated when asked for (the horizontal ground's integration, [`GroundAt`]).
#[derive(Debug, Clone)]
pub struct VerticalTable(GroundAt);

impl VerticalTable {
    /// The motion at step times `t_k = k·dt`.
    pub fn new(vertical: &Vertical, dt: f64) -> Self {
        Self(GroundAt::new(
            &Excitation::GroundAcceleration(vertical.signal.clone()),
            dt,
        ))
    }

    /// yg(t_k), m (positive upward).
    #[inline]
    pub fn disp(&self, k: usize) -> f64 {
        self.0.disp(k)
    }

    /// vg_y(t_k⁺), m/s.
    #[inline]
    pub fn vel(&self, k: usize) -> f64 {
        self.0.vel(k)
    }
}

/// (xg, vg) at `t` for a ground *acceleration* signal starting from rest at the origin.
fn integrated(s: &Signal, t: f64) -> (f64, f64) {
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
        // (`GroundAt::new` integrates a record once; this per-time path is not used.)
        Signal::Record { dt, samples, .. } => {
            record_at(&integrate(*dt, samples, RECORD_BASELINE), *dt, t)
        }
    }
}

/// (xg, vg) at `t` of an integrated record sampled every `rdt`: exact for its piecewise-
/// linear acceleration; after the last sample the acceleration is zero and the ground
/// coasts at its final velocity.
fn record_at(m: &GroundMotion, rdt: f64, t: f64) -> (f64, f64) {
    let last = m.acc.len().saturating_sub(1);
    if m.acc.is_empty() || t <= 0.0 {
        return (0.0, 0.0);
    }
    let i = ((t / rdt).floor() as usize).min(last);
    let tau = t - i as f64 * rdt;
    if i == last {
        return (m.disp[i] + m.vel[i] * tau, m.vel[i]);
    }
    let (a0, slope) = (m.acc[i], (m.acc[i + 1] - m.acc[i]) / rdt);
    let v = m.vel[i] + a0 * tau + slope * tau * tau / 2.0;
    let x = m.disp[i] + m.vel[i] * tau + a0 * tau * tau / 2.0 + slope * tau * tau * tau / 6.0;
    (x, v)
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
        let g = GroundTable::new(&Excitation::GroundAcceleration(s), 0.5);
        let v_end = 4.0 / std::f64::consts::PI;
        assert!((g.vel(2) - v_end).abs() < 1e-12);
        assert!((g.vel(4) - v_end).abs() < 1e-12);
        assert!((g.disp(4) - g.disp(2) - v_end).abs() < 1e-12);
    }

    #[test]
    fn displacement_pulse_velocity_is_right_continuous() {
        let s = Signal::SinePulse {
            amplitude: 1.0,
            omega: std::f64::consts::PI,
            cycles: 0.5,
        };
        let g = GroundTable::new(&Excitation::GroundDisplacement(s), 0.5);
        assert!(
            (g.vel(0) - std::f64::consts::PI).abs() < 1e-12,
            "vg(0+) = Aθ"
        );
        assert_eq!(g.vel(2), 0.0, "vg(td+) = 0");
    }

    #[test]
    fn record_tables_are_exact_between_samples() {
        // A ramp a = 3t, 11 samples × 0.1 s, stepped at 0.025 s: the tables must equal
        // `integrate`'s corrected motion at the samples and its exact quadratic between.
        let acc: Vec<f64> = (0..11).map(|i| 0.3 * i as f64).collect(); // a = 3t
        let s = Signal::Record {
            dt: 0.1,
            samples: std::sync::Arc::from(acc.clone()),
            label: String::new(),
        };
        let m = integrate(0.1, &acc, RECORD_BASELINE);
        // Step 0.025 s: 4 step times per sample; at samples the table equals `integrate`.
        let g = GroundTable::new(&Excitation::GroundAcceleration(s), 0.025);
        for i in 0..11 {
            assert!(
                (g.disp(4 * i) - m.disp[i]).abs() < 1e-14,
                "disp at sample {i}"
            );
            assert!((g.vel(4 * i) - m.vel[i]).abs() < 1e-14, "vel at sample {i}");
        }
        // Between samples: the corrected acceleration is linear, so v is the exact
        // quadratic; check the midpoint against Simpson on the corrected a (exact here).
        let (a0, a1) = (m.acc[3], m.acc[4]);
        let v_mid = m.vel[3] + 0.05 * (a0 + (a0 + a1) / 2.0) / 2.0;
        assert!((g.vel(14) - v_mid).abs() < 1e-14);
        // After the record the ground coasts at its last velocity.
        assert!((g.vel(48) - m.vel[10]).abs() < 1e-14);
        assert!((g.disp(48) - m.disp[10] - 0.2 * m.vel[10]).abs() < 1e-14);
    }
}

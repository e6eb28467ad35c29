//! The energy audit of a run: input work = kinetic + strain + friction + damping energy,
//! computed from a trace and the scene alone, so that every engine (and the exact
//! reference) is audited by the same independent arithmetic. It owns the bookkeeping
//! the stability classification uses to detect energy growth.
//!
//! For a sliding oscillator in relative coordinates (paper Eq 2: M·ẍ + C·ẋ + R = F):
//!
//! - input work      W(t) = ∫ F dx, plus the work ½M(v⁺² − v⁻²) of each impulse a
//!   ground-velocity jump gives the mass (support-displacement pulses);
//! - kinetic energy  K = ½·M·v²;
//! - strain energy   U = ½·R²/K_s (the elastic part e = x − xp = R/K_s; for the
//!   double-element arrangement K_s is the series stiffness, both elements carry R);
//! - friction work   D_f = ∫ R dxp (≥ 0 for a dissipative slip);
//! - damping work    D_c = ∫ C·v dx.
//!
//! Integrals use the trapezoidal rule on the trace rows, ½(f₀ + f₁)·Δx. Because
//! e = R/K_s, ∫ R de = ΔU holds exactly row by row, so an audit of a correct trace
//! closes to the accuracy of ∫F dx and ∫C v dx alone. The balance error is
//! E0 + W − (K + U + D_f + D_c), E0 the energy at the first row (it contains any
//! velocity jump at t = 0).
//!
//! A rigid block (Newmark, Housner) is audited in the ground's frame with its rotation,
//! gravity potential, friction work and impact losses (see `audit_block`). A rocking body
//! on elastic supports (RPEPO) cannot be audited from sums over its supports, which is
//! all its kinematic channels give: its strain energy needs each element's forces. It is
//! audited from the energy channels its engine records per step from its own element
//! states ([`ROCKING_CHANNELS`]; the fe engine writes them), and skipped with
//! [`ROCKING_MISSING`] otherwise. Traces lacking a channel are skipped with a reason
//! rather than guessed at.

use rockslide_core::case::{Excitation, Model, Scene};
use rockslide_core::trace::{Trace, q};
use rockslide_engine_api::Arrangement;

/// Energy histories of one run, one value per trace row, J.
#[derive(Debug, Clone, PartialEq)]
pub struct EnergyHistory {
    /// Row times, s.
    pub time: Vec<f64>,
    /// E0 + input work (energy supplied so far).
    pub supplied: Vec<f64>,
    /// Kinetic energy ½Mv².
    pub kinetic: Vec<f64>,
    /// Strain energy ½R²/K_s.
    pub strain: Vec<f64>,
    /// Friction work ∫R dxp.
    pub friction: Vec<f64>,
    /// Damping work ∫C v dx.
    pub damping: Vec<f64>,
    /// Gravity potential M·g·z_cm above the static position (rigid blocks; 0 for
    /// oscillators, whose normal motion is not part of the balance).
    pub potential: Vec<f64>,
    /// Energy lost in impacts (rigid blocks: the balance residual booked in a window
    /// around each pivot change; 0 for oscillators).
    pub impact: Vec<f64>,
    /// The stiffness used for the strain energy, N/m, and why (for reports).
    pub stiffness: (f64, &'static str),
}

/// The audit of one run in a few numbers.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EnergySummary {
    /// Energy supplied over the run (E0 + W at the end), J.
    #[serde(with = "crate::json::real")]
    pub supplied: f64,
    /// Kinetic energy at the end, J.
    #[serde(with = "crate::json::real")]
    pub kinetic: f64,
    /// Strain energy at the end, J.
    #[serde(with = "crate::json::real")]
    pub strain: f64,
    /// Friction work at the end, J.
    #[serde(with = "crate::json::real")]
    pub friction: f64,
    /// Damping work at the end, J.
    #[serde(with = "crate::json::real")]
    pub damping: f64,
    /// Gravity potential at the end, J.
    #[serde(with = "crate::json::real")]
    pub potential: f64,
    /// Impact losses at the end, J.
    #[serde(with = "crate::json::real")]
    pub impact: f64,
    /// Largest |balance error| over the run, J.
    #[serde(with = "crate::json::real")]
    pub max_error: f64,
    /// Balance error at the end (supplied − accounted), J: positive means energy lost
    /// (numerical dissipation), negative energy created.
    #[serde(with = "crate::json::real")]
    pub end_error: f64,
    /// Normalising energy: the largest of supplied and accounted energy over the run, J.
    #[serde(with = "crate::json::real")]
    pub scale: f64,
    /// `max_error / scale`: the audit's relative error.
    #[serde(with = "crate::json::real")]
    pub relative_error: f64,
}

impl EnergyHistory {
    /// Balance error at row `i`: supplied − (K + U + D_f + D_c), J.
    pub fn error(&self, i: usize) -> f64 {
        self.supplied[i] - self.accounted(i)
    }

    /// K + U + V + D_f + D_c + D_i at row `i`, J.
    pub fn accounted(&self, i: usize) -> f64 {
        self.kinetic[i]
            + self.strain[i]
            + self.potential[i]
            + self.friction[i]
            + self.damping[i]
            + self.impact[i]
    }

    /// The run in a few numbers.
    pub fn summary(&self) -> EnergySummary {
        let n = self.time.len();
        let mut max_error = 0.0_f64;
        let mut scale = 0.0_f64;
        for i in 0..n {
            max_error = max_error.max(self.error(i).abs());
            scale = scale
                .max(self.supplied[i].abs())
                .max(self.accounted(i).abs());
        }
        let last = n.saturating_sub(1);
        EnergySummary {
            supplied: self.supplied[last],
            kinetic: self.kinetic[last],
            strain: self.strain[last],
            friction: self.friction[last],
            damping: self.damping[last],
            potential: self.potential[last],
            impact: self.impact[last],
            max_error,
            end_error: self.error(last),
            scale,
            relative_error: if scale > 0.0 { max_error / scale } else { 0.0 },
        }
    }

    /// First time at which the energy the run accounts for (kinetic + strain + friction +
    /// damping: stored plus dissipated) exceeds `1 + factor` times the most energy ever
    /// supplied to it up to then: energy created by the method, the signature of a
    /// numerical instability. (Comparing with the *largest* supplied energy keeps negative
    /// input work — a force pushing against the motion — from counting as growth.)
    /// Returns the time and the ratio.
    pub fn growth_time(&self, factor: f64) -> Option<(f64, f64)> {
        self.growth_time_above(factor, 0.0)
    }

    /// As [`Self::growth_time`], and also the first time the accounted energy exceeds
    /// `ceiling`, J (when positive): an absolute limit — the `stability` command uses
    /// 100 times the most energy the exact solution was ever given — that catches a
    /// run whose trace shows no input at all (rapier at Δt = T samples the half-sine
    /// force at its zeros while applying its step mean) and still blows up.
    pub fn growth_time_above(&self, factor: f64, ceiling: f64) -> Option<(f64, f64)> {
        // Rows where less than 1 % of the run's largest supplied energy has come in are
        // not judged: there the trapezoidal input work of the first steps of a steep
        // pulse (10 g in one step) is too coarse for a ratio to mean anything.
        let total = self.supplied.iter().fold(0.0_f64, |a, &b| a.max(b));
        let mut supplied_max = 0.0_f64;
        for i in 0..self.time.len() {
            supplied_max = supplied_max.max(self.supplied[i]);
            let accounted = self.accounted(i);
            if supplied_max > 0.01 * total && accounted > (1.0 + factor) * supplied_max {
                return Some((self.time[i], accounted / supplied_max));
            }
            if ceiling > 0.0 && accounted > ceiling {
                return Some((self.time[i], accounted / supplied_max.max(ceiling / 100.0)));
            }
        }
        None
    }
}

/// Audit a run on `scene` from its trace, its supports arranged as `arrangement` (the
/// run's, [`Run::arrangement`](rockslide_engine_api::Run); an exact reference's is
/// single); `Err` says why it cannot be done.
pub fn audit(
    trace: &Trace,
    scene: &Scene,
    arrangement: Arrangement,
) -> Result<EnergyHistory, String> {
    let osc = match &scene.model {
        Model::Oscillator(o) => o,
        Model::RigidBlock(b) => return audit_block(trace, scene, b),
        Model::RockingBody(r) => return audit_rocking(trace, r),
    };
    let keys = [
        q::FORCE.key,
        q::RESISTANCE.key,
        q::REL_DISP.key,
        q::SLIDE.key,
        q::VEL.key,
    ];
    let missing: Vec<&str> = keys.iter().copied().filter(|k| !trace.has(k)).collect();
    if !missing.is_empty() {
        return Err(format!(
            "energy audit skipped: the trace lacks channel(s) {}",
            missing.join(", ")
        ));
    }
    if trace.len() < 2 {
        return Err("energy audit skipped: the trace has fewer than two rows".into());
    }
    let col = |k: &str| trace.column(k).expect("checked above");
    let (f, r, x, xp, v) = (
        col(q::FORCE.key),
        col(q::RESISTANCE.key),
        col(q::REL_DISP.key),
        col(q::SLIDE.key),
        col(q::VEL.key),
    );
    let m = osc.mass;
    let c = osc.damping();
    // Double-element variants carry R through both elements in series.
    let stiffness = match (&osc.double, arrangement) {
        (Some(d), Arrangement::Double) => (d.series().0, "series stiffness of the double element"),
        _ => (osc.contact.kx, "single-element stiffness Kx"),
    };
    let k = stiffness.0;
    // Relative-velocity jumps of a support-displacement pulse (the jump at t = 0 is
    // already in the first row's state, E0).
    let jumps: Vec<(usize, f64)> = match &scene.excitation {
        Excitation::GroundDisplacement(s) => s
            .derivative_jumps()
            .iter()
            .filter(|j| j.time > trace.time[0])
            .filter_map(|j| nearest_row(&trace.time, j.time).map(|i| (i, -j.size)))
            .collect(),
        _ => Vec::new(),
    };

    let n = trace.len();
    let mut h = EnergyHistory {
        time: trace.time.clone(),
        supplied: vec![0.0; n],
        kinetic: vec![0.0; n],
        strain: vec![0.0; n],
        friction: vec![0.0; n],
        damping: vec![0.0; n],
        potential: vec![0.0; n],
        impact: vec![0.0; n],
        stiffness,
    };
    let strain = |r: f64| if k.is_finite() { 0.5 * r * r / k } else { 0.0 };
    h.kinetic[0] = 0.5 * m * v[0] * v[0];
    h.strain[0] = strain(r[0]);
    h.supplied[0] = h.kinetic[0] + h.strain[0];
    for i in 1..n {
        let dx = x[i] - x[i - 1];
        let mut w = 0.5 * (f[i - 1] + f[i]) * dx; // ∫F dx
        for &(row, dv) in &jumps {
            if row == i {
                let before = v[i] - dv;
                w += 0.5 * m * (v[i] * v[i] - before * before); // impulse work
            }
        }
        h.supplied[i] = h.supplied[i - 1] + w;
        h.kinetic[i] = 0.5 * m * v[i] * v[i];
        h.strain[i] = strain(r[i]);
        h.friction[i] = h.friction[i - 1] + 0.5 * (r[i - 1] + r[i]) * (xp[i] - xp[i - 1]);
        h.damping[i] = h.damping[i - 1] + c * 0.5 * (v[i - 1] + v[i]) * dx;
    }
    Ok(h)
}

/// Why a rocking body on elastic supports (RPEPO) is not audited when its trace lacks the
/// engine-recorded energy channels ([`ROCKING_CHANNELS`]).
pub const ROCKING_MISSING: &str = "energy audit not available for a rocking body from this trace: its strain energy Σ½T_i²/Kx + Σ½N_i²/Kz and friction work Σ∫T_i ds_i need each support's tangential force T_i (or slip s_i) and normal force N_i, which the trace carries only as sums (base_shear, normal) and the slip's mean and spread (slide, slide_spread); the engine that wrote it records no energy channels from its own states (energy_input, energy_kinetic, energy_strain, energy_friction, energy_potential, energy_error: the fe engine does, rapier does not)";

/// The channels an engine records for a rocking body's audit, in the order
/// (input work, kinetic, strain, friction, potential).
pub const ROCKING_CHANNELS: [&str; 5] = [
    q::ENERGY_INPUT.key,
    q::ENERGY_KINETIC.key,
    q::ENERGY_STRAIN.key,
    q::ENERGY_FRICTION.key,
    q::ENERGY_POTENTIAL.key,
];

/// The audit of a rocking body on elastic supports from the energy terms its engine
/// recorded per step from its own element states (the trace's sums over supports cannot
/// give them): supplied = E0 + W (`energy_input`, E0 = K + U + V at the first row),
/// kinetic, strain (Σ over every contact element), friction, gravity potential. No
/// viscous damping (the RPEPO has none) and no impact term: an engine's losses at contact
/// opening and closing, and HHT-α's numerical dissipation, stay in the balance error.
fn audit_rocking(
    trace: &Trace,
    r: &rockslide_core::case::RockingBody,
) -> Result<EnergyHistory, String> {
    if !ROCKING_CHANNELS.iter().all(|k| trace.has(k)) {
        return Err(ROCKING_MISSING.into());
    }
    let n = trace.len();
    if n < 2 {
        return Err("energy audit skipped: the trace has fewer than two rows".into());
    }
    let [w, k, u, d, v] = ROCKING_CHANNELS.map(|key| trace.column(key).expect("checked above"));
    let e0 = k[0] + u[0] + v[0];
    Ok(EnergyHistory {
        time: trace.time.clone(),
        supplied: w.iter().map(|w| e0 + w).collect(),
        kinetic: k.to_vec(),
        strain: u.to_vec(),
        friction: d.to_vec(),
        damping: vec![0.0; n],
        potential: v.to_vec(),
        impact: vec![0.0; n],
        stiffness: (
            r.contact.kx,
            "per contact element, Σ½T²/Kx + ½N²/Kz, recorded by the engine",
        ),
    })
}

/// Window around a pivot change in which the balance residual is booked as impact loss, s.
pub const IMPACT_WINDOW: f64 = 0.01;

/// The audit of a rigid block on a rigid ground (Newmark sliding, Housner rocking), in
/// the ground's frame:
///
/// - kinetic  K = ½M(ẋ² + ż²) + ½I_G·φ̇², I_G = M(b² + h²)/3 of the uniform 2b × 2h block;
///   ẋ from `vel` (the centre of mass's horizontal velocity), else from `cm_x`; ż and φ̇
///   from `cm_z` and `rotation` by central differences (zero when the trace has no such
///   channel: a sliding-only model);
/// - potential V = M·g·z (z = `cm_z`, from the resting position);
/// - input work W = ∫F dx_cm (trapezoidal; F from the `force` channel, else from the
///   scene: M·a(t), or −M·ag(t) in the ground's frame);
/// - friction D_f = ∫R dxp (`resistance`, `slide`) when the trace has both;
/// - impact losses D_i (Housner 1963: the plastic impact when the pivot changes corner
///   loses 1 − r² of the kinetic energy): the balance residual accumulated within
///   ±[`IMPACT_WINDOW`] of each sign change of `rotation`. What is left is the error.
fn audit_block(
    trace: &Trace,
    scene: &Scene,
    b: &rockslide_core::case::RigidBlock,
) -> Result<EnergyHistory, String> {
    let n = trace.len();
    if n < 3 {
        return Err("energy audit skipped: the trace has fewer than three rows".into());
    }
    let x = trace
        .column(q::CM_X.key)
        .or_else(|| trace.column(q::REL_DISP.key))
        .ok_or("energy audit skipped: the trace has neither cm_x nor rel_disp")?;
    let force: Vec<f64> = match trace.column(q::FORCE.key) {
        Some(f) => f.to_vec(),
        None => {
            let m = b.mass;
            let f: Box<dyn Fn(f64) -> f64> = match &scene.excitation {
                Excitation::None => Box::new(|_| 0.0),
                Excitation::MassAcceleration(s) => Box::new(move |t| m * s.value(t)),
                Excitation::GroundAcceleration(s) => Box::new(move |t| -m * s.value(t)),
                Excitation::GroundDisplacement(_) => {
                    return Err("energy audit skipped: a block under ground displacement needs the trace's force channel (the ground's velocity jumps are impulses)".into());
                }
            };
            trace.time.iter().map(|&t| f(t)).collect()
        }
    };
    let t = &trace.time;
    // Central differences inside, one-sided at the ends.
    let rate = |c: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| {
                let (a, z) = (i.saturating_sub(1), (i + 1).min(n - 1));
                (c[z] - c[a]) / (t[z] - t[a])
            })
            .collect()
    };
    let vx = match trace.column(q::VEL.key) {
        Some(v) => v.to_vec(),
        None => rate(x),
    };
    let zero = vec![0.0; n];
    let z = trace.column(q::CM_Z.key).unwrap_or(&zero);
    let phi = trace.column(q::ROTATION.key).unwrap_or(&zero);
    let (vz, w) = (rate(z), rate(phi));
    let m = b.mass;
    let inertia = m * (b.half_width.powi(2) + b.half_height.powi(2)) / 3.0;
    let friction = match (trace.column(q::RESISTANCE.key), trace.column(q::SLIDE.key)) {
        (Some(r), Some(s)) => Some((r, s)),
        _ => None,
    };
    let mut h = EnergyHistory {
        time: t.clone(),
        supplied: vec![0.0; n],
        kinetic: vec![0.0; n],
        strain: vec![0.0; n],
        friction: vec![0.0; n],
        damping: vec![0.0; n],
        potential: vec![0.0; n],
        impact: vec![0.0; n],
        stiffness: (f64::INFINITY, "rigid block: no strain energy"),
    };
    for i in 0..n {
        h.kinetic[i] = 0.5 * m * (vx[i] * vx[i] + vz[i] * vz[i]) + 0.5 * inertia * w[i] * w[i];
        h.potential[i] = m * b.gravity * z[i];
    }
    h.supplied[0] = h.kinetic[0] + h.potential[0];
    for i in 1..n {
        h.supplied[i] = h.supplied[i - 1] + 0.5 * (force[i - 1] + force[i]) * (x[i] - x[i - 1]);
        if let Some((r, s)) = friction {
            h.friction[i] = h.friction[i - 1] + 0.5 * (r[i - 1] + r[i]) * (s[i] - s[i - 1]);
        }
    }
    // Impacts: rows within the window of a pivot change (rotation changes sign).
    let mut in_window = vec![false; n];
    for i in 1..n {
        if phi[i - 1] * phi[i] < 0.0 || (phi[i] == 0.0 && phi[i - 1] != 0.0) {
            let (lo, hi) = (t[i] - IMPACT_WINDOW, t[i] + IMPACT_WINDOW);
            for (k, flag) in in_window.iter_mut().enumerate() {
                if t[k] >= lo && t[k] <= hi {
                    *flag = true;
                }
            }
        }
    }
    let mut booked = 0.0;
    for (i, &impact) in in_window.iter().enumerate().skip(1) {
        if impact {
            let before = h.supplied[i - 1] - h.accounted(i - 1);
            let now = h.supplied[i] - (h.accounted(i) - h.impact[i]) - booked;
            booked += now - before;
        }
        h.impact[i] = booked;
    }
    Ok(h)
}

/// The row whose time is nearest `t`, if `t` lies within the trace.
fn nearest_row(time: &[f64], t: f64) -> Option<usize> {
    let last = *time.last()?;
    if t > last {
        return None;
    }
    let i = time.partition_point(|&x| x < t);
    let i = i.min(time.len() - 1);
    if i > 0 && (t - time[i - 1]).abs() < (time[i] - t).abs() {
        Some(i - 1)
    } else {
        Some(i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::case::{Contact, Oscillator, Signal};

    fn scene(mu: f64) -> Scene {
        Scene {
            model: Model::Oscillator(Oscillator {
                mass: 2.0,
                gravity: 1.0,
                damping_ratio: 0.0,
                contact: Contact {
                    kx: 8.0,
                    kz: 8.0,
                    mu,
                },
                double: None,
            }),
            excitation: Excitation::MassAcceleration(Signal::SinePulse {
                amplitude: 1.0,
                omega: 1.0,
                cycles: 0.5,
            }),
            vertical: None,
            spatial: None,
        }
    }

    /// Exact free vibration x = cos 2t (ω² = K/M = 4), sampled finely: the audit closes
    /// to the trapezoidal error of ∫F dx, here zero (F = 0), so only round-off remains.
    #[test]
    fn free_vibration_closes_exactly() {
        let chans = [&q::FORCE, &q::RESISTANCE, &q::REL_DISP, &q::SLIDE, &q::VEL];
        let mut t = Trace::with_channels(&chans, 101);
        for i in 0..=100 {
            let s = i as f64 * 0.05;
            let x = (2.0 * s).cos();
            t.push(s, &[0.0, 8.0 * x, x, 0.0, -2.0 * (2.0 * s).sin()]);
        }
        let h = audit(&t, &scene(f64::INFINITY), Arrangement::Single).unwrap();
        let s = h.summary();
        assert!((s.supplied - 4.0).abs() < 1e-12); // E0 = ½·8·1²
        assert!(s.relative_error < 1e-12, "{}", s.relative_error);
        assert_eq!(h.growth_time(1.0), None);
    }

    /// A block sliding at R = Ru against a constant force F = Ru at constant speed: the
    /// input work all goes to friction.
    #[test]
    fn steady_slip_is_all_friction() {
        let chans = [&q::FORCE, &q::RESISTANCE, &q::REL_DISP, &q::SLIDE, &q::VEL];
        let mut t = Trace::with_channels(&chans, 11);
        let ru = 1.0; // μ M g = 0.5·2·1
        for i in 0..=10 {
            let s = i as f64 * 0.1;
            // e = R/K = 0.125 constant, x = 0.125 + 0.3 s
            t.push(s, &[ru, ru, 0.125 + 0.3 * s, 0.3 * s, 0.3]);
        }
        let h = audit(&t, &scene(0.5), Arrangement::Single).unwrap();
        let s = h.summary();
        assert!((s.friction - 0.3).abs() < 1e-12);
        assert!(s.end_error.abs() < 1e-12);
    }

    #[test]
    fn missing_channels_are_named() {
        let t = Trace::with_channels(&[&q::REL_DISP], 1);
        let why = audit(&t, &scene(0.5), Arrangement::Single).unwrap_err();
        assert!(why.contains("force") && why.contains("vel"), "{why}");
    }
}

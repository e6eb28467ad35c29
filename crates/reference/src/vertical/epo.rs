//! The undamped elastic–perfectly-plastic oscillator (the paper's PEPO) under horizontal
//! and vertical ground motion: the friction limit breathes with the normal force N(t) —
//! exact for both accelerations piecewise linear on the grid of [`super::LinearInputs`].
//!
//! Vertical: with the contact's stiffness Kz (`normal_force = "dynamic"`), the compression
//! δ obeys M·δ'' + Kz·δ = M·(g + a_v) (a_v positive upward), from static equilibrium
//! δ = M·g/Kz; on an interval g + a_v = g_e0 + γτ, so (Duhamel, closed form)
//! δ = (g_e0 + γτ)/ωz² + C cos ωzτ + D sin ωzτ and N = Kz·δ. A rigid vertical contact
//! (`"quasi-static"`) has N = M·(g_e0 + γτ). Either way N(τ) = n0 + n1τ + a cos ωzτ +
//! b sin ωzτ. With Kz the contact is compression-only: where N reaches 0 it opens and the
//! mass flies — vertically ballistic, δ'' = g + a_v (δ < 0 a gap, cubic on an interval),
//! horizontally free, u'' = d, no force — until the gap closes (δ rises through 0). The Kz
//! spring is elastic: the mass lands with its vertical velocity and the spring takes it up
//! again (no impact loss). The horizontal stick point follows the mass while the contact is
//! open and the contact closes unstressed (e = 0), as CONTA178 re-establishes sticking
//! at contact (and as the fe engine's element does): the flight's horizontal travel is
//! sliding. A rigid vertical contact whose g + a_v falls below 0 is an error here (the
//! rigid block's reference has that flight).
//!
//! Horizontal, relative coordinates, drive d = d0 + d'τ per unit mass, e = u − up:
//! - stuck: e'' + ω²e = d, so e = (d0 + d'τ)/ω² + C cos ωτ + D sin ωτ, R = K·e;
//! - slipping in direction s: R = s·μ·N(τ), u'' = d − s·μ·N/M (u closed form: N integrated
//!   twice), e = s·μ·N/K, up = u − e.
//!
//! An onset where K·|e| reaches μ·N(τ); a stop where the slip rate λ = s·u' − μ·N'/K
//! (it is s·up') returns to zero. Both located by [`super::crossing::first_rise`] with a
//! bound on the event function's curvature, then bisection to the last float.

use super::LinearInputs;
use super::crossing::first_rise;

/// Events allowed per grid interval before the solver reports it is not progressing.
const EVENTS_PER_INTERVAL: usize = 64;

/// N(τ) = n0 + n1·τ + a·cos ωzτ + b·sin ωzτ on an interval, N.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalLaw {
    n0: f64,
    n1: f64,
    a: f64,
    b: f64,
    wz: f64,
}

impl NormalLaw {
    /// N at τ.
    pub fn at(&self, t: f64) -> f64 {
        let (s, c) = sin_cos(self.wz * t);
        self.n0 + self.n1 * t + self.a * c + self.b * s
    }
    fn rate(&self, t: f64) -> f64 {
        let (s, c) = sin_cos(self.wz * t);
        self.n1 + self.wz * (-self.a * s + self.b * c)
    }
    /// ∫₀^τ N.
    fn once(&self, t: f64) -> f64 {
        let mut x = self.n0 * t + self.n1 * t * t / 2.0;
        if self.wz > 0.0 {
            let (s, c) = (self.wz * t).sin_cos();
            x += self.a * s / self.wz + self.b * (1.0 - c) / self.wz;
        }
        x
    }
    /// ∫₀^τ∫₀^x N.
    fn twice(&self, t: f64) -> f64 {
        let mut x = self.n0 * t * t / 2.0 + self.n1 * t * t * t / 6.0;
        if self.wz > 0.0 {
            let (s, c) = (self.wz * t).sin_cos();
            let w2 = self.wz * self.wz;
            x += self.a * (1.0 - c) / w2 + self.b * (t - s / self.wz) / self.wz;
        }
        x
    }
    fn amplitude(&self) -> f64 {
        self.a.hypot(self.b)
    }
    /// The same law with its origin moved to τ = `s`.
    fn shifted(&self, s: f64) -> NormalLaw {
        let (sn, cs) = sin_cos(self.wz * s);
        NormalLaw {
            n0: self.n0 + self.n1 * s,
            n1: self.n1,
            a: self.a * cs + self.b * sn,
            b: -self.a * sn + self.b * cs,
            wz: self.wz,
        }
    }
}

/// (sin x, cos x); at x = ±0 (a rigid vertical contact, ωz = 0) the exact (x, 1) without
/// the library call — the values `sin_cos` gives there, bit for bit.
fn sin_cos(x: f64) -> (f64, f64) {
    if x == 0.0 { (x, 1.0) } else { x.sin_cos() }
}

/// Contact phase.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EpoPhase {
    /// Elastic.
    Stuck,
    /// Slipping in direction s (±1).
    Slipping(f64),
    /// The contact open (N = 0): flying, the stick point following the mass.
    Open,
}

/// The oscillator's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EpoState {
    /// Relative displacement u, m.
    pub u: f64,
    /// Relative velocity, m/s.
    pub v: f64,
    /// Accumulated slip up, m.
    pub up: f64,
    /// Vertical compression δ, m (dynamic normal force; unused when quasi-static).
    pub dz: f64,
    /// Its rate, m/s.
    pub vz: f64,
    /// Contact phase.
    pub phase: EpoPhase,
}

/// One slip: start, end, direction, slip added.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerticalSlip {
    /// Onset, s.
    pub start: f64,
    /// Stop, s.
    pub end: f64,
    /// Direction.
    pub direction: f64,
    /// Slip added, m.
    pub distance: f64,
}

/// The oscillator's constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EpoConstants {
    /// Mass, kg.
    pub m: f64,
    /// Horizontal stiffness, N/m.
    pub k: f64,
    /// Friction coefficient.
    pub mu: f64,
    /// Gravity, m/s².
    pub g: f64,
    /// Vertical stiffness Kz, N/m; `None`: quasi-static N = M·(g + a_v).
    pub kz: Option<f64>,
}

impl EpoConstants {
    fn omega(&self) -> f64 {
        (self.k / self.m).sqrt()
    }
    fn omega_z(&self) -> f64 {
        self.kz.map_or(0.0, |kz| (kz / self.m).sqrt())
    }
    /// At rest in static equilibrium.
    pub fn rest(&self) -> EpoState {
        let wz = self.omega_z();
        EpoState {
            u: 0.0,
            v: 0.0,
            up: 0.0,
            dz: if wz > 0.0 { self.g / (wz * wz) } else { 0.0 },
            vz: 0.0,
            phase: EpoPhase::Stuck,
        }
    }
    /// The normal-force law over an interval from `state`, with g_e = ge0 + γτ.
    pub fn normal_law(&self, state: &EpoState, ge0: f64, gamma: f64) -> NormalLaw {
        let wz = self.omega_z();
        let (a, b) = match self.kz {
            Some(kz) => {
                let w2 = wz * wz;
                (
                    kz * (state.dz - ge0 / w2),
                    kz * (state.vz - gamma / w2) / wz,
                )
            }
            None => (0.0, 0.0),
        };
        NormalLaw {
            n0: self.m * ge0,
            n1: self.m * gamma,
            a,
            b,
            wz,
        }
    }
}

/// Steps the oscillator over intervals with linear inputs.
#[derive(Debug, Clone)]
pub struct EpoWalker {
    c: EpoConstants,
    /// Current state.
    pub state: EpoState,
    /// Every slip.
    pub slips: Vec<VerticalSlip>,
    /// Every flight (contact open): start, end, horizontal travel (direction 0).
    pub flights: Vec<VerticalSlip>,
}

impl EpoWalker {
    /// From `state`.
    pub fn new(c: EpoConstants, state: EpoState) -> Self {
        EpoWalker {
            c,
            state,
            slips: Vec::new(),
            flights: Vec::new(),
        }
    }

    /// Advance over `[t0, t0 + h]` with drive `d` and vertical acceleration `av` linear.
    pub fn interval(
        &mut self,
        t0: f64,
        h: f64,
        d: (f64, f64),
        av: (f64, f64),
    ) -> Result<(), String> {
        let (ds, gamma) = ((d.1 - d.0) / h, (av.1 - av.0) / h);
        let mut s = 0.0;
        let mut events = 0;
        while s < h {
            let (d0, ge0) = (d.0 + ds * s, self.c.g + av.0 + gamma * s);
            s += if self.state.phase == EpoPhase::Open {
                events += 1;
                self.fly(t0 + s, (d0, ds), (ge0, gamma), h - s)?
            } else {
                self.closed(t0 + s, (d0, ds), (ge0, gamma), h - s, &mut events)?
            };
            if events > EVENTS_PER_INTERVAL {
                return Err(format!(
                    "more than {EVENTS_PER_INTERVAL} events in the grid interval at t = {t0} s: the vertical oscillator reference is not progressing"
                ));
            }
        }
        Ok(())
    }

    /// The contact closed over `span` from `t`, or until it opens (N falls to 0; with Kz
    /// only — a rigid vertical contact with g + a_v < 0 is an error); returns the time used.
    fn closed(
        &mut self,
        t: f64,
        (d0, ds): (f64, f64),
        (ge0, gamma): (f64, f64),
        span: f64,
        events: &mut usize,
    ) -> Result<f64, String> {
        let law = self.c.normal_law(&self.state, ge0, gamma);
        let curvature = law.wz * law.wz * law.amplitude() + self.c.m * gamma.abs();
        // The contact opens where N falls below zero by more than a rounding residue (1e-12
        // of the weight): a contact that has just closed starts at N = 0 to rounding.
        let residue = 1e-12 * self.c.m * self.c.g;
        let opening = first_rise(|x| -law.at(x) - residue, span, curvature, law.wz)?;
        if opening.is_some() && self.c.kz.is_none() {
            return Err(format!(
                "g + a_v < 0 at t ≈ {:.6} s: a rigid vertical contact would lift off, which this oscillator reference does not model",
                t + opening.unwrap_or(0.0)
            ));
        }
        let sub = opening.unwrap_or(span);
        let mut s = 0.0;
        while s < sub {
            *events += 1;
            if *events > EVENTS_PER_INTERVAL {
                return Ok(s.max(f64::MIN_POSITIVE));
            }
            let local = law.shifted(s);
            let d_s = d0 + ds * s;
            s += match self.state.phase {
                EpoPhase::Slipping(dir) => self.slip(t + s, dir, &local, d_s, ds, sub - s)?,
                _ => self.stuck(t + s, &local, d_s, ds, sub - s)?,
            };
        }
        // the vertical oscillator over the span (independent of the horizontal)
        if let Some(kz) = self.c.kz {
            self.state.dz = law.at(sub) / kz;
            self.state.vz = law.rate(sub) / kz;
        }
        if opening.is_some() {
            self.state.phase = EpoPhase::Open;
            self.state.up = self.state.u;
            self.flights.push(VerticalSlip {
                start: t + sub,
                end: t + sub,
                direction: 0.0,
                distance: 0.0,
            });
        }
        Ok(sub)
    }

    /// The contact open: ballistic vertically (δ'' = g_e), free horizontally (u'' = d), the
    /// stick point with the mass, until the gap closes or the span ends; returns the time
    /// used. At closure the contact is closed and unstressed (e = 0), δ = 0.
    fn fly(
        &mut self,
        t: f64,
        (d0, ds): (f64, f64),
        (ge0, gamma): (f64, f64),
        span: f64,
    ) -> Result<f64, String> {
        let (u0, v0, z0, w0) = (self.state.u, self.state.v, self.state.dz, self.state.vz);
        let dz = |x: f64| z0 + w0 * x + ge0 * x * x / 2.0 + gamma * x * x * x / 6.0;
        let curvature = ge0.abs().max((ge0 + gamma * span).abs());
        let closing = first_rise(dz, span, curvature, 0.0)?;
        let tau = closing.unwrap_or(span);
        let u = u0 + v0 * tau + d0 * tau * tau / 2.0 + ds * tau * tau * tau / 6.0;
        self.state.v = v0 + d0 * tau + ds * tau * tau / 2.0;
        self.state.vz = w0 + ge0 * tau + gamma * tau * tau / 2.0;
        if let Some(flight) = self.flights.last_mut() {
            flight.distance += u - self.state.up;
            flight.end = t + tau;
        }
        self.state.u = u;
        self.state.up = u;
        if closing.is_some() {
            self.state.dz = 0.0;
            self.state.phase = EpoPhase::Stuck;
        } else {
            self.state.dz = dz(tau).min(0.0);
        }
        Ok(tau)
    }

    /// Elastic until an onset or the span's end; returns the time used.
    fn stuck(
        &mut self,
        t: f64,
        law: &NormalLaw,
        d0: f64,
        ds: f64,
        span: f64,
    ) -> Result<f64, String> {
        let (k, mu, w) = (self.c.k, self.c.mu, self.c.omega());
        let w2 = w * w;
        let e0 = self.state.u - self.state.up;
        let (cc, dd) = (e0 - d0 / w2, (self.state.v - ds / w2) / w);
        let e = |t: f64| {
            let (s, c) = (w * t).sin_cos();
            (d0 + ds * t) / w2 + cc * c + dd * s
        };
        let e_rate = |t: f64| {
            let (s, c) = (w * t).sin_cos();
            ds / w2 + w * (-cc * s + dd * c)
        };
        // An onset must rise through the limit, not touch it: an undamped oscillator that
        // has stopped slipping touches μN every half period and a rounding residue
        // there is no slip. The margin, 1e-10 of the friction limit, moves a true onset by
        // ~1e-10 of the time the force takes to rise by the limit.
        let margin = 1e-10 * mu * (law.n0.abs() + law.amplitude());
        let excess = |t: f64| k * e(t).abs() - mu * law.at(t) - margin;
        let curvature = k * w2 * cc.hypot(dd) + mu * law.wz * law.wz * law.amplitude();
        let onset = if mu.is_finite() {
            first_rise(excess, span, curvature, w.max(law.wz))?
        } else {
            None
        };
        let tau = onset.unwrap_or(span);
        self.state.u = self.state.up + e(tau);
        self.state.v = e_rate(tau);
        if onset.is_some() {
            let dir = e(tau).signum();
            self.state.phase = EpoPhase::Slipping(dir);
            self.slips.push(VerticalSlip {
                start: t + tau,
                end: t + tau,
                direction: dir,
                distance: 0.0,
            });
        }
        Ok(tau)
    }

    /// Slipping in direction `dir` until the slip rate returns to zero or the span ends.
    fn slip(
        &mut self,
        t: f64,
        dir: f64,
        law: &NormalLaw,
        d0: f64,
        ds: f64,
        span: f64,
    ) -> Result<f64, String> {
        let (m, k, mu) = (self.c.m, self.c.k, self.c.mu);
        let (u0, v0) = (self.state.u, self.state.v);
        let f = dir * mu / m;
        let u = |t: f64| u0 + v0 * t + d0 * t * t / 2.0 + ds * t * t * t / 6.0 - f * law.twice(t);
        let v = |t: f64| v0 + d0 * t + ds * t * t / 2.0 - f * law.once(t);
        let rate = |t: f64| dir * v(t) - mu * law.rate(t) / k;
        let wz = law.wz;
        let amp = law.amplitude();
        let curvature =
            ds.abs() + (mu / m) * (law.n1.abs() + wz * amp) + (mu / k) * wz.powi(3) * amp;
        let stop = first_rise(|t| -rate(t), span, curvature, wz)?;
        let tau = stop.unwrap_or(span);
        self.state.u = u(tau);
        self.state.v = v(tau);
        let up = self.state.u - dir * mu * law.at(tau) / k;
        // (a walk that starts inside a slip, between grid points, has no record of it)
        if let Some(slip) = self.slips.last_mut() {
            slip.distance += up - self.state.up;
            slip.end = t + tau;
        }
        self.state.up = up;
        if stop.is_some() {
            self.state.phase = EpoPhase::Stuck;
        }
        Ok(tau)
    }
}

/// The oscillator's history on a grid: the state at every grid point, its slips.
#[derive(Debug, Clone)]
pub struct EpoHistory {
    /// State at each grid point.
    pub states: Vec<EpoState>,
    /// Every slip.
    pub slips: Vec<VerticalSlip>,
    /// Every flight (the contact open).
    pub flights: Vec<VerticalSlip>,
}

/// Solve from static rest under `inputs` (through contact openings with Kz; an error if a
/// rigid vertical contact's g + a_v falls below zero).
pub fn solve_epo(inputs: &LinearInputs, c: EpoConstants) -> Result<EpoHistory, String> {
    let valid = |x: f64| x.is_finite() && x > 0.0;
    if !(valid(c.m) && valid(c.k) && valid(c.g) && c.mu >= 0.0 && c.kz.is_none_or(valid)) {
        return Err("mass, stiffnesses and gravity must be positive and finite, μ ≥ 0".into());
    }
    let mut walker = EpoWalker::new(c, c.rest());
    let mut states = Vec::with_capacity(inputs.drive.len());
    states.push(walker.state);
    let h = inputs.h;
    for i in 1..inputs.drive.len() {
        let t0 = (i - 1) as f64 * h;
        let av = (inputs.vertical[i - 1], inputs.vertical[i]);
        walker.interval(t0, h, (inputs.drive[i - 1], inputs.drive[i]), av)?;
        states.push(walker.state);
    }
    Ok(EpoHistory {
        states,
        slips: walker.slips,
        flights: walker.flights,
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_shortcut_at_zero_is_the_library_s_value() {
        for x in [0.0_f64, -0.0, 1e-300, -2.5, f64::NAN] {
            let (a, b) = (super::sin_cos(x), x.sin_cos());
            assert_eq!(
                (a.0.to_bits(), a.1.to_bits()),
                (b.0.to_bits(), b.1.to_bits()),
                "{x}"
            );
        }
    }
}

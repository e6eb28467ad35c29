//! The rigid-plastic block (Newmark 1965) under horizontal and vertical ground motion, with
//! lift-off — exact for both accelerations piecewise linear on the grid of
//! [`super::LinearInputs`].
//!
//! Relative coordinates: u, v the block's horizontal displacement and velocity relative to
//! the ground, z ≥ 0 and w its height above the ground and vertical velocity; d(t) the
//! horizontal drive per unit mass, g_e(t) = g + a_v(t) the effective gravity (a_v positive
//! upward). On each interval d and g_e are linear in τ.
//! - In contact (z = 0), N = M·g_e. Stuck while |d| ≤ μ·g_e; sliding in direction σ once
//!   σ·d exceeds μ·g_e (one-way: σ = +1 only), with v' = d − σ·μ·g_e (linear, so v is
//!   quadratic and u cubic) until v returns to zero.
//! - g_e < 0: the ground pulls away faster than gravity — the block is airborne: no
//!   friction, v' = d, z'' = −g_e (cubic z), until it lands (z returns to 0). At landing
//!   the vertical velocity w is lost (a plastic impact on rigid ground, normal impulse
//!   M·|w|) and Coulomb friction acts on the impact impulse: the friction impulse is at
//!   most μ·M·|w| against the slide, so |v| falls by μ·|w| (Routh's plastic impact with
//!   friction, no reversal), or to zero and the block sticks; it slides on in the direction
//!   of v (one-way: a landing with v < 0 stops it). Keeping the horizontal velocity instead
//!   would let the impulsive normal force act without its friction — the law |T| = μ·N of
//!   a sliding contact broken for the one instant N is largest.
//!
//! Events: onset and lift-off where a linear function crosses zero (closed form), a
//! slide's stop at the root of a quadratic ([`crate::block_record::stop_time`]), a landing
//! at the first root of the cubic z ([`super::crossing`], bounded). Events per interval
//! are bounded; a run that stops progressing is an error, never a silent skip.

use super::LinearInputs;
use super::crossing::first_rise;
use crate::block_record::{Sliding, stop_time};

/// Events allowed per grid interval before the solver reports it is not progressing.
const EVENTS_PER_INTERVAL: usize = 64;

/// What the block does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BlockPhase {
    /// In contact, not moving relative to the ground.
    Stuck,
    /// In contact, sliding in direction σ (±1).
    Sliding(f64),
    /// Off the ground.
    Airborne,
}

/// One stretch of motion: a slide or a flight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Start, s.
    pub start: f64,
    /// End, s (the end of the run if it does not end).
    pub end: f64,
    /// The phase (`Sliding(σ)` or `Airborne`).
    pub phase: BlockPhase,
    /// Horizontal displacement added, m (signed).
    pub distance: f64,
}

/// The block's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockState {
    /// Horizontal displacement and velocity relative to the ground, m, m/s.
    pub u: f64,
    /// Horizontal velocity relative to the ground, m/s.
    pub v: f64,
    /// Height above the ground, m.
    pub z: f64,
    /// Vertical velocity relative to the ground, m/s.
    pub w: f64,
    /// Contact phase.
    pub phase: BlockPhase,
}

impl BlockState {
    /// At rest on the ground.
    pub const REST: BlockState = BlockState {
        u: 0.0,
        v: 0.0,
        z: 0.0,
        w: 0.0,
        phase: BlockPhase::Stuck,
    };
}

/// Steps the block over intervals with linear inputs, recording its motions.
#[derive(Debug, Clone)]
pub struct BlockWalker {
    mu: f64,
    g: f64,
    sliding: Sliding,
    /// Current state.
    pub state: BlockState,
    /// Every slide and flight, in time order.
    pub motions: Vec<Motion>,
}

impl BlockWalker {
    /// A block with friction `mu`, gravity `g` (m/s²), one- or two-way, from `state`.
    pub fn new(mu: f64, g: f64, sliding: Sliding, state: BlockState) -> Self {
        BlockWalker {
            mu,
            g,
            sliding,
            state,
            motions: Vec::new(),
        }
    }

    /// Advance over `[t0, t0 + h]` with drive `d0 → d1` and vertical acceleration
    /// `av0 → av1` (both linear).
    pub fn interval(
        &mut self,
        t0: f64,
        h: f64,
        d: (f64, f64),
        av: (f64, f64),
    ) -> Result<(), String> {
        let (ds, gs) = ((d.1 - d.0) / h, (av.1 - av.0) / h);
        let mut s = 0.0;
        for _ in 0..EVENTS_PER_INTERVAL {
            if s >= h {
                return Ok(());
            }
            let (d0, ge0) = (d.0 + ds * s, self.g + av.0 + gs * s);
            let span = h - s;
            let used = match self.state.phase {
                BlockPhase::Stuck => self.stuck(t0 + s, d0, ds, ge0, gs, span),
                BlockPhase::Sliding(sigma) => self.slide(t0 + s, sigma, d0, ds, ge0, gs, span),
                BlockPhase::Airborne => self.fly(t0 + s, d0, ds, ge0, gs, span)?,
            };
            s += used;
        }
        Err(format!(
            "more than {EVENTS_PER_INTERVAL} events in the grid interval at t = {t0} s: the vertical rigid-block reference is not progressing"
        ))
    }

    /// Stuck: wait for lift-off (g_e < 0) or an onset (σ·d > μ·g_e); returns time used.
    fn stuck(&mut self, t: f64, d0: f64, ds: f64, ge0: f64, gs: f64, span: f64) -> f64 {
        let lift = crossing_below(ge0, gs, span);
        let dirs: &[f64] = match self.sliding {
            Sliding::OneWay => &[1.0],
            Sliding::TwoWay => &[1.0, -1.0],
        };
        let mut onset: Option<(f64, f64)> = None;
        for &dir in dirs {
            // r > 0: beyond the friction limit in direction dir
            let (r0, rate) = (dir * d0 - self.mu * ge0, dir * ds - self.mu * gs);
            if let Some(tau) = crossing_below(-r0, -rate, span)
                && onset.is_none_or(|(_, b)| tau < b)
            {
                onset = Some((dir, tau));
            }
        }
        match (lift, onset) {
            (Some(tl), o) if o.is_none_or(|(_, to)| tl <= to) => {
                self.take_off(t + tl);
                tl
            }
            (_, Some((dir, to))) => {
                self.state.phase = BlockPhase::Sliding(dir);
                self.state.v = 0.0;
                self.begin(t + to, BlockPhase::Sliding(dir));
                to
            }
            _ => span,
        }
    }

    /// Sliding in direction σ: until the stop, a lift-off, or the span's end.
    #[allow(clippy::too_many_arguments)]
    fn slide(&mut self, t: f64, sigma: f64, d0: f64, ds: f64, ge0: f64, gs: f64, span: f64) -> f64 {
        // σv = q obeys q' = r0 + ρτ
        let q0 = sigma * self.state.v;
        let (mut r0, rho) = (sigma * d0 - self.mu * ge0, sigma * ds - self.mu * gs);
        if q0 == 0.0 {
            r0 = r0.max(0.0); // just started: a rounding residue must not stop it at once
        }
        let lift = crossing_below(ge0, gs, span);
        let stop = stop_time(q0, r0, rho, lift.unwrap_or(span));
        let tau = stop.or(lift).unwrap_or(span);
        let dq = q0 * tau + r0 * tau * tau / 2.0 + rho * tau * tau * tau / 6.0;
        self.advance(t + tau, sigma * dq);
        if stop.is_some() {
            self.state.v = 0.0;
            self.state.phase = BlockPhase::Stuck;
        } else {
            self.state.v = sigma * (q0 + r0 * tau + rho * tau * tau / 2.0);
            if lift.is_some() {
                self.take_off(t + tau);
            }
        }
        tau
    }

    /// Airborne: free horizontally, ballistic vertically, until the landing.
    fn fly(
        &mut self,
        t: f64,
        d0: f64,
        ds: f64,
        ge0: f64,
        gs: f64,
        span: f64,
    ) -> Result<f64, String> {
        let (z0, w0) = (self.state.z, self.state.w);
        let z = |tau: f64| z0 + w0 * tau - ge0 * tau * tau / 2.0 - gs * tau * tau * tau / 6.0;
        // −z'' = g_e, linear: its extreme on the span bounds the curvature of −z
        let curvature = ge0.abs().max((ge0 + gs * span).abs());
        let landing = first_rise(|tau| -z(tau), span, curvature, 0.0)?;
        let tau = landing.unwrap_or(span);
        let v0 = self.state.v;
        self.advance(
            t + tau,
            v0 * tau + d0 * tau * tau / 2.0 + ds * tau * tau * tau / 6.0,
        );
        self.state.v = v0 + d0 * tau + ds * tau * tau / 2.0;
        if landing.is_some() {
            // plastic landing with Coulomb friction on the impact impulse: the vertical
            // velocity w is lost (normal impulse M·|w|), the friction impulse is at most
            // μ·M·|w| against the slide, so |v| falls by μ·|w| or the block sticks
            let w = w0 - ge0 * tau - gs * tau * tau / 2.0;
            let v = self.state.v;
            self.state.v = v.signum() * (v.abs() - self.mu * w.abs()).max(0.0);
            self.state.z = 0.0;
            self.state.w = 0.0;
            let v = self.state.v;
            let phase = match self.sliding {
                _ if v == 0.0 => BlockPhase::Stuck,
                Sliding::OneWay if v < 0.0 => BlockPhase::Stuck,
                _ => BlockPhase::Sliding(v.signum()),
            };
            if phase == BlockPhase::Stuck {
                self.state.v = 0.0;
            }
            self.state.phase = phase;
            if let BlockPhase::Sliding(_) = phase {
                self.begin(t + tau, phase);
            }
        } else {
            self.state.z = z(tau).max(0.0);
            self.state.w = w0 - ge0 * tau - gs * tau * tau / 2.0;
        }
        Ok(tau)
    }

    fn take_off(&mut self, t: f64) {
        self.state.phase = BlockPhase::Airborne;
        self.state.z = 0.0;
        self.state.w = 0.0;
        self.begin(t, BlockPhase::Airborne);
    }

    fn begin(&mut self, t: f64, phase: BlockPhase) {
        self.motions.push(Motion {
            start: t,
            end: t,
            phase,
            distance: 0.0,
        });
    }

    /// Add `du` to u over the current motion, which now ends at `t`.
    fn advance(&mut self, t: f64, du: f64) {
        self.state.u += du;
        if let Some(m) = self.motions.last_mut() {
            m.distance += du;
            m.end = t;
        }
    }
}

/// First τ in [0, span] at which the linear `x0 + rate·τ` is below zero (or at zero and
/// falling), if it is.
fn crossing_below(x0: f64, rate: f64, span: f64) -> Option<f64> {
    if x0 < 0.0 || (x0 == 0.0 && rate < 0.0) {
        Some(0.0)
    } else if rate < 0.0 && x0 + rate * span < 0.0 {
        Some((-x0 / rate).min(span))
    } else {
        None
    }
}

/// The block's whole history on a grid: the state at every grid point and its motions.
#[derive(Debug, Clone)]
pub struct BlockHistory {
    /// State at each grid point.
    pub states: Vec<BlockState>,
    /// Every slide and flight.
    pub motions: Vec<Motion>,
}

/// Solve the block (friction `mu`, gravity `g`) under `inputs` from rest.
pub fn solve_block(
    inputs: &LinearInputs,
    mu: f64,
    g: f64,
    sliding: Sliding,
) -> Result<BlockHistory, String> {
    if !(mu.is_finite() && mu >= 0.0 && g.is_finite() && g > 0.0) {
        return Err(format!(
            "μ = {mu} and g = {g} m/s² must be finite, μ ≥ 0, g > 0"
        ));
    }
    let mut walker = BlockWalker::new(mu, g, sliding, BlockState::REST);
    let mut states = Vec::with_capacity(inputs.drive.len());
    states.push(walker.state);
    let h = inputs.h;
    for i in 1..inputs.drive.len() {
        let d = (inputs.drive[i - 1], inputs.drive[i]);
        let av = (inputs.vertical[i - 1], inputs.vertical[i]);
        walker.interval((i - 1) as f64 * h, h, d, av)?;
        states.push(walker.state);
    }
    Ok(BlockHistory {
        states,
        motions: walker.motions,
    })
}

//! The exact solution of the undamped elastic-perfectly-plastic oscillator under a sine
//! pulse: closed form between events (sticking: harmonic; slipping: constant friction
//! force), slip-start and slip-stop events located by root finding, the relative-velocity
//! jumps of a ground-displacement pulse applied exactly. Written from the equations of
//! motion alone — it shares nothing with the engines.
//!
//! Relative coordinates: u (mass relative to ground), up (slip), e = u − up (elastic
//! deflection), R = K·e with |R| ≤ Ru. Sticking: M·u'' + K·e = P(t). Slipping with
//! sign s: M·u'' = P(t) − s·Ru while s·u' > 0.

use super::root::bisect;
use super::{ExactSolution, SineForcing};
use rockslide_core::case::Oscillator;
use rockslide_core::trace::{Quantity, q};

/// What the contact does during a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Phase {
    /// Elastic, no slip.
    Stick,
    /// Slipping in direction `s` (+1 or −1) at R = s·Ru.
    Slip(f64),
}

/// A stretch of time with one phase and one forcing law, and its initial state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Start, s.
    pub t0: f64,
    /// End, s.
    pub t1: f64,
    /// Phase.
    pub phase: Phase,
    /// Relative displacement at t0, m.
    pub u0: f64,
    /// Relative velocity at t0 (after any jump), m/s.
    pub v0: f64,
    /// Slip at t0, m.
    pub up0: f64,
}

/// The event-driven exact solution.
#[derive(Debug, Clone)]
pub struct EpoExact {
    m: f64,
    k: f64,
    ru: f64,
    omega: f64,
    forcing: SineForcing,
    /// The segments, in time order, covering [0, duration].
    pub segments: Vec<Segment>,
}

/// Most scan steps the event search may take over a run.
const MAX_SCAN_STEPS: f64 = 5e7;

/// State at one instant: (u, v, R, up).
type State = (f64, f64, f64, f64);

impl EpoExact {
    /// Solve the oscillator `osc` under `forcing` over `[0, duration]`.
    pub fn new(osc: &Oscillator, forcing: SineForcing, duration: f64) -> Result<Self, String> {
        if osc.damping_ratio != 0.0 {
            return Err(
                "the exact elastic-plastic reference is for the undamped oscillator".into(),
            );
        }
        let omega = (osc.contact.kx / osc.mass).sqrt();
        if forcing.p0 != 0.0 && ((forcing.theta - omega) / omega).abs() < 1e-9 {
            return Err(
                "the exact elastic-plastic reference does not cover resonant forcing (θ = ω)"
                    .into(),
            );
        }
        let mut sol = EpoExact {
            m: osc.mass,
            k: osc.contact.kx,
            ru: osc.contact.mu * osc.mass * osc.gravity,
            omega,
            forcing,
            segments: Vec::new(),
        };
        // The events are bracketed on a scan of 64 points per period: bound that work
        // (a stiff contact or a fast pulse would otherwise run for minutes).
        let scans = duration / sol.scan_step();
        if scans.is_nan() || scans > MAX_SCAN_STEPS {
            return Err(format!(
                "the exact reference would scan {scans:.3e} steps (ω = {omega:.3e} rad/s, θ = {:.3e} rad/s over {duration} s): more than {MAX_SCAN_STEPS:e}; the oscillator or the pulse is too fast for it",
                sol.forcing.theta
            ));
        }
        sol.solve(duration)?;
        Ok(sol)
    }

    fn solve(&mut self, duration: f64) -> Result<(), String> {
        let td = self.forcing.td;
        let mut pieces = vec![];
        if td > 0.0 && td < duration {
            pieces.push((0.0, td));
            pieces.push((td, duration));
        } else {
            pieces.push((0.0, duration));
        }
        let (mut u, mut v, mut up) = (0.0, self.jump_at(0.0), 0.0);
        let mut phase = Phase::Stick;
        let tol = 1e-10 * self.ru;
        for (start, end) in pieces {
            let mut t = start;
            while t < end {
                if self.segments.len() > 1_000_000 {
                    return Err(
                        "more than a million slip/stick events: the reference gives up".into(),
                    );
                }
                let mut seg = Segment {
                    t0: t,
                    t1: end,
                    phase,
                    u0: u,
                    v0: v,
                    up0: up,
                };
                let event = match phase {
                    Phase::Stick => self.slip_start(&seg, tol),
                    Phase::Slip(s) => self.slip_stop(&seg, s),
                };
                let (t_next, next_phase) = match event {
                    Some((te, p)) => (te, p),
                    None => (end, phase),
                };
                seg.t1 = t_next;
                let (u1, v1, _, up1) = self.state_in(&seg, t_next);
                self.segments.push(seg);
                (u, v, up, t, phase) = (u1, v1, up1, t_next, next_phase);
                if let Phase::Stick = phase {
                    if event.is_some() {
                        v = 0.0; // a slip stops at exactly zero slip rate
                    }
                }
            }
            if end < duration {
                v += self.jump_at(end);
                if let Phase::Slip(s) = phase {
                    if s * v <= 0.0 {
                        phase = Phase::Stick;
                    }
                }
            }
        }
        Ok(())
    }

    fn jump_at(&self, t: f64) -> f64 {
        self.forcing
            .velocity_jumps
            .iter()
            .filter(|(tj, _)| *tj == t)
            .map(|(_, dv)| dv)
            .sum()
    }

    /// Force amplitude of the piece a segment lies in.
    fn piece_p(&self, seg: &Segment) -> f64 {
        if seg.t0 < self.forcing.td {
            self.forcing.p0
        } else {
            0.0
        }
    }

    fn scan_step(&self) -> f64 {
        let mut period = 2.0 * std::f64::consts::PI / self.omega;
        if self.forcing.p0 != 0.0 {
            period = period.min(2.0 * std::f64::consts::PI / self.forcing.theta);
        }
        period / 64.0
    }

    /// First time in the segment at which |R| reaches Ru while moving outward.
    fn slip_start(&self, seg: &Segment, tol: f64) -> Option<(f64, Phase)> {
        if self.ru.is_infinite() {
            return None;
        }
        let h = self.scan_step();
        let mut a = seg.t0;
        while a < seg.t1 {
            let b = (a + h).min(seg.t1);
            let mut best: Option<(f64, Phase)> = None;
            for s in [1.0, -1.0] {
                let g = |t: f64| s * self.state_in(seg, t).2 - self.ru;
                let sv = |t: f64| s * self.state_in(seg, t).1;
                let crossing = if g(b) > tol {
                    Some(if g(a) > 0.0 { a } else { bisect(a, b, g) })
                } else if sv(a) > 0.0 && sv(b) < 0.0 {
                    // g has a maximum inside: does it rise above Ru?
                    let tm = bisect(a, b, |t| -sv(t));
                    (g(tm) > tol).then(|| if g(a) > 0.0 { a } else { bisect(a, tm, g) })
                } else {
                    None
                };
                if let Some(te) = crossing {
                    if best.is_none_or(|(tb, _)| te < tb) {
                        best = Some((te, Phase::Slip(s)));
                    }
                }
            }
            if best.is_some() {
                return best;
            }
            a = b;
        }
        None
    }

    /// First time in the segment at which the slip rate reaches zero.
    fn slip_stop(&self, seg: &Segment, s: f64) -> Option<(f64, Phase)> {
        let h = self.scan_step();
        let sv = |t: f64| s * self.state_in(seg, t).1;
        let mut a = seg.t0;
        while a < seg.t1 {
            let b = (a + h).min(seg.t1);
            if sv(b) <= 0.0 {
                let te = if sv(a) <= 0.0 {
                    a
                } else {
                    bisect(a, b, |t| -sv(t))
                };
                return Some((te, Phase::Stick));
            }
            a = b;
        }
        None
    }

    /// (u, v, R, up) at `t` within `seg`.
    fn state_in(&self, seg: &Segment, t: f64) -> State {
        self.state_with(seg, self.segment_constants(seg), t)
    }

    /// The stick forcing's amplitude p/(K − Mθ²) on `seg` (0 without forcing).
    fn stick_amplitude(&self, seg: &Segment) -> f64 {
        let p = self.piece_p(seg);
        let (m, k, th) = (self.m, self.k, self.forcing.theta);
        if p != 0.0 { p / (k - m * th * th) } else { 0.0 }
    }

    /// What every time in `seg` shares: the stick's (c1, c2), or the slip's
    /// (cos θt0, sin θt0) under forcing — computed once a segment when sampling.
    fn segment_constants(&self, seg: &Segment) -> (f64, f64) {
        let th = self.forcing.theta;
        match seg.phase {
            Phase::Stick => {
                let amp = self.stick_amplitude(seg);
                let ep = |t: f64| amp * (th * t).sin();
                let ep_dot = |t: f64| amp * th * (th * t).cos();
                let c1 = (seg.u0 - seg.up0) - ep(seg.t0);
                let c2 = (seg.v0 - ep_dot(seg.t0)) / self.omega;
                (c1, c2)
            }
            Phase::Slip(_) if self.piece_p(seg) != 0.0 => {
                ((th * seg.t0).cos(), (th * seg.t0).sin())
            }
            Phase::Slip(_) => (0.0, 0.0),
        }
    }

    /// [`Self::state_in`] with the segment's constants ([`Self::segment_constants`]).
    fn state_with(&self, seg: &Segment, (ca, cb): (f64, f64), t: f64) -> State {
        let p = self.piece_p(seg);
        let (m, k, th, w) = (self.m, self.k, self.forcing.theta, self.omega);
        let tau = t - seg.t0;
        match seg.phase {
            Phase::Stick => {
                // e = ep + c1 cos ωτ + c2 sin ωτ, ep = p/(K − Mθ²)·sin θt
                let amp = self.stick_amplitude(seg);
                let ep = |t: f64| amp * (th * t).sin();
                let ep_dot = |t: f64| amp * th * (th * t).cos();
                let (c1, c2) = (ca, cb);
                let (sn, cs) = (w * tau).sin_cos();
                let e = ep(t) + c1 * cs + c2 * sn;
                let v = ep_dot(t) - c1 * w * sn + c2 * w * cs;
                (seg.up0 + e, v, k * e, seg.up0)
            }
            Phase::Slip(s) => {
                // M·u'' = p·sin θt − s·Ru, integrated twice from (u0, v0)
                let (mut dv, mut du) =
                    (-s * self.ru * tau / m, -s * self.ru * tau * tau / (2.0 * m));
                if p != 0.0 {
                    let (c0, s0) = (ca, cb);
                    dv += p / (m * th) * (c0 - (th * t).cos());
                    du += p / (m * th) * (c0 * tau - ((th * t).sin() - s0) / th);
                }
                let u = seg.u0 + seg.v0 * tau + du;
                let r = s * self.ru;
                (u, seg.v0 + dv, r, u - r / k)
            }
        }
    }

    /// The segment containing `t` (the last one from its end on).
    fn segment_at(&self, t: f64) -> &Segment {
        self.segment_from(self.segments.partition_point(|s| s.t0 <= t))
    }

    /// The segment before partition point `i` of the segments' starts (the first).
    fn segment_from(&self, i: usize) -> &Segment {
        &self.segments[i.saturating_sub(1)]
    }

    /// The channels at `t` in `seg` (the segment holding `t`), in
    /// [`ExactSolution::channels`] order.
    fn write(&self, seg: &Segment, constants: (f64, f64), t: f64, out: &mut [f64]) {
        let (u, v, r, up) = self.state_with(seg, constants, t);
        let p = self.forcing.at(t);
        out[0] = p;
        out[1] = r;
        out[2] = u;
        out[3] = up;
        out[4] = v;
        out[5] = (p - r) / self.m;
        if let Some(g) = self.forcing.ground(t) {
            out[6] = g;
        }
    }

    /// (u, v, R, up) at `t`.
    pub fn state(&self, t: f64) -> State {
        self.state_in(self.segment_at(t), t)
    }

    /// Start and end of every slip, s.
    pub fn slips(&self) -> Vec<(f64, f64, f64)> {
        self.segments
            .iter()
            .filter_map(|s| match s.phase {
                Phase::Slip(dir) => Some((s.t0, s.t1, dir)),
                Phase::Stick => None,
            })
            .collect()
    }
}

impl ExactSolution for EpoExact {
    fn name(&self) -> &'static str {
        "exact"
    }

    fn method(&self) -> String {
        format!(
            "exact event-driven solution of the undamped elastic-plastic oscillator: closed form between {} slip/stick events located by bisection",
            self.segments.len().saturating_sub(1)
        )
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        q::sliding(self.forcing.ground_amplitude.is_some())
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        let seg = self.segment_at(t);
        self.write(seg, self.segment_constants(seg), t, out);
    }

    fn sample_into(&self, times: &[f64], trace: &mut rockslide_core::trace::Trace) {
        // the segment's constants, kept while the times stay in it
        let mut constants: Option<(usize, (f64, f64))> = None;
        let segments = &self.segments;
        crate::each_row_by_piece(
            trace,
            times,
            segments,
            |s, t| s.t0 <= t,
            |i, t, out| {
                let seg = self.segment_from(i);
                let c = match constants {
                    Some((j, c)) if j == i => c,
                    _ => self.segment_constants(seg),
                };
                constants = Some((i, c));
                self.write(seg, c, t, out);
            },
        );
    }

    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        let slips = self.slips();
        match (slips.first(), slips.last()) {
            (Some(first), Some(last)) => vec![("slip_start", first.0), ("slip_end", last.1)],
            _ => vec![],
        }
    }
}

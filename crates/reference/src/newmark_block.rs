//! Newmark's rigid-plastic sliding block (Newmark 1965, "Effects of earthquakes on dams
//! and embankments"): a rigid block on a rigid ground with Coulomb friction μ, driven by a
//! sine-pulse ground (or mass) acceleration. The block sticks while the driving
//! acceleration stays within ±μg and slides with the constant friction force μMg
//! otherwise; each phase is integrated in closed form and the slip-start and slip-stop
//! events are located by bisection. Written from the equations of motion alone — it
//! shares nothing with the engines.
//!
//! Relative coordinates: u is the block's displacement relative to the ground,
//! p(t) = F(t)/M the driving acceleration (−ag for ground motion, a for a mass force).
//! Sticking: u' = 0 while |p| ≤ μg. Sliding with s = sign(u'): u'' = p(t) − s·μg.

use super::root::bisect;
use super::{ExactSolution, SineForcing};
use rockslide_core::case::RigidBlock;
use rockslide_core::trace::{Quantity, q};

/// One phase of the motion between two events.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockSegment {
    /// Start, s.
    pub t0: f64,
    /// End, s.
    pub t1: f64,
    /// 0 when stuck, ±1 sliding direction.
    pub s: f64,
    /// Relative displacement at t0, m.
    pub u0: f64,
    /// Relative velocity at t0 (after any jump), m/s.
    pub v0: f64,
}

/// The closed-form sliding history.
#[derive(Debug, Clone)]
pub struct NewmarkBlock {
    m: f64,
    mug: f64,
    forcing: SineForcing,
    /// Phases in time order, covering [0, duration].
    pub segments: Vec<BlockSegment>,
}

impl NewmarkBlock {
    /// Solve `block` under `forcing` over `[0, duration]`. The block must not rock: the
    /// driving acceleration must stay below g·b/h (the overturning-initiation limit).
    pub fn new(block: &RigidBlock, forcing: SineForcing, duration: f64) -> Result<Self, String> {
        let peak = (forcing.p0 / block.mass).abs();
        let tan_alpha = block.half_width / block.half_height;
        if peak >= block.gravity * tan_alpha {
            return Err(format!(
                "Newmark's sliding block assumes no rocking, but the peak driving acceleration {peak} m/s² reaches g·b/h = {} m/s²",
                block.gravity * tan_alpha
            ));
        }
        let mut sol = NewmarkBlock {
            m: block.mass,
            mug: block.mu * block.gravity,
            forcing,
            segments: Vec::new(),
        };
        sol.solve(duration);
        Ok(sol)
    }

    /// Driving acceleration p(t), m/s² (right-continuous).
    fn p(&self, t: f64) -> f64 {
        self.forcing.at(t) / self.m
    }

    /// (∫p, ∫∫p) from 0 to t.
    fn integrals(&self, t: f64) -> (f64, f64) {
        let f = &self.forcing;
        if f.td <= 0.0 || f.p0 == 0.0 {
            return (0.0, 0.0);
        }
        let (a, th) = (f.p0 / self.m, f.theta);
        let tt = t.clamp(0.0, f.td);
        let p1 = a / th * (1.0 - (th * tt).cos());
        let p2 = a / th * (tt - (th * tt).sin() / th);
        (p1, p2 + p1 * (t - tt))
    }

    /// (u, v) at `t` within `seg`.
    fn state_in(&self, seg: &BlockSegment, t: f64) -> (f64, f64) {
        if seg.s == 0.0 {
            return (seg.u0, 0.0);
        }
        let tau = t - seg.t0;
        let (p1a, p2a) = self.integrals(seg.t0);
        let (p1, p2) = self.integrals(t);
        let f = seg.s * self.mug;
        let v = seg.v0 + p1 - p1a - f * tau;
        let u = seg.u0 + seg.v0 * tau + p2 - p2a - p1a * tau - 0.5 * f * tau * tau;
        (u, v)
    }

    fn jump_at(&self, t: f64) -> f64 {
        self.forcing
            .velocity_jumps
            .iter()
            .filter(|(tj, _)| *tj == t)
            .map(|(_, dv)| dv)
            .sum()
    }

    fn solve(&mut self, duration: f64) {
        let td = self.forcing.td;
        let h = if td > 0.0 {
            td.min(duration) / 4000.0
        } else {
            duration / 4000.0
        };
        // Break points where the velocity may jump.
        let mut stops = vec![duration];
        if td > 0.0 && td < duration && self.jump_at(td) != 0.0 {
            stops.insert(0, td);
        }
        let (mut t, mut u, mut v) = (0.0, 0.0, self.jump_at(0.0));
        for (i, &end) in stops.iter().enumerate() {
            if i > 0 {
                v += self.jump_at(t);
            }
            while t < end {
                let s = if v != 0.0 {
                    v.signum()
                } else if self.p(t).abs() > self.mug {
                    self.p(t).signum()
                } else {
                    0.0
                };
                let mut seg = BlockSegment {
                    t0: t,
                    t1: end,
                    s,
                    u0: u,
                    v0: v,
                };
                let event = if s == 0.0 {
                    self.scan(t, end, h, |x| self.p(x).abs() - self.mug)
                } else {
                    self.scan(t + 1e-12 * h, end, h, |x| -s * self.state_in(&seg, x).1)
                };
                seg.t1 = event.unwrap_or(end);
                let (u1, v1) = self.state_in(&seg, seg.t1);
                self.segments.push(seg);
                t = seg.t1;
                u = u1;
                v = if s != 0.0 && event.is_some() { 0.0 } else { v1 };
            }
        }
    }

    /// First time in (a, end] where `f` becomes positive, by scanning with step `h` and
    /// bisecting the bracket.
    fn scan(&self, a: f64, end: f64, h: f64, f: impl Fn(f64) -> f64) -> Option<f64> {
        let mut x0 = a;
        while x0 < end {
            let x1 = (x0 + h).min(end);
            if f(x1) > 0.0 {
                return Some(if f(x0) > 0.0 { x0 } else { bisect(x0, x1, &f) });
            }
            x0 = x1;
        }
        None
    }

    fn segment_at(&self, t: f64) -> &BlockSegment {
        let i = self.segments.partition_point(|s| s.t0 <= t);
        &self.segments[i.saturating_sub(1)]
    }

    /// (u, v) at `t`.
    pub fn state(&self, t: f64) -> (f64, f64) {
        self.state_in(self.segment_at(t), t)
    }

    /// (start, end, direction) of every slide.
    pub fn slides(&self) -> Vec<(f64, f64, f64)> {
        self.segments
            .iter()
            .filter(|s| s.s != 0.0)
            .map(|s| (s.t0, s.t1, s.s))
            .collect()
    }
}

impl ExactSolution for NewmarkBlock {
    fn name(&self) -> &'static str {
        "Newmark"
    }

    fn method(&self) -> String {
        format!(
            "Newmark (1965) rigid-plastic sliding block: closed form between {} stick/slide events located by bisection",
            self.segments.len().saturating_sub(1)
        )
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        q::sliding(false)
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        let seg = *self.segment_at(t);
        let (u, v) = self.state_in(&seg, t);
        let p = self.p(t);
        // M·u'' = F − R: stuck R = F, sliding R = s·μMg.
        let acc = if seg.s == 0.0 {
            0.0
        } else {
            p - seg.s * self.mug
        };
        out[0] = self.m * p;
        out[1] = self.m * (p - acc);
        out[2] = u;
        out[3] = u;
        out[4] = v;
        out[5] = acc;
    }

    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        let slides = self.slides();
        match (slides.first(), slides.last()) {
            (Some(first), Some(last)) => vec![("slip_start", first.0), ("slip_end", last.1)],
            _ => vec![],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block(mu: f64) -> RigidBlock {
        RigidBlock {
            mass: 1.0,
            gravity: 10.0,
            half_width: 1.0,
            half_height: 0.25,
            mu,
            initial_tilt: 0.0,
        }
    }

    #[test]
    fn half_sine_pulse_matches_hand_integration() {
        // ag = A sin θt on [0, π/θ]; the block slides back while A sin θt > μg and until
        // its relative velocity returns to zero. Check against a fine explicit
        // integration of u'' = −ag + μg·[sliding], written independently here.
        let (a, th, mu) = (4.0, std::f64::consts::PI, 0.2);
        let forcing = SineForcing {
            p0: -a,
            theta: th,
            td: 1.0,
            velocity_jumps: vec![],
            ground_amplitude: None,
        };
        let sol = NewmarkBlock::new(&block(mu), forcing, 3.0).unwrap();
        let h = 1e-6;
        let (mut u, mut v, mut t) = (0.0_f64, 0.0_f64, 0.0);
        while t < 3.0 {
            let ag = if t < 1.0 { a * (th * t).sin() } else { 0.0 };
            let acc = if v < 0.0 || -ag < -mu * 10.0 {
                -ag + mu * 10.0
            } else {
                0.0
            };
            v += acc * h;
            if v > 0.0 {
                v = 0.0;
            }
            u += v * h;
            t += h;
        }
        let (u_ref, _) = sol.state(3.0);
        assert!(
            (u_ref - u).abs() < 1e-5 * u.abs(),
            "closed form {u_ref}, explicit {u}"
        );
        // Slide starts where A sin θt = μg.
        let t_start = (mu * 10.0 / a).asin() / th;
        assert!((sol.slides()[0].0 - t_start).abs() < 1e-12);
    }
}

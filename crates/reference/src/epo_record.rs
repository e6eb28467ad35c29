//! The undamped elastic–perfectly-plastic oscillator (the paper's PEPO) under a sampled
//! ground acceleration, exact for the ground acceleration taken piecewise linear between
//! samples (the convention of trapezoidal integration) and zero after the last sample.
//!
//! Relative coordinates: u (mass relative to ground), up (slip), e = u − up (elastic
//! deflection), R = K·e with |R| ≤ Ru, ω² = K/M, ey = Ru/K. In a sample interval the ground
//! acceleration is `a0 + β·τ`:
//! - stuck: `e'' + ω²e = −(a0 + βτ)`, so `e = −(a0 + βτ)/ω² + C cos ωτ + D sin ωτ`;
//! - slipping with direction s: `u'' = −(a0 + βτ) − s·Ru/M`, a cubic in τ.
//!
//! A slip starts where s·e reaches ey: e is monotone between its stationary points, which
//! are known in closed form (`cos(ωτ + φ) = β/(ω³·√(C² + D²))`), so the first monotone piece
//! whose end lies beyond ey brackets the onset, found by bisection to the last float. A
//! slip ends where its velocity returns to zero: the root of a quadratic (stable formula,
//! one Newton polish). |u| is largest at a stationary point or an event, so the peak is
//! exact in continuous time. Written from the equations of motion alone.

use crate::ExactSolution;
use crate::block_record::stop_time;
use rockslide_core::case::{Excitation, Oscillator, Signal};
use rockslide_core::trace::{Quantity, q};

/// Events allowed in one sample interval before the solver reports it is not progressing.
const EVENTS_PER_INTERVAL: usize = 64;
/// Stationary points of the elastic motion allowed in one interval (ω·Δt/π): beyond, the
/// oscillator is too stiff for the record's sampling and the work would not be bounded.
const STATIONARY_PER_INTERVAL: f64 = 1e6;

/// What the contact does during a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Phase {
    Stick,
    Slip(f64),
}

/// A stretch of one interval with one phase, its start state and its ground acceleration.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Segment {
    t0: f64,
    phase: Phase,
    u0: f64,
    v0: f64,
    up0: f64,
    /// Ground acceleration at t0 and its slope, m/s², m/s³.
    a0: f64,
    beta: f64,
}

/// One slip: start, end, direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slip {
    /// Onset, s.
    pub start: f64,
    /// Stop, s (the end of the run if it never stops).
    pub end: f64,
    /// Direction s (+1 or −1).
    pub direction: f64,
    /// Slip added, m (signed).
    pub distance: f64,
}

/// The exact solution of the PEPO under a piecewise-linear ground acceleration.
#[derive(Debug, Clone)]
pub struct EpoRecord {
    m: f64,
    k: f64,
    ru: f64,
    omega: f64,
    dt: f64,
    samples: Vec<f64>,
    segments: Vec<Segment>,
    /// Every slip, in time order.
    pub slips: Vec<Slip>,
    /// Largest |u| in continuous time, m.
    pub peak_abs_u: f64,
    /// Slip at the onset of the current slip, m.
    slip_up0: f64,
    /// End of the run, s.
    end: f64,
}

type State = (f64, f64, f64, f64);

impl EpoRecord {
    /// The reference for an oscillator driven by a recorded excitation, or why there is none.
    pub fn for_excitation(
        osc: &Oscillator,
        excitation: &Excitation,
        duration: f64,
    ) -> Result<Self, String> {
        let (sign, signal) = match excitation {
            Excitation::GroundAcceleration(s) => (1.0, s),
            // a force M·a on the mass is a ground acceleration −a
            Excitation::MassAcceleration(s) => (-1.0, s),
            _ => {
                return Err(
                    "the exact record reference takes a ground or mass acceleration record".into(),
                );
            }
        };
        let Signal::Record { dt, samples, .. } = signal else {
            return Err("not a record".into());
        };
        let ground: Vec<f64> = samples.iter().map(|a| sign * a).collect();
        Self::new(osc, *dt, ground, duration)
    }

    /// Solve `osc` under the ground acceleration `samples` (m/s², every `dt` s, linear in
    /// between, zero after the last) over `[0, duration]`.
    pub fn new(
        osc: &Oscillator,
        dt: f64,
        samples: Vec<f64>,
        duration: f64,
    ) -> Result<Self, String> {
        if osc.damping_ratio != 0.0 {
            return Err(
                "the exact elastic-plastic record reference is for the undamped oscillator".into(),
            );
        }
        let omega = (osc.contact.kx / osc.mass).sqrt();
        let ru = osc.contact.mu * osc.mass * osc.gravity;
        check(omega, ru, dt, &samples, duration)?;
        let mut sol = EpoRecord {
            m: osc.mass,
            k: osc.contact.kx,
            ru,
            omega,
            dt,
            samples,
            segments: Vec::new(),
            slips: Vec::new(),
            peak_abs_u: 0.0,
            slip_up0: 0.0,
            end: duration,
        };
        sol.solve(duration)?;
        Ok(sol)
    }

    /// Sample intervals of the record within the run, then the quiet tail as one.
    fn intervals(&self, duration: f64) -> Vec<(f64, f64, f64, f64)> {
        let n = self.samples.len();
        let mut out = Vec::with_capacity(n + 1);
        for i in 1..n {
            let t0 = (i - 1) as f64 * self.dt;
            if t0 >= duration {
                return out;
            }
            let t1 = (i as f64 * self.dt).min(duration);
            let (a0, a1) = (self.samples[i - 1], self.samples[i]);
            out.push((t0, t1, a0, (a1 - a0) / self.dt));
        }
        let end = n.saturating_sub(1) as f64 * self.dt;
        if end < duration {
            out.push((end, duration, 0.0, 0.0));
        }
        out
    }

    fn solve(&mut self, duration: f64) -> Result<(), String> {
        let mut seg = Segment {
            t0: 0.0,
            phase: Phase::Stick,
            u0: 0.0,
            v0: 0.0,
            up0: 0.0,
            a0: 0.0,
            beta: 0.0,
        };
        for (t0, t1, a0, beta) in self.intervals(duration) {
            let h = t1 - t0;
            if self.omega * h / std::f64::consts::PI > STATIONARY_PER_INTERVAL {
                return Err(format!(
                    "ω·Δt = {:.3e} rad in the interval at t = {t0} s: the oscillator (ω = {:.3e} rad/s) is too stiff for an exact solution over this sampling",
                    self.omega * h,
                    self.omega
                ));
            }
            seg = Segment {
                t0,
                a0,
                beta,
                ..seg
            };
            seg = self.interval(seg, t1)?;
        }
        self.close(duration);
        Ok(())
    }

    /// Walk one interval from `seg` (its start state) to `t1`, pushing segments; returns
    /// the state at `t1` as the next segment's start.
    fn interval(&mut self, mut seg: Segment, t1: f64) -> Result<Segment, String> {
        let t_start = seg.t0;
        for _ in 0..EVENTS_PER_INTERVAL {
            self.segments.push(seg);
            let event = match seg.phase {
                Phase::Stick => self.slip_onset(&seg, t1),
                Phase::Slip(s) => self.slip_stop(&seg, s, t1),
            };
            let te = event.map_or(t1, |e| e.0);
            self.note_stationary_peaks(&seg, te);
            let Some((te, next)) = event else {
                let end = self.state_in(&seg, t1);
                self.note_peak(end.0);
                if let Phase::Slip(_) = seg.phase {
                    self.extend_slip(t1, end.3);
                }
                return Ok(self.start_of(&seg, t1, seg.phase, end));
            };
            let mut st = self.state_in(&seg, te);
            self.note_peak(st.0);
            match next {
                Phase::Slip(s) => {
                    self.slips.push(Slip {
                        start: te,
                        end: te,
                        direction: s,
                        distance: 0.0,
                    });
                    // the contact is at ±Ru exactly when it starts to slip
                    st.3 = st.0 - s * self.ru / self.k;
                    self.slip_up0 = st.3;
                }
                Phase::Stick => {
                    let Phase::Slip(s) = seg.phase else {
                        unreachable!()
                    };
                    st.1 = 0.0; // a slip stops at exactly zero slip rate
                    st.3 = st.0 - s * self.ru / self.k;
                    self.extend_slip(te, st.3);
                }
            }
            seg = self.start_of(&seg, te, next, st);
        }
        Err(format!(
            "more than {EVENTS_PER_INTERVAL} slip/stick events in the sample interval at t = {t_start} s: the exact reference is not progressing"
        ))
    }

    fn start_of(&self, seg: &Segment, t: f64, phase: Phase, st: State) -> Segment {
        Segment {
            t0: t,
            phase,
            u0: st.0,
            v0: st.1,
            up0: st.3,
            a0: seg.a0 + seg.beta * (t - seg.t0),
            beta: seg.beta,
        }
    }

    fn note_peak(&mut self, u: f64) {
        self.peak_abs_u = self.peak_abs_u.max(u.abs());
    }

    /// |u| at the stationary points of a stuck segment ending at `te`.
    fn note_stationary_peaks(&mut self, seg: &Segment, te: f64) {
        if seg.phase != Phase::Stick {
            return;
        }
        for tau in self.stationary(seg, te - seg.t0) {
            let u = self.state_in(seg, seg.t0 + tau).0;
            self.note_peak(u);
        }
    }

    fn extend_slip(&mut self, t: f64, up: f64) {
        let up0 = self.slip_up0;
        if let Some(slip) = self.slips.last_mut() {
            slip.end = t;
            slip.distance = up - up0;
        }
    }

    /// A slip still under way at the end of the run ends there.
    fn close(&mut self, duration: f64) {
        if let Some(last) = self.segments.last().copied() {
            if let Phase::Slip(_) = last.phase {
                let st = self.state_in(&last, duration);
                self.extend_slip(duration, st.3);
            }
        }
    }

    /// Stationary points of the elastic motion in (0, h), in order (ωτ values).
    fn stationary(&self, seg: &Segment, h: f64) -> Vec<f64> {
        let w = self.omega;
        let (c, d) = self.stick_coefficients(seg);
        let amp = c.hypot(d);
        let mut out = Vec::new();
        if amp == 0.0 {
            return out;
        }
        let ratio = seg.beta / (w * w * w * amp);
        if ratio.abs() > 1.0 {
            return out;
        }
        // v = 0 ⇔ D cos x − C sin x = β/ω³ ⇔ cos(x + φ) = ratio, φ = atan2(C, D)
        let phi = c.atan2(d);
        let alpha = ratio.acos();
        let x_end = w * h;
        let two_pi = 2.0 * std::f64::consts::PI;
        for base in [alpha - phi, -alpha - phi] {
            let mut x = base - two_pi * (base / two_pi).floor();
            while x < x_end {
                if x > 0.0 {
                    out.push(x / w);
                }
                x += two_pi;
            }
        }
        out.sort_by(f64::total_cmp);
        out
    }

    /// First onset of slip in the stuck segment before `t1`.
    fn slip_onset(&self, seg: &Segment, t1: f64) -> Option<(f64, Phase)> {
        if !self.ru.is_finite() {
            return None;
        }
        let ey = self.ru / self.k;
        let tol = 1e-12 * ey;
        let e0 = seg.u0 - seg.up0;
        let e2 = -seg.a0 - self.omega * self.omega * e0;
        for s in [1.0, -1.0] {
            let outward = s * seg.v0 > 0.0 || (seg.v0 == 0.0 && s * e2 > 0.0);
            if s * e0 >= ey - tol && outward {
                return Some((seg.t0, Phase::Slip(s)));
            }
        }
        let h = t1 - seg.t0;
        let g = |tau: f64, s: f64| {
            let (u, _, _, up) = self.state_in(seg, seg.t0 + tau);
            s * (u - up) - ey
        };
        let mut a = 0.0;
        let mut ends = self.stationary(seg, h);
        ends.push(h);
        for b in ends {
            for s in [1.0, -1.0] {
                if g(b, s) > tol {
                    let tau = first_above(a, b, |x| g(x, s));
                    return Some((seg.t0 + tau, Phase::Slip(s)));
                }
            }
            a = b;
        }
        None
    }

    /// Where the slip rate of a slipping segment returns to zero before `t1`.
    fn slip_stop(&self, seg: &Segment, s: f64, t1: f64) -> Option<(f64, Phase)> {
        let c = seg.a0 + s * self.ru / self.m;
        let mut w0 = (s * seg.v0).max(0.0);
        let mut r0 = -s * c;
        if seg.v0 * s <= 0.0 {
            w0 = 0.0;
            r0 = r0.max(0.0);
        }
        stop_time(w0, r0, -s * seg.beta, t1 - seg.t0).map(|tau| (seg.t0 + tau, Phase::Stick))
    }

    fn stick_coefficients(&self, seg: &Segment) -> (f64, f64) {
        let w2 = self.omega * self.omega;
        let e0 = seg.u0 - seg.up0;
        (e0 + seg.a0 / w2, (seg.v0 + seg.beta / w2) / self.omega)
    }

    /// (u, v, R, up) at `t` within `seg`.
    fn state_in(&self, seg: &Segment, t: f64) -> State {
        let tau = t - seg.t0;
        let (a0, beta) = (seg.a0, seg.beta);
        match seg.phase {
            Phase::Stick => {
                let w = self.omega;
                let w2 = w * w;
                let (c, d) = self.stick_coefficients(seg);
                let (sn, cs) = (w * tau).sin_cos();
                let e = -(a0 + beta * tau) / w2 + c * cs + d * sn;
                let v = -beta / w2 - c * w * sn + d * w * cs;
                (seg.up0 + e, v, self.k * e, seg.up0)
            }
            Phase::Slip(s) => {
                let c = a0 + s * self.ru / self.m;
                let v = seg.v0 - c * tau - beta * tau * tau / 2.0;
                let u = seg.u0 + seg.v0 * tau - c * tau * tau / 2.0 - beta * tau * tau * tau / 6.0;
                let r = s * self.ru;
                (u, v, r, u - r / self.k)
            }
        }
    }

    fn segment_at(&self, t: f64) -> &Segment {
        self.segment_from(self.segments.partition_point(|s| s.t0 <= t))
    }

    /// The segment before partition point `i` of the segments' starts (the first).
    fn segment_from(&self, i: usize) -> &Segment {
        &self.segments[i.saturating_sub(1)]
    }

    /// The channels at `t` in `seg` (the segment holding `t`), in
    /// [`ExactSolution::channels`] order.
    fn write(&self, seg: &Segment, t: f64, out: &mut [f64]) {
        let (u, v, r, up) = self.state_in(seg, t);
        let p = -self.m * (seg.a0 + seg.beta * (t - seg.t0));
        out[0] = p;
        out[1] = r;
        out[2] = u;
        out[3] = up;
        out[4] = v;
        out[5] = (p - r) / self.m;
    }

    /// (u, v, R, up) at `t`.
    pub fn state(&self, t: f64) -> State {
        self.state_in(self.segment_at(t), t)
    }

    /// Ground acceleration at `t`, m/s² (linear between samples, zero after the last).
    pub fn ground_acceleration(&self, t: f64) -> f64 {
        let seg = self.segment_at(t);
        seg.a0 + seg.beta * (t - seg.t0)
    }

    /// Largest |slip| over the run, m (slip changes only while slipping, monotonically, so
    /// its extremes are at the segment starts and the end).
    pub fn peak_abs_slip(&self) -> f64 {
        let end = self
            .segments
            .last()
            .map_or(0.0, |s| self.state_in(s, self.end).3.abs());
        self.segments.iter().fold(end, |m, s| m.max(s.up0.abs()))
    }

    /// Sum of |slip| over the slips, m.
    pub fn total_slid(&self) -> f64 {
        self.slips.iter().map(|s| s.distance.abs()).sum()
    }
}

fn check(omega: f64, ru: f64, dt: f64, samples: &[f64], duration: f64) -> Result<(), String> {
    if !(omega.is_finite() && omega > 0.0) {
        return Err(format!(
            "natural frequency ω = √(Kx/M) = {omega} rad/s is not a positive finite number"
        ));
    }
    if ru.is_nan() || ru < 0.0 {
        return Err(format!("friction limit Ru = μ·M·g = {ru} N is not ≥ 0"));
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(format!(
            "record sample interval {dt} s is not a positive finite number"
        ));
    }
    if !(duration.is_finite() && duration >= 0.0) {
        return Err(format!("duration {duration} s is not a finite number ≥ 0"));
    }
    if samples.is_empty() {
        return Err("the record has no samples".into());
    }
    if let Some(i) = samples.iter().position(|a| !a.is_finite()) {
        return Err(format!("record sample {i} is not finite"));
    }
    Ok(())
}

/// First x in [a, b] with f(x) > 0, given f(b) > 0 and f monotone on [a, b]: bisection to
/// adjacent floats (returns a when f(a) > 0 already).
fn first_above(mut a: f64, mut b: f64, f: impl Fn(f64) -> f64) -> f64 {
    if f(a) > 0.0 {
        return a;
    }
    for _ in 0..crate::root::BISECTION_LIMIT {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if f(m) > 0.0 {
            b = m;
        } else {
            a = m;
        }
    }
    b
}

impl ExactSolution for EpoRecord {
    fn name(&self) -> &'static str {
        "exact"
    }

    fn method(&self) -> String {
        format!(
            "exact solution of the undamped elastic-plastic oscillator for the ground acceleration piecewise linear between samples: closed form in each sample interval, {} slips located by root finding between analytic stationary points",
            self.slips.len()
        )
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        q::sliding(false)
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        self.write(self.segment_at(t), t, out);
    }

    fn sample_into(&self, times: &[f64], trace: &mut rockslide_core::trace::Trace) {
        crate::each_row_by_piece(
            trace,
            times,
            &self.segments,
            |s, t| s.t0 <= t,
            |i, t, out| {
                self.write(self.segment_from(i), t, out);
            },
        );
    }

    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        let mut q = vec![("peak_relative_displacement", self.peak_abs_u)];
        if let (Some(first), Some(last)) = (self.slips.first(), self.slips.last()) {
            q.push(("slip_start", first.start));
            q.push(("slip_end", last.end));
        }
        // the slip is monotone within a slip, so its extremes are at slip ends
        let (mut up, mut peak_abs, mut total) = (0.0_f64, 0.0_f64, 0.0);
        for s in &self.slips {
            up += s.distance;
            peak_abs = peak_abs.max(up.abs());
            total += s.distance.abs();
        }
        q.push(("peak_abs_sliding", peak_abs));
        q.push(("total_slid", total));
        q.push(("slip_episodes", self.slips.len() as f64));
        q
    }
}

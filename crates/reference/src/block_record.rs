//! The rigid-plastic sliding block (Newmark 1965) under a sampled acceleration, exact for
//! the ground acceleration taken piecewise linear between samples.
//!
//! The block follows a driving acceleration `d(t)` (linear in each sample interval) while
//! it sticks; it slides in direction σ once σ·d exceeds the yield acceleration ky, and then
//! its sliding velocity obeys `dv/dt = d(t) − σ·ky` until v returns to zero. In each
//! interval every event is located in closed form: an onset where the linear σ·d(t)
//! crosses ky, a stop at the root of the quadratic v(t) (stable formula, one Newton
//! polish), a direct reversal when the block stops with −σ·d already beyond ky. There is
//! no fixed cap on the events in an interval: each pass of the loop either advances time
//! or changes the phase in a way that must advance time next, and a pass that does
//! neither ends the run with an error rather than a silent skip.

use rockslide_core::case::limits;
use rockslide_core::case::record::MIN_DT;

/// Whether the block may slide both ways or only with σ = +1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sliding {
    /// Slides only with σ = +1 (SLAMMER's one-way rigid block).
    OneWay,
    /// Slides either way with the same ky (a block on a level frictional base).
    TwoWay,
}

/// One slide: start, end, direction and the displacement it adds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slide {
    /// Onset, s.
    pub start: f64,
    /// Stop, s (the end of the run if it never stops).
    pub end: f64,
    /// Direction σ (+1 or −1).
    pub direction: f64,
    /// Displacement added, m (signed).
    pub distance: f64,
}

/// The exact history of a block under a record, at the samples and at its events.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockRecord {
    /// Sample interval, s.
    pub dt: f64,
    /// Sliding velocity at each sample (tail included), m/s.
    pub vel: Vec<f64>,
    /// Accumulated sliding displacement at each sample (tail included), m.
    pub disp: Vec<f64>,
    /// Every slide, in time order (a direct reversal starts a new one).
    pub slides: Vec<Slide>,
    /// Largest |displacement| in continuous time, m.
    pub peak_abs: f64,
}

/// Events allowed per sample interval before the solver declares it is not progressing.
/// A linear drive admits at most an onset, a stop and a reversal's onset and stop; the
/// bound is generous and only turns a rounding loop into an error.
const EVENTS_PER_INTERVAL: usize = 64;

impl BlockRecord {
    /// Solve for the drive `acc` (m/s², samples every `dt` s, linear in between, zero
    /// after the last sample for `tail` more seconds), yield acceleration `ky` ≥ 0.
    pub fn solve(
        dt: f64,
        acc: &[f64],
        ky: f64,
        sliding: Sliding,
        tail: f64,
    ) -> Result<Self, String> {
        check_inputs(dt, acc, ky, tail)?;
        let extra = (tail / dt).ceil() as usize;
        let n = acc.len() + extra;
        let a_at = |i: usize| acc.get(i).copied().unwrap_or(0.0);
        let mut state = Walker::new(ky, sliding);
        let mut vel = Vec::with_capacity(n);
        let mut disp = Vec::with_capacity(n);
        if n > 0 {
            vel.push(0.0);
            disp.push(0.0);
        }
        for i in 1..n {
            let t0 = (i - 1) as f64 * dt;
            state.interval(t0, dt, a_at(i - 1), a_at(i))?;
            vel.push(state.v);
            disp.push(state.u);
        }
        let end = n.saturating_sub(1) as f64 * dt;
        state.close(end);
        Ok(BlockRecord {
            dt,
            vel,
            disp,
            slides: state.slides,
            peak_abs: state.peak_abs,
        })
    }

    /// Final displacement, m.
    pub fn residual(&self) -> f64 {
        self.disp.last().copied().unwrap_or(0.0)
    }

    /// Sum of |distance| over the slides, m.
    pub fn total_slid(&self) -> f64 {
        self.slides.iter().map(|s| s.distance.abs()).sum()
    }

    /// Number of slides.
    pub fn episodes(&self) -> usize {
        self.slides.len()
    }
}

fn check_inputs(dt: f64, acc: &[f64], ky: f64, tail: f64) -> Result<(), String> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(format!(
            "sample interval {dt} s is not a positive finite number"
        ));
    }
    if dt < MIN_DT {
        return Err(format!(
            "sample interval {dt:e} s is below the smallest a record may have ({MIN_DT:e} s)"
        ));
    }
    if !(ky.is_finite() && ky >= 0.0) {
        return Err(format!(
            "yield acceleration {ky} m/s² is not a finite number ≥ 0"
        ));
    }
    if !(tail.is_finite() && tail >= 0.0) {
        return Err(format!("tail {tail} s is not a finite number ≥ 0"));
    }
    if let Some(i) = acc.iter().position(|a| !a.is_finite()) {
        return Err(format!("sample {i} of the record is not finite"));
    }
    // each sample keeps a velocity and a displacement: held to the step limit
    let intervals = tail / dt + acc.len() as f64;
    let limit = limits::max_steps();
    if intervals > limit as f64 {
        return Err(format!(
            "{intervals:.3e} sample intervals (record plus a {tail:e} s tail at {dt:e} s): \
             more than the limit of {limit} (set {} to raise it)",
            limits::MAX_STEPS_VARIABLE
        ));
    }
    Ok(())
}

/// The solver's running state (also stepped over part of an interval by
/// [`crate::block_case`] to evaluate between samples).
pub(crate) struct Walker {
    ky: f64,
    sliding: Sliding,
    /// Velocity and displacement.
    pub(crate) v: f64,
    pub(crate) u: f64,
    /// Direction of the current slide, 0 when stuck.
    pub(crate) sigma: f64,
    pub(crate) slides: Vec<Slide>,
    peak_abs: f64,
}

impl Walker {
    pub(crate) fn new(ky: f64, sliding: Sliding) -> Self {
        Walker {
            ky,
            sliding,
            v: 0.0,
            u: 0.0,
            sigma: 0.0,
            slides: Vec::new(),
            peak_abs: 0.0,
        }
    }

    /// Advance over one interval `[t0, t0 + h]` with the drive linear from `a0` to `a1`.
    pub(crate) fn interval(&mut self, t0: f64, h: f64, a0: f64, a1: f64) -> Result<(), String> {
        let slope = (a1 - a0) / h;
        let mut s = 0.0; // time used within the interval
        for _ in 0..EVENTS_PER_INTERVAL {
            if s >= h {
                return Ok(());
            }
            let d0 = a0 + slope * s;
            if self.sigma == 0.0 {
                match self.onset(d0, slope, h - s) {
                    Some((dir, tau)) => {
                        s += tau;
                        self.start(t0 + s, dir);
                    }
                    None => return Ok(()),
                }
            } else {
                s += self.slide(d0, slope, h - s, t0 + s);
            }
        }
        Err(format!(
            "more than {EVENTS_PER_INTERVAL} stick/slide events in the sample interval at t = {t0} s: the rigid-block reference is not progressing"
        ))
    }

    /// Earliest (direction, delay) within `[0, span]` at which the drive `d0 + slope·τ`
    /// exceeds ky, or does so from now on (σ·d = ky and rising), if it does.
    fn onset(&self, d0: f64, slope: f64, span: f64) -> Option<(f64, f64)> {
        let dirs: &[f64] = match self.sliding {
            Sliding::OneWay => &[1.0],
            Sliding::TwoWay => &[1.0, -1.0],
        };
        let mut best: Option<(f64, f64)> = None;
        for &dir in dirs {
            let r0 = dir * d0 - self.ky; // > 0: beyond yield in direction dir
            let rate = dir * slope;
            let tau = if r0 > 0.0 || (r0 == 0.0 && rate > 0.0) {
                0.0
            } else if rate > 0.0 && r0 + rate * span > 0.0 {
                (-r0 / rate).min(span)
            } else {
                continue;
            };
            if best.is_none_or(|(_, b)| tau < b) {
                best = Some((dir, tau));
            }
        }
        best
    }

    fn start(&mut self, t: f64, dir: f64) {
        self.sigma = dir;
        self.v = 0.0;
        self.slides.push(Slide {
            start: t,
            end: t,
            direction: dir,
            distance: 0.0,
        });
    }

    /// Slide from now for at most `span` with the drive `d0 + slope·τ`; returns the time
    /// used (up to the stop, or `span`).
    fn slide(&mut self, d0: f64, slope: f64, span: f64, t: f64) -> f64 {
        let sigma = self.sigma;
        // w = σ·v ≥ 0 obeys w' = r0 + ρτ.
        let (w0, mut r0, rho) = (sigma * self.v, sigma * d0 - self.ky, sigma * slope);
        if w0 == 0.0 {
            // just started: the drive is at or beyond yield (a computed crossing may leave
            // a rounding residue below it, which must not stop the slide at once)
            r0 = r0.max(0.0);
        }
        let stop = stop_time(w0, r0, rho, span);
        let tau = stop.unwrap_or(span);
        let dw = w0 * tau + r0 * tau * tau / 2.0 + rho * tau * tau * tau / 6.0;
        self.u += sigma * dw;
        self.peak_abs = self.peak_abs.max(self.u.abs());
        let slide = self.slides.last_mut().expect("a slide has started");
        slide.distance += sigma * dw;
        slide.end = t + tau;
        if stop.is_some() {
            self.v = 0.0;
            self.sigma = 0.0;
        } else {
            self.v = sigma * (w0 + r0 * tau + rho * tau * tau / 2.0);
        }
        tau
    }

    /// After the last sample: a slide still under way decelerates at ky to rest.
    fn close(&mut self, end: f64) {
        if self.sigma == 0.0 {
            return;
        }
        if let Some(slide) = self.slides.last_mut() {
            slide.end = slide.end.max(end);
        }
    }
}

/// First τ in (0, span] at which w(τ) = w0 + r0·τ + ρτ²/2 (w0 ≥ 0) returns to zero from
/// above, if it does: the stable quadratic root, polished by one Newton step.
pub(crate) fn stop_time(w0: f64, r0: f64, rho: f64, span: f64) -> Option<f64> {
    let w = |t: f64| w0 + r0 * t + rho * t * t / 2.0;
    let mut roots = [f64::NAN; 2];
    if w0 == 0.0 {
        // w = τ(r0 + ρτ/2): the start is a root; the other is −2r0/ρ.
        if rho != 0.0 {
            roots[0] = -2.0 * r0 / rho;
        }
    } else if rho == 0.0 {
        if r0 != 0.0 {
            roots[0] = -w0 / r0;
        }
    } else {
        let disc = r0 * r0 - 2.0 * rho * w0;
        if disc >= 0.0 {
            // Numerical Recipes §5.6: q = −(b + sgn(b)·√disc)/2, roots q/a and c/q.
            let q = -0.5 * (r0 + r0.signum() * disc.sqrt());
            if q != 0.0 {
                roots[0] = q / (rho / 2.0);
                roots[1] = w0 / q;
            }
        }
    }
    let first = roots
        .into_iter()
        .filter(|t| t.is_finite() && *t > 0.0 && *t <= span)
        .fold(None, |m: Option<f64>, t| Some(m.map_or(t, |m| m.min(t))));
    match first {
        Some(t) => {
            let slope = r0 + rho * t;
            let polished = if slope != 0.0 { t - w(t) / slope } else { t };
            Some(if polished > 0.0 && polished <= span {
                polished
            } else {
                t
            })
        }
        // rounding: w ends at or below zero with no root found inside
        None if w(span) <= 0.0 && (w0 > 0.0 || r0 > 0.0 || rho > 0.0) => Some(span),
        None => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found by the `python_references` fuzz target: a tail of 1e9 s at 0.01 s passed the
    /// old bound of 1e9 intervals and reserved 3.4 GB before solving.
    #[test]
    fn a_tail_beyond_the_step_limit_is_refused_before_allocating() {
        let why = BlockRecord::solve(0.01, &[1.0; 3], 0.1, Sliding::TwoWay, 1e9).unwrap_err();
        assert!(why.starts_with("1.000e11 sample intervals"), "{why}");
        assert!(why.contains("more than the limit of"), "{why}");
        // within the limit it solves: 1e5 s of tail at 0.01 s is 1e7 intervals
        assert!(BlockRecord::solve(0.01, &[1.0; 3], 0.1, Sliding::TwoWay, 1e4).is_ok());
    }

    #[test]
    fn constant_drive_from_rest_is_exact() {
        // d = 3, ky = 1 for 1 s: v = 2t, u = t².
        let r = BlockRecord::solve(0.01, &[3.0; 101], 1.0, Sliding::OneWay, 0.0).unwrap();
        assert!((r.disp[100] - 1.0).abs() < 1e-12, "{}", r.disp[100]);
        assert_eq!(r.episodes(), 1);
    }

    #[test]
    fn stop_time_of_a_falling_velocity() {
        // w = 1 − τ²/2 ⇒ τ = √2
        let t = stop_time(1.0, 0.0, -1.0, 3.0).unwrap();
        assert!((t - 2f64.sqrt()).abs() < 1e-15);
        assert_eq!(stop_time(1.0, 0.0, -1.0, 1.0), None);
    }

    #[test]
    fn bad_inputs_are_errors() {
        assert!(BlockRecord::solve(0.0, &[1.0], 1.0, Sliding::OneWay, 0.0).is_err());
        assert!(BlockRecord::solve(0.01, &[f64::NAN], 1.0, Sliding::OneWay, 0.0).is_err());
        assert!(BlockRecord::solve(1e-300, &[1.0], 1.0, Sliding::OneWay, 1.0).is_err());
    }
}

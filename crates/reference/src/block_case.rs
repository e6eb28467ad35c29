//! A rigid block on a level frictional base under a recorded excitation — the case
//! reference for `kind = "rigid-block"` with a record: the two-way rigid-plastic block of
//! [`crate::block_record`] (exact for the acceleration piecewise linear between samples),
//! evaluated at any instant by re-solving the sub-interval from the sample before it.
//!
//! Relative coordinates, as [`crate::NewmarkBlock`]: the drive is the force per unit mass
//! on the block, −ag for a ground acceleration, a for a mass acceleration; the block slides
//! once |drive| exceeds ky = μ·g.

use crate::ExactSolution;
use crate::block_record::{BlockRecord, Slide, Sliding, Walker};
use rockslide_core::case::{Excitation, RigidBlock, Signal};
use rockslide_core::trace::{Quantity, q};

/// The exact sliding of a rigid block under a record.
#[derive(Debug, Clone)]
pub struct BlockOnRecord {
    m: f64,
    ky: f64,
    dt: f64,
    /// Drive per unit mass at the samples, m/s².
    drive: Vec<f64>,
    /// The exact history at the samples and its slides.
    pub solution: BlockRecord,
}

impl BlockOnRecord {
    /// The reference for a rigid block driven by a record over `[0, duration]`, or why
    /// there is none (not a record; the block would rock).
    pub fn for_excitation(
        block: &RigidBlock,
        excitation: &Excitation,
        duration: f64,
    ) -> Result<Self, String> {
        let (sign, signal) = match excitation {
            Excitation::GroundAcceleration(s) => (-1.0, s),
            Excitation::MassAcceleration(s) => (1.0, s),
            _ => {
                return Err(
                    "the exact rigid-block record reference takes a ground or mass acceleration record"
                        .into(),
                );
            }
        };
        let Signal::Record { dt, samples, .. } = signal else {
            return Err("not a record".into());
        };
        let drive: Vec<f64> = samples.iter().map(|a| sign * a).collect();
        let peak = drive.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
        let tipping = block.gravity * block.half_width / block.half_height;
        if block.initial_tilt != 0.0 || peak > tipping {
            return Err(format!(
                "the block may rock (peak drive {peak:.4} m/s² against g·b/h = {tipping:.4} m/s², \
                 initial tilt {} rad): no exact reference for rocking under a record",
                block.initial_tilt
            ));
        }
        let ky = block.mu * block.gravity;
        let tail = (duration - *dt * samples.len().saturating_sub(1) as f64).max(0.0) + dt;
        let solution = BlockRecord::solve(*dt, &drive, ky, Sliding::TwoWay, tail)?;
        Ok(BlockOnRecord {
            m: block.mass,
            ky,
            dt: *dt,
            drive,
            solution,
        })
    }

    /// Drive at `t`: linear between samples and over the interval after the last sample
    /// (to zero), zero after — as the solver takes it.
    fn drive_at(&self, t: f64) -> f64 {
        let at = |i: usize| self.drive.get(i).copied().unwrap_or(0.0);
        let x = (t / self.dt).max(0.0);
        let i = x.floor() as usize;
        let f = x - i as f64;
        at(i) * (1.0 - f) + at(i.saturating_add(1)) * f
    }

    /// (displacement, velocity, sliding direction) at `t`: the sample before `t`, then
    /// the solver's own interval step over the rest.
    fn state(&self, t: f64) -> (f64, f64, f64) {
        let s = &self.solution;
        let last = s.disp.len().saturating_sub(1);
        let i = ((t.max(0.0) / self.dt).floor() as usize).min(last);
        let (u, v) = (s.disp[i], s.vel[i]);
        let ti = i as f64 * self.dt;
        let h = t.min(last as f64 * self.dt) - ti;
        let sigma = if v > 0.0 {
            1.0
        } else if v < 0.0 {
            -1.0
        } else {
            0.0
        };
        if h <= 0.0 {
            return (u, v, sigma);
        }
        let mut w = Walker::new(self.ky, Sliding::TwoWay);
        (w.u, w.v, w.sigma) = (u, v, sigma);
        if sigma != 0.0 {
            w.slides.push(Slide {
                start: ti,
                end: ti,
                direction: sigma,
                distance: 0.0,
            });
        }
        match w.interval(ti, h, self.drive_at(ti), self.drive_at(ti + h)) {
            Ok(()) => (w.u, w.v, w.sigma),
            Err(_) => (f64::NAN, f64::NAN, 0.0),
        }
    }

    /// Slip episodes as a trace read step by step sees them: slides separated by a stick
    /// of positive length (a direct reversal continues the episode).
    pub fn episodes(&self) -> usize {
        let slides = &self.solution.slides;
        slides
            .iter()
            .enumerate()
            .filter(|&(i, s)| i == 0 || s.start > slides[i - 1].end)
            .count()
    }
}

impl ExactSolution for BlockOnRecord {
    fn name(&self) -> &'static str {
        "Newmark (record)"
    }

    fn method(&self) -> String {
        format!(
            "exact two-way rigid-plastic block (Newmark 1965) for the acceleration piecewise linear between samples: closed form in each sample interval, {} slides located in closed form",
            self.solution.slides.len()
        )
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        q::sliding(false)
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        let (u, v, sigma) = self.state(t);
        let d = self.drive_at(t);
        // M·u'' = F − R: stuck R = F, sliding R = σ·μMg.
        let acc = if sigma == 0.0 {
            0.0
        } else {
            d - sigma * self.ky
        };
        out[0] = self.m * d;
        out[1] = self.m * (d - acc);
        out[2] = u;
        out[3] = u;
        out[4] = v;
        out[5] = acc;
    }

    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        let s = &self.solution;
        let mut q = vec![
            ("peak_relative_displacement", s.peak_abs),
            ("peak_abs_sliding", s.peak_abs),
            ("total_slid", s.total_slid()),
            ("slip_episodes", self.episodes() as f64),
        ];
        if let (Some(first), Some(last)) = (s.slides.first(), s.slides.last()) {
            q.push(("slip_start", first.start));
            q.push(("slip_end", last.end));
        }
        q
    }
}

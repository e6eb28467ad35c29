//! Plot data of a streamed run at full resolution in fixed memory: for
//! every channel, the minimum and the maximum — each with its time — of each of
//! [`ENVELOPE_BUCKETS`] equal slices of the run's duration, folded over **every** step as
//! the run streams. A figure drawn from it shows what a figure of the whole trace shows
//! (a spike between two kept rows included), whatever the run's length: the memory is
//! channels × buckets, allocated once before the first step.
//!
//! [`Envelope::of_trace`] folds a whole trace the same way, row by row, so a streamed
//! run's envelope equals its whole run's bit for bit (tests/all/plot_envelope.rs).

use rockslide_core::trace::{Quantity, Trace};

/// Time slices of an envelope: more than the pixel columns of any time-history figure's
/// plot area (1,000 px wide), so each column draws the extremes of the steps it covers.
pub const ENVELOPE_BUCKETS: usize = 2000;

/// The extremes of one channel over one time slice: the first row of the smallest value
/// and the first row of the largest, with their times.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremes {
    /// Time of the minimum, s.
    pub t_min: f64,
    /// The minimum.
    pub min: f64,
    /// Time of the maximum, s.
    pub t_max: f64,
    /// The maximum.
    pub max: f64,
}

/// Per-slice extremes of every channel of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Envelope {
    /// The channels, in the trace's column order.
    pub channels: Vec<&'static Quantity>,
    /// The span the slices divide, [0, duration] s (a later row falls in the last slice).
    pub duration: f64,
    /// Slices.
    pub buckets: usize,
    /// Whether a slice has seen a row.
    seen: Vec<bool>,
    /// Channel-major: `extremes[channel * buckets + bucket]`.
    extremes: Vec<Extremes>,
}

impl Envelope {
    /// An empty envelope of `channels` over [0, `duration`] in `buckets` slices (at least one).
    pub fn new(channels: &[&'static Quantity], duration: f64, buckets: usize) -> Self {
        let buckets = buckets.max(1);
        let none = Extremes {
            t_min: 0.0,
            min: 0.0,
            t_max: 0.0,
            max: 0.0,
        };
        Self {
            channels: channels.to_vec(),
            duration,
            buckets,
            seen: vec![false; buckets],
            extremes: vec![none; channels.len() * buckets],
        }
    }

    /// The envelope of a whole trace: its rows folded in order, as a streamed run folds them.
    pub fn of_trace(trace: &Trace, duration: f64, buckets: usize) -> Self {
        let mut e = Self::new(&trace.channels, duration, buckets);
        let mut row = vec![0.0; trace.channels.len()];
        for (i, &t) in trace.time.iter().enumerate() {
            for (v, column) in row.iter_mut().zip(&trace.columns) {
                *v = column[i];
            }
            e.row(t, &row);
        }
        e
    }

    /// The slice of time `t`: ⌊t / duration · buckets⌋, clamped to the slices.
    fn bucket(&self, t: f64) -> usize {
        if self.duration.is_nan() || self.duration <= 0.0 {
            return 0;
        }
        // `as` saturates: a negative or NaN time falls in the first slice
        ((t / self.duration * self.buckets as f64) as usize).min(self.buckets - 1)
    }

    /// Fold one row (`values` in channel order). Allocates nothing.
    pub fn row(&mut self, t: f64, values: &[f64]) {
        let b = self.bucket(t);
        let first = !self.seen[b];
        self.seen[b] = true;
        for (c, &x) in values.iter().enumerate().take(self.channels.len()) {
            let e = &mut self.extremes[c * self.buckets + b];
            if first {
                *e = Extremes {
                    t_min: t,
                    min: x,
                    t_max: t,
                    max: x,
                };
                continue;
            }
            if x < e.min {
                (e.t_min, e.min) = (t, x);
            }
            if x > e.max {
                (e.t_max, e.max) = (t, x);
            }
        }
    }

    /// The column of channel `key`, if the envelope has it.
    fn column(&self, key: &str) -> Option<usize> {
        self.channels.iter().position(|c| c.key == key)
    }

    /// The extremes of channel `key` in each slice that saw a row, in time order.
    pub fn extremes(&self, key: &str) -> Option<impl Iterator<Item = &Extremes>> {
        let c = self.column(key)?;
        let slices = &self.extremes[c * self.buckets..(c + 1) * self.buckets];
        Some(
            slices
                .iter()
                .zip(&self.seen)
                .filter(|(_, s)| **s)
                .map(|(e, _)| e),
        )
    }

    /// The points to draw of channel `key`: each slice's minimum and maximum in time order
    /// (one point when they are the same row).
    pub fn points(&self, key: &str) -> Option<Vec<(f64, f64)>> {
        let mut out = Vec::with_capacity(2 * self.buckets);
        for e in self.extremes(key)? {
            let (a, b) = ((e.t_min, e.min), (e.t_max, e.max));
            if a.0 == b.0 {
                out.push(a);
            } else if a.0 < b.0 {
                out.extend([a, b]);
            } else {
                out.extend([b, a]);
            }
        }
        Some(out)
    }

    /// The largest |value| of channel `key` over every row folded (`None` without the channel).
    pub fn peak_abs(&self, key: &str) -> Option<f64> {
        Some(
            self.extremes(key)?
                .flat_map(|e| [e.min, e.max])
                .filter(|v| v.is_finite())
                .fold(0.0_f64, |m, v| m.max(v.abs())),
        )
    }

    /// Values held in memory (the extremes' four numbers per channel and slice).
    pub fn values_held(&self) -> usize {
        4 * self.extremes.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::trace::q;

    #[test]
    fn each_slice_keeps_its_first_minimum_and_maximum_with_their_times() {
        // 4 slices of [0, 2] s: rows at 0, 0.25, …, 2.0 of x = (−1)^i · i, a spike 9 at
        // 1.25, the row at 2.0 (= duration) in the last slice
        let mut trace = Trace::with_channels(&[&q::REL_DISP], 9);
        for i in 0..9 {
            let t = 0.25 * i as f64;
            let x = if i == 5 {
                9.0
            } else {
                (-1.0f64).powi(i) * i as f64
            };
            trace.push(t, &[x]);
        }
        let e = Envelope::of_trace(&trace, 2.0, 4);
        let slices: Vec<_> = e.extremes("rel_disp").unwrap().copied().collect();
        let ex = |t_min, min, t_max, max| Extremes {
            t_min,
            min,
            t_max,
            max,
        };
        assert_eq!(
            slices,
            [
                ex(0.25, -1.0, 0.0, 0.0),
                ex(0.75, -3.0, 0.5, 2.0),
                ex(1.0, 4.0, 1.25, 9.0),
                ex(1.75, -7.0, 2.0, 8.0),
            ]
        );
        assert_eq!(
            e.points("rel_disp").unwrap(),
            [
                (0.0, 0.0),
                (0.25, -1.0),
                (0.5, 2.0),
                (0.75, -3.0),
                (1.0, 4.0),
                (1.25, 9.0),
                (1.75, -7.0),
                (2.0, 8.0)
            ]
        );
        assert_eq!(e.peak_abs("rel_disp"), Some(9.0));
        assert!(e.points("vel").is_none());
    }
}

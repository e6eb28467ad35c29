//! Traces: the one output format every engine and reference writes. A trace is a table of
//! time histories, one column per [`Quantity`] the scene has, in SI units (`quantity`, the
//! catalogue); `contacts` is the per-contact block (forces, slip, gap of each contact)
//! engines record beside it; `unit` the units a column may be written in and the column
//! header `key [unit]`. Its files (CSV, MCAP, the Foxglove 3D scene) and the readers of
//! other programs' results are the file formats' crate, which engines do not need.

mod contacts;
mod quantity;
mod unit;

pub use contacts::{CONTACT_FIELDS, ContactBlock, ContactState, plan_slip_increment};
pub use quantity::{Quantity, q};
pub use unit::{ColumnKind, ColumnMeaning, UNITS, Unit, parse_header};

/// Time histories of one run: `time` plus one column per channel, all the same length.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Trace {
    /// The quantities recorded, in column order (time excluded).
    pub channels: Vec<&'static Quantity>,
    /// Simulation time of each row, s.
    pub time: Vec<f64>,
    /// One column per channel.
    pub columns: Vec<Vec<f64>>,
    /// Per-contact forces, slip and gap (engines' runs; empty for references).
    pub contacts: ContactBlock,
}

impl Trace {
    /// An empty trace with room for `rows` rows, so recording never reallocates.
    pub fn with_channels(channels: &[&'static Quantity], rows: usize) -> Self {
        Self {
            channels: channels.to_vec(),
            time: Vec::with_capacity(rows),
            columns: channels.iter().map(|_| Vec::with_capacity(rows)).collect(),
            contacts: ContactBlock::default(),
        }
    }

    /// The rows a trace file keeps at output step `output_dt`: the first row, then the
    /// first row at or after each multiple of `output_dt` (within 1e-9 of a step, so
    /// rounding in the engines' time sums does not skip a row), and the last row.
    pub fn output_rows(&self, output_dt: f64) -> Vec<usize> {
        let mut keep = OutputStep::new(output_dt);
        let mut rows: Vec<usize> = (0..self.time.len())
            .filter(|&i| keep.keeps(self.time[i]))
            .collect();
        if let Some(last) = self.time.len().checked_sub(1)
            && rows.last() != Some(&last)
        {
            rows.push(last);
        }
        rows
    }

    /// This trace at output step `output_dt` ([`Trace::output_rows`]), contacts included.
    pub fn at_output_step(&self, output_dt: f64) -> Trace {
        let rows = self.output_rows(output_dt);
        Trace {
            channels: self.channels.clone(),
            time: rows.iter().map(|&i| self.time[i]).collect(),
            columns: self
                .columns
                .iter()
                .map(|c| rows.iter().map(|&i| c[i]).collect())
                .collect(),
            contacts: if self.contacts.len() == self.time.len() {
                self.contacts.select_rows(&rows)
            } else {
                self.contacts.clone()
            },
        }
    }

    /// Append one row; `values` in channel order.
    pub fn push(&mut self, t: f64, values: &[f64]) {
        debug_assert_eq!(values.len(), self.columns.len());
        self.time.push(t);
        for (col, v) in self.columns.iter_mut().zip(values) {
            col.push(*v);
        }
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// Whether the trace has no rows.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// The column of a quantity, by key.
    pub fn column(&self, key: &str) -> Option<&[f64]> {
        self.channels
            .iter()
            .position(|c| c.key == key)
            .map(|i| self.columns[i].as_slice())
    }

    /// Whether the trace has a channel.
    pub fn has(&self, key: &str) -> bool {
        self.channels.iter().any(|c| c.key == key)
    }

    /// Value of a channel at time `t`, linearly interpolated (clamped at the ends).
    pub fn sample(&self, key: &str, t: f64) -> Option<f64> {
        let col = self.column(key)?;
        let n = self.time.len();
        if n == 0 {
            return None;
        }
        let i = self.time.partition_point(|&x| x <= t);
        Some(match i {
            0 => col[0],
            i if i >= n => col[n - 1],
            i => {
                let (t0, t1) = (self.time[i - 1], self.time[i]);
                let f = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
                col[i - 1] + f * (col[i] - col[i - 1])
            }
        })
    }

    /// Last row's time, s (0 when empty).
    pub fn end_time(&self) -> f64 {
        self.time.last().copied().unwrap_or(0.0)
    }
}

impl ContactBlock {
    /// Whether this block only repeats `trace`'s own columns: one contact, a row per trace
    /// row, its T the trace's `resistance` and its slip its `slide` bit for bit, its N and
    /// gap constant (the predictor-corrector's one contact: N = M·g, gap = −N/Kz, both
    /// given by the case). Its CSV file would hold nothing the run's CSV and the case do
    /// not, so it is not written; the MCAP state messages still carry it.
    pub fn repeats(&self, trace: &Trace) -> bool {
        let (Some(resistance), Some(slide)) = (trace.column("resistance"), trace.column("slide"))
        else {
            return false;
        };
        if self.count() != 1 || self.len() != trace.len() || self.is_empty() {
            return false;
        }
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
        let first = self.at(0, 0);
        (0..self.len()).all(|i| {
            let c = self.at(i, 0);
            same(self.time[i], trace.time[i])
                && same(c.tangential, resistance[i])
                && same(c.slip, slide[i])
                && same(c.normal, first.normal)
                && same(c.gap, first.gap)
        })
    }
}

/// The row selection of [`Trace::output_rows`], one time at a time, for a run streamed
/// step by step: [`OutputStep::keeps`] says whether a row at time `t` is kept (the first
/// row, then the first row at or after each multiple of the step, within 1e-9 of a step);
/// the last row, which only the end of the run reveals, is the caller's to add.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputStep {
    step: f64,
    next: f64,
    k: u64,
}

impl OutputStep {
    /// Selection at output step `step`, s.
    pub fn new(step: f64) -> Self {
        Self {
            step,
            next: f64::NEG_INFINITY,
            k: 0,
        }
    }

    /// Whether the row at time `t` (times ascending) is kept.
    pub fn keeps(&mut self, t: f64) -> bool {
        let slack = 1e-9 * self.step;
        let due = t >= self.next - slack; // a NaN time is never due
        if !due {
            return false;
        }
        while self.next - slack <= t {
            self.k += 1;
            self.next = self.k as f64 * self.step;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A trace whose times are running sums of 1 ms (as some engines accumulate them:
    /// 0.009000000000000001 and the like), 1.0035 s long.
    fn summed_times() -> Trace {
        let mut trace = Trace::with_channels(&[&q::REL_DISP], 1004);
        let mut t = 0.0;
        for i in 0..1004 {
            trace.push(t, &[i as f64]);
            t += 1e-3;
        }
        trace
    }

    #[test]
    fn output_rows_are_every_multiple_and_the_last_row() {
        let trace = summed_times();
        // 5 ms: rows 0, 5, …, 1000 (201 rows) and the last row, 1003
        let rows = trace.output_rows(5e-3);
        let expected: Vec<usize> = (0..=200).map(|k| 5 * k).chain([1003]).collect();
        assert_eq!(rows, expected);
        let out = trace.at_output_step(5e-3);
        assert_eq!(
            out.columns[0],
            expected.iter().map(|&i| i as f64).collect::<Vec<_>>()
        );
        // an output step equal to the step keeps every row
        assert_eq!(trace.output_rows(1e-3).len(), 1004);
    }
}

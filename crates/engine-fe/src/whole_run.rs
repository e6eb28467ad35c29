//! The sink of a whole run ([`super::simulate`], the 3D model's `simulate_space`): every
//! row kept in a trace sized for the run up front, as engine-api's `TraceSink` keeps it,
//! at about half the instructions a row.
//!
//! A trace stores one `Vec` per channel, so pushing a row into it costs a length,
//! capacity and pointer per channel (≈ 12 instructions each, ≈ 300 a step on a rocking
//! body's 25 channels). This sink copies each row into a small row-major block of
//! [`BLOCK_ROWS`] rows (one copy a row) and moves a full block into the columns a channel
//! at a time ([`BLOCK_ROWS`] values with one capacity check). The contact block is
//! row-major already and filled as it is; the trace's times are its times. The values are
//! the ones handed over, so the trace is the same bit for bit as `TraceSink`'s.

use rockslide_core::trace::{ContactBlock, ContactState, Trace};
use rockslide_engine_api::StepSink;

/// Rows gathered in the block before they are moved into the columns.
const BLOCK_ROWS: usize = 8;

/// Channels the block holds (a 2D rocking body records 25, a 3D one more); a trace with
/// more is pushed a row at a time instead.
const BLOCK_CHANNELS: usize = 48;

/// Keeps every row of a run of at most `rows` rows without reallocating in the time loop.
#[derive(Debug)]
pub(crate) struct WholeRun {
    /// Rows the trace is sized for.
    rows: usize,
    /// The rows so far, under the run's layout: the columns up to the last full block
    /// (every row when `blocked` is false), the contact block with every row; the times
    /// are taken from the contact block at the end.
    trace: Trace,
    /// Whether the rows go through `block` (the layout has at most [`BLOCK_CHANNELS`]
    /// channels).
    blocked: bool,
    /// The rows not yet in the columns, row-major.
    block: [[f64; BLOCK_CHANNELS]; BLOCK_ROWS],
    /// Rows in `block`.
    filled: usize,
}

impl WholeRun {
    /// A sink for a run of `rows` rows.
    pub(crate) fn sized(rows: usize) -> Self {
        Self {
            rows,
            trace: Trace::default(),
            blocked: false,
            block: [[0.0; BLOCK_CHANNELS]; BLOCK_ROWS],
            filled: 0,
        }
    }

    /// The run's trace.
    pub(crate) fn into_trace(mut self) -> Trace {
        if self.blocked {
            self.move_block();
            self.trace.time = self.trace.contacts.time.clone();
        }
        self.trace
    }

    /// Move the rows of the block into the columns: a full block a channel at a time,
    /// the last, partial one a row at a time.
    fn move_block(&mut self) {
        let block = &self.block;
        if self.filled == BLOCK_ROWS {
            for (column, c) in self.trace.columns.iter_mut().zip(0..BLOCK_CHANNELS) {
                let values: [f64; BLOCK_ROWS] = std::array::from_fn(|k| block[k][c]);
                column.extend_from_slice(&values);
            }
        } else {
            for row in &block[..self.filled] {
                for (column, v) in self.trace.columns.iter_mut().zip(row) {
                    column.push(*v);
                }
            }
        }
        self.filled = 0;
    }
}

impl StepSink for WholeRun {
    fn begin(&mut self, layout: &Trace) {
        self.blocked = layout.channels.len() <= BLOCK_CHANNELS;
        self.filled = 0;
        // Blocked, the times are the contact block's, copied once at the end.
        let time_rows = if self.blocked { 0 } else { self.rows };
        self.trace = Trace {
            channels: layout.channels.clone(),
            time: Vec::with_capacity(time_rows),
            columns: layout
                .channels
                .iter()
                .map(|_| Vec::with_capacity(self.rows))
                .collect(),
            contacts: ContactBlock::default(),
        };
        let names: Vec<&str> = layout.contacts.names.iter().map(String::as_str).collect();
        self.trace.contacts =
            ContactBlock::with_contacts(&names, &layout.contacts.compliance, self.rows);
    }

    #[inline]
    fn row(&mut self, t: f64, values: &[f64], contacts: &[ContactState]) {
        debug_assert_eq!(values.len(), self.trace.channels.len());
        self.trace.contacts.push(t, contacts);
        if self.blocked {
            self.block[self.filled][..values.len()].copy_from_slice(values);
            self.filled += 1;
            if self.filled == BLOCK_ROWS {
                self.move_block();
            }
        } else {
            self.trace.push(t, values);
        }
    }
}

//! The sink of a whole run (`simulate`, planar or 3D): every
//! row kept in a trace sized for the run up front, as engine-api's `TraceSink` keeps it,
//! at fewer instructions a row.
//!
//! A trace stores one `Vec` per channel, so pushing a row into it costs a length,
//! capacity and pointer per channel (≈ 12 instructions each, ≈ 300 a step on a rocking
//! body's 25 channels), and the contact block checks its capacity once per contact. This
//! sink gathers [`BLOCK_ROWS`] rows in a block (the 2D recorder writes each row's values
//! and contact fields straight into it, [`RowSink`]) and moves a full block into the trace
//! at once: [`BLOCK_ROWS`] values a channel with one capacity check, the contact fields
//! and times with one copy each. The values are the ones recorded, so the trace is the
//! same bit for bit as `TraceSink`'s.

use super::recording::{FIELDS, ROW_VALUES, RowSink};
use rockslide_core::trace::{ContactBlock, ContactState, Trace};
use rockslide_engine_api::StepSink;

/// Rows gathered in the block before they are moved into the trace.
const BLOCK_ROWS: usize = 16;

/// Keeps every row of a run of at most `rows` rows without reallocating in the time loop.
#[derive(Debug)]
pub(crate) struct WholeRun {
    /// Rows the trace is sized for.
    rows: usize,
    /// The rows moved so far, under the run's layout; its times are its contact block's,
    /// copied once at the end.
    trace: Trace,
    /// Whether the channel values go through `values` (at most [`ROW_VALUES`] channels;
    /// else, only from the 3D model's [`StepSink`] rows, they are pushed a row at a time).
    blocked: bool,
    /// The channel values of the rows in the block, row-major.
    values: [[f64; ROW_VALUES]; BLOCK_ROWS],
    /// The times of the rows in the block.
    times: [f64; BLOCK_ROWS],
    /// The contact fields of the rows in the block, row × contact.
    contact_fields: Vec<[f64; FIELDS]>,
    /// Contacts a row.
    row_contacts: usize,
    /// Where the row being recorded starts in `contact_fields`.
    row_at: usize,
    /// Rows in the block (the row being recorded is the next).
    filled: usize,
}

impl WholeRun {
    /// A sink for a run of `rows` rows.
    pub(crate) fn sized(rows: usize) -> Self {
        Self {
            rows,
            trace: Trace::default(),
            blocked: false,
            values: [[0.0; ROW_VALUES]; BLOCK_ROWS],
            times: [0.0; BLOCK_ROWS],
            contact_fields: Vec::new(),
            row_contacts: 0,
            row_at: 0,
            filled: 0,
        }
    }

    /// The run's trace.
    pub(crate) fn into_trace(mut self) -> Trace {
        self.move_block();
        self.trace.time = self.trace.contacts.time.clone();
        self.trace
    }

    /// Move the rows of the block into the trace: a full block's values a channel at a
    /// time, the last, partial one's a row at a time; the contact fields and times at once.
    fn move_block(&mut self) {
        let rows = self.filled;
        if self.blocked {
            let values = &self.values;
            if rows == BLOCK_ROWS {
                for (column, c) in self.trace.columns.iter_mut().zip(0..ROW_VALUES) {
                    let column_values: [f64; BLOCK_ROWS] = std::array::from_fn(|k| values[k][c]);
                    column.extend_from_slice(&column_values);
                }
            } else {
                for row in &values[..rows] {
                    for (column, v) in self.trace.columns.iter_mut().zip(row) {
                        column.push(*v);
                    }
                }
            }
        }
        let contacts = &mut self.trace.contacts;
        contacts
            .values
            .extend_from_slice(self.contact_fields[..self.row_at].as_flattened());
        contacts.time.extend_from_slice(&self.times[..rows]);
        self.filled = 0;
        self.row_at = 0;
    }

    /// Close the row being recorded at time `t`.
    #[inline]
    fn close_row(&mut self, t: f64) {
        self.times[self.filled] = t;
        self.filled += 1;
        self.row_at += self.row_contacts;
        if self.filled == BLOCK_ROWS {
            self.move_block();
        }
    }
}

impl RowSink for WholeRun {
    fn start(&mut self, layout: &Trace) {
        self.blocked = layout.channels.len() <= ROW_VALUES;
        self.filled = 0;
        self.row_at = 0;
        self.trace = Trace {
            channels: layout.channels.clone(),
            time: Vec::new(),
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
        self.row_contacts = names.len();
        self.contact_fields = vec![[0.0; FIELDS]; BLOCK_ROWS * self.row_contacts];
    }

    #[inline]
    fn contacts(&mut self) -> &mut [[f64; FIELDS]] {
        &mut self.contact_fields[self.row_at..self.row_at + self.row_contacts]
    }

    #[inline]
    fn values(&mut self) -> &mut [f64; ROW_VALUES] {
        &mut self.values[self.filled]
    }

    #[inline]
    fn end_row(&mut self, t: f64, count: usize) {
        debug_assert_eq!(count, self.trace.channels.len());
        debug_assert!(
            self.blocked,
            "a recorder's row holds at most ROW_VALUES channels"
        );
        self.close_row(t);
    }
}

/// The 3D model's recorder hands its rows to a [`StepSink`].
impl StepSink for WholeRun {
    fn begin(&mut self, layout: &Trace) {
        self.start(layout);
    }

    fn row(&mut self, t: f64, values: &[f64], contacts: &[ContactState]) {
        debug_assert_eq!(values.len(), self.trace.channels.len());
        for (fields, state) in self.contacts().iter_mut().zip(contacts) {
            *fields = state.fields();
        }
        if self.blocked {
            self.values[self.filled][..values.len()].copy_from_slice(values);
        } else {
            for (column, v) in self.trace.columns.iter_mut().zip(values) {
                column.push(*v);
            }
        }
        self.close_row(t);
    }
}

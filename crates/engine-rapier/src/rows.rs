//! Where a run's rows go. Every time loop hands its rows to a [`StepSink`] as it records
//! them and holds none itself: a whole run ([`Engine::run`]) keeps them in a
//! [`TraceSink`] (engine-api), a streamed run ([`Engine::run_streaming`]) gives them to the caller's
//! sink, so its memory does not grow with its length. A pilot run keeps only the one sum
//! it is run for ([`PathLength`]).
//!
//! [`Engine::run`]: rockslide_engine_api::Engine::run
//! [`Engine::run_streaming`]: rockslide_engine_api::Engine::run_streaming

use rockslide_core::trace::{ContactBlock, ContactState, Quantity, Trace};
use rockslide_engine_api::StepSink;
pub(crate) use rockslide_engine_api::TraceSink;

/// The layout of a run: its channels and a contact block of `contacts` supports of normal
/// compliance `compliance` (m/N), without rows.
pub(crate) fn layout(channels: &[&'static Quantity], contacts: usize, compliance: f64) -> Trace {
    let mut trace = Trace::with_channels(channels, 0);
    trace.contacts = ContactBlock::for_supports(contacts, compliance, 0);
    trace
}

/// The length of the path one or two channels travel, Σ‖x(k+1) − x(k)‖ (|Δx| for one
/// channel, hypot(Δx, Δy) for two), summed row by row in row order: what a pilot run of
/// the block's step rule measures, without keeping its rows.
pub(crate) struct PathLength {
    keys: (&'static str, Option<&'static str>),
    columns: (usize, Option<usize>),
    last: Option<(f64, f64)>,
    /// The length so far, m.
    pub(crate) sum: f64,
}

impl PathLength {
    /// The path of channel `x` (and `y`, for a path in plan).
    pub(crate) fn of(x: &'static str, y: Option<&'static str>) -> Self {
        Self {
            keys: (x, y),
            columns: (usize::MAX, None),
            last: None,
            sum: 0.0,
        }
    }
}

impl StepSink for PathLength {
    fn begin(&mut self, layout: &Trace) {
        let column = |key: &str| layout.channels.iter().position(|q| q.key == key);
        self.columns = (
            column(self.keys.0).unwrap_or(usize::MAX),
            self.keys.1.and_then(column),
        );
    }

    fn row(&mut self, _t: f64, values: &[f64], _contacts: &[ContactState]) {
        let Some(&x) = values.get(self.columns.0) else {
            return;
        };
        let y = self.columns.1.map_or(0.0, |c| values[c]);
        if let Some((x0, y0)) = self.last {
            self.sum += match self.columns.1 {
                Some(_) => (x - x0).hypot(y - y0),
                None => (x - x0).abs(),
            };
        }
        self.last = Some((x, y));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::trace::q;

    #[test]
    fn path_length_is_the_sum_of_the_increments() {
        let layout = layout(&[&q::FORCE, &q::SLIDE, &q::SLIDE_Y], 1, 0.0);
        let rows = [
            [9.0, 0.0, 0.0],
            [9.0, 3.0, 4.0],
            [9.0, 0.0, 0.0],
            [9.0, -1.0, 0.0],
        ];
        let mut plan = PathLength::of(q::SLIDE.key, Some(q::SLIDE_Y.key));
        let mut line = PathLength::of(q::SLIDE.key, None);
        for sink in [&mut plan as &mut dyn StepSink, &mut line] {
            sink.begin(&layout);
            for r in &rows {
                sink.row(0.0, r, &[ContactState::default()]);
            }
        }
        assert_eq!(plan.sum, 5.0 + 5.0 + 1.0);
        assert_eq!(line.sum, 3.0 + 3.0 + 1.0);
    }
}

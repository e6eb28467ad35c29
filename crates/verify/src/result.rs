//! Everything known about one case after running it ([`CaseResult`]): its runs, their
//! response quantities and history errors, the reference, the checks and invariants.
//! Whether it passes the gate is the verdict's ([`crate::verdict`]).

use crate::analysis::{Check, Responses};
use crate::azimuth_record::AzimuthSweep;
use crate::reference::ReferenceResult;
use rockslide_core::case::Case;
use rockslide_core::trace::Trace;
use rockslide_engine_api::Run;

/// Whole-history difference of one run from the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryError {
    /// max |Δ| / peak of the primary displacement.
    pub max: f64,
    /// RMS Δ / peak of the primary displacement.
    pub rms: f64,
}

/// Everything known about one case after running it.
pub struct CaseResult {
    /// The case.
    pub case: Case,
    /// The runs, in plan order.
    pub runs: Vec<Run>,
    /// Response quantities of each run.
    pub run_responses: Vec<Responses>,
    /// Relative-displacement history error of each run against the reference.
    pub history_errors: Vec<Option<HistoryError>>,
    /// Engines that do not apply, and why.
    pub not_applicable: Vec<(&'static str, String)>,
    /// The reference, or why there is none.
    pub reference: Result<ReferenceResult, String>,
    /// Tolerance checks.
    pub checks: Vec<Check>,
    /// Physical invariants of every completed run ([`crate::invariants`]).
    pub invariants: Vec<crate::invariants::InvariantCheck>,
    /// Per run (in run order; missing or `None`: draw the trace), the per-slice extremes
    /// of every channel over every step of a streamed run, which the figures draw instead
    /// of its kept rows ([`crate::analysis::envelope`]).
    pub envelopes: Vec<Option<crate::analysis::envelope::Envelope>>,
    /// A case with a set of azimuths ([`crate::azimuths`]): the figures at each azimuth
    /// and their maxima; everything above is the governing azimuth's.
    pub azimuths: Option<Box<AzimuthSweep>>,
}

impl CaseResult {
    /// The envelope of run `i`, when it was streamed.
    pub fn envelope(&self, i: usize) -> Option<&crate::analysis::envelope::Envelope> {
        self.envelopes.get(i).and_then(Option::as_ref)
    }

    /// Release the time histories once the case's own files are written: every run's
    /// trace and per-contact block, the reference's sampled traces and the streamed runs'
    /// envelopes, down to each trace's last row (its end time and final values). What the
    /// suite's pages, the gate and the JUnit XML read — checks, responses, invariants,
    /// statuses, solver statistics — stays. A run of many cases then holds the histories
    /// of the cases in flight, not of every case at once.
    pub fn release_histories(&mut self) {
        for run in &mut self.runs {
            keep_last_row(&mut run.trace);
        }
        if let Ok(reference) = &mut self.reference {
            keep_last_row(&mut reference.trace);
            keep_last_row(&mut reference.output);
        }
        self.envelopes.clear();
    }
}

/// Cut a trace to its last row (none when it has none), its memory returned.
fn keep_last_row(trace: &mut Trace) {
    let n = trace.time.len();
    let keep = |v: &mut Vec<f64>, from: usize| {
        let tail = v.get(from..).map(<[f64]>::to_vec).unwrap_or_default();
        *v = tail;
    };
    let from = n.saturating_sub(1);
    keep(&mut trace.time, from);
    for column in &mut trace.columns {
        keep(column, from);
    }
    let contacts = &mut trace.contacts;
    let rows = contacts.time.len();
    if let Some(width) = contacts.values.len().checked_div(rows) {
        keep(&mut contacts.time, rows - 1);
        keep(&mut contacts.values, (rows - 1) * width);
    }
}

//! A run analysed while it runs: the engine hands each step to a sink
//! ([`rockslide_engine_api::StepSink`]) and nothing in proportion to the run's length is
//! held — only the rows at the case's output step (what the trace files and the figures
//! show) and running summaries at full resolution, so the verdict still reads every step:
//! the response quantities ([`Summaries`]: peaks, residuals, total slid, slip start, end
//! and episodes, first zero and crossings), the physical invariants
//! ([`crate::invariants::StreamedInvariants`]) and the history error against the reference,
//! evaluated pointwise at every step.
//!
//! Some summaries depend on a run-wide scale: slip is a slide rate above 10⁻³ of the run's
//! largest, a crossing ignores samples below 10⁻³ of the peak, the energy balance is over
//! the peak input. A streamed run is therefore made twice (the engines are deterministic,
//! which every run checks): a first pass reads those scales ([`Peaks`]), the second
//! computes every summary with them, with the same arithmetic in the same order as the
//! whole-trace readings ([`super::responses`], [`crate::invariants::check_run`],
//! [`super::history_difference`]), so the numbers are the same bit for bit. One reading is
//! taken off the kept rows instead: the peak tilt between the first two impacts (rotation;
//! no streaming engine records one). The figures draw each channel's per-slice extremes
//! over every step ([`super::envelope`]), not the kept rows.

use rockslide_core::case::Case;
use rockslide_core::response::{DEFS, Reading};
use rockslide_core::trace::{ContactBlock, ContactState, OutputStep, Trace};
use rockslide_engine_api::{Run, StepSink};
use rockslide_reference::ExactSolution;

use super::envelope::{ENVELOPE_BUCKETS, Envelope};
use super::metrics::{EPISODE_MIN_SLIP, slide_rate, step_slide};
use super::{Responses, responses};
use crate::invariants::{InvariantCheck, StreamedInvariants};

/// First pass: the run-wide scales of each channel — its peak |value| and its peak |rate|
/// between rows, and on a plan trace the peak planar slide rate — and the number of rows
/// and the last time (to check the second pass saw the same run).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Peaks {
    /// Peak |value| of each channel (0 for none).
    pub peak_abs: Vec<f64>,
    /// Peak |Δvalue / Δt| of each channel (0 for none; NaN rates ignored).
    pub peak_rate: Vec<f64>,
    /// Peak planar slide rate |(Δslide, Δslide_y)| / Δt of a plan trace, what slip
    /// episodes are counted against (0 when the trace has no `slide_y`; NaN rates ignored).
    pub peak_plan_rate: f64,
    /// Columns of `slide` and `slide_y` on a plan trace.
    plan_columns: Option<(usize, usize)>,
    /// Rows seen.
    pub rows: u64,
    /// Time of the last row, s.
    pub last_time: f64,
    previous: Vec<f64>,
}

impl StepSink for Peaks {
    fn begin(&mut self, layout: &Trace) {
        let n = layout.channels.len();
        self.peak_abs = vec![0.0; n];
        self.peak_rate = vec![0.0; n];
        self.previous = vec![0.0; n];
        self.peak_plan_rate = 0.0;
        self.plan_columns = plan_slide_columns(layout);
        self.rows = 0;
    }

    fn row(&mut self, t: f64, values: &[f64], _contacts: &[ContactState]) {
        if let (Some((x, y)), true) = (self.plan_columns, self.rows > 0) {
            let (dx, dy) = (values[x] - self.previous[x], values[y] - self.previous[y]);
            let rate = slide_rate(t - self.last_time, dx, Some(dy));
            self.peak_plan_rate = self.peak_plan_rate.max(rate);
        }
        for (c, &x) in values.iter().enumerate() {
            self.peak_abs[c] = self.peak_abs[c].max(x.abs());
            if self.rows > 0 {
                let rate = ((x - self.previous[c]) / (t - self.last_time)).abs();
                self.peak_rate[c] = self.peak_rate[c].max(rate);
            }
            self.previous[c] = x;
        }
        self.last_time = t;
        self.rows += 1;
    }
}

/// Columns of a plan trace's slide and its y component: the channels slip episodes read
/// along the slip path ([`rockslide_core::response::QuantityDef::plan_partner`]); `None`
/// when the trace lacks either.
fn plan_slide_columns(layout: &Trace) -> Option<(usize, usize)> {
    let d = DEFS.iter().find(|d| d.plan_partner().is_some())?;
    let column = |key: &str| layout.channels.iter().position(|c| c.key == key);
    Some((column(d.channel.key)?, column(d.plan_partner()?.key)?))
}

/// One response quantity read step by step.
struct ReadingState {
    key: &'static str,
    reading: Reading,
    column: usize,
    /// Slip episodes on a plan trace: the column of the slide's y component, read with
    /// `column` for the planar rate.
    partner: Option<usize>,
    /// The folded value (peak, extreme, last, sum, count).
    value: f64,
    /// Slip: the rate threshold; crossings: the floor.
    threshold: f64,
    /// Slip: whether the channel slips at all (its peak rate is positive).
    applies: bool,
    first: Option<f64>,
    last: Option<f64>,
    slipping: bool,
    /// Episodes: the distance slid in the current run of slipping steps.
    slid: f64,
    /// Crossings: the sign of the last sample above the floor, the first raw crossing
    /// after it (t0, x0, t1, x1), and the crossing times found.
    sign: Option<f64>,
    raw: Option<(f64, f64, f64, f64)>,
    crossings: [f64; 2],
    found: usize,
}

impl ReadingState {
    fn new(
        key: &'static str,
        reading: Reading,
        (column, partner): (usize, Option<usize>),
        peaks: &Peaks,
    ) -> Self {
        let (value, threshold, applies) = match reading {
            Reading::Max => (f64::NEG_INFINITY, 0.0, true),
            Reading::Min => (f64::INFINITY, 0.0, true),
            Reading::TotalVariation => (std::iter::empty::<f64>().sum(), 0.0, true),
            Reading::SlipStart | Reading::SlipEnd | Reading::SlipEpisodes => {
                let peak = match partner {
                    Some(_) => peaks.peak_plan_rate,
                    None => peaks.peak_rate[column],
                };
                (0.0, 1e-3 * peak, !(peak.is_nan() || peak <= 0.0))
            }
            Reading::FirstCrossing | Reading::SecondCrossing => {
                (0.0, 1e-3 * peaks.peak_abs[column], true)
            }
            _ => (0.0, 0.0, true),
        };
        Self {
            key,
            reading,
            column,
            partner,
            value,
            threshold,
            applies,
            first: None,
            last: None,
            slipping: false,
            slid: 0.0,
            sign: None,
            raw: None,
            crossings: [0.0; 2],
            found: 0,
        }
    }

    /// Row `(t, values)` after `previous` (the row before, `None` for the first).
    fn row(&mut self, t: f64, values: &[f64], previous_row: Option<(f64, &[f64])>) {
        let x = values[self.column];
        let previous = previous_row.map(|(t0, v)| (t0, v[self.column]));
        match self.reading {
            Reading::PeakAbs => self.value = self.value.max(x.abs()),
            Reading::SignedPeak => {
                if x.abs() > self.value.abs() {
                    self.value = x;
                }
            }
            Reading::Max => self.value = self.value.max(x),
            Reading::Min => self.value = self.value.min(x),
            Reading::Last => self.value = x,
            Reading::TotalVariation => {
                if let Some((_, x0)) = previous {
                    self.value += (x - x0).abs();
                }
            }
            Reading::FirstZero => {
                if self.first.is_none() && x <= 0.0 {
                    self.first = Some(t);
                }
            }
            Reading::SlipStart | Reading::SlipEnd | Reading::SlipEpisodes => {
                if let (Some((t0, v0)), true) = (previous_row, self.applies) {
                    let dy = self.partner.map(|y| values[y] - v0[y]);
                    let dx = x - v0[self.column];
                    self.slip_step(t0, t, slide_rate(t - t0, dx, dy), step_slide(dx, dy));
                }
            }
            Reading::FirstCrossing | Reading::SecondCrossing => self.crossing(t, x, previous),
            Reading::PeakAbsAfterFirstCrossing => {}
        }
    }

    /// A step from `t0` to `t1` at slide rate `rate` that slid `slid`: the slip window
    /// grows, and an episode that ends is counted when it slid more than
    /// [`EPISODE_MIN_SLIP`] (the same sums as [`super::metrics`]' episodes, in order).
    fn slip_step(&mut self, t0: f64, t1: f64, rate: f64, slid: f64) {
        let slipping = rate > self.threshold;
        if slipping {
            self.first.get_or_insert(t0);
            self.last = Some(t1);
            if !self.slipping {
                self.slid = 0.0;
            }
            self.slid += slid;
        } else if self.slipping {
            self.value += self.episode_counts();
        }
        self.slipping = slipping;
    }

    /// 1 when the current run of slipping steps slid more than [`EPISODE_MIN_SLIP`].
    fn episode_counts(&self) -> f64 {
        if self.slid > EPISODE_MIN_SLIP {
            1.0
        } else {
            0.0
        }
    }

    /// [`super::metrics`]' sign changes, one sample at a time.
    fn crossing(&mut self, t: f64, x: f64, previous: Option<(f64, f64)>) {
        if let (Some(s), Some((t0, x0)), None) = (self.sign, previous, self.raw)
            && (x.signum() != s || x == 0.0)
        {
            self.raw = Some((t0, x0, t, x));
        }
        if x.abs() <= self.threshold {
            return;
        }
        if let Some(s) = self.sign
            && x.signum() != s
        {
            let (t0, x0, t1, x1) = self
                .raw
                .or(previous.map(|(t0, x0)| (t0, x0, t, x)))
                .unwrap_or((t, x, t, x));
            let f = if x1 != x0 { x0 / (x0 - x1) } else { 0.0 };
            if self.found < 2 {
                self.crossings[self.found] = t0 + f * (t1 - t0);
            }
            self.found += 1;
        }
        self.sign = Some(x.signum());
        self.raw = None;
    }

    fn result(&self, rows: u64) -> Option<f64> {
        if rows == 0 {
            return None;
        }
        match self.reading {
            Reading::SlipStart => self.first,
            Reading::SlipEnd => self.last,
            Reading::FirstZero => self.first,
            Reading::FirstCrossing => (self.found > 0).then_some(self.crossings[0]),
            Reading::SecondCrossing => (self.found > 1).then_some(self.crossings[1]),
            Reading::PeakAbsAfterFirstCrossing => None,
            Reading::SlipEpisodes if self.slipping => Some(self.value + self.episode_counts()),
            _ => Some(self.value),
        }
    }
}

/// The history error of the relative displacement against the reference, step by step:
/// the reference evaluated at each row's time (as the whole-trace comparison samples it).
struct HistoryState<'a> {
    solution: &'a dyn ExactSolution,
    /// Column of `rel_disp` in the run and in the solution.
    run_column: usize,
    basis_column: usize,
    basis: Vec<f64>,
    peak: f64,
    max: f64,
    sum: f64,
}

impl HistoryState<'_> {
    fn row(&mut self, t: f64, values: &[f64]) {
        self.solution.eval(t, &mut self.basis);
        let b = self.basis[self.basis_column];
        self.peak = self.peak.max(b.abs());
        let d = values[self.run_column] - b;
        self.max = self.max.max(d.abs());
        self.sum += d * d;
    }

    fn result(&self, rows: u64) -> Option<(f64, f64)> {
        if self.peak == 0.0 || rows == 0 {
            return None;
        }
        Some((
            self.max / self.peak,
            (self.sum / rows as f64).sqrt() / self.peak,
        ))
    }
}

/// What a streamed run leaves beside its kept rows: its summaries at full resolution.
#[derive(Debug, Clone, Default)]
pub struct StreamedSummary {
    /// Response quantities, read at every step.
    pub responses: Responses,
    /// (max, RMS) relative-displacement history error against the reference, every step.
    pub history: Option<(f64, f64)>,
    /// Physical invariants, every step.
    pub invariants: Vec<InvariantCheck>,
    /// Rows the run produced (steps + 1).
    pub rows: u64,
    /// Rows kept in memory (the output step's).
    pub kept_rows: usize,
    /// Every channel's per-slice extremes over every step: what the figures draw.
    pub envelope: Option<Envelope>,
}

/// Second pass: keeps the rows at the output step and reads every summary step by step.
pub struct Summaries<'a> {
    case: &'a Case,
    peaks: &'a Peaks,
    solution: Option<&'a dyn ExactSolution>,
    output_dt: Option<f64>,
    capacity: usize,
    kept: Trace,
    step: Option<OutputStep>,
    /// The last row seen (time, values, contacts), and whether it was kept.
    last: (f64, Vec<f64>, Vec<ContactState>),
    last_kept: bool,
    readings: Vec<ReadingState>,
    invariants: Option<StreamedInvariants>,
    history: Option<HistoryState<'a>>,
    envelope: Option<Envelope>,
    rows: u64,
}

impl<'a> Summaries<'a> {
    /// Ready for the second pass of a run of `case` whose first pass gave `peaks`: rows
    /// kept at `output_dt` (every row when `None`), room for `capacity` of them up front;
    /// the history error against `solution` when given.
    pub fn new(
        case: &'a Case,
        peaks: &'a Peaks,
        solution: Option<&'a dyn ExactSolution>,
        output_dt: Option<f64>,
        capacity: usize,
    ) -> Self {
        Self {
            case,
            peaks,
            solution,
            output_dt,
            capacity,
            kept: Trace::default(),
            step: None,
            last: (0.0, Vec::new(), Vec::new()),
            last_kept: false,
            readings: Vec::new(),
            invariants: None,
            history: None,
            envelope: None,
            rows: 0,
        }
    }

    /// The run with its kept rows as its trace, and the summaries of every step.
    pub fn finish(mut self, run: &mut Run) -> StreamedSummary {
        if self.rows > 0 && !self.last_kept {
            let (t, values, contacts) = &self.last;
            keep(&mut self.kept, *t, values, contacts);
        }
        let mut out = Responses::new();
        for r in &self.readings {
            if let Some(v) = r.result(self.rows) {
                out.insert(r.key, v);
            }
        }
        let kept = std::mem::take(&mut self.kept);
        // the one reading not streamed (rotation only): off the kept rows
        let from_kept = responses(&kept);
        for d in DEFS {
            if matches!(d.reading, Reading::PeakAbsAfterFirstCrossing)
                && let Some(&v) = from_kept.get(d.key)
            {
                out.insert(d.key, v);
            }
        }
        run.trace = kept;
        let invariants = self
            .invariants
            .as_ref()
            .map(|i| i.checks(self.case, run))
            .unwrap_or_default();
        StreamedSummary {
            responses: out,
            history: self.history.as_ref().and_then(|h| h.result(self.rows)),
            invariants,
            rows: self.rows,
            kept_rows: run.trace.len(),
            envelope: self.envelope.take(),
        }
    }
}

/// Keep one row (and its contacts, when the run has them).
fn keep(kept: &mut Trace, t: f64, values: &[f64], contacts: &[ContactState]) {
    kept.push(t, values);
    if !contacts.is_empty() {
        kept.contacts.push(t, contacts);
    }
}

impl StepSink for Summaries<'_> {
    fn begin(&mut self, layout: &Trace) {
        self.kept = Trace::with_channels(&layout.channels, self.capacity);
        let names: Vec<&str> = layout.contacts.names.iter().map(String::as_str).collect();
        self.kept.contacts =
            ContactBlock::with_contacts(&names, &layout.contacts.compliance, self.capacity);
        self.step = self.output_dt.map(OutputStep::new);
        self.last = (
            0.0,
            vec![0.0; layout.channels.len()],
            Vec::with_capacity(names.len()),
        );
        let column = |key: &str| layout.channels.iter().position(|c| c.key == key);
        let peaks = self.peaks;
        self.readings = DEFS
            .iter()
            .filter_map(|d| {
                let partner = d.plan_partner().and_then(|y| column(y.key));
                column(d.channel.key)
                    .map(|c| ReadingState::new(d.key, d.reading, (c, partner), peaks))
            })
            .collect();
        let energy_scale = column("energy_input").map_or(0.0, |c| self.peaks.peak_abs[c]);
        self.invariants = Some(StreamedInvariants::new(self.case, layout, energy_scale));
        self.history = self.solution.and_then(|solution| {
            let basis_column = solution
                .channels()
                .iter()
                .position(|c| c.key == "rel_disp")?;
            Some(HistoryState {
                solution,
                run_column: column("rel_disp")?,
                basis_column,
                basis: vec![0.0; solution.channels().len()],
                peak: 0.0,
                max: 0.0,
                sum: 0.0,
            })
        });
        self.envelope = Some(Envelope::new(
            &layout.channels,
            self.case.run.duration,
            ENVELOPE_BUCKETS,
        ));
        self.rows = 0;
    }

    fn row(&mut self, t: f64, values: &[f64], contacts: &[ContactState]) {
        let first = self.rows == 0;
        let previous_time = self.last.0;
        let previous = (!first).then_some((previous_time, self.last.1.as_slice()));
        for r in &mut self.readings {
            r.row(t, values, previous);
        }
        if let Some(i) = &mut self.invariants {
            i.row(t, values, contacts);
        }
        if let Some(h) = &mut self.history {
            h.row(t, values);
        }
        if let Some(e) = &mut self.envelope {
            e.row(t, values);
        }
        let kept = self.step.as_mut().is_none_or(|s| s.keeps(t));
        if kept {
            keep(&mut self.kept, t, values, contacts);
        }
        self.last_kept = kept;
        self.last.0 = t;
        self.last.1.copy_from_slice(values);
        self.last.2.clear();
        self.last.2.extend_from_slice(contacts);
        self.rows += 1;
    }
}

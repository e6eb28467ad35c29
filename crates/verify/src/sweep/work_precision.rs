//! `rockslide sweep <case>`: error against run time. For every engine and variant that
//! applies, a Δt ladder from T/10 down (default 8 rungs at ratio 2: T/10 … T/1280, two
//! decades); per rung the error of the primary displacement against the exact reference
//! (max and RMS, normalised by its peak), the residual-sliding and event-time errors, the
//! energy audit and the run time (median, min and max of repeats). Where no exact
//! reference exists the basis is the engine's own finest rung, and Richardson
//! extrapolation estimates the converged peak displacement and residual sliding.
//!
//! The result, [`SweepResult`], is written as `<out>/<case>/sweep.json` ([`SweepResult::save`])
//! and read back by the case report ([`SweepResult::load`]); its Markdown, HTML, CSV and
//! figure are rendered by `rockslide-present`.

use std::path::Path;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::plan::{NotApplicable, applicable, characteristic_period, fine_grid};
use super::{Options, Series};
use crate::analysis::energy::{EnergySummary, audit};
use crate::analysis::history_difference;
use crate::analysis::responses;
use crate::analysis::sweep::{
    Richardson, RungError, asymptotic_order, exact_channel_cached, fitted_order, ladder,
    local_orders, resample_channel, richardson, richardson_at_order, rung_error,
};
use crate::registry;
use crate::run::{Outcome, TimeStats, Timed, guarded};
use crate::suite::ReferenceResult;
use rockslide_core::case::Case;
use rockslide_core::error::{Error, InputErrors};
use rockslide_core::trace::{Trace, q};
use rockslide_engine_api::{Arrangement, Run};

/// File name of the typed result in the case's output folder.
pub const FILE: &str = "sweep.json";

/// One rung of one series.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Rung {
    /// Time step, s.
    pub dt: f64,
    /// Δt / T.
    pub dt_over_t: f64,
    /// How the run ended (a panic included).
    pub outcome: Outcome,
    /// Steps taken (the engine's `steps` counter, else trace rows − 1).
    pub steps: u64,
    /// Solver substeps per step, for an engine that counts them (rapier).
    #[serde(with = "crate::json::real_opt")]
    pub substeps: Option<f64>,
    /// Wall time over the repeats, s (`None`: no repeat finished).
    pub seconds: Option<TimeStats>,
    /// Repeats timed.
    pub repeats: usize,
    /// Whether every repeat gave a bit-identical trace.
    pub deterministic: bool,
    /// Error against the basis (`None` for the basis itself or a failed run).
    pub error: Option<RungError>,
    /// Peak relative displacement, m.
    #[serde(with = "crate::json::real_opt")]
    pub peak_displacement: Option<f64>,
    /// Residual sliding, m.
    #[serde(with = "crate::json::real_opt")]
    pub residual_sliding: Option<f64>,
    /// Energy audit, or why there is none.
    pub energy: Result<EnergySummary, String>,
    /// Self-convergence: max |x − x_next| / peak against the next finer rung of the same
    /// series (`None` for the finest rung or a failed run).
    #[serde(with = "crate::json::real_opt")]
    pub change: Option<f64>,
}

/// A value read off a rung (its peak displacement, its residual sliding).
type RungValue = fn(&Rung) -> Option<f64>;

impl SeriesResult {
    /// The one observed order of the series, shown wherever an order is
    /// ([`crate::analysis::sweep::ORDER_METHOD`]: the fit over the asymptotic rungs).
    pub fn observed_order(&self) -> Option<f64> {
        self.fine_order
    }

    /// Richardson extrapolation of peak relative displacement and residual sliding from
    /// the two finest completed rungs with the series' one observed order (`None` where
    /// a value or the order is missing).
    pub fn extrapolations(&self, ratio: f64) -> Vec<(&'static str, Option<Richardson>)> {
        let done: Vec<&Rung> = self.rungs.iter().filter(|r| r.completed()).collect();
        let quantities: [(&'static str, RungValue); 2] = [
            ("peak relative displacement", |r| r.peak_displacement),
            ("residual sliding", |r| r.residual_sliding),
        ];
        quantities
            .into_iter()
            .filter(|(_, get)| done.last().is_some_and(|r| get(r).is_some()))
            .map(|(name, get)| {
                let n = done.len();
                let est = match (n >= 2, self.observed_order()) {
                    (true, Some(p)) => match (get(done[n - 1]), get(done[n - 2])) {
                        (Some(f1), Some(f2)) => richardson_at_order(f1, f2, ratio, p),
                        _ => None,
                    },
                    _ => None,
                };
                (name, est)
            })
            .collect()
    }
}

impl Rung {
    /// Whether the run reached the end.
    pub fn completed(&self) -> bool {
        self.outcome.completed()
    }
}

/// Where the cost budget stopped a series.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Skipped {
    /// The first rung not run (this and every finer rung), s.
    pub from_dt: f64,
    /// Its projected wall time for one run, s.
    pub projected: f64,
    /// Wall time already spent on the series, s.
    pub spent: f64,
}

/// A Richardson estimate of one quantity (`None`: the differences do not shrink
/// monotonically, so the rungs are not in the asymptotic range).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RichardsonRow {
    /// Quantity, in words (`peak relative displacement`, `residual sliding`), m.
    pub quantity: String,
    /// The estimate.
    pub estimate: Option<Richardson>,
}

/// One engine variant over the ladder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SeriesResult {
    /// `engine/variant`.
    pub label: String,
    /// The rungs, coarsest first.
    pub rungs: Vec<Rung>,
    /// Observed order: least-squares slope of ln(max error) against ln Δt.
    #[serde(with = "crate::json::real_opt")]
    pub fitted_order: Option<f64>,
    /// Observed order between consecutive rungs (on max error).
    pub local_orders: Vec<Option<f64>>,
    /// Richardson estimates from the three finest completed rungs.
    pub richardson: Vec<RichardsonRow>,
    /// Self-convergence order: least-squares slope of ln(change to the next rung) against
    /// ln Δt — the method's own order even where its converged solution is not the exact
    /// one (a model error, e.g. rapier's foot mass, puts a floor under the exact error).
    #[serde(with = "crate::json::real_opt")]
    pub self_order: Option<f64>,
    /// Self-convergence order between consecutive changes (one per pair of rungs that
    /// both have a change).
    pub self_local_orders: Vec<Option<f64>>,
    /// The observed order against the basis fitted on the finest four rungs only (the
    /// asymptotic range, where the coarse rungs are not).
    #[serde(with = "crate::json::real_opt")]
    pub fine_order: Option<f64>,
    /// The self-convergence order fitted on the finest three changes only.
    #[serde(with = "crate::json::real_opt")]
    pub fine_self_order: Option<f64>,
    /// Where the cost budget stopped the series, if it did.
    pub skipped: Option<Skipped>,
}

/// A whole sweep of one case: the typed result of `rockslide sweep`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepResult {
    /// Case name.
    pub case: String,
    /// Case title.
    pub title: String,
    /// Characteristic period T, s, and how it was found.
    pub period: (f64, String),
    /// Refinement ratio.
    pub ratio: f64,
    /// What errors are measured against, in words.
    pub basis: String,
    /// Whether the basis is an exact reference.
    pub exact_basis: bool,
    /// The reference's own energy audit (exact basis only).
    pub reference_energy: Option<Result<EnergySummary, String>>,
    /// One per engine variant.
    pub series: Vec<SeriesResult>,
    /// Engines that do not apply, and why.
    pub not_applicable: Vec<NotApplicable>,
    /// Worker threads used.
    pub threads: usize,
    /// Wall-time budget per series, s.
    pub budget: Option<f64>,
    /// Options the sweep set for itself, in words.
    pub overrides: Vec<String>,
    /// Rungs of the full ladder.
    pub planned_rungs: usize,
}

impl SweepResult {
    /// Write `sweep.json` into `dir` (the case's output folder).
    pub fn save(&self, dir: &Path) -> Result<(), Error> {
        crate::json::write(&dir.join(FILE), self)
    }

    /// Read `sweep.json` from `dir`: `None` when there is none, else the result or why it
    /// could not be read.
    pub fn load(dir: &Path) -> Option<Result<SweepResult, String>> {
        let path = dir.join(FILE);
        path.exists().then(|| crate::json::read(&path))
    }

    /// The series labelled `engine/variant`.
    pub fn series(&self, label: &str) -> Option<&SeriesResult> {
        self.series.iter().find(|s| s.label == label)
    }
}

/// The case as the sweep runs it: each engine's own changes where the case is silent
/// ([`Engine::for_sweep`](rockslide_engine_api::Engine::for_sweep): runs that only feed a
/// report, not the error of the run, are switched off so the timing is the method's).
/// Returns the case and the changes, in words.
pub fn prepare(case: &Case) -> (Case, Vec<String>) {
    registry::for_sweep(case)
}

/// Per series: the timed rungs, coarsest first, and where the budget stopped it.
struct Ladder {
    timed: Vec<Vec<Timed>>,
    stopped: Vec<Option<Skipped>>,
}

/// Sweep one case. Rungs are run in waves, coarse to fine: every series' rung k in
/// parallel, then the budget decides which series go on to rung k + 1.
pub fn sweep_case(case: &Case, opts: &Options) -> Result<SweepResult, Error> {
    opts.validate()?;
    let (case, overrides) = prepare(case);
    let case = &case;
    let engines = registry::all();
    let (series, not_applicable) = applicable(case, &engines)?;
    let period = characteristic_period(case);
    let dts = ladder(period.0 / 10.0, opts.ratio, opts.rungs);
    let bar = crate::progress::bar(series.len() * dts.len(), !opts.quiet, "runs", &case.name);
    let (reference, ladder_runs, threads) =
        opts.install(series.len(), || -> Result<_, InputErrors> {
            let reference = sweep_reference(case);
            let runs = run_ladder(case, &engines, &series, &dts, opts, &|| bar.inc(1))?;
            Ok((reference, runs, rayon::current_num_threads()))
        })??;
    bar.finish_and_clear();

    let (basis, reference_energy) = match &reference {
        Ok(r) => (
            format!(
                "exact reference: {} ({})",
                r.solution.name(),
                r.solution.method()
            ),
            Some(audit(&r.trace, &case.scene, Arrangement::Single).map(|h| h.summary())),
        ),
        Err(why) => (
            format!(
                "no exact reference ({why}); each engine variant is measured against its own finest completed rung, with a Richardson estimate"
            ),
            None,
        ),
    };
    // The reference at each rung's rows, shared by the series' runs of the rung.
    let mut sampled: Vec<Option<Trace>> = vec![None; dts.len()];
    let results = series
        .iter()
        .zip(ladder_runs.timed.iter().zip(ladder_runs.stopped))
        .map(|(s, (block, stopped))| {
            let basis = Basis {
                reference: &reference,
                sampled: &mut sampled,
            };
            let rungs = measure_rungs(case, block, &dts, period.0, basis);
            let mut r = summarise(s.label(), rungs, opts.ratio);
            r.skipped = stopped;
            r
        })
        .collect();
    Ok(SweepResult {
        case: case.name.clone(),
        title: case.title.clone(),
        period,
        ratio: opts.ratio,
        basis,
        exact_basis: reference.is_ok(),
        reference_energy,
        series: results,
        not_applicable,
        threads,
        budget: opts.budget,
        overrides,
        planned_rungs: dts.len(),
    })
}

/// The exact reference as a sweep reads it: sampled on the fine grid (the energy audit
/// and the event times read it), with the response quantities a rung's error compares —
/// residual sliding and the event times
/// ([`crate::analysis::sweep::EVENT_KEYS`]) — and no others, nor a second copy of the
/// trace for files (a sweep writes none). The values are those of
/// `crate::suite::solve_reference`, bit for bit: the same grid, the same readings of the
/// same columns, the solution's exact quantities over them.
fn sweep_reference(case: &Case) -> Result<ReferenceResult, String> {
    let solution = rockslide_reference::for_case(case)?;
    let n = fine_grid(case.run.duration);
    let trace = rockslide_reference::sample_uniform(solution.as_ref(), case.run.duration, n);
    let compared = [q::SLIDE.key, q::CONTACTS.key];
    let mut read = Trace {
        time: trace.time.clone(),
        ..Trace::default()
    };
    for (c, col) in trace.channels.iter().zip(&trace.columns) {
        if compared.contains(&c.key) {
            read.channels.push(c);
            read.columns.push(col.clone());
        }
    }
    let resp = responses(&read);
    Ok(ReferenceResult::from_parts(solution, trace, resp))
}

/// Run every series down the ladder in waves, within the cost budget.
fn run_ladder(
    case: &Case,
    engines: &[Box<dyn rockslide_engine_api::Engine>],
    series: &[Series],
    dts: &[f64],
    opts: &Options,
    tick: &(dyn Fn() + Sync),
) -> Result<Ladder, InputErrors> {
    let mut done: Vec<Vec<Timed>> = vec![Vec::new(); series.len()];
    let mut spent = vec![0.0_f64; series.len()];
    let mut stopped: Vec<Option<Skipped>> = vec![None; series.len()];
    for (k, &dt) in dts.iter().enumerate() {
        // Plan the wave: which series run rung k, with how many repeats.
        let mut wave: Vec<(usize, usize)> = Vec::new();
        for si in 0..series.len() {
            if stopped[si].is_some() {
                continue;
            }
            let projected = done[si].last().map(|t| {
                let med = t.time_stats().map_or(f64::NAN, |s| s.median);
                let steps_prev =
                    rockslide_engine_api::step_count(case.run.duration, dts[k - 1]) as f64;
                let steps = rockslide_engine_api::step_count(case.run.duration, dt) as f64;
                med * steps / steps_prev
            });
            let repeats = match (opts.budget, projected) {
                (Some(b), Some(p)) if k >= 3 => {
                    let left = b - spent[si];
                    if p * opts.repeats as f64 <= left {
                        opts.repeats
                    } else if p <= left {
                        1
                    } else {
                        stopped[si] = Some(Skipped {
                            from_dt: dt,
                            projected: p,
                            spent: spent[si],
                        });
                        continue;
                    }
                }
                _ => opts.repeats,
            };
            wave.push((si, repeats));
        }
        let timed = wave
            .par_iter()
            .map(|&(si, repeats)| {
                let s = &series[si];
                let own = engines[s.engine].at_rung(case, dt);
                let case = own.as_ref().unwrap_or(case);
                let r = guarded(engines[s.engine].as_ref(), case, s.variant, dt, repeats);
                tick();
                r
            })
            .collect::<Vec<_>>();
        for ((si, _), t) in wave.iter().zip(timed) {
            let t = t?;
            spent[*si] += t.seconds.iter().sum::<f64>();
            done[*si].push(t);
        }
    }
    Ok(Ladder {
        timed: done,
        stopped,
    })
}

/// What the rungs are measured against: the exact reference (or why there is none), and
/// the reference at each rung's rows, shared between the series
/// ([`exact_channel_cached`]).
struct Basis<'a> {
    reference: &'a Result<ReferenceResult, String>,
    sampled: &'a mut [Option<Trace>],
}

/// The rungs of one series: each run's error against the basis (the reference, else the
/// series' finest completed rung), its responses, energy audit and change to the next
/// finer rung.
fn measure_rungs(
    case: &Case,
    block: &[Timed],
    dts: &[f64],
    period: f64,
    basis: Basis,
) -> Vec<Rung> {
    let Basis { reference, sampled } = basis;
    let own_basis: Option<&Run> = if reference.is_ok() {
        None
    } else {
        block
            .iter()
            .rev()
            .find_map(|t| t.run.as_ref().ok().filter(|r| r.status.completed()))
    };
    let own_resp = own_basis.map(|r| responses(&r.trace));
    let mut rungs: Vec<Rung> = block
        .iter()
        .zip(dts)
        .zip(sampled.iter_mut())
        .map(|((t, &dt), at)| {
            let mut rung = Rung {
                dt,
                dt_over_t: dt / period,
                outcome: Outcome::of(&t.run),
                steps: 0,
                substeps: None,
                seconds: t.time_stats(),
                repeats: t.seconds.len(),
                deterministic: t.deterministic,
                error: None,
                peak_displacement: None,
                residual_sliding: None,
                energy: Err("no trace: the engine panicked".into()),
                change: None,
            };
            let Ok(run) = &t.run else {
                return rung;
            };
            let resp = responses(&run.trace);
            rung.steps = run.stats.steps;
            rung.substeps = run.stats.substeps_per_step.map(|n| n as f64);
            rung.error = if !run.status.completed() {
                None
            } else if let Ok(r) = reference {
                exact_channel_cached(at, r.solution.as_ref(), q::REL_DISP.key, &run.trace.time)
                    .and_then(|at| rung_error(&run.trace, &resp, at, &r.responses))
            } else {
                match (own_basis, &own_resp) {
                    (Some(b), Some(br)) if !std::ptr::eq(b, run) => {
                        resample_channel(&b.trace, q::REL_DISP.key, &run.trace.time)
                            .and_then(|at| rung_error(&run.trace, &resp, &at, br))
                    }
                    _ => None,
                }
            };
            rung.peak_displacement = resp.get("peak_relative_displacement").copied();
            rung.residual_sliding = resp.get("residual_sliding").copied();
            rung.energy = audit(&run.trace, &case.scene, run.arrangement).map(|h| h.summary());
            rung
        })
        .collect();
    // Self-convergence: each rung against the next finer one.
    for i in 0..rungs.len().saturating_sub(1) {
        if let (Ok(a), Ok(b)) = (&block[i].run, &block[i + 1].run)
            && a.status.completed()
            && b.status.completed()
        {
            rungs[i].change = resample_channel(&b.trace, q::REL_DISP.key, &a.trace.time)
                .and_then(|at| history_difference(&a.trace, &at, q::REL_DISP.key))
                .map(|e| e.0);
        }
    }
    rungs
}

/// Orders and Richardson estimates of one series.
fn summarise(label: String, rungs: Vec<Rung>, ratio: f64) -> SeriesResult {
    let points: Vec<(f64, f64)> = rungs
        .iter()
        .map(|r| (r.dt, r.error.map_or(f64::NAN, |e| e.max)))
        .collect();
    let done: Vec<&Rung> = rungs.iter().filter(|r| r.completed()).collect();
    let mut rich = Vec::new();
    for (name, get) in [
        (
            "peak relative displacement",
            (|r: &Rung| r.peak_displacement) as fn(&Rung) -> Option<f64>,
        ),
        ("residual sliding", |r: &Rung| r.residual_sliding),
    ] {
        let n = done.len();
        let est = if n >= 3 {
            match (get(done[n - 1]), get(done[n - 2]), get(done[n - 3])) {
                (Some(f1), Some(f2), Some(f3)) => richardson(f1, f2, f3, ratio),
                _ => None,
            }
        } else {
            None
        };
        if get(done.last().copied().unwrap_or(&rungs[0])).is_some() {
            rich.push(RichardsonRow {
                quantity: name.to_string(),
                estimate: est,
            });
        }
    }
    let changes: Vec<(f64, f64)> = rungs
        .iter()
        .filter_map(|r| r.change.map(|c| (r.dt, c)))
        .collect();
    SeriesResult {
        label,
        fitted_order: fitted_order(&points),
        local_orders: local_orders(&points),
        richardson: rich,
        self_order: fitted_order(&changes),
        self_local_orders: local_orders(&changes),
        fine_order: asymptotic_order(&points),
        fine_self_order: fitted_order(&changes[changes.len().saturating_sub(3)..]),
        skipped: None,
        rungs,
    }
}

//! `rockslide sweep <case>`: error against run time. For every engine and variant that
//! applies, a Δt ladder from T/10 down (default 8 rungs at ratio 2: T/10 … T/1280, two
//! decades); per rung the error of the primary displacement against the exact reference
//! (max and RMS, normalised by its peak), the residual-sliding and event-time errors, the
//! energy audit and the run time (median, min and max of repeats). Where no exact
//! reference exists the basis is the engine's own finest rung, and Richardson
//! extrapolation estimates the converged peak displacement and residual sliding.
//! Output: `<out>/<case>/sweep.md`, `sweep.csv` and the log-log plot `sweep.svg`.

use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use rayon::prelude::*;

use super::{Options, Timed, applicable, characteristic_period, progress, run_timed, sci};
use crate::analysis::energy::{EnergySummary, audit};
use crate::analysis::history_difference;
use crate::analysis::responses;
use crate::analysis::sweep::{
    Richardson, RungError, fitted_order, ladder, local_orders, resample, richardson, rung_error,
};
use crate::registry;
use crate::registry::load_case;
use rockslide_core::case::{Case, OptionValue};
use rockslide_core::error::{Error, InputErrors};
use rockslide_core::io::write_atomically;
use rockslide_engine_api::RunStatus;

use crate::suite::solve_reference;
use rockslide_core::trace::q;

/// One rung of one series.
#[derive(Debug, Clone)]
pub struct Rung {
    /// Time step, s.
    pub dt: f64,
    /// Δt / T.
    pub dt_over_t: f64,
    /// How the run ended (`Err`: the engine panicked, with its message).
    pub status: Result<RunStatus, String>,
    /// Steps taken (the engine's `steps` counter, else trace rows − 1).
    pub steps: u64,
    /// Solver substeps per step, for an engine that counts them (rapier).
    pub substeps: Option<f64>,
    /// Wall time (median, min, max) over the repeats, s.
    pub seconds: (f64, f64, f64),
    /// Repeats timed.
    pub repeats: usize,
    /// Whether every repeat gave a bit-identical trace.
    pub deterministic: bool,
    /// Error against the basis (`None` for the basis itself or a failed run).
    pub error: Option<RungError>,
    /// Peak relative displacement, m.
    pub peak_displacement: Option<f64>,
    /// Residual sliding, m.
    pub residual_sliding: Option<f64>,
    /// Energy audit, or why there is none.
    pub energy: Result<EnergySummary, String>,
    /// Self-convergence: max |x − x_next| / peak against the next finer rung of the same
    /// series (`None` for the finest rung or a failed run).
    pub change: Option<f64>,
}

/// Where the cost budget stopped a series.
#[derive(Debug, Clone, PartialEq)]
pub struct Skipped {
    /// The first rung not run (this and every finer rung), s.
    pub from_dt: f64,
    /// Its projected wall time for one run, s.
    pub projected: f64,
    /// Wall time already spent on the series, s.
    pub spent: f64,
}

impl Rung {
    /// Whether the run reached the end.
    pub fn completed(&self) -> bool {
        matches!(self.status, Ok(RunStatus::Completed))
    }
    /// Status in words.
    pub fn status_text(&self) -> String {
        match &self.status {
            Ok(s) => s.to_string(),
            Err(p) => format!("panicked: {p}"),
        }
    }
}

/// One engine variant over the ladder.
#[derive(Debug, Clone)]
pub struct SeriesResult {
    /// `engine/variant`.
    pub label: String,
    /// The rungs, coarsest first.
    pub rungs: Vec<Rung>,
    /// Observed order: least-squares slope of ln(max error) against ln Δt.
    pub fitted_order: Option<f64>,
    /// Observed order between consecutive rungs (on max error).
    pub local_orders: Vec<Option<f64>>,
    /// Richardson estimates from the three finest completed rungs: (quantity, estimate).
    pub richardson: Vec<(&'static str, Option<Richardson>)>,
    /// Self-convergence order: least-squares slope of ln(change to the next rung) against
    /// ln Δt — the method's own order even where its converged solution is not the exact
    /// one (a model error, e.g. rapier's foot mass, puts a floor under the exact error).
    pub self_order: Option<f64>,
    /// Self-convergence order between consecutive changes (one per pair of rungs that
    /// both have a change).
    pub self_local_orders: Vec<Option<f64>>,
    /// Both orders fitted on the finest four rungs only (the asymptotic range, where
    /// the coarse rungs are not): (against the basis, self-convergence).
    pub fine_orders: (Option<f64>, Option<f64>),
    /// Where the cost budget stopped the series, if it did.
    pub skipped: Option<Skipped>,
}

/// A whole sweep of one case.
#[derive(Debug, Clone)]
pub struct SweepResult {
    /// Case name.
    pub case: String,
    /// Case title.
    pub title: String,
    /// Characteristic period T, s, and how it was found.
    pub period: (f64, String),
    /// Refinement ratio.
    pub ratio: f64,
    /// What errors are measured against.
    pub basis: String,
    /// Whether the basis is an exact reference.
    pub exact_basis: bool,
    /// The reference's own energy audit (exact basis only).
    pub reference_energy: Option<Result<EnergySummary, String>>,
    /// One per engine variant.
    pub series: Vec<SeriesResult>,
    /// Engines that do not apply, and why.
    pub not_applicable: Vec<(&'static str, String)>,
    /// Worker threads used.
    pub threads: usize,
    /// Wall-time budget per series, s.
    pub budget: Option<f64>,
    /// Options the sweep set for itself, in words.
    pub overrides: Vec<String>,
    /// Rungs of the full ladder.
    pub planned_rungs: usize,
}

/// Options a sweep sets for itself (unless the case sets them): runs that only feed a
/// report, not the error of the run, are switched off so the timing is the method's.
/// (engine, option, value, why)
pub const SWEEP_OVERRIDES: &[(&str, &str, bool, &str)] = &[(
    "fe",
    "sensitivity",
    false,
    "the FE engine's rotational-inertia and P-Delta sensitivity reruns (four extra runs of a rocking body) are not part of the method's cost",
)];

/// The case as the sweep runs it: [`SWEEP_OVERRIDES`] applied where the case is silent.
/// Returns the case and the overrides applied.
pub fn prepare(case: &Case) -> (Case, Vec<String>) {
    let mut case = case.clone();
    let mut applied = Vec::new();
    for (engine, key, value, why) in SWEEP_OVERRIDES {
        let section = case.engines.entry(engine.to_string()).or_default();
        if !section.options.contains_key(*key) {
            section
                .options
                .insert(key.to_string(), OptionValue::Bool(*value));
            applied.push(format!("`[engines.{engine}] {key} = {value}`: {why}"));
        }
    }
    (case, applied)
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
    let bar = progress(series.len() * dts.len(), opts.quiet, &case.name);
    // Per series: the timed rungs so far, wall time spent, and why it stopped (if it did).
    let mut done: Vec<Vec<Timed>> = vec![Vec::new(); series.len()];
    let mut spent = vec![0.0_f64; series.len()];
    let mut stopped: Vec<Option<Skipped>> = vec![None; series.len()];
    let (reference, threads) = opts.install(|| -> Result<_, InputErrors> {
        let reference = solve_reference(case);
        for (k, &dt) in dts.iter().enumerate() {
            // Plan the wave: which series run rung k, with how many repeats.
            let mut wave: Vec<(usize, usize)> = Vec::new();
            for si in 0..series.len() {
                if stopped[si].is_some() {
                    continue;
                }
                let projected = done[si].last().map(|t| {
                    let (med, _, _) = t.time_stats();
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
                    let r = run_timed(engines[s.engine].as_ref(), case, &s.variant, dt, repeats);
                    bar.inc(1);
                    r
                })
                .collect::<Vec<_>>();
            for ((si, _), t) in wave.iter().zip(timed) {
                let t = t?;
                spent[*si] += t.seconds.iter().sum::<f64>();
                done[*si].push(t);
            }
        }
        Ok((reference, rayon::current_num_threads()))
    })??;
    bar.finish_and_clear();

    let (basis, reference_energy) = match &reference {
        Ok(r) => (
            format!(
                "exact reference: {} ({})",
                r.solution.name(),
                r.solution.method()
            ),
            Some(audit(&r.trace, &case.scene, "reference").map(|h| h.summary())),
        ),
        Err(why) => (
            format!(
                "no exact reference ({why}); each engine variant is measured against its own finest completed rung, with a Richardson estimate"
            ),
            None,
        ),
    };

    let mut results = Vec::new();
    for (si, s) in series.iter().enumerate() {
        let block = &done[si];
        // The basis of this series: the reference, else the finest completed rung.
        let own_basis = if reference.is_ok() {
            None
        } else {
            block
                .iter()
                .rev()
                .find_map(|t| t.run.as_ref().ok().filter(|r| r.status.completed()))
        };
        let own_resp = own_basis.map(|r| responses(&r.trace));
        let mut rungs = Vec::new();
        for (t, &dt) in block.iter().zip(&dts) {
            let (status, steps, substeps, error, peak, resid, energy) = match &t.run {
                Err(p) => (
                    Err(p.clone()),
                    0,
                    None,
                    None,
                    None,
                    None,
                    Err("no trace: the engine panicked".into()),
                ),
                Ok(run) => {
                    let resp = responses(&run.trace);
                    let counter = |name: &str| {
                        run.counters
                            .iter()
                            .find(|(k, _)| k == name)
                            .map(|(_, v)| *v)
                    };
                    let steps =
                        counter("steps").unwrap_or(run.trace.len().saturating_sub(1) as u64);
                    let substeps = counter("substeps")
                        .filter(|_| steps > 0)
                        .map(|n| n as f64 / steps as f64);
                    let error = if !run.status.completed() {
                        None
                    } else if let Ok(r) = &reference {
                        let at = rockslide_reference::sample(r.solution.as_ref(), &run.trace.time);
                        rung_error(&run.trace, &resp, &at, &r.responses)
                    } else {
                        match (own_basis, &own_resp) {
                            (Some(b), Some(br)) if !std::ptr::eq(b, run) => {
                                let at = resample(&b.trace, &run.trace.time);
                                rung_error(&run.trace, &resp, &at, br)
                            }
                            _ => None,
                        }
                    };
                    (
                        Ok(run.status.clone()),
                        steps,
                        substeps,
                        error,
                        resp.get("peak_relative_displacement").copied(),
                        resp.get("residual_sliding").copied(),
                        audit(&run.trace, &case.scene, &s.variant).map(|h| h.summary()),
                    )
                }
            };
            rungs.push(Rung {
                dt,
                dt_over_t: dt / period.0,
                status,
                steps,
                substeps,
                seconds: t.time_stats(),
                repeats: t.seconds.len(),
                deterministic: t.deterministic,
                error,
                peak_displacement: peak,
                residual_sliding: resid,
                energy,
                change: None,
            });
        }
        // Self-convergence: each rung against the next finer one.
        for i in 0..rungs.len().saturating_sub(1) {
            if let (Ok(a), Ok(b)) = (&block[i].run, &block[i + 1].run)
                && a.status.completed()
                && b.status.completed()
            {
                let at = resample(&b.trace, &a.trace.time);
                rungs[i].change = history_difference(&a.trace, &at, q::REL_DISP.key).map(|e| e.0);
            }
        }
        let mut r = summarise(s.label(), rungs, opts.ratio);
        r.skipped = stopped[si].clone();
        results.push(r);
    }
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
            rich.push((name, est));
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
        fine_orders: (
            fitted_order(&points[points.len().saturating_sub(4)..]),
            fitted_order(&changes[changes.len().saturating_sub(3)..]),
        ),
        skipped: None,
        rungs,
    }
}

/// The sweep as Markdown.
pub fn sweep_markdown(r: &SweepResult) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# {} — error against run time\n", r.case);
    let _ = writeln!(s, "*{}*\n", r.title);
    let _ = writeln!(
        s,
        "- Characteristic period T = {:.6} s: {}.",
        r.period.0, r.period.1
    );
    let _ = writeln!(
        s,
        "- Δt ladder: from T/10 down by a ratio of {} per rung.",
        r.ratio
    );
    let _ = writeln!(s, "- Basis: {}.", r.basis);
    if let Some(e) = &r.reference_energy {
        match e {
            Ok(e) => {
                let _ = writeln!(
                    s,
                    "- Energy audit of the reference itself (sampled trace): relative error {:.3e} (the audit's own floor).",
                    e.relative_error
                );
            }
            Err(why) => {
                let _ = writeln!(s, "- Reference energy audit: {why}.");
            }
        }
    }
    let _ = writeln!(
        s,
        "- Errors: max and RMS of the relative displacement difference over the whole history, normalised by the basis's peak; residual sliding error in mm; event-time error = largest |Δt| of slip start, slip end and first lift-off, in ms. Energy: max |input − (kinetic + strain + friction + damping)| / largest energy."
    );
    let _ = writeln!(
        s,
        "- Run time: median (min–max) of the repeats, wall clock, with {} worker threads running rungs in parallel (timings share the machine; use `--jobs 1` for quiet timings).\n",
        r.threads
    );
    let _ = writeln!(
        s,
        "- Self-convergence: \"change\" = max |x − x(next finer rung)| / peak; its slope against Δt is the method's own order, which holds even where the engine converges to something other than the exact solution (a model error puts a floor under the error against the reference)."
    );
    match r.budget {
        Some(b) => {
            let _ = writeln!(
                s,
                "- Cost budget: {b} s of wall time per engine variant (all repeats). Rungs run coarse to fine; a rung projected (previous rung's time × step ratio) past the budget runs once instead of repeating, and is skipped with every finer rung when even one run would overrun. The first three rungs always run."
            );
        }
        None => {
            let _ = writeln!(s, "- Cost budget: none (every rung of every series ran).");
        }
    }
    for o in &r.overrides {
        let _ = writeln!(s, "- Sweep setting {o}.");
    }
    for (id, why) in &r.not_applicable {
        let _ = writeln!(s, "- {id}: not applicable — {why}");
    }
    if !r.not_applicable.is_empty() {
        s.push('\n');
    }
    for se in &r.series {
        let _ = writeln!(s, "## {}\n", se.label);
        let _ = writeln!(
            s,
            "Observed order (least-squares slope of ln max error against ln Δt): **{}**\n",
            se.fitted_order.map_or("—".into(), |p| format!("{p:.3}"))
        );
        let _ = writeln!(
            s,
            "Self-convergence order (slope of ln change against ln Δt): **{}**\n",
            se.self_order.map_or("—".into(), |p| format!("{p:.3}"))
        );
        let _ = writeln!(
            s,
            "Fitted on the finest four rungs only: against the basis **{}**, self-convergence **{}**\n",
            se.fine_orders.0.map_or("—".into(), |p| format!("{p:.3}")),
            se.fine_orders.1.map_or("—".into(), |p| format!("{p:.3}"))
        );
        if let Some(k) = &se.skipped {
            let _ = writeln!(
                s,
                "**Cost budget:** {} of {} rungs run; Δt ≤ {:.4e} s skipped (one run projected at {:.2} s, {:.2} s of the {} s budget already spent).\n",
                se.rungs.len(),
                r.planned_rungs,
                k.from_dt,
                k.projected,
                k.spent,
                r.budget.unwrap_or(f64::NAN)
            );
        }
        let _ = writeln!(
            s,
            "| Δt [s] | Δt/T | substep [s] | status | max error | RMS error | order | change (order) | resid. sliding err [mm] | event-time err [ms] | energy rel. err | run time [ms] median (min–max) | repeats | steps | µs/step | det. |"
        );
        let _ = writeln!(
            s,
            "|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
        );
        for (i, g) in se.rungs.iter().enumerate() {
            let order = if i == 0 {
                "—".to_string()
            } else {
                se.local_orders[i - 1].map_or("—".into(), |p| format!("{p:.2}"))
            };
            let e = g.error;
            let energy = match &g.energy {
                Ok(e) => format!("{:.2e}", e.relative_error),
                Err(_) => "n/a".into(),
            };
            let (med, lo, hi) = g.seconds;
            let per_step = if g.steps > 0 {
                format!("{:.3}", med * 1e6 / g.steps as f64)
            } else {
                "—".into()
            };
            let status = if g.completed() {
                "completed".to_string()
            } else {
                g.status_text()
            };
            let _ = writeln!(
                s,
                "| {:.4e} | {:.5} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.3} ({:.3}–{:.3}) | {} | {} | {} | {} |",
                g.dt,
                g.dt_over_t,
                g.substeps
                    .map_or("—".into(), |n| format!("{:.3e}", g.dt / n)),
                status,
                sci(e.map(|e| e.max)),
                sci(e.map(|e| e.rms)),
                order,
                match (
                    g.change,
                    i.checked_sub(1)
                        .and_then(|j| se.self_local_orders.get(j))
                        .copied()
                        .flatten()
                ) {
                    (Some(c), Some(p)) if se.rungs[i - 1].change.is_some() =>
                        format!("{c:.3e} ({p:.2})"),
                    (c, _) => sci(c),
                },
                sci(e.and_then(|e| e.residual_sliding).map(|x| x * 1e3)),
                match e {
                    Some(e) if e.events_missing > 0 => format!(
                        "{} ({} missing)",
                        sci(e.event_time.map(|x| x * 1e3)),
                        e.events_missing
                    ),
                    _ => sci(e.and_then(|e| e.event_time).map(|x| x * 1e3)),
                },
                energy,
                med * 1e3,
                lo * 1e3,
                hi * 1e3,
                g.repeats,
                g.steps,
                per_step,
                if g.deterministic { "yes" } else { "NO" },
            );
        }
        if let Some(why) = se.rungs.iter().find_map(|g| g.energy.as_ref().err()) {
            let _ = writeln!(s, "\nEnergy audit: {why}.");
        }
        if !se.richardson.is_empty() {
            let _ = writeln!(
                s,
                "\nRichardson extrapolation from the three finest completed rungs (ratio {}):\n",
                r.ratio
            );
            let _ = writeln!(
                s,
                "| quantity | observed order | extrapolated | GCI (fine) |"
            );
            let _ = writeln!(s, "|---|---:|---:|---:|");
            for (name, est) in &se.richardson {
                match est {
                    Some(e) => {
                        let _ = writeln!(
                            s,
                            "| {name} | {:.3} | {:.6e} m | {:.3e} |",
                            e.order, e.extrapolated, e.gci
                        );
                    }
                    None => {
                        let _ = writeln!(
                            s,
                            "| {name} | — | — (differences do not shrink monotonically: not in the asymptotic range) | — |"
                        );
                    }
                }
            }
        }
        s.push('\n');
    }
    let _ = writeln!(
        s,
        "![error against Δt and run time](sweep.svg)\n\nLeft: max error against Δt (observed order = slope). Right: work-precision, max error against median run time."
    );
    s
}

/// The sweep as CSV, one row per rung.
pub fn sweep_csv(r: &SweepResult) -> String {
    let mut s = String::from(
        "series,dt_s,dt_over_T,status,max_error,rms_error,residual_sliding_error_m,event_time_error_s,energy_relative_error,time_median_s,time_min_s,time_max_s,steps,deterministic,change_to_next,substeps_per_step,repeats\n",
    );
    let f = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:e}"));
    for se in &r.series {
        for g in &se.rungs {
            let e = g.error;
            let _ = writeln!(
                s,
                "{},{:e},{:e},{},{},{},{},{},{},{:e},{:e},{:e},{},{},{},{},{}",
                se.label,
                g.dt,
                g.dt_over_t,
                g.status.as_ref().map_or("panicked", |s| s.label()),
                f(e.map(|e| e.max)),
                f(e.map(|e| e.rms)),
                f(e.and_then(|e| e.residual_sliding)),
                f(e.and_then(|e| e.event_time)),
                f(g.energy.as_ref().ok().map(|e| e.relative_error)),
                g.seconds.0,
                g.seconds.1,
                g.seconds.2,
                g.steps,
                g.deterministic,
                f(g.change),
                f(g.substeps),
                g.repeats
            );
        }
    }
    s
}

/// Write `sweep.md`, `sweep.csv` and `sweep.svg` under `out/<case>/`; returns the folder.
pub fn write_sweep(r: &SweepResult, out: &Path) -> Result<PathBuf, Error> {
    let dir = out.join(&r.case);
    let svg = super::plot::sweep_svg(r)?;
    write_atomically(&dir.join("sweep.svg"), svg.as_bytes())?;
    write_atomically(&dir.join("sweep.csv"), sweep_csv(r).as_bytes())?;
    write_atomically(&dir.join("sweep.md"), sweep_markdown(r).as_bytes())?;
    Ok(dir)
}

/// The `sweep` command: every case given, one after the other (each in parallel inside).
pub fn command(cases: &[PathBuf], out: &Path, opts: &Options) -> Result<ExitCode, Error> {
    if cases.is_empty() {
        return Err(Error::Other(
            "sweep needs at least one case file (e.g. cases/pepo-mass-accel.toml)".into(),
        ));
    }
    let mut loaded = Vec::new();
    let mut errors = Vec::new();
    for p in cases {
        match load_case(p) {
            Ok(c) => loaded.push(c),
            Err(e) => errors.extend(e.0),
        }
    }
    if !errors.is_empty() {
        return Err(InputErrors(errors).into());
    }
    for case in &loaded {
        let r = sweep_case(case, opts)?;
        let dir = write_sweep(&r, out)?;
        if !opts.quiet {
            for se in &r.series {
                println!(
                    "{}: {}: observed order {} (self-convergence {}){}",
                    r.case,
                    se.label,
                    se.fitted_order.map_or("—".into(), |p| format!("{p:.3}")),
                    se.self_order.map_or("—".into(), |p| format!("{p:.3}")),
                    se.skipped.as_ref().map_or(String::new(), |k| format!(
                        "; cost budget: {} of {} rungs, Δt ≤ {:.3e} s skipped",
                        se.rungs.len(),
                        r.planned_rungs,
                        k.from_dt
                    ))
                );
            }
            println!("{}: → {}", r.case, dir.join("sweep.md").display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

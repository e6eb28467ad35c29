//! The sweep as documents, built from its typed result: the sweep's own page
//! (`sweep.md`, `sweep.html`: every rung of every series, orders, Richardson estimates,
//! the figure) and the work-precision section of the case report (a summary per series,
//! the figure and the rung table), which reads `sweep.json` and never recomputes.

use super::figure::figure;
use crate::doc::format::{order, sci};
use crate::doc::{Block, Cell, Table, Tone};
use rockslide_verify::analysis::sweep::{ORDER_METHOD, Richardson};
use rockslide_verify::suite::CaseResult;
use rockslide_verify::sweep::SweepResult;
use rockslide_verify::sweep::work_precision::{Rung, SeriesResult};

/// Cells of one Richardson estimate (made with the series' one observed order): quantity,
/// extrapolated value, GCI.
fn richardson_cells(quantity: &str, estimate: Option<Richardson>) -> Vec<Cell> {
    match estimate {
        Some(e) => vec![
            quantity.into(),
            format!("{:.6e} m", e.extrapolated).into(),
            format!("{:.3e}", e.gci).into(),
        ],
        None => vec![
            quantity.into(),
            "— (no observed order: fewer than two completed rungs with a finite error)".into(),
            "—".into(),
        ],
    }
}

const RICHARDSON_COLUMNS: [(&str, bool); 3] = [
    ("quantity", false),
    ("extrapolated", true),
    ("GCI (fine)", true),
];

/// The sentence that says how the Richardson estimates are made.
fn richardson_sentence(ratio: f64) -> String {
    format!(
        "Richardson extrapolation of the two finest completed rungs (ratio r = {ratio}) with the engine's observed order p above: f ≈ f₁ + (f₁ − f₂)/(r^p − 1), Grid Convergence Index GCI = 1.25·|f₁ − f₂|/|f₁|/(r^p − 1) (Roache 1994) — the converged value each engine is heading for."
    )
}

/// The header of the one observed order.
fn order_header() -> String {
    format!("observed order p ({ORDER_METHOD})")
}

/// Median run time of a rung in ms, 3 decimals.
fn median_ms(g: &Rung) -> String {
    g.seconds
        .map_or("—".into(), |s| format!("{:.3}", s.median * 1e3))
}

/// The event-time error cell: ms, with the number of events one side lacks.
fn event_cell(g: &Rung) -> String {
    let e = g.error;
    let ms = sci(e.and_then(|e| e.event_time).map(|x| x * 1e3));
    match e {
        Some(e) if e.events_missing > 0 => format!("{ms} ({} missing)", e.events_missing),
        _ => ms,
    }
}

/// The full rung table of one series (the sweep's own page).
fn rung_table(se: &SeriesResult) -> Table {
    let mut t = Table::with_columns(&[
        ("Δt [s]", true),
        ("Δt/T", true),
        ("substep [s]", true),
        ("status", false),
        ("max error", true),
        ("RMS error", true),
        ("local slope", true),
        ("change (local slope)", true),
        ("resid. sliding err [mm]", true),
        ("event-time err [ms]", true),
        ("energy rel. err", true),
        ("run time [ms] median (min–max)", true),
        ("repeats", true),
        ("steps", true),
        ("µs/step", true),
        ("det.", false),
    ]);
    for (i, g) in se.rungs.iter().enumerate() {
        let local = |orders: &[Option<f64>]| {
            i.checked_sub(1)
                .and_then(|j| orders.get(j))
                .copied()
                .flatten()
        };
        let e = g.error;
        let change = match (g.change, local(&se.self_local_orders)) {
            (Some(c), Some(p)) if se.rungs[i - 1].change.is_some() => format!("{c:.3e} ({p:.2})"),
            (c, _) => sci(c),
        };
        let (time, per_step) = match g.seconds {
            Some(s) => (
                format!(
                    "{:.3} ({:.3}–{:.3})",
                    s.median * 1e3,
                    s.min * 1e3,
                    s.max * 1e3
                ),
                if g.steps > 0 {
                    format!("{:.3}", s.median * 1e6 / g.steps as f64)
                } else {
                    "—".into()
                },
            ),
            None => ("—".into(), "—".into()),
        };
        t.rows.push(vec![
            format!("{:.4e}", g.dt).into(),
            format!("{:.5}", g.dt_over_t).into(),
            g.substeps
                .map_or("—".into(), |n| format!("{:.3e}", g.dt / n))
                .into(),
            if g.completed() {
                Cell::plain("completed")
            } else {
                Cell::toned(g.outcome.to_string(), Tone::Warn)
            },
            sci(e.map(|e| e.max)).into(),
            sci(e.map(|e| e.rms)).into(),
            if i == 0 {
                "—".to_string()
            } else {
                order(local(&se.local_orders), 2)
            }
            .into(),
            change.into(),
            sci(e.and_then(|e| e.residual_sliding).map(|x| x * 1e3)).into(),
            event_cell(g).into(),
            match &g.energy {
                Ok(e) => format!("{:.2e}", e.relative_error),
                Err(_) => "n/a".into(),
            }
            .into(),
            time.into(),
            g.repeats.to_string().into(),
            g.steps.to_string().into(),
            per_step.into(),
            if g.deterministic {
                Cell::plain("yes")
            } else {
                Cell::toned("NO", Tone::Warn)
            },
        ]);
    }
    t
}

/// The sweep's own page.
pub(crate) fn document(r: &SweepResult) -> Vec<Block> {
    let mut b = vec![
        Block::Heading(1, format!("{} — error against run time", r.case)),
        Block::Para(r.title.clone()),
    ];
    b.push(sweep_facts(r));
    for se in &r.series {
        b.extend(series_blocks(r, se));
    }
    if let Some(svg) = figure(r) {
        b.push(Block::Figure {
            file: "sweep.svg".into(),
            caption: format!(
                "Left: max error against Δt, against the {} (the legend gives each engine's observed order p: {ORDER_METHOD}). Right: work-precision, max error against median run time.",
                if r.exact_basis {
                    "exact reference"
                } else {
                    "own finest rung"
                }
            ),
            svg,
        });
    }
    b
}

/// The work-precision section of a case report: the sweep's summary per series, figure
/// and rung table, or how to produce them.
pub(crate) fn case_section(
    r: &CaseResult,
    sweep: Option<&Result<SweepResult, String>>,
) -> Vec<Block> {
    let mut b = vec![Block::Heading(
        2,
        "Error against run time (work-precision)".into(),
    )];
    let case = &r.case.name;
    let file = rockslide_verify::sweep::work_precision::FILE;
    let how = format!(
        "`rockslide sweep {} --out <this folder>` writes it — every applicable engine and variant over a Δt ladder from T/10 down, a few minutes — and `rockslide run` and `check` pick it up from the output folder without recomputing it.",
        r.case.path.display()
    );
    let s = match sweep {
        None => {
            b.push(Block::Para(format!(
                "No sweep in the output folder ({case}/{file}): {how}"
            )));
            return b;
        }
        Some(Err(why)) => {
            b.push(Block::Para(format!("{file} could not be read: {why}.")));
            return b;
        }
        Some(Ok(s)) => s,
    };
    b.push(Block::Para(format!(
        "Picked up from {case}/{file}: {how} Basis: {}. Errors: max and RMS of the relative-displacement difference over the whole history, normalised by the basis's peak; residual-sliding error in mm; event-time error (slip start/end, first lift-off) in ms. Run time: median of the repeats, wall clock. Observed order p: {ORDER_METHOD} — one number per engine on this page, the one the Richardson estimates below use.",
        s.basis
    )));
    if !s.exact_basis {
        b.push(Block::Para(
            "Without an exact reference these are convergence errors against each engine's own finest solution: they show how fast a method converges, not whether it converges to the right answer — the cross-code comparison above does that.".into(),
        ));
    }
    b.push(Block::Table(summary_table(s)));
    if let Some(svg) = figure(s) {
        b.push(Block::Figure {
            file: "plot-work-precision.svg".into(),
            caption: "Left: max error against Δt, log-log (the legend gives each engine's observed order p of the table above). Right: work-precision, max error against median run time — lower left is better. Where series coincide, the earlier one is drawn wider so that it shows around the later ones.".into(),
            svg,
        });
    }
    b.push(Block::Table(rungs_table(s)));
    b.extend(richardson_blocks(s));
    b
}

/// The sweep's facts: the period, the ladder, the basis, what the errors and run times
/// are, the cost budget, the sweep's settings, the engines that do not apply, the tool.
fn sweep_facts(r: &SweepResult) -> Block {
    let mut facts = vec![
        (
            "Characteristic period".to_string(),
            format!("T = {:.6} s: {}", r.period.0, r.period.1),
        ),
        (
            "Δt ladder".into(),
            format!("from T/10 down by a ratio of {} per rung", r.ratio),
        ),
        ("Basis".into(), r.basis.clone()),
    ];
    match &r.reference_energy {
        Some(Ok(e)) => facts.push((
            "Energy audit of the reference itself".into(),
            format!(
                "relative error {:.3e} on its sampled trace (the audit's own floor)",
                e.relative_error
            ),
        )),
        Some(Err(why)) => facts.push(("Reference energy audit".into(), why.clone())),
        None => {}
    }
    facts.extend([
        (
            "Errors".to_string(),
            "max and RMS of the relative displacement difference over the whole history, normalised by the basis's peak; residual sliding error in mm; event-time error = largest |Δt| of slip start, slip end and first lift-off, in ms. Energy: max |input − (kinetic + strain + friction + damping)| / largest energy".to_string(),
        ),
        (
            "Run time".into(),
            format!(
                "median (min–max) of the repeats, wall clock, with {} worker threads running rungs in parallel (timings share the machine; use `--jobs 1` for quiet timings)",
                r.threads
            ),
        ),
        (
            "Self-convergence".into(),
            "\"change\" = max |x − x(next finer rung)| / peak; its slope against Δt is the method's own order, which holds even where the engine converges to something other than the exact solution (a model error puts a floor under the error against the reference)".into(),
        ),
        (
            "Cost budget".into(),
            match r.budget {
                Some(b) => format!(
                    "{b} s of wall time per engine variant (all repeats). Rungs run coarse to fine; a rung projected (previous rung's time × step ratio) past the budget runs once instead of repeating, and is skipped with every finer rung when even one run would overrun. The first three rungs always run"
                ),
                None => "none (every rung of every series ran)".into(),
            },
        ),
    ]);
    facts.extend(
        r.overrides
            .iter()
            .map(|o| ("Sweep setting".to_string(), o.clone())),
    );
    facts.extend(
        r.not_applicable
            .iter()
            .map(|(id, why)| (id.clone(), format!("not applicable — {why}"))),
    );
    facts.push((
        "Made by".into(),
        format!("{}, commit {}", crate::stamp::tool(), crate::stamp::COMMIT),
    ));
    Block::Facts(facts)
}

/// One series of the sweep: its observed order and diagnostics, what the cost budget
/// skipped, its rungs and its Richardson estimates.
fn series_blocks(r: &SweepResult, se: &SeriesResult) -> Vec<Block> {
    let mut b = Vec::new();
    b.push(Block::Heading(2, se.label.clone()));
    let mut facts = vec![
        (order_header(), order(se.observed_order(), 2)),
        (
            "Diagnostics (slopes, not the order)".into(),
            format!(
                "ln(max error) over the whole ladder, coarse rungs included: {}; ln(change to the next rung), self-convergence: {} (finest three changes: {})",
                order(se.fitted_order, 2),
                order(se.self_order, 2),
                order(se.fine_self_order, 2)
            ),
        ),
    ];
    if let Some(k) = &se.skipped {
        facts.push((
            "Cost budget".into(),
            format!(
                "{} of {} rungs run; Δt ≤ {:.4e} s skipped (one run projected at {:.2} s, {:.2} s of the {} s budget already spent)",
                se.rungs.len(),
                r.planned_rungs,
                k.from_dt,
                k.projected,
                k.spent,
                r.budget.unwrap_or(f64::NAN)
            ),
        ));
    }
    b.push(Block::Facts(facts));
    b.push(Block::Table(rung_table(se)));
    if let Some(why) = se.rungs.iter().find_map(|g| g.energy.as_ref().err()) {
        b.push(Block::Para(format!("Energy audit: {why}.")));
    }
    let extrapolations = se.extrapolations(r.ratio);
    if !extrapolations.is_empty() {
        b.push(Block::Para(richardson_sentence(r.ratio)));
        let mut t = Table::with_columns(&RICHARDSON_COLUMNS);
        t.rows.extend(
            extrapolations
                .into_iter()
                .map(|(q, e)| richardson_cells(q, e)),
        );
        b.push(Block::Table(t));
    }
    b
}

/// The case report's summary of a sweep: per series, its order and its finest rung.
fn summary_table(s: &SweepResult) -> Table {
    let mut summary = Table::with_columns(&[
        ("Engine/variant", false),
        (&order_header(), true),
        ("rungs", true),
        ("finest Δt [s]", true),
        ("max error there", true),
        ("median time there [ms]", true),
    ]);
    for se in &s.series {
        let last = se.rungs.iter().rev().find(|g| g.error.is_some());
        summary.rows.push(vec![
            se.label.clone().into(),
            order(se.observed_order(), 2).into(),
            se.rungs.len().to_string().into(),
            last.map_or("—".into(), |g| format!("{:.4e}", g.dt)).into(),
            sci(last.and_then(|g| g.error).map(|e| e.max)).into(),
            last.map_or("—".into(), median_ms).into(),
        ]);
    }
    summary
}

/// Every rung of every series of a sweep, for the case report.
fn rungs_table(s: &SweepResult) -> Table {
    let mut t = Table::with_columns(&[
        ("Engine/variant", false),
        ("Δt [s]", true),
        ("Δt/T", true),
        ("status", false),
        ("max error", true),
        ("RMS error", true),
        ("resid. sliding err [mm]", true),
        ("event-time err [ms]", true),
        ("energy rel. err", true),
        ("median time [ms]", true),
    ]);
    for se in &s.series {
        for g in &se.rungs {
            let e = g.error;
            t.rows.push(vec![
                se.label.clone().into(),
                format!("{:.4e}", g.dt).into(),
                format!("{:.5}", g.dt_over_t).into(),
                if g.completed() {
                    Cell::plain("completed")
                } else {
                    Cell::toned(g.outcome.label(), Tone::Warn).hint(g.outcome.to_string())
                },
                sci(e.map(|e| e.max)).into(),
                sci(e.map(|e| e.rms)).into(),
                sci(e.and_then(|e| e.residual_sliding).map(|x| x * 1e3)).into(),
                sci(e.and_then(|e| e.event_time).map(|x| x * 1e3)).into(),
                sci(g.energy.as_ref().ok().map(|e| e.relative_error)).into(),
                median_ms(g).into(),
            ]);
        }
    }
    t
}

/// The Richardson estimates of every series of a sweep (none when no series has one).
fn richardson_blocks(s: &SweepResult) -> Vec<Block> {
    let mut b = Vec::new();
    if s.series
        .iter()
        .any(|se| !se.extrapolations(s.ratio).is_empty())
    {
        b.push(Block::Para(richardson_sentence(s.ratio)));
        let mut columns = vec![("Engine/variant", false)];
        columns.extend(RICHARDSON_COLUMNS);
        let mut rt = Table::with_columns(&columns);
        for se in &s.series {
            for (q, e) in se.extrapolations(s.ratio) {
                let mut cells: Vec<Cell> = vec![se.label.clone().into()];
                cells.extend(richardson_cells(q, e));
                rt.rows.push(cells);
            }
        }
        b.push(Block::Table(rt));
    }
    b
}

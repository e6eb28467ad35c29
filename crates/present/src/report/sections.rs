//! Report sections about each method's consistency and cost, beside the response tables of
//! `document.rs`: the energy audit of every run and of the reference (issue 7: input =
//! kinetic + strain + friction + damping, computed by `analysis::energy` from the trace),
//! the work-precision section of a case (from `sweep.csv`, picked up, never recomputed),
//! and the stability section of the suite (from `stability.csv` and `stability.md`).

use super::attachments::{Stability, Sweep};
use super::doc::{Block, Cell, Table, Tone};
use super::format::sig;
use super::study_plots::{stability_figure, sweep_figure};
use rockslide_verify::analysis::energy::{EnergySummary, audit};
use rockslide_verify::suite::CaseResult;

/// J → kJ, 4 significant digits.
fn kj(x: f64) -> String {
    sig(x / 1e3)
}

/// `x` in engineering notation with 3 significant digits, `—` when absent.
fn sci(x: Option<f64>) -> String {
    x.map_or("—".into(), |v| format!("{v:.3e}"))
}

/// The energy audit of the reference and of every run.
pub(crate) fn energy_blocks(r: &CaseResult) -> Vec<Block> {
    let mut b = vec![Block::Heading(2, "Energy audit".into())];
    let mut audits: Vec<(String, Result<EnergySummary, String>)> = Vec::new();
    if let Ok(x) = &r.reference {
        audits.push((
            format!("reference ({})", x.solution.name()),
            audit(&x.trace, &r.case.scene, "reference").map(|h| h.summary()),
        ));
    }
    for run in &r.runs {
        audits.push((
            run.label(),
            audit(&run.trace, &r.case.scene, &run.variant).map(|h| h.summary()),
        ));
    }
    if audits.is_empty() {
        b.push(Block::Para("No run to audit.".into()));
        return b;
    }
    // One reason for all: say it once.
    if let Some(Err(first)) = audits.first().map(|a| &a.1)
        && audits
            .iter()
            .all(|(_, a)| a.as_ref().err().is_some_and(|w| w == first))
    {
        b.push(Block::Para(format!("Not audited: {first}.")));
        return b;
    }
    b.push(Block::Para(
        "Each trace is audited by the same independent arithmetic (`analysis::energy`), whatever engine wrote it: input work W = ∫F dx (plus the work of ground-velocity jumps) against kinetic ½Mv², strain ½R²/K, friction ∫R dxp and damping ∫C·v dx, all at the end of the run, in kJ. Balance error = E0 + W − (kinetic + strain + friction + damping): positive is energy the method lost, negative energy it created. Relative error = largest |balance error| over the run / largest energy. The reference's own audit is the floor set by the trapezoidal rule on its sampled trace.".into(),
    ));
    let mut t = Table {
        header: [
            "Run",
            "input E0 + W [kJ]",
            "kinetic [kJ]",
            "strain [kJ]",
            "friction [kJ]",
            "damping [kJ]",
            "balance error at end [kJ]",
            "relative error",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![false, true, true, true, true, true, true, true],
        rows: Vec::new(),
    };
    let mut skipped = Vec::new();
    for (label, a) in &audits {
        match a {
            Ok(e) => t.rows.push(vec![
                label.clone().into(),
                kj(e.supplied).into(),
                kj(e.kinetic).into(),
                kj(e.strain).into(),
                kj(e.friction).into(),
                kj(e.damping).into(),
                kj(e.end_error).into(),
                Cell::plain(format!("{:.2e}", e.relative_error)),
            ]),
            Err(why) => skipped.push(format!("{label}: not audited — {why}")),
        }
    }
    b.push(Block::Table(t));
    if !skipped.is_empty() {
        b.push(Block::List(skipped));
    }
    b
}

/// The work-precision section of a case: the sweep's table, observed orders and figure,
/// or how to produce them.
pub(crate) fn sweep_blocks(r: &CaseResult, sweep: Option<&Result<Sweep, String>>) -> Vec<Block> {
    let mut b = vec![Block::Heading(
        2,
        "Error against run time (work-precision)".into(),
    )];
    let case = &r.case.name;
    let how = format!(
        "`rockslide sweep {} --out <this folder>` writes it — every applicable engine and variant over a Δt ladder from T/10 down, a few minutes — and `rockslide run` and `check` pick it up from the output folder without recomputing it.",
        r.case.path.display()
    );
    let s = match sweep {
        None => {
            b.push(Block::Para(format!(
                "No sweep in the output folder ({case}/sweep.csv): {how}"
            )));
            return b;
        }
        Some(Err(why)) => {
            b.push(Block::Para(format!("sweep.csv could not be read: {why}.")));
            return b;
        }
        Some(Ok(s)) => s,
    };
    let basis = s.basis.clone().unwrap_or_else(|| match &r.reference {
        Ok(x) => format!("exact reference: {}", x.solution.name()),
        Err(_) => "no exact reference; each engine variant against its own finest rung".into(),
    });
    b.push(Block::Para(format!(
        "Picked up from {case}/sweep.csv: {how} Basis: {basis}. Errors: max and RMS of the relative-displacement difference over the whole history, normalised by the basis's peak; residual-sliding error in mm; event-time error (slip start/end, first lift-off) in ms. Run time: median of the repeats, wall clock. Observed order: least-squares slope of ln(max error) against ln Δt."
    )));
    if r.reference.is_err() {
        b.push(Block::Para(
            "Without an exact reference these are convergence errors against each engine's own finest solution: they show how fast a method converges, not whether it converges to the right answer — the cross-code comparison above does that.".into(),
        ));
    }
    let mut summary = Table {
        header: [
            "Engine/variant",
            "observed order",
            "rungs",
            "finest Δt [s]",
            "max error there",
            "median time there [ms]",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![false, true, true, true, true, true],
        rows: Vec::new(),
    };
    for series in s.series() {
        let rungs: Vec<_> = s.rungs(series).collect();
        let last = rungs.iter().rev().find(|g| g.max_error.is_some());
        summary.rows.push(vec![
            series.into(),
            Cell::plain(s.order(series).map_or("—".into(), |p| format!("{p:.2}"))),
            rungs.len().to_string().into(),
            last.map_or("—".into(), |g| format!("{:.4e}", g.dt)).into(),
            sci(last.and_then(|g| g.max_error)).into(),
            last.and_then(|g| g.time_median)
                .map_or("—".into(), |t| format!("{:.3}", t * 1e3))
                .into(),
        ]);
    }
    b.push(Block::Table(summary));
    if let Some(svg) = sweep_figure(s, case) {
        b.push(Block::Figure {
            file: "plot-work-precision.svg".into(),
            caption: "Left: max error against Δt, log-log (the slope is the observed order). Right: work-precision, max error against median run time — lower left is better. Where series coincide, the earlier one is drawn wider so that it shows around the later ones.".into(),
            svg,
        });
    }
    let mut t = Table {
        header: [
            "Engine/variant",
            "Δt [s]",
            "Δt/T",
            "status",
            "max error",
            "RMS error",
            "resid. sliding err [mm]",
            "event-time err [ms]",
            "energy rel. err",
            "median time [ms]",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![false, true, true, false, true, true, true, true, true, true],
        rows: Vec::new(),
    };
    for g in &s.rows {
        let status = if g.status == "completed" {
            Cell::plain("completed")
        } else {
            Cell::toned(g.status.clone(), Tone::Warn)
        };
        t.rows.push(vec![
            g.series.clone().into(),
            format!("{:.4e}", g.dt).into(),
            format!("{:.5}", g.dt_over_t).into(),
            status,
            sci(g.max_error).into(),
            sci(g.rms_error).into(),
            sci(g.residual_sliding_error.map(|x| x * 1e3)).into(),
            sci(g.event_time_error.map(|x| x * 1e3)).into(),
            sci(g.energy_error).into(),
            g.time_median
                .map_or("—".into(), |t| format!("{:.3}", t * 1e3))
                .into(),
        ]);
    }
    b.push(Block::Table(t));
    if !s.richardson.is_empty() {
        b.push(Block::Para(
            "Richardson extrapolation from the three finest completed rungs (from sweep.md): the converged value each engine is heading for, with the observed order and the Grid Convergence Index of the finest rung; “—” where the differences do not shrink monotonically (not yet in the asymptotic range).".into(),
        ));
        let mut rt = Table {
            header: [
                "Engine/variant",
                "quantity",
                "observed order",
                "extrapolated",
                "GCI (fine)",
            ]
            .map(String::from)
            .to_vec(),
            numeric: vec![false, false, true, false, true],
            rows: Vec::new(),
        };
        for (series, cells) in &s.richardson {
            let mut row: Vec<Cell> = vec![series.clone().into()];
            row.extend(cells.iter().map(|c| Cell::plain(c.clone())));
            rt.rows.push(row);
        }
        b.push(Block::Table(rt));
    }
    b
}

/// Short map cell: class symbol with the error or the failure time.
fn map_cell(class: &str, error: Option<f64>, time: Option<f64>) -> Cell {
    let at = |t: Option<f64>| t.map_or(String::new(), |t| format!(" t={t:.3}"));
    // Three digits keep the eleven-column map on a page; the CSV has them all.
    let e = error.map_or("—".into(), |v| format!("{v:.2e}"));
    match class {
        "accurate" => Cell::toned(format!("✓ {e}"), Tone::Pass),
        "inaccurate" => Cell::toned(format!("~ {e}"), Tone::Warn),
        "diverged" => Cell::toned(format!("✗{}", at(time)), Tone::Fail),
        c => Cell::toned(format!("{c}{}", at(time)), Tone::Fail),
    }
}

/// The stability section of the suite, or how to produce it.
pub(crate) fn stability_blocks(st: Option<&Result<Stability, String>>) -> Vec<Block> {
    let mut b = vec![Block::Heading(
        2,
        "Stability on stiff and extreme scenes".into(),
    )];
    let st = match st {
        None => {
            b.push(Block::Para(
                "No stability study in the output folder (stability/stability.csv): `rockslide stability` runs the scenes of cases/stability/ and writes it; `rockslide run` and `check` pick it up.".into(),
            ));
            return b;
        }
        Some(Err(why)) => {
            b.push(Block::Para(format!(
                "stability.csv could not be read: {why}."
            )));
            return b;
        }
        Some(Ok(s)) => s,
    };
    b.push(Block::Para(
        "From stability/stability.csv (`rockslide stability`): every stiff and extreme scene run by every applicable engine variant over Δt/T; each run classified as accurate (✓, max error of the relative displacement within the accuracy criterion), inaccurate (~, completed and stable, larger error), diverged (✗, NaN/Inf, engine-reported divergence, panic or energy growth, with the time) or not converged (an iterative solver gave up, with the time).".into(),
    ));
    if let Some((header, rows)) = &st.limits {
        b.push(Block::Heading(3, "Stated stability limits".into()));
        let n = header.len();
        b.push(Block::Table(Table {
            header: header.clone(),
            numeric: (0..n).map(|i| i > 0).collect(),
            rows: rows
                .iter()
                .map(|r| r.iter().map(|c| Cell::plain(c.clone())).collect())
                .collect(),
        }));
    }
    let mut dts: Vec<f64> = st.runs.iter().map(|r| r.dt_over_t).collect();
    dts.sort_by(f64::total_cmp);
    dts.dedup();
    let mut labels: Vec<String> = Vec::new();
    for r in &st.runs {
        let l = format!("{} · {}", r.scene, r.series);
        if !labels.contains(&l) {
            labels.push(l);
        }
    }
    b.push(Block::Heading(3, "Map".into()));
    b.push(Block::Para(
        "Rows: scene · engine/variant; columns: Δt/T. Cells: ✓ accurate, ~ inaccurate (with the max error), ✗ diverged (with the time, s); hover a failed cell for the reason.".into(),
    ));
    let mut header = vec!["scene · engine/variant  ·  Δt/T →".to_string()];
    header.extend(dts.iter().map(|x| format!("{x}")));
    let mut t = Table {
        numeric: std::iter::once(false)
            .chain(std::iter::repeat_n(true, dts.len()))
            .collect(),
        header,
        rows: Vec::new(),
    };
    for l in &labels {
        let mut row: Vec<Cell> = vec![l.clone().into()];
        for &x in &dts {
            let hit = st
                .runs
                .iter()
                .find(|r| format!("{} · {}", r.scene, r.series) == *l && r.dt_over_t == x);
            row.push(match hit {
                Some(r) => {
                    let c = map_cell(&r.class, r.max_error, r.time);
                    if r.reason.is_empty() {
                        c
                    } else {
                        c.hint(r.reason.clone())
                    }
                }
                None => Cell::plain(""),
            });
        }
        t.rows.push(row);
    }
    b.push(Block::Table(t));
    if let Some(svg) = stability_figure(st, &labels) {
        b.push(Block::Figure {
            file: "stability-map.svg".into(),
            caption: "Stability map: the class of every run against Δt/T (log scale).".into(),
            svg,
        });
    }
    let failures: Vec<String> = st
        .runs
        .iter()
        .filter(|r| !r.reason.is_empty())
        .map(|r| {
            format!(
                "{} · {} at Δt/T = {}: {}{} — {}",
                r.scene,
                r.series,
                r.dt_over_t,
                r.class,
                r.time
                    .map_or(String::new(), |t| format!(" at t = {t:.4} s")),
                r.reason
            )
        })
        .collect();
    if !failures.is_empty() {
        b.push(Block::Heading(3, "Why runs failed".into()));
        b.push(Block::List(failures));
    }
    b
}

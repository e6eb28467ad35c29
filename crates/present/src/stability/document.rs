//! The stability study as documents, built from its typed result: the study's own page
//! (`stability.md`, `stability.html`: limits, scenes, map, every run) and the stability
//! section of the suite report (the stated limits, the map, why runs failed), which reads
//! `stability.json` and never recomputes. Both use the same limits table and map cells.

use super::figure::figure;
use crate::doc::format::sci;
use crate::doc::{Block, Cell, Table, Tone};
use rockslide_verify::analysis::stability::Class;
use rockslide_verify::sweep::StabilityResult;
use rockslide_verify::sweep::stability::{Limit, StabilityRun};

/// The practical stability limits, one row per engine variant; the limit in bold.
fn limits_table(limits: &[Limit]) -> Table {
    let mut t = Table::with_columns(&[
        ("engine/variant", false),
        ("first diverging rung Δt/T (scenes)", false),
        ("stable up to (ladder)", true),
        ("bisection bracket Δt/T (scene)", false),
        ("limit Δt/T", true),
        ("accurate on every scene up to Δt/T", true),
    ]);
    for l in limits {
        t.rows.push(vec![
            l.label.clone().into(),
            l.first_diverged
                .as_ref()
                .map_or("none up to 1.0".into(), |(x, c)| {
                    format!("{x} ({})", c.join(", "))
                })
                .into(),
            l.stable_up_to.map_or("—".into(), |x| format!("{x}")).into(),
            l.refined
                .as_ref()
                .map_or("—".into(), |(a, b, c)| format!("[{a:.5}, {b:.5}] ({c})"))
                .into(),
            Cell::toned(
                l.limit()
                    .map_or("> 1.0 (none found)".into(), |x| format!("{x:.4}")),
                Tone::Strong,
            ),
            l.accurate_up_to
                .map_or("—".into(), |x| format!("{x}"))
                .into(),
        ]);
    }
    t
}

/// Short map cell: class symbol with the error or the failure time; the reason on hover.
fn map_cell(r: &StabilityRun) -> Cell {
    let at = |t: Option<f64>| t.map_or(String::new(), |t| format!(" t={t:.3}"));
    // Three digits keep the eleven-column map on a page; the CSV has them all.
    let e = r.error.map_or("—".into(), |v| format!("{v:.2e}"));
    let cell = match &r.class {
        Class::Accurate => Cell::toned(format!("✓ {e}"), Tone::Pass),
        Class::Inaccurate => Cell::toned(format!("~ {e}"), Tone::Warn),
        Class::Diverged { time: None, .. } => Cell::toned("✗ panic", Tone::Fail),
        Class::Diverged { time, .. } => Cell::toned(format!("✗{}", at(*time)), Tone::Fail),
        Class::NotConverged { time, .. } => {
            Cell::toned(format!("NC{}", at(Some(*time))), Tone::Fail)
        }
    };
    match r.class.reason() {
        "" => cell,
        why => cell.hint(why),
    }
}

/// The map: rows `scene · engine/variant`, columns Δt/T.
fn map_table(st: &StabilityResult) -> Table {
    let mut dts: Vec<f64> = st.runs.iter().map(|r| r.dt_over_t).collect();
    dts.sort_by(f64::total_cmp);
    dts.dedup();
    let mut header = vec!["scene · engine/variant  ·  Δt/T →".to_string()];
    header.extend(dts.iter().map(|x| format!("{x}")));
    let mut t = Table {
        numeric: std::iter::once(false)
            .chain(std::iter::repeat_n(true, dts.len()))
            .collect(),
        header,
        rows: Vec::new(),
    };
    for l in st.rows() {
        let mut row: Vec<Cell> = vec![l.clone().into()];
        for &x in &dts {
            let hit = st.runs.iter().find(|r| r.is_row(&l) && r.dt_over_t == x);
            row.push(hit.map_or(Cell::plain(""), map_cell));
        }
        t.rows.push(row);
    }
    t
}

const MAP_LEGEND: &str = "Rows: scene · engine/variant; columns: Δt/T. Cells: ✓ accurate, ~ inaccurate (with the max error), ✗ diverged (with the time, s), NC not converged (with the time, s); hover a failed cell for the reason.";

/// Every run with its class, time, error and energy audit.
fn runs_table(st: &StabilityResult) -> Table {
    let mut t = Table::with_columns(&[
        ("scene", false),
        ("engine/variant", false),
        ("Δt/T", true),
        ("Δt [s]", true),
        ("class", false),
        ("at t [s]", true),
        ("max error", true),
        ("energy rel. err", true),
        ("energy lost at end [% of supplied]", true),
        ("reason", false),
    ]);
    for q in &st.runs {
        let (energy, lost) = match &q.energy {
            Ok(e) => (
                format!("{:.2e}", e.relative_error),
                if e.supplied != 0.0 {
                    format!("{:+.2}", 100.0 * e.end_error / e.supplied)
                } else {
                    "—".into()
                },
            ),
            Err(_) => ("n/a".into(), "—".into()),
        };
        t.rows.push(vec![
            q.case.clone().into(),
            q.series.clone().into(),
            format!("{}", q.dt_over_t).into(),
            format!("{:.4e}", q.dt).into(),
            q.class.label().into(),
            q.class
                .time()
                .map_or("—".into(), |t| format!("{t:.5}"))
                .into(),
            sci(q.error).into(),
            energy.into(),
            lost.into(),
            q.class.reason().into(),
        ]);
    }
    t
}

/// The study's own page.
pub(crate) fn document(r: &StabilityResult) -> Vec<Block> {
    let mut b = vec![
        Block::Heading(1, "Stability on stiff and extreme scenes".into()),
        Block::Para(format!(
            "Classes: accurate (✓) max error of the relative displacement ≤ {} % of its peak (SAP2000 \"Acceptable\"); inaccurate (~) completed, stable, larger error; diverged (✗) NaN/Inf in the trace, divergence reported by the engine, an engine panic, or energy growth (stored + dissipated energy above 1 + {} times the most energy ever supplied); not converged (NC) an iterative solver gave up. Cells show the max error or the time of the failure. The worker count and the wall time of every run are in `{}` (this page and `{}` are the same whatever the number of workers).",
            100.0 * r.criteria.accuracy,
            r.criteria.growth_factor,
            rockslide_verify::sweep::stability::TIMING_FILE,
            rockslide_verify::sweep::stability::FILE,
        )),
        Block::Facts(vec![(
            "Made by".into(),
            format!("{}, commit {}", crate::stamp::tool(), crate::stamp::COMMIT),
        )]),
        Block::Heading(2, "Practical stability limits".into()),
        Block::Table(limits_table(&r.limits)),
        Block::Heading(2, "Scenes".into()),
    ];
    let mut scenes = Table::with_columns(&[
        ("scene", false),
        ("title", false),
        ("T [s]", true),
        ("basis", false),
    ]);
    for s in &r.cases {
        scenes.rows.push(vec![
            s.name.clone().into(),
            s.title.clone().into(),
            format!("{:.6}", s.period).into(),
            s.basis.clone().into(),
        ]);
    }
    b.push(Block::Table(scenes));
    if !r.not_applicable.is_empty() {
        b.push(Block::List(
            r.not_applicable
                .iter()
                .map(|n| format!("{}: {} not applicable — {}", n.scene, n.engine, n.why))
                .collect(),
        ));
    }
    b.push(Block::Heading(2, "Map".into()));
    b.push(Block::Para(MAP_LEGEND.into()));
    b.push(Block::Table(map_table(r)));
    if let Some(svg) = figure(r) {
        b.push(Block::Figure {
            file: "stability.svg".into(),
            caption: "Stability map: the class of every run against Δt/T (log scale), each engine variant's practical limit dashed.".into(),
            svg,
        });
    }
    b.push(Block::Heading(2, "Every run".into()));
    b.push(Block::Table(runs_table(r)));
    if let Some((c, why)) = r
        .runs
        .iter()
        .find_map(|q| q.energy.as_ref().err().map(|w| (&q.case, w)))
    {
        b.push(Block::Para(format!(
            "Energy audit not available for some runs (e.g. {c}): {why}."
        )));
    }
    b
}

/// The stability section of the suite report, or how to produce it.
pub(crate) fn suite_section(st: Option<&Result<StabilityResult, String>>) -> Vec<Block> {
    let file = format!(
        "{}/{}",
        rockslide_verify::sweep::stability::DIR,
        rockslide_verify::sweep::stability::FILE
    );
    let mut b = vec![Block::Heading(
        2,
        "Stability on stiff and extreme scenes".into(),
    )];
    let st = match st {
        None => {
            b.push(Block::Para(format!(
                "No stability study in the output folder ({file}): `rockslide stability` runs the scenes of cases/stability/ and writes it; `rockslide run` and `check` pick it up."
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
        "From {file} (`rockslide stability`): every stiff and extreme scene run by every applicable engine variant over Δt/T; each run classified as accurate (✓, max error of the relative displacement within {} % of its peak), inaccurate (~, completed and stable, larger error), diverged (✗, NaN/Inf, engine-reported divergence, panic or energy growth, with the time) or not converged (NC, an iterative solver gave up, with the time).",
        100.0 * st.criteria.accuracy
    )));
    b.push(Block::Heading(3, "Stated stability limits".into()));
    b.push(Block::Table(limits_table(&st.limits)));
    b.push(Block::Heading(3, "Map".into()));
    b.push(Block::Para(MAP_LEGEND.into()));
    b.push(Block::Table(map_table(st)));
    if let Some(svg) = figure(st) {
        b.push(Block::Figure {
            file: "stability-map.svg".into(),
            caption: "Stability map: the class of every run against Δt/T (log scale), each engine variant's practical limit dashed.".into(),
            svg,
        });
    }
    let failures: Vec<String> = st
        .runs
        .iter()
        .filter(|r| !r.class.reason().is_empty())
        .map(|r| {
            format!(
                "{} · {} at Δt/T = {}: {}{} — {}",
                r.case,
                r.series,
                r.dt_over_t,
                r.class.label(),
                r.class
                    .time()
                    .map_or(String::new(), |t| format!(" at t = {t:.4} s")),
                r.class.reason()
            )
        })
        .collect();
    if !failures.is_empty() {
        b.push(Block::Heading(3, "Why runs failed".into()));
        b.push(Block::List(failures));
    }
    b
}

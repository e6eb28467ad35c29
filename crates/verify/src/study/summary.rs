//! A study's summary: read the per-point result files back (from one output folder or
//! from several shards' folders), check that every grid point is there with a matching
//! hash, and write one table as CSV and Markdown, a headline, and plots. The summary is
//! built only from result files, never from in-memory runs, so a sharded study merged
//! afterwards gives byte-identical output to the same study run in one go; wall times are
//! left out of it for the same reason.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::grid::{Grid, short_name};
use super::plot::{residual_vs_pga_svg, residual_vs_pga_svg_of, run_slug};
use super::runner::{PointResult, read_result, result_path};
use rockslide_core::case::record::STANDARD_GRAVITY;
use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;

/// The results of every grid point, in point order.
#[derive(Debug, Clone)]
pub struct Collected {
    /// One result per point.
    pub results: Vec<PointResult>,
}

/// Gather the result of every grid point from the `from` folders (first match wins),
/// copying each into `<out>/runs/` when it is not there yet. Error when a point is
/// missing everywhere: the message lists the missing points.
pub fn collect(grid: &Grid, from: &[PathBuf], out: &Path) -> Result<Collected, Error> {
    let mut results = Vec::with_capacity(grid.points.len());
    let mut missing = Vec::new();
    for p in &grid.points {
        let hash = grid.point_hash(p);
        let mut found = None;
        for dir in std::iter::once(out).chain(from.iter().map(PathBuf::as_path)) {
            let path = result_path(dir, p);
            if let Some(r) = read_result(&path).filter(|r| r.hash == hash) {
                if dir != out {
                    let bytes = std::fs::read(&path).map_err(|e| Error::io(&path, e))?;
                    write_atomically(&result_path(out, p), &bytes)?;
                }
                found = Some(r);
                break;
            }
        }
        match found {
            Some(r) => results.push(r),
            None => missing.push(p.id()),
        }
    }
    if !missing.is_empty() {
        let shown: Vec<&str> = missing.iter().take(20).map(String::as_str).collect();
        return Err(Error::Other(format!(
            "{} of {} grid points have no matching result ({}{}): run the missing shards (or `rockslide study` without --shard) first",
            missing.len(),
            grid.points.len(),
            shown.join(", "),
            if missing.len() > shown.len() {
                ", …"
            } else {
                ""
            }
        )));
    }
    Ok(Collected { results })
}

/// One row per (point, run).
struct Row<'a> {
    r: &'a PointResult,
    run: &'a super::runner::RunSummary,
}

fn rows(c: &Collected) -> Vec<Row<'_>> {
    c.results
        .iter()
        .flat_map(|r| r.runs.iter().map(move |run| Row { r, run }))
        .collect()
}

fn opt(x: Option<f64>) -> String {
    x.map_or_else(String::new, |v| format!("{v}"))
}

/// The summary table as CSV (SI values at full precision, plus cm and g columns).
pub fn summary_csv(c: &Collected) -> String {
    let mut s = String::from(
        "point,record,pga_m_s2,pga_g,scale_factor,mu,polarity,engine,variant,dt_s,status,residual_sliding_m,residual_sliding_cm,peak_abs_sliding_m,peak_relative_displacement_m,steps\n",
    );
    for Row { r, run } in rows(c) {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},\"{}\",{},{},{},{},{}",
            r.point.id(),
            short_name(&r.record),
            r.pga,
            r.pga / STANDARD_GRAVITY,
            r.scale_factor,
            r.mu,
            r.point.polarity,
            run.engine,
            run.variant,
            run.dt,
            run.status.replace('"', "'"),
            opt(run.residual_sliding),
            opt(run.residual_sliding.map(|m| m * 100.0)),
            opt(run.peak_abs_sliding),
            opt(run.peak_relative_displacement),
            run.steps
        );
    }
    s
}

/// The run labels `engine/variant` in the order they first appear (engines in the
/// order the base case plans them, the rigid block last).
pub fn run_labels(c: &Collected) -> Vec<String> {
    let mut labels: Vec<String> = Vec::new();
    for Row { run, .. } in rows(c) {
        let l = format!("{}/{}", run.engine, run.variant);
        if !labels.contains(&l) {
            labels.push(l);
        }
    }
    labels
}

/// Residual sliding of run `label` at every point where it and `basis` both have one and
/// |basis| > 0.1 mm: the relative differences 100·(label/basis − 1), in point order.
pub fn agreement(c: &Collected, label: &str, basis: &str) -> Vec<f64> {
    let find = |r: &PointResult, l: &str| {
        r.runs
            .iter()
            .find(|x| format!("{}/{}", x.engine, x.variant) == l)
            .and_then(|x| x.residual_sliding)
    };
    c.results
        .iter()
        .filter_map(|r| match (find(r, label), find(r, basis)) {
            (Some(a), Some(b)) if b.abs() > 1e-4 => Some(100.0 * (a / b - 1.0)),
            _ => None,
        })
        .collect()
}

/// Headline lines: per engine/variant, the largest |residual sliding| and where; each
/// engine/variant against the first one planned (residual sliding, point by point); and
/// engine-to-rigid-block ratios when both are present.
pub fn headline(c: &Collected) -> Vec<String> {
    let labels = run_labels(c);
    let mut out = Vec::new();
    for l in &labels {
        let best = rows(c)
            .into_iter()
            .filter(|row| format!("{}/{}", row.run.engine, row.run.variant) == *l)
            .filter_map(|row| row.run.residual_sliding.map(|v| (v.abs(), row)))
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((v, row)) = best {
            out.push(format!(
                "{l}: largest |residual sliding| {:.2} cm ({:.4} m) — {} at PGA {:.3} g, μ = {}, polarity {:+}",
                v * 100.0,
                v,
                short_name(&row.r.record),
                row.r.pga / STANDARD_GRAVITY,
                row.r.mu,
                row.r.point.polarity
            ));
        }
    }
    // Engines against the first engine planned, point by point.
    let engines: Vec<&String> = labels
        .iter()
        .filter(|l| !l.starts_with("newmark-rigid"))
        .collect();
    if let Some((basis, others)) = engines.split_first() {
        for l in others {
            let mut d: Vec<f64> = agreement(c, l, basis).iter().map(|x| x.abs()).collect();
            if d.is_empty() {
                continue;
            }
            d.sort_by(f64::total_cmp);
            out.push(format!(
                "{l} against {basis}, residual sliding: median |Δ| {:.2} %, largest {:.2} % over {} points with |sliding| > 0.1 mm",
                d[d.len() / 2],
                d[d.len() - 1],
                d.len()
            ));
        }
    }
    // Engines against the rigid block, point by point.
    for l in labels.iter().filter(|l| !l.starts_with("newmark-rigid")) {
        let mut ratios = Vec::new();
        for r in &c.results {
            let e = r
                .runs
                .iter()
                .find(|x| format!("{}/{}", x.engine, x.variant) == *l);
            let n = r.runs.iter().find(|x| x.engine == "newmark-rigid");
            if let (Some(e), Some(n)) = (e, n) {
                if let (Some(a), Some(b)) = (e.residual_sliding, n.residual_sliding) {
                    if b.abs() > 1e-4 {
                        ratios.push(a.abs() / b.abs());
                    }
                }
            }
        }
        if !ratios.is_empty() {
            ratios.sort_by(f64::total_cmp);
            out.push(format!(
                "{l} / newmark-rigid |residual sliding|: median {:.2}, range {:.2}–{:.2} over {} points with rigid-block sliding > 0.1 mm",
                ratios[ratios.len() / 2],
                ratios[0],
                ratios[ratios.len() - 1],
                ratios.len()
            ));
        }
    }
    out
}

/// The summary as Markdown: provenance, headline, the table in display units.
pub fn summary_markdown(grid: &Grid, c: &Collected) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Study: {}\n", grid.title);
    let _ = writeln!(
        s,
        "- grid: `{}` (sha256 {})\n- base case: `{}` — {} (sha256 {})\n- points: {}, runs: {}\n- rigid block: Newmark 1965, ky = μ·g of the model, two-way sliding, exact for piecewise-linear records; sliding sign: mass minus ground\n- tool: rockslide {}\n",
        grid.path.display(),
        &grid.sha256[..12],
        grid.base.path.display(),
        grid.base.title,
        &grid.base.sha256[..12],
        c.results.len(),
        rows(c).len(),
        env!("CARGO_PKG_VERSION"),
    );
    let _ = writeln!(s, "## Headline\n");
    for h in headline(c) {
        let _ = writeln!(s, "- {h}");
    }
    let _ = writeln!(
        s,
        "\n## Runs\n\n| point | record | PGA [g] | μ | pol. | run | status | residual sliding [cm] | peak abs. sliding [cm] |\n|---|---|---:|---:|---:|---|---|---:|---:|"
    );
    for Row { r, run } in rows(c) {
        let cm = |x: Option<f64>| x.map_or_else(|| "—".into(), |v| format!("{:.3}", v * 100.0));
        let _ = writeln!(
            s,
            "| {} | {} | {:.3} | {} | {:+} | {}/{} | {} | {} | {} |",
            r.point.id(),
            short_name(&r.record),
            r.pga / STANDARD_GRAVITY,
            r.mu,
            r.point.polarity,
            run.engine,
            run.variant,
            run.status,
            cm(run.residual_sliding),
            cm(run.peak_abs_sliding)
        );
    }
    let na: Vec<String> = c
        .results
        .first()
        .map(|r| {
            r.not_applicable
                .iter()
                .map(|(e, why)| format!("- {e}: not applicable — {why}"))
                .collect()
        })
        .unwrap_or_default();
    if !na.is_empty() {
        let _ = writeln!(s, "\n## Engines not applicable\n\n{}", na.join("\n"));
    }
    let _ = writeln!(s, "\n![residual sliding against PGA](residual-vs-pga.svg)");
    let labels = run_labels(c);
    let engines: Vec<&String> = labels
        .iter()
        .filter(|l| !l.starts_with("newmark-rigid"))
        .collect();
    if engines.len() > 1 {
        let _ = writeln!(s, "\n## Per engine (with the rigid block)\n");
        for l in engines {
            let _ = writeln!(s, "![{l}](residual-vs-pga-{}.svg)", run_slug(l));
        }
    }
    s
}

/// Write `summary.csv`, `summary.md` and `residual-vs-pga.svg` into `out`, and with more
/// than one engine/variant `residual-vs-pga-<engine>-<variant>.svg` for each.
pub fn write_summary(grid: &Grid, c: &Collected, out: &Path) -> Result<(), Error> {
    write_atomically(&out.join("summary.csv"), summary_csv(c).as_bytes())?;
    write_atomically(
        &out.join("summary.md"),
        summary_markdown(grid, c).as_bytes(),
    )?;
    let svg = residual_vs_pga_svg(&grid.title, c)?;
    write_atomically(&out.join("residual-vs-pga.svg"), svg.as_bytes())?;
    let labels = run_labels(c);
    let engines: Vec<&String> = labels
        .iter()
        .filter(|l| !l.starts_with("newmark-rigid"))
        .collect();
    if engines.len() > 1 {
        for l in engines {
            let svg = residual_vs_pga_svg_of(&grid.title, c, Some(l))?;
            let name = format!("residual-vs-pga-{}.svg", run_slug(l));
            write_atomically(&out.join(name), svg.as_bytes())?;
        }
    }
    Ok(())
}

//! Study plots (plotters, SVG): residual sliding against PGA, one line per engine/variant
//! and record (and μ, polarity when the grid varies them), so engines can be compared with
//! each other and with Newmark's rigid block across intensity; and the same plot for one
//! engine/variant at a time (with the rigid block beside it), so that a study with every
//! engine stays readable.

use std::collections::BTreeMap;

use plotters::prelude::*;

use super::grid::short_name;
use super::summary::Collected;
use rockslide_core::case::record::STANDARD_GRAVITY;
use rockslide_core::error::Error;

/// |Residual sliding| (cm) against PGA (g), as an SVG document: every run of the study.
pub fn residual_vs_pga_svg(title: &str, c: &Collected) -> Result<String, Error> {
    residual_vs_pga_svg_of(title, c, None)
}

/// File-name-safe form of a run label `engine/variant`.
pub fn run_slug(label: &str) -> String {
    label
        .chars()
        .map(|ch| if ch.is_ascii_alphanumeric() { ch } else { '-' })
        .collect()
}

/// |Residual sliding| (cm) against PGA (g) of one run label `engine/variant` and, beside
/// it, the rigid block (`newmark-rigid/…`); `None`: every run.
pub fn residual_vs_pga_svg_of(
    title: &str,
    c: &Collected,
    only: Option<&str>,
) -> Result<String, Error> {
    // Series key → points (pga g, |residual| cm).
    let vary_mu = distinct(c.results.iter().map(|r| r.mu.to_bits())) > 1;
    let vary_pol = distinct(c.results.iter().map(|r| r.point.polarity.to_bits())) > 1;
    let mut series: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for r in &c.results {
        for run in &r.runs {
            let Some(res) = run.residual_sliding else {
                continue;
            };
            let label = format!("{}/{}", run.engine, run.variant);
            if only.is_some_and(|o| o != label && run.engine != "newmark-rigid") {
                continue;
            }
            let mut key = format!("{}/{} — {}", run.engine, run.variant, short_name(&r.record));
            if vary_mu {
                key.push_str(&format!(", μ = {}", r.mu));
            }
            if vary_pol {
                key.push_str(&format!(", pol. {:+}", r.point.polarity));
            }
            series
                .entry(key)
                .or_default()
                .push((r.pga / STANDARD_GRAVITY, res.abs() * 100.0));
        }
    }
    for pts in series.values_mut() {
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    let x_max = series
        .values()
        .flatten()
        .fold(0.0_f64, |m, p| m.max(p.0))
        .max(1e-3)
        * 1.05;
    let y_max = series
        .values()
        .flatten()
        .fold(0.0_f64, |m, p| m.max(p.1))
        .max(1e-3)
        * 1.05;
    let mut svg = String::new();
    {
        let height = 480 + 18 * series.len() as u32;
        let root = SVGBackend::with_string(&mut svg, (900, height)).into_drawing_area();
        let err = |e: &dyn std::fmt::Display| Error::Other(format!("plot: {e}"));
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                match only {
                    Some(l) => format!("{title}: residual sliding against PGA, {l}"),
                    None => format!("{title}: residual sliding against PGA"),
                },
                ("sans-serif", 18),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..x_max, 0.0..y_max)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("PGA [g]")
            .y_desc("|residual sliding| [cm]")
            .draw()
            .map_err(|e| err(&e))?;
        for (i, (name, pts)) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
                .map_err(|e| err(&e))?
                .label(name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
                });
            chart
                .draw_series(
                    pts.iter()
                        .map(|&(x, y)| Circle::new((x, y), 3, color.filled())),
                )
                .map_err(|e| err(&e))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    Ok(svg)
}

fn distinct(it: impl Iterator<Item = u64>) -> usize {
    let mut v: Vec<u64> = it.collect();
    v.sort_unstable();
    v.dedup();
    v.len()
}

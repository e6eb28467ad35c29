//! Study figures: residual sliding against PGA, one line per engine/variant and record
//! (and μ, polarity when the grid varies them), so that engines can be compared with each
//! other and with Newmark's rigid block across intensity; and the same plot for one
//! engine/variant at a time (with the rigid block beside it), so that a study with every
//! engine stays readable. Drawn from the typed [`Study`] only: the same results give the
//! same bytes.

use std::collections::BTreeMap;

use plotters::prelude::*;

use crate::doc::figure::{
    Entry, GRID, compact_svg, draw_legend, failed_svg, legend_height, palette,
};
use rockslide_core::case::record::STANDARD_GRAVITY;
use rockslide_verify::study::{RIGID, Study, label, short_name};

/// Width of the figure, pixels.
const W: u32 = 900;
/// Height of the plot area, pixels (the legend strip comes below).
const H: u32 = 480;

/// File-name-safe form of a run label `engine/variant`.
pub(crate) fn run_slug(label: &str) -> String {
    label
        .chars()
        .map(|ch| if ch.is_ascii_alphanumeric() { ch } else { '-' })
        .collect()
}

fn distinct(it: impl Iterator<Item = u64>) -> usize {
    let mut v: Vec<u64> = it.collect();
    v.sort_unstable();
    v.dedup();
    v.len()
}

/// |Residual sliding| (mm) against PGA (g) of one run label `engine/variant` and, beside
/// it, the rigid block; `None`: every run.
pub(crate) fn residual_vs_pga(c: &Study, only: Option<&str>) -> String {
    let vary_mu = distinct(c.results.iter().map(|r| r.mu.to_bits())) > 1;
    let vary_pol = distinct(c.results.iter().map(|r| r.point.polarity.to_bits())) > 1;
    // Series key → points (PGA in g, |residual| in mm).
    let mut series: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for (r, run) in c.rows() {
        let Some(res) = run.residual_resultant_sliding.or(run.residual_sliding) else {
            continue;
        };
        let l = label(run);
        if only.is_some_and(|o| o != l && run.engine != RIGID) {
            continue;
        }
        let mut key = format!("{l} — {}", short_name(&r.record));
        if vary_mu {
            key.push_str(&format!(", μ = {}", r.mu));
        }
        if vary_pol {
            key.push_str(&format!(", pol. {:+}", r.point.polarity));
        }
        series
            .entry(key)
            .or_default()
            .push((r.pga / STANDARD_GRAVITY, res.abs() * 1000.0));
    }
    for pts in series.values_mut() {
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    let max = |f: fn(&(f64, f64)) -> f64| {
        series
            .values()
            .flatten()
            .map(f)
            .filter(|v| v.is_finite())
            .fold(0.0_f64, f64::max)
            .max(1e-3)
            * 1.05
    };
    let (x_max, y_max) = (max(|p| p.0), max(|p| p.1));
    let entries: Vec<Entry> = series
        .keys()
        .enumerate()
        .map(|(i, k)| (k.clone(), palette(i), false))
        .collect();
    let lh = legend_height(&entries, W);
    let caption = match only {
        Some(l) => format!("{}: residual sliding against PGA, {l}", c.title),
        None => format!("{}: residual sliding against PGA", c.title),
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (W, H + lh)).into_drawing_area();
        let result = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let (plot, legend) = root.split_vertically(H);
            let mut chart = ChartBuilder::on(&plot)
                .caption(caption, ("sans-serif", 16))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(0.0..x_max, 0.0..y_max)?;
            chart
                .configure_mesh()
                .x_desc("PGA [g]")
                .y_desc("|residual sliding| [mm]")
                .label_style(("sans-serif", 13))
                .light_line_style(GRID)
                .draw()?;
            for (i, pts) in series.values().enumerate() {
                let color = palette(i);
                chart.draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))?;
                chart.draw_series(
                    pts.iter()
                        .map(|&p| Circle::new(p, 3, ShapeStyle::from(color).filled())),
                )?;
            }
            draw_legend(&legend, &entries)?;
            root.present()?;
            Ok(())
        })();
        if let Err(e) = result {
            drop(root);
            return failed_svg(W, &e.to_string());
        }
    }
    compact_svg(&svg)
}

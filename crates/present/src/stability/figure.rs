//! The stability map, drawn from the typed result: one row per `scene · engine/variant`,
//! one marker per run at its Δt/T (log scale) coloured by class, and each engine
//! variant's practical limit as a dashed vertical line in a colour no class uses. `stability.svg` beside the study
//! and `stability-map.svg` in the suite report are this figure.

use plotters::prelude::*;

use crate::doc::figure::{
    Entry, GRID, class_colour, compact_svg, draw_legend, failed_svg, legend_height, limit_colour,
    log_range,
};
use rockslide_verify::sweep::StabilityResult;

/// Width of the figure, pixels.
const W: u32 = 1100;
/// The classes, in legend order.
const CLASSES: [&str; 4] = ["accurate", "inaccurate", "diverged", "not converged"];

/// The map as an SVG document; `None` when there is no run.
pub(crate) fn figure(st: &StabilityResult) -> Option<String> {
    let rows = st.rows();
    if rows.is_empty() {
        return None;
    }
    let (x0, x1) = log_range(st.runs.iter().map(|r| r.dt_over_t))?;
    let plot_h = 80 + 22 * rows.len() as u32;
    let limits: Vec<(String, f64)> = st
        .limits
        .iter()
        .filter_map(|l| l.limit().map(|x| (l.label.clone(), x)))
        .collect();
    let mut entries: Vec<Entry> = CLASSES
        .iter()
        .map(|c| (c.to_string(), class_colour(c), false))
        .collect();
    entries.extend(
        limits
            .iter()
            .enumerate()
            .map(|(i, (l, x))| (format!("{l} limit Δt/T = {x:.4}"), limit_colour(i), true)),
    );
    let lh = legend_height(&entries, W);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (W, plot_h + lh)).into_drawing_area();
        let result = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let (plot, legend) = root.split_vertically(plot_h);
            let n = rows.len();
            let mut chart = ChartBuilder::on(&plot)
                .caption("Stability map: class of every run", ("sans-serif", 16))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(330)
                .build_cartesian_2d((x0..x1).log_scale(), -0.5..(n as f64 - 0.5))?;
            chart
                .configure_mesh()
                .x_desc("Δt / T")
                .y_labels(n)
                .y_label_formatter(&|v| {
                    let i = v.round();
                    if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < n {
                        rows[n - 1 - i as usize].clone()
                    } else {
                        String::new()
                    }
                })
                .x_label_formatter(&|v| format!("{v}"))
                .label_style(("sans-serif", 12))
                .light_line_style(GRID)
                .draw()?;
            for r in &st.runs {
                let Some(i) = rows.iter().position(|x| r.is_row(x)) else {
                    continue;
                };
                let y = (n - 1 - i) as f64;
                let c = class_colour(r.class.label());
                chart.draw_series(std::iter::once(Circle::new(
                    (r.dt_over_t, y),
                    6,
                    ShapeStyle::from(c).filled(),
                )))?;
            }
            for (i, (_, x)) in limits.iter().enumerate() {
                chart.draw_series(DashedLineSeries::new(
                    [(*x, -0.5), (*x, n as f64 - 0.5)],
                    6,
                    4,
                    limit_colour(i).stroke_width(2),
                ))?;
            }
            draw_legend(&legend, &entries)?;
            root.present()?;
            Ok(())
        })();
        if let Err(e) = result {
            drop(root);
            return Some(failed_svg(W, &e.to_string()));
        }
    }
    Some(compact_svg(&svg))
}

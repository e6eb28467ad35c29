//! The work-precision figure of a sweep, drawn from its typed result: left, max error
//! against Δt (log-log: the slope is the observed order); right, max error against median
//! run time (lower left is better). The same figure is `sweep.svg` beside the sweep and
//! `plot-work-precision.svg` in the case report.

use plotters::prelude::*;

use crate::doc::figure::{
    Entry, GRID, compact_svg, draw_legend, failed_svg, legend_height, log_range, palette,
};
use rockslide_verify::sweep::SweepResult;

/// Width of the figure, pixels.
const W: u32 = 1100;
/// Height of the plot area, pixels (the legend strip comes below).
const H: u32 = 420;

/// The figure as an SVG document; `None` when no rung has an error.
pub(crate) fn figure(sweep: &SweepResult) -> Option<String> {
    let rungs = || sweep.series.iter().flat_map(|s| &s.rungs);
    let err = log_range(rungs().filter_map(|r| r.error.map(|e| e.max)))?;
    let dt = log_range(rungs().map(|r| r.dt))?;
    let time = log_range(
        rungs()
            .filter(|r| r.error.is_some())
            .filter_map(|r| r.seconds.map(|s| s.median)),
    );
    let entries: Vec<Entry> = sweep
        .series
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let order = s
                .observed_order()
                .map_or("p —".into(), |p| format!("p = {p:.2}"));
            (format!("{} ({order})", s.label), palette(i), false)
        })
        .collect();
    let lh = legend_height(&entries, W);
    let case = &sweep.case;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (W, H + lh)).into_drawing_area();
        let result = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let (plots, legend) = root.split_vertically(H);
            let (left, right) = plots.split_horizontally(W / 2);
            // (area, title, x axis, x range)
            let panels = [
                (
                    &left,
                    format!("{case}: max error against Δt (slope = order)"),
                    "Δt [s]",
                    Some(dt),
                ),
                (
                    &right,
                    format!("{case}: work-precision"),
                    "median run time [s]",
                    time,
                ),
            ];
            for (k, (area, title, xdesc, xr)) in panels.into_iter().enumerate() {
                let Some((x0, x1)) = xr else { continue };
                let mut chart = ChartBuilder::on(area)
                    .caption(title, ("sans-serif", 16))
                    .margin(12)
                    .x_label_area_size(40)
                    .y_label_area_size(70)
                    .build_cartesian_2d((x0..x1).log_scale(), (err.0..err.1).log_scale())?;
                chart
                    .configure_mesh()
                    .x_desc(xdesc)
                    .y_desc("max |Δx| / peak |x|")
                    .x_labels(6)
                    .y_labels(8)
                    .x_label_formatter(&|v| format!("{v:.0e}"))
                    .y_label_formatter(&|v| format!("{v:.0e}"))
                    .label_style(("sans-serif", 13))
                    .light_line_style(GRID)
                    .draw()?;
                let n = sweep.series.len() as u32;
                for (i, s) in sweep.series.iter().enumerate() {
                    let c = palette(i);
                    // Earlier series wider, so coinciding curves stay visible.
                    let w = 1 + (n - 1 - i as u32).min(4);
                    let pts: Vec<(f64, f64)> = s
                        .rungs
                        .iter()
                        .filter_map(|r| {
                            let x = if k == 0 {
                                Some(r.dt)
                            } else {
                                r.seconds.map(|s| s.median)
                            };
                            Some((x?, r.error?.max))
                        })
                        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && y.is_finite())
                        .collect();
                    chart.draw_series(LineSeries::new(pts.iter().copied(), c.stroke_width(w)))?;
                    chart.draw_series(
                        pts.iter()
                            .map(|&p| Circle::new(p, 2 + w, ShapeStyle::from(c).filled())),
                    )?;
                }
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

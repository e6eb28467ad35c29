//! Figures of the picked-up studies, drawn again from their CSV files with `plotters` so
//! that they share the report's look: the work-precision pair of a sweep (max error
//! against Δt — the slope is the observed order — and against median run time, both
//! log-log) and the stability map (class of every run over Δt/T, one row per scene and
//! engine variant). Also the legend strip every report figure puts *below* its plot area,
//! so that no legend box hides data.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::attachments::{Stability, Sweep};

/// Colour of the i-th series (a qualitative palette, dark enough on white).
pub(crate) fn palette(i: usize) -> RGBColor {
    const P: [RGBColor; 8] = [
        RGBColor(0x1f, 0x77, 0xb4),
        RGBColor(0xd6, 0x27, 0x28),
        RGBColor(0x2c, 0xa0, 0x2c),
        RGBColor(0xff, 0x7f, 0x0e),
        RGBColor(0x94, 0x67, 0xbd),
        RGBColor(0x8c, 0x56, 0x4b),
        RGBColor(0xe3, 0x77, 0xc2),
        RGBColor(0x17, 0xbe, 0xcf),
    ];
    P[i % P.len()]
}

/// One legend entry: label, colour, dashed line.
pub(crate) type Entry = (String, RGBColor, bool);

/// Entries per legend row for a figure `width` pixels wide.
fn per_row(width: u32) -> usize {
    ((width / 250) as usize).max(1)
}

/// Height in pixels of the legend strip for `n` entries.
pub(crate) fn legend_height(n: usize, width: u32) -> u32 {
    (n.div_ceil(per_row(width)) as u32) * 18 + 10
}

/// Draw a legend strip (a short line and the label per entry, in rows) on `area`.
pub(crate) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[Entry],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (w, _) = area.dim_in_pixel();
    let cols = per_row(w);
    let col_w = (w as i32 - 20) / cols as i32;
    for (k, (label, c, dashed)) in entries.iter().enumerate() {
        let x = 20 + (k % cols) as i32 * col_w;
        let y = 8 + (k / cols) as i32 * 18;
        if *dashed {
            for s in 0..3 {
                area.draw(&PathElement::new(
                    vec![(x + s * 9, y + 6), (x + s * 9 + 5, y + 6)],
                    c.stroke_width(2),
                ))?;
            }
        } else {
            area.draw(&PathElement::new(
                vec![(x, y + 6), (x + 24, y + 6)],
                c.stroke_width(2),
            ))?;
        }
        area.draw(&Text::new(
            label.clone(),
            (x + 30, y),
            ("sans-serif", 13).into_font().color(&BLACK),
        ))?;
    }
    Ok(())
}

fn failed_svg(width: u32, why: &str) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"40\"><text x=\"8\" y=\"24\">plot failed: {}</text></svg>",
        super::format::esc(why)
    )
}

/// Decade bounds around positive values.
fn log_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, 0.0_f64), |(a, b), v| (a.min(v), b.max(v)));
    (hi > 0.0).then(|| {
        // Whole decades, widened a little so the end ticks are labelled inside the axis.
        (
            0.8 * 10f64.powf(lo.log10().floor()),
            1.25 * 10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0)),
        )
    })
}

/// The work-precision figure of a sweep: left, max error against Δt; right, max error
/// against median run time. Returns `None` when no rung has an error.
pub(crate) fn sweep_figure(sweep: &Sweep, case: &str) -> Option<String> {
    const W: u32 = 1100;
    let series = sweep.series();
    let err = log_range(sweep.rows.iter().filter_map(|r| r.max_error))?;
    let dt = log_range(sweep.rows.iter().map(|r| r.dt))?;
    let time = log_range(
        sweep
            .rows
            .iter()
            .filter(|r| r.max_error.is_some())
            .filter_map(|r| r.time_median),
    );
    let entries: Vec<Entry> = series
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let order = sweep
                .order(s)
                .map_or("order —".into(), |p| format!("order {p:.2}"));
            (format!("{s} ({order})"), palette(i), false)
        })
        .collect();
    let lh = legend_height(entries.len(), W);
    let h = 420 + lh;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (W, h)).into_drawing_area();
        let result = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let (plots, legend) = root.split_vertically(420);
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
                    .light_line_style(RGBColor(238, 238, 238))
                    .draw()?;
                let n = series.len() as u32;
                for (i, s) in series.iter().enumerate() {
                    let c = palette(i);
                    // Earlier series wider, so coinciding curves stay visible.
                    let w = 1 + (n - 1 - i as u32).min(4);
                    let pts: Vec<(f64, f64)> = sweep
                        .rungs(s)
                        .filter_map(|r| {
                            let x = if k == 0 { Some(r.dt) } else { r.time_median };
                            Some((x?, r.max_error?))
                        })
                        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
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
    Some(svg)
}

/// Colour of a stability class.
fn class_colour(class: &str) -> RGBColor {
    match class {
        "accurate" => RGBColor(0x2c, 0xa0, 0x2c),
        "inaccurate" => RGBColor(0xff, 0x9f, 0x1c),
        "diverged" => RGBColor(0xd6, 0x27, 0x28),
        _ => RGBColor(0x55, 0x55, 0x55),
    }
}

/// The stability map: one row per `scene · engine/variant`, one marker per run at its
/// Δt/T (log scale), coloured by class.
pub(crate) fn stability_figure(st: &Stability, rows: &[String]) -> Option<String> {
    const W: u32 = 1100;
    if rows.is_empty() {
        return None;
    }
    let (x0, x1) = log_range(st.runs.iter().map(|r| r.dt_over_t))?;
    let plot_h = 80 + 22 * rows.len() as u32;
    let classes = ["accurate", "inaccurate", "diverged", "not converged"];
    let entries: Vec<Entry> = classes
        .iter()
        .map(|c| (c.to_string(), class_colour(c), false))
        .collect();
    let lh = legend_height(entries.len(), W);
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
                .light_line_style(RGBColor(240, 240, 240))
                .draw()?;
            for r in &st.runs {
                let Some(i) = rows
                    .iter()
                    .position(|x| *x == format!("{} · {}", r.scene, r.series))
                else {
                    continue;
                };
                let y = (n - 1 - i) as f64;
                let c = class_colour(&r.class);
                chart.draw_series(std::iter::once(Circle::new(
                    (r.dt_over_t, y),
                    6,
                    ShapeStyle::from(c).filled(),
                )))?;
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
    Some(svg)
}

//! SVG figures of the sweep (error against Δt and work-precision, log-log) and of the
//! stability map (class of each run against Δt/T), drawn with plotters' SVG backend into
//! a string so that the caller writes them atomically.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::stability::StabilityResult;
use super::work_precision::SweepResult;
use rockslide_core::error::Error;

fn err<E: std::fmt::Display>(e: E) -> Error {
    Error::Other(format!("plot: {e}"))
}

type Points = Vec<(f64, f64)>;

/// Two panels: max error against Δt, and max error against median run time.
pub fn sweep_svg(r: &SweepResult) -> Result<String, Error> {
    let keep = |p: &(f64, f64)| p.0 > 0.0 && p.1 > 0.0 && p.0.is_finite() && p.1.is_finite();
    let mut by_dt: Vec<(String, Points)> = Vec::new();
    let mut by_time: Vec<(String, Points)> = Vec::new();
    for se in &r.series {
        let pts = |x: &dyn Fn(&super::work_precision::Rung) -> f64| -> Points {
            se.rungs
                .iter()
                .filter_map(|g| g.error.map(|e| (x(g), e.max)))
                .filter(keep)
                .collect()
        };
        let order = se
            .fitted_order
            .map_or(String::new(), |p| format!(" (p = {p:.2})"));
        by_dt.push((format!("{}{order}", se.label), pts(&|g| g.dt)));
        by_time.push((se.label.clone(), pts(&|g| g.seconds.0)));
    }
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (1200, 520)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let (left, right) = root.split_horizontally(600);
        let basis = if r.exact_basis {
            "vs exact reference"
        } else {
            "vs own finest rung"
        };
        loglog(
            &left,
            &format!("{}: max error {basis}", r.case),
            "Δt [s]",
            "max |Δx| / peak |x|",
            &by_dt,
        )?;
        loglog(
            &right,
            &format!("{}: work-precision", r.case),
            "median run time [s]",
            "max |Δx| / peak |x|",
            &by_time,
        )?;
        root.present().map_err(err)?;
    }
    Ok(buf)
}

/// Log-log lines with markers, one per series, with a legend.
fn loglog<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    caption: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[(String, Points)],
) -> Result<(), Error> {
    let all: Vec<(f64, f64)> = series.iter().flat_map(|s| s.1.iter().copied()).collect();
    if all.is_empty() {
        area.draw(&Text::new(
            format!("{caption}: no finite errors to plot"),
            (20, 40),
            ("sans-serif", 16),
        ))
        .map_err(err)?;
        return Ok(());
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in &all {
        (x0, x1, y0, y1) = (x0.min(*x), x1.max(*x), y0.min(*y), y1.max(*y));
    }
    let (x0, x1, y0, y1) = (x0 / 1.5, x1 * 1.5, y0 / 2.0, y1 * 2.0);
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()
        .map_err(err)?;
    for (i, (name, pts)) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
            .map_err(err)?
            .label(name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
        chart
            .draw_series(pts.iter().map(|p| Circle::new(*p, 4, color.filled())))
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(err)?;
    Ok(())
}

/// The stability map: one row per case and engine variant, one marker per Δt/T, coloured
/// by class, with each engine's measured limit as a vertical line.
pub fn stability_svg(r: &StabilityResult) -> Result<String, Error> {
    let rows = r.rows();
    let n = rows.len().max(1);
    let height = (120 + 28 * n) as u32;
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (1100, height)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let xs: Vec<f64> = r.runs.iter().map(|x| x.dt_over_t).collect();
        let lo = xs.iter().copied().fold(f64::MAX, f64::min).min(0.01) / 1.5;
        let hi = xs.iter().copied().fold(f64::MIN, f64::max).max(1.0) * 1.5;
        let labels = rows.clone();
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Stability map: class of each run against Δt/T",
                ("sans-serif", 18),
            )
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(330)
            .build_cartesian_2d((lo..hi).log_scale(), -0.5..(n as f64 - 0.5))
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("Δt / T")
            .y_labels(n)
            .y_label_formatter(&|y| {
                let i = y.round();
                if (y - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < labels.len() {
                    labels[i as usize].clone()
                } else {
                    String::new()
                }
            })
            .x_label_formatter(&|x| format!("{x:.2}"))
            .disable_y_mesh()
            .draw()
            .map_err(err)?;
        let classes = [
            ("accurate", GREEN.to_rgba()),
            ("inaccurate", RGBColor(230, 160, 0).to_rgba()),
            ("diverged", RED.to_rgba()),
            ("not converged", MAGENTA.to_rgba()),
        ];
        for (name, color) in classes {
            let pts: Vec<(f64, f64)> = r
                .runs
                .iter()
                .filter(|x| x.class.label() == name)
                .filter_map(|x| {
                    rows.iter()
                        .position(|l| *l == x.row_label())
                        .map(|i| (x.dt_over_t, i as f64))
                })
                .collect();
            chart
                .draw_series(pts.iter().map(|p| Circle::new(*p, 6, color.filled())))
                .map_err(err)?
                .label(name)
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, color.filled()));
        }
        for (i, l) in r.limits.iter().enumerate() {
            if let Some(limit) = l.limit() {
                let color = Palette99::pick(i).to_rgba();
                chart
                    .draw_series(DashedLineSeries::new(
                        vec![(limit, -0.5), (limit, n as f64 - 0.5)],
                        6,
                        4,
                        color.stroke_width(2),
                    ))
                    .map_err(err)?
                    .label(format!("{} limit Δt/T = {limit:.4}", l.label))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            }
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        root.present().map_err(err)?;
    }
    Ok(buf)
}

//! Plan motion in a case report: the orbit plot. The sliding path in the x–y plane
//! (`slide` along x, `slide_y` along y, in mm) of every participant — the reference and
//! every run — overlaid on equal axis scales, each participant's peak resultant sliding
//! marked by a dot and an arrow from the origin along its direction. The axes extend to
//! ± the largest peak resultant sliding of any participant, so a path that reaches its
//! peak touches the frame. Only for spatial (bidirectional) scenes.

use plotters::prelude::*;

use crate::doc::figure::Figure;
use crate::doc::figure::{GRID, draw_legend, failed_svg, legend_height, participants};
use rockslide_core::trace::Trace;
use rockslide_verify::suite::CaseResult;

/// Side of the square figure in pixels (the plot area inside it is square too).
const SIDE: u32 = 560;
/// Height of the title strip above the square.
const TITLE: u32 = 30;
/// Margin and axis-label band of the chart: the same on both axes keeps the area square.
const MARGIN: u32 = 12;
const LABELS: u32 = 60;
/// Points drawn per path at most (every k-th sample beyond, the peak always kept).
const MAX_POINTS: usize = 4000;
/// The response key of the peak resultant sliding.
const PEAK_KEY: &str = "peak_resultant_sliding";

/// One participant's path in plan, in mm.
struct Orbit {
    label: String,
    colour: RGBColor,
    /// (x, y) points of the path, mm.
    path: Vec<(f64, f64)>,
    /// The sample of largest |p| (mm) and that length.
    peak: ((f64, f64), f64),
}

/// The orbit figure of a case, if its scene is spatial and some participant has both
/// sliding channels.
pub(crate) fn orbit_figure(r: &CaseResult) -> Option<Figure> {
    r.case.scene.spatial()?;
    let orbits = orbits(r);
    if orbits.is_empty() {
        return None;
    }
    let extent = extent(r, &orbits);
    let peaks: Vec<String> = orbits
        .iter()
        .map(|o| {
            let ((x, y), p) = o.peak;
            format!("{} {p:.4} mm at {:.1}°", o.label, azimuth_deg(x, y))
        })
        .collect();
    let caption = format!(
        "Sliding path in plan: slide along x, slide_y along y, in mm, equal scales; axes \
         ±{extent:.4} mm, the largest peak resultant sliding. Peak resultant sliding \
         (dot, arrow from the origin): {}.",
        peaks.join("; ")
    );
    Some(Figure {
        id: "orbit".into(),
        caption,
        svg: draw(&orbits, extent),
    })
}

/// The half-width of both axes, mm: the largest peak resultant sliding of any participant
/// (its response quantity, or its trace's when larger or missing); 1 mm when nothing slid.
fn extent(r: &CaseResult, orbits: &[Orbit]) -> f64 {
    let reported = r
        .reference
        .iter()
        .map(|x| &x.responses)
        .chain(&r.run_responses)
        .filter_map(|resp| resp.get(PEAK_KEY).copied())
        .map(|p| p * 1e3);
    let drawn = orbits.iter().map(|o| o.peak.1);
    let e = reported
        .chain(drawn)
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    if e > 0.0 { e } else { 1.0 }
}

/// The reference and every run that has `slide` and `slide_y`, in the report's colours.
fn orbits(r: &CaseResult) -> Vec<Orbit> {
    let lines = participants(r);
    lines
        .into_iter()
        .filter_map(|(label, trace, colour, _)| {
            let (path, peak) = path(trace)?;
            Some(Orbit {
                label,
                colour,
                path,
                peak,
            })
        })
        .collect()
}

/// Every k-th (slide, slide_y) point in mm (at most [`MAX_POINTS`], the last and the
/// peak kept) and the peak: the point of largest length and that length.
#[allow(clippy::type_complexity)]
fn path(trace: &Trace) -> Option<(Vec<(f64, f64)>, ((f64, f64), f64))> {
    let x = trace.column("slide")?;
    let y = trace.column("slide_y")?;
    let n = x.len().min(y.len());
    let point = |i: usize| (x[i] * 1e3, y[i] * 1e3);
    let mut peak = ((0.0, 0.0), 0.0);
    let mut peak_index = 0;
    for i in 0..n {
        let (px, py) = point(i);
        let length = px.hypot(py);
        if length > peak.1 {
            peak = ((px, py), length);
            peak_index = i;
        }
    }
    let k = n.div_ceil(MAX_POINTS).max(1);
    let mut indices: Vec<usize> = (0..n).step_by(k).collect();
    indices.extend([peak_index, n.saturating_sub(1)]);
    indices.sort_unstable();
    indices.dedup();
    let path = indices.into_iter().filter(|&i| i < n).map(point).collect();
    Some((path, peak))
}

/// Azimuth of (x, y) in degrees from +x toward +y, 0 at the origin.
fn azimuth_deg(x: f64, y: f64) -> f64 {
    if x == 0.0 && y == 0.0 {
        0.0
    } else {
        y.atan2(x).to_degrees()
    }
}

fn draw(orbits: &[Orbit], extent: f64) -> String {
    let entries: Vec<(String, RGBColor, bool)> = orbits
        .iter()
        .map(|o| (o.label.clone(), o.colour, false))
        .collect();
    let legend = legend_height(&entries, SIDE);
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (SIDE, TITLE + SIDE + legend)).into_drawing_area();
        let result = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let (title, rest) = root.split_vertically(TITLE);
            let (plot, strip) = rest.split_vertically(SIDE);
            title.draw(&Text::new(
                "Sliding path in plan (orbit)",
                (MARGIN as i32 + LABELS as i32, 8),
                ("sans-serif", 18).into_font().color(&BLACK),
            ))?;
            let mut chart = ChartBuilder::on(&plot)
                .margin(MARGIN)
                .x_label_area_size(LABELS)
                .y_label_area_size(LABELS)
                .build_cartesian_2d(-extent..extent, -extent..extent)?;
            chart
                .configure_mesh()
                .x_desc("sliding x [mm]")
                .y_desc("sliding y [mm]")
                .label_style(("sans-serif", 13))
                .light_line_style(GRID)
                .draw()?;
            for o in orbits.iter().rev() {
                chart.draw_series(LineSeries::new(
                    o.path.iter().copied(),
                    o.colour.stroke_width(2),
                ))?;
                let (tip, _) = o.peak;
                chart.draw_series(std::iter::once(PathElement::new(
                    arrow(tip, extent),
                    o.colour.stroke_width(1),
                )))?;
                chart.draw_series(std::iter::once(Circle::new(tip, 4, o.colour.filled())))?;
            }
            draw_legend(&strip, &entries)?;
            root.present()?;
            Ok(())
        })();
        if let Err(e) = result {
            drop(root);
            return failed_svg(SIDE, &e.to_string());
        }
    }
    crate::doc::figure::compact_svg(&svg)
}

/// An arrow from the origin to `tip` with a head 4 % of the axes' half-width long.
fn arrow(tip: (f64, f64), extent: f64) -> Vec<(f64, f64)> {
    let length = tip.0.hypot(tip.1);
    if length == 0.0 {
        return vec![(0.0, 0.0)];
    }
    let head = (0.04 * extent).min(0.5 * length);
    let (ux, uy) = (tip.0 / length, tip.1 / length);
    let back = (tip.0 - head * ux, tip.1 - head * uy);
    let side = 0.5 * head;
    vec![
        (0.0, 0.0),
        tip,
        (back.0 - side * uy, back.1 + side * ux),
        tip,
        (back.0 + side * uy, back.1 - side * ux),
    ]
}

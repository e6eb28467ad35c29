//! Vertical ground motion in a case report: the friction limit that breathes. One figure
//! puts each participant's resistance R(t) beside its friction limit ±μ·N(t) (dashed, same
//! colour) and its normal force N(t), in kN; its caption carries the finding — the exact
//! residual sliding with the vertical component against the horizontal-only run of the
//! same case (the reference solved again without `[excitation.vertical]`). Only for cases
//! with a vertical component.

use plotters::prelude::*;

use crate::doc::figure::{DASH_MARK, Figure, dash_marked};
use crate::doc::figure::{
    GRID, Participant, channel_points, draw_legend, failed_svg, legend_height, participants,
};
use rockslide_core::case::Model;
use rockslide_core::trace::Trace;
use rockslide_verify::analysis::envelope::Envelope;
use rockslide_verify::suite::CaseResult;

/// Figure size in pixels (the time-history figures' width), before the legend.
const SIZE: (u32, u32) = (1000, 380);
/// Points drawn per line at most: a min/max pair per pixel column.
const MAX_POINTS: usize = 2 * SIZE.0 as usize;

/// The vertical-motion figure of a case, if it has a vertical component.
pub(crate) fn vertical_figure(r: &CaseResult) -> Option<Figure> {
    let vertical = r.case.scene.vertical()?;
    let mu = match &r.case.scene.model {
        Model::Oscillator(o) => o.contact.mu,
        Model::RockingBody(b) => b.contact.mu,
        Model::RigidBlock(b) => b.mu,
    };
    let mut lines = participants(r);
    lines.retain(|(_, t, _, _)| t.has("normal") && t.has("resistance"));
    if lines.is_empty() {
        return None;
    }
    let caption = format!(
        "Resistance R(t) (solid), friction limit ±μ·N(t) (dashed) and normal force N(t) \
         (thin) in kN, μ = {mu}; vertical a_v(t) positive upward, normal force {}. {}",
        vertical.normal_force.name(),
        finding(r)
    );
    Some(Figure {
        id: "vertical".into(),
        caption,
        svg: draw(&lines, mu, r.case.run.duration),
    })
}

/// The vertical component's effect on the exact residual sliding, in one sentence.
fn finding(r: &CaseResult) -> String {
    let residual = |case: &rockslide_core::case::Case| -> Result<f64, String> {
        let solution = rockslide_reference::for_case(case)?;
        let s = rockslide_reference::sample(solution.as_ref(), &[case.run.duration]);
        s.column("slide")
            .and_then(|c| c.last().copied())
            .ok_or_else(|| "no sliding channel".to_string())
    };
    let mut horizontal = r.case.clone();
    horizontal.scene.vertical = None;
    match (residual(&r.case), residual(&horizontal)) {
        (Ok(with), Ok(without)) => {
            let change = if without != 0.0 {
                format!(" ({:+.1} %)", 100.0 * (with / without - 1.0))
            } else {
                String::new()
            };
            format!(
                "Finding: exact residual sliding {:.3} mm with the vertical component, {:.3} mm horizontal only{change}.",
                with * 1e3,
                without * 1e3
            )
        }
        (a, b) => format!(
            "No exact residual to compare ({}).",
            a.err().or(b.err()).unwrap_or_default()
        ),
    }
}

/// A channel's (time, factor·value·1e-3) points reduced to a min/max pair per pixel column
/// (at most [`MAX_POINTS`]; a streamed run's per-slice extremes of every step), so that
/// every peak stays drawn.
fn points(trace: &Trace, envelope: Option<&Envelope>, key: &str, factor: f64) -> Vec<(f64, f64)> {
    channel_points(trace, envelope, key, |v| factor * v * 1e-3, MAX_POINTS)
}

fn draw(lines: &[Participant<'_>], mu: f64, duration: f64) -> String {
    let mu = if mu.is_finite() { mu } else { 0.0 };
    let series: Vec<_> = lines
        .iter()
        .map(|(_, t, c, e)| {
            (
                points(t, *e, "resistance", 1.0),
                points(t, *e, "normal", mu),
                points(t, *e, "normal", 1.0),
                *c,
            )
        })
        .collect();
    let peak = series
        .iter()
        .flat_map(|(r, l, n, _)| r.iter().chain(l).chain(n))
        .map(|p| p.1.abs())
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    let y = if peak > 0.0 { 1.05 * peak } else { 1.0 };
    let entries: Vec<(String, RGBColor, bool)> = lines
        .iter()
        .flat_map(|(label, _, c, _)| {
            [
                (format!("{label}: R"), *c, false),
                (format!("{label}: ±μN"), *c, true),
            ]
        })
        .collect();
    let legend = legend_height(&entries, SIZE.0);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (SIZE.0, SIZE.1 + legend)).into_drawing_area();
        let result = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let (plot, strip) = root.split_vertically(SIZE.1);
            let mut chart = ChartBuilder::on(&plot)
                .caption(
                    "Resistance and the friction limit μ·N(t)",
                    ("sans-serif", 18),
                )
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..duration.max(f64::MIN_POSITIVE), -y..y)?;
            chart
                .configure_mesh()
                .x_desc("time [s]")
                .y_desc("force [kN]")
                .label_style(("sans-serif", 13))
                .light_line_style(GRID)
                .draw()?;
            for (r, limit, n, c) in &series {
                chart.draw_series(LineSeries::new(
                    n.iter().copied(),
                    c.mix(0.5).stroke_width(1),
                ))?;
                for sign in [1.0, -1.0] {
                    // one polyline marked for a dash pattern, not one element per dash
                    chart.draw_series(LineSeries::new(
                        limit.iter().map(|&(t, v)| (t, sign * v)),
                        c.mix(DASH_MARK).stroke_width(1),
                    ))?;
                }
                chart.draw_series(LineSeries::new(r.iter().copied(), c.stroke_width(2)))?;
            }
            draw_legend(&strip, &entries)?;
            root.present()?;
            Ok(())
        })();
        if let Err(e) = result {
            drop(root);
            return failed_svg(SIZE.0, &e.to_string());
        }
    }
    crate::doc::figure::compact_svg(&dash_marked(&svg))
}

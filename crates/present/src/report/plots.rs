//! Time-history plots in the style of the paper's Figures 3–11: one figure per quantity
//! (force and resistance, relative displacement, sliding, centre-of-mass horizontal and
//! vertical motion, rotation), every participant overlaid, axes in the paper's units
//! (kN, mm). Drawn with `plotters`' SVG backend into strings, so the HTML can embed them
//! inline and the Markdown can link the same SVG files.
//!
//! A run far off the others' scale (peak more than [`OFF_SCALE`] times the reference's, or
//! the median's) would flatten every other curve: it is left out of the main figure —
//! whose caption says so — and shown in a second figure with everything.

use plotters::prelude::*;

use crate::doc::figure::{
    DASH_MARK, Entry, Figure, GRID, NOTE, REFERENCE, dash_marked, draw_legend, failed_svg,
    legend_height, palette,
};
use rockslide_core::trace::{Quantity, Trace, q};
use rockslide_verify::suite::CaseResult;

/// Ratio of a run's peak to the reference's (or median) peak beyond which it is off scale.
pub(crate) const OFF_SCALE: f64 = 5.0;
/// Figure size in pixels.
const SIZE: (u32, u32) = (1000, 440);
/// Traces longer than this are reduced to per-bucket min/max before drawing: one bucket
/// (its min and max) per pixel column of the figure, so nothing visible is lost and the
/// SVG (inlined again in the HTML pages) stays small.
const MAX_POINTS: usize = 2 * SIZE.0 as usize;

/// What a figure shows: channels sharing one axis.
struct Spec {
    id: &'static str,
    title: &'static str,
    channels: &'static [&'static Quantity],
    paper: &'static str,
    /// Title and paper figures for a rocking body (RPEPO, paper Figs 8–11).
    rocking: (&'static str, &'static str),
}

const SPECS: &[Spec] = &[
    Spec {
        id: "force-resistance",
        title: "Force F (dashed) and resistance R (solid)",
        channels: &[&q::FORCE, &q::RESISTANCE],
        paper: "paper Figs 3, 4 (force and resistance)",
        rocking: (
            "Force F (dashed) and base shear R (solid)",
            "force and resistance, RPEPO",
        ),
    },
    Spec {
        id: "relative-displacement",
        title: "Relative displacement",
        channels: &[&q::REL_DISP],
        paper: "paper Figs 3–5",
        rocking: (
            "Relative displacement of O (base centre − ground)",
            "paper Fig 8",
        ),
    },
    Spec {
        id: "sliding",
        title: "Sliding",
        channels: &[&q::SLIDE],
        paper: "paper Figs 3, 4, 6",
        rocking: (
            "Sliding of O (mean accumulated slip of the supports)",
            "paper Fig 9",
        ),
    },
    Spec {
        id: "cm-horizontal",
        title: "Centre of mass, horizontal",
        channels: &[&q::CM_X],
        paper: "paper Fig 10",
        rocking: ("Centre of mass, horizontal", "paper Fig 10"),
    },
    Spec {
        id: "cm-vertical",
        title: "Centre of mass, vertical",
        channels: &[&q::CM_Z],
        paper: "paper Fig 11",
        rocking: ("Centre of mass, vertical", "paper Fig 11"),
    },
    Spec {
        id: "rotation",
        title: "Base rotation",
        channels: &[&q::ROTATION],
        paper: "rocking scenes",
        rocking: ("Base rotation", "rocking scenes"),
    },
];

/// A line to draw: participant label, trace, and a streamed run's envelope.
struct Line<'a> {
    label: String,
    trace: &'a Trace,
    envelope: Option<&'a rockslide_verify::analysis::envelope::Envelope>,
}

fn lines(r: &CaseResult) -> Vec<Line<'_>> {
    let mut out = Vec::new();
    if let Ok(x) = &r.reference {
        out.push(Line {
            label: format!("reference ({})", x.solution.name()),
            trace: &x.output,
            envelope: None,
        });
    }
    for (i, run) in r.runs.iter().enumerate() {
        let mut label = run.label();
        if !run.status.completed() {
            label.push_str(&format!(" ({})", run.status.label()));
        }
        out.push(Line {
            label,
            trace: &run.trace,
            envelope: r.envelope(i),
        });
    }
    out
}

/// Colour of the i-th participant: the reference black, then the shared palette.
fn colour(i: usize, has_reference: bool) -> RGBColor {
    match (has_reference, i) {
        (true, 0) => REFERENCE,
        (true, i) => palette(i - 1),
        (false, i) => palette(i),
    }
}

/// (time, value·factor) points of a channel, reduced to per-bucket min and max (in time
/// order) when long, so that peaks survive and the SVG stays small.
#[cfg(test)]
fn points(trace: &Trace, key: &str, factor: f64) -> Vec<(f64, f64)> {
    crate::doc::figure::channel_points(trace, None, key, |v| v * factor, MAX_POINTS)
}

/// The points of a line's channel: a streamed run's envelope, else its trace reduced.
fn line_points(line: &Line<'_>, key: &str, factor: f64) -> Vec<(f64, f64)> {
    crate::doc::figure::channel_points(line.trace, line.envelope, key, |v| v * factor, MAX_POINTS)
}

/// The largest |value| of a line's channels over every step (a streamed run's envelope
/// has every step's; its trace only the kept rows).
fn peak(line: &Line<'_>, channels: &[&Quantity]) -> f64 {
    let mut peak = 0.0_f64;
    for c in channels {
        if let Some(p) = line.envelope.and_then(|e| e.peak_abs(c.key)) {
            peak = peak.max(p);
        } else if let Some(col) = line.trace.column(c.key) {
            peak = col
                .iter()
                .filter(|v| v.is_finite())
                .fold(peak, |m, v| m.max(v.abs()));
        }
    }
    peak
}

/// Every figure of a case whose channels some participant has.
pub(crate) fn figures(r: &CaseResult) -> Vec<Figure> {
    let all = lines(r);
    let has_reference = r.reference.is_ok();
    let rocking = matches!(
        r.case.scene.model,
        rockslide_core::case::Model::RockingBody(_)
    );
    // The earliest first full lift-off of any completed run: the cross-code comparison
    // is made up to it, so the figures mark it.
    let liftoff = r
        .runs
        .iter()
        .zip(&r.run_responses)
        .filter(|(run, _)| run.status.completed())
        .filter_map(|(_, resp)| resp.get(super::crosscode::LIFTOFF_KEY).copied())
        .fold(None, |m: Option<f64>, t| Some(m.map_or(t, |m| m.min(t))));
    let mut out: Vec<Figure> = super::record_plot::record_figure(r).into_iter().collect();
    out.extend(super::vertical_plot::vertical_figure(r));
    out.extend(super::orbit_plot::orbit_figure(r));
    for spec in SPECS {
        let members: Vec<usize> = (0..all.len())
            .filter(|&i| spec.channels.iter().any(|c| all[i].trace.has(c.key)))
            .collect();
        if members.is_empty() {
            continue;
        }
        let peaks: Vec<f64> = members
            .iter()
            .map(|&i| peak(&all[i], spec.channels))
            .collect();
        let scale = if has_reference && members[0] == 0 {
            peaks[0]
        } else {
            let mut s = peaks.clone();
            s.sort_by(f64::total_cmp);
            s[s.len() / 2]
        };
        let off: Vec<usize> = members
            .iter()
            .zip(&peaks)
            .filter(|&(_, &p)| scale > 0.0 && p > OFF_SCALE * scale)
            .map(|(&i, _)| i)
            .collect();
        let kept: Vec<usize> = members
            .iter()
            .copied()
            .filter(|i| !off.contains(i))
            .collect();
        let (title, paper) = if rocking {
            spec.rocking
        } else {
            (spec.title, spec.paper)
        };
        let mut caption = format!("{title} — {paper}");
        if !off.is_empty() {
            let names: Vec<String> = off
                .iter()
                .map(|&i| {
                    let p = peak(&all[i], spec.channels) * spec.channels[0].display.1;
                    format!(
                        "{} (peak {} {})",
                        all[i].label,
                        crate::doc::format::sig(p),
                        spec.channels[0].display.0
                    )
                })
                .collect();
            caption.push_str(&format!(
                "; off scale and left out here (> {OFF_SCALE}× the {} peak): {} — see the next figure",
                if has_reference {
                    "reference's"
                } else {
                    "median"
                },
                names.join(", ")
            ));
        }
        out.push(Figure {
            id: spec.id.to_string(),
            caption,
            svg: draw(spec, title, &all, &kept, has_reference, liftoff),
        });
        if !off.is_empty() {
            out.push(Figure {
                id: format!("{}-all", spec.id),
                caption: format!("{title} — every run, including off-scale ones"),
                svg: draw(spec, title, &all, &members, has_reference, liftoff),
            });
        }
    }
    out
}

/// One line of a figure: participant index, channel index, points.
type Series = (usize, usize, Vec<(f64, f64)>);

/// The lines of a figure: each member's points of each of the spec's channels, in
/// display units (participant, channel index, points); channels without points left out.
fn series_of(spec: &Spec, all: &[Line<'_>], members: &[usize], factor: f64) -> Vec<Series> {
    // (participant, channel index, points)
    let mut series: Vec<Series> = Vec::new();
    for &i in members {
        for (ci, c) in spec.channels.iter().enumerate() {
            let p = line_points(&all[i], c.key, factor);
            if !p.is_empty() {
                series.push((i, ci, p));
            }
        }
    }
    series
}

/// The time axis's end and the value axis's range (5 % padding; ±1 around 0 when flat) of
/// a figure's lines.
fn axis_ranges(series: &[Series]) -> (f64, f64, f64) {
    let (mut t1, mut y0, mut y1) = (0.0_f64, f64::INFINITY, f64::NEG_INFINITY);
    for (_, _, p) in series {
        for &(t, y) in p {
            if y.is_finite() {
                t1 = t1.max(t);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
    }
    if y0.partial_cmp(&y1) != Some(std::cmp::Ordering::Less) {
        (y0, y1) = (y0.min(0.0) - 1.0, y1.max(0.0) + 1.0);
    }
    let pad = 0.05 * (y1 - y0);
    let (y0, y1) = (y0 - pad, y1 + pad);
    let t1 = if t1 > 0.0 { t1 } else { 1.0 };
    (t1, y0, y1)
}

/// The legend's entries of a figure's lines: the participant (with the channel when the
/// figure has several), its colour, and dashed for the first of several channels.
fn legend_entries(
    spec: &Spec,
    all: &[Line<'_>],
    series: &[Series],
    has_reference: bool,
) -> Vec<Entry> {
    series
        .iter()
        .map(|(i, ci, _)| {
            let name = if spec.channels.len() > 1 {
                format!("{} {}", spec.channels[*ci].label, all[*i].label)
            } else {
                all[*i].label.clone()
            };
            let dashed = spec.channels.len() > 1 && *ci == 0;
            (name, colour(*i, has_reference), dashed)
        })
        .collect()
}

/// Draw one figure into an SVG string.
fn draw(
    spec: &Spec,
    title: &str,
    all: &[Line<'_>],
    members: &[usize],
    has_reference: bool,
    liftoff: Option<f64>,
) -> String {
    let (unit, factor) = spec.channels[0].display;
    let series = series_of(spec, all, members, factor);
    let (t1, y0, y1) = axis_ranges(&series);
    let names: Vec<&str> = spec.channels.iter().map(|c| c.label).collect();
    let ylabel = format!("{} [{unit}]", names.join(", "));

    // Legend entries, drawn in a strip below the plot so that no box hides a curve.
    let entries = legend_entries(spec, all, &series, has_reference);
    let legend_h = legend_height(&entries, SIZE.0);

    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (SIZE.0, SIZE.1 + legend_h)).into_drawing_area();
        let result = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let (plot, legend) = root.split_vertically(SIZE.1);
            let mut chart = ChartBuilder::on(&plot)
                .caption(title, ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..t1, y0..y1)?;
            chart
                .configure_mesh()
                .x_desc("time [s]")
                .y_desc(ylabel.as_str())
                .label_style(("sans-serif", 13))
                .light_line_style(GRID)
                .draw()?;
            if let Some(t) = liftoff {
                let grey = NOTE;
                chart.draw_series(DashedLineSeries::new(
                    [(t, y0), (t, y1)],
                    4,
                    4,
                    grey.stroke_width(1),
                ))?;
                chart.draw_series(std::iter::once(Text::new(
                    format!(" first full lift-off {t:.3} s"),
                    (t, y1),
                    ("sans-serif", 12).into_font().color(&grey),
                )))?;
            }
            for (i, ci, p) in &series {
                let c = colour(*i, has_reference);
                let style = c.stroke_width(if *i == 0 && has_reference { 2 } else { 1 });
                let dashed = spec.channels.len() > 1 && *ci == 0;
                if dashed {
                    // one polyline marked for a dash pattern (see `dash_marked`), not one
                    // element per dash: a noisy record's force is thousands of dashes
                    let marked = c.mix(DASH_MARK).stroke_width(style.stroke_width);
                    chart.draw_series(LineSeries::new(p.iter().copied(), marked))?;
                } else {
                    chart.draw_series(LineSeries::new(p.iter().copied(), style))?;
                }
            }
            draw_legend(&legend, &entries)?;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_traces_are_reduced_but_keep_their_extremes() {
        // 100 001 samples of sin(2π·7t) + a spike: reduced to ≤ MAX_POINTS points, and
        // the global max (the spike, 3.0) and min (−1.0 at the troughs) survive exactly.
        let n = 100_001;
        let mut t = Trace::with_channels(&[&q::REL_DISP], n);
        for i in 0..n {
            let x = i as f64 / (n - 1) as f64;
            let v = if i == 54_321 {
                3.0
            } else {
                (2.0 * std::f64::consts::PI * 7.0 * x).sin()
            };
            t.push(x, &[v]);
        }
        let p = points(&t, "rel_disp", 1e3);
        assert!(p.len() <= MAX_POINTS, "{}", p.len());
        let max = p.iter().map(|x| x.1).fold(f64::MIN, f64::max);
        let min = p.iter().map(|x| x.1).fold(f64::MAX, f64::min);
        assert_eq!(max, 3.0e3);
        let exact_min = t
            .column("rel_disp")
            .unwrap()
            .iter()
            .fold(f64::MAX, |m, &v| m.min(v));
        assert_eq!(min, exact_min * 1e3);
        assert!(p.windows(2).all(|w| w[0].0 <= w[1].0), "time order kept");
    }

    #[test]
    fn a_dashed_line_of_many_points_is_one_svg_element_with_a_dash_pattern() {
        // 2,000 points of a noisy line drawn as plotters draws a marked series: one
        // polyline, dashed by the pattern plotters' own dashed series uses (6 on, 4 off)
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (400, 200)).into_drawing_area();
            let mut chart = ChartBuilder::on(&root)
                .build_cartesian_2d(0.0..1.0, -1.0..1.0)
                .unwrap();
            let points =
                (0..2000).map(|i| (i as f64 / 2000.0, if i % 2 == 0 { 0.9 } else { -0.9 }));
            let marked = RED.mix(DASH_MARK).stroke_width(1);
            chart.draw_series(LineSeries::new(points, marked)).unwrap();
            root.present().unwrap();
        }
        let svg = dash_marked(&svg);
        assert_eq!(svg.matches("<polyline").count(), 1, "{svg}");
        assert_eq!(svg.matches("stroke-dasharray=\"6 4\"").count(), 1);
        assert!(!svg.contains("0.999"));
    }
}

//! The excitation of a case — a record, or an analytic pulse or sine — plotted (accelerations
//! in g, a ground displacement in mm). A record is plotted in g (1 g = 9.80665 m/s², the unit engineers
//! read ground motions in): the scaled samples, linear in between as every engine and the
//! exact reference take them, over the case's run. Only for cases driven by a record.

use plotters::prelude::*;

use crate::doc::figure::Figure;
use crate::doc::figure::{GRID, failed_svg};
use rockslide_core::case::record::STANDARD_GRAVITY;
use rockslide_core::case::{Excitation, Signal};
use rockslide_verify::suite::CaseResult;

/// Figure size in pixels (the time-history figures' width).
const SIZE: (u32, u32) = (1000, 320);
/// Records longer than this are reduced to per-bucket min/max before drawing.
const MAX_POINTS: usize = 4000;
/// Line colour: the reference's black, the record being the given input.
const INK: RGBColor = RGBColor(0, 0, 0);

/// The excitation figure of a case — the record, or the analytic ground motion or mass
/// acceleration (pulse, sine) — if one drives it.
pub(crate) fn record_figure(r: &CaseResult) -> Option<Figure> {
    let (what, symbol, signal) = match &r.case.scene.excitation {
        Excitation::GroundAcceleration(s) => ("Ground acceleration", "ag", s),
        Excitation::MassAcceleration(s) => ("Mass acceleration", "a", s),
        Excitation::GroundDisplacement(s) => return Some(displacement_figure(r, s)),
        Excitation::None => return None,
    };
    let Signal::Record { dt, samples, label } = signal else {
        return Some(analytic_figure(r, what, symbol, signal));
    };
    let points = in_g(*dt, samples);
    let title = format!("{what} {symbol}(t), record");
    let ylabel = format!("{symbol} [g]");
    Some(Figure {
        id: "record".into(),
        caption: format!(
            "{what} of the record in g (1 g = {STANDARD_GRAVITY} m/s²), linear between samples \
             — {label}"
        ),
        svg: draw(&title, &ylabel, &points, r.case.run.duration),
    })
}

/// Samples drawn of an analytic excitation over the run.
const ANALYTIC_POINTS: usize = 2000;

/// (time, scale · value) of an analytic signal at [`ANALYTIC_POINTS`] + 1 times over the run.
fn sampled(signal: &Signal, duration: f64, scale: f64) -> Vec<(f64, f64)> {
    (0..=ANALYTIC_POINTS)
        .map(|i| {
            let t = duration * i as f64 / ANALYTIC_POINTS as f64;
            (t, scale * signal.value(t))
        })
        .collect()
}

/// An analytic acceleration (pulse, sine) in g.
fn analytic_figure(r: &CaseResult, what: &str, symbol: &str, signal: &Signal) -> Figure {
    let duration = r.case.run.duration;
    let points = sampled(signal, duration, 1.0 / STANDARD_GRAVITY);
    Figure {
        id: "record".into(),
        caption: format!(
            "{what} {symbol}(t) in g (1 g = {STANDARD_GRAVITY} m/s²), as the case defines it"
        ),
        svg: draw(
            &format!("{what} {symbol}(t)"),
            &format!("{symbol} [g]"),
            &points,
            duration,
        ),
    }
}

/// A prescribed ground displacement in mm.
fn displacement_figure(r: &CaseResult, signal: &Signal) -> Figure {
    let duration = r.case.run.duration;
    let points = sampled(signal, duration, 1000.0);
    Figure {
        id: "record".into(),
        caption: "Ground displacement xg(t) in mm, as the case defines it".into(),
        svg: draw("Ground displacement xg(t)", "xg [mm]", &points, duration),
    }
}

/// (time s, value g) of every sample, reduced to per-bucket min and max beyond
/// [`MAX_POINTS`] so that every peak stays drawn.
fn in_g(dt: f64, samples: &[f64]) -> Vec<(f64, f64)> {
    crate::doc::figure::extreme_indices(samples.len(), MAX_POINTS, |i| samples[i])
        .into_iter()
        .map(|i| (i as f64 * dt, samples[i] / STANDARD_GRAVITY))
        .collect()
}

/// Draw the record into an SVG string, symmetric about zero.
fn draw(title: &str, ylabel: &str, points: &[(f64, f64)], duration: f64) -> String {
    let peak = points
        .iter()
        .map(|p| p.1.abs())
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    let y = if peak > 0.0 { 1.05 * peak } else { 1.0 };
    let t1 = points
        .last()
        .map_or(duration, |p| p.0.max(duration))
        .max(f64::MIN_POSITIVE);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        let result = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let mut chart = ChartBuilder::on(&root)
                .caption(title, ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..t1, -y..y)?;
            chart
                .configure_mesh()
                .x_desc("time [s]")
                .y_desc(ylabel)
                .label_style(("sans-serif", 13))
                .light_line_style(GRID)
                .draw()?;
            chart.draw_series(LineSeries::new(points.iter().copied(), INK.stroke_width(1)))?;
            root.present()?;
            Ok(())
        })();
        if let Err(e) = result {
            drop(root);
            return failed_svg(SIZE.0, &e.to_string());
        }
    }
    crate::doc::figure::compact_svg(&svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_shown_in_g_with_their_peaks() {
        // 0.1 g and −0.2 g peaks in a long record survive the reduction, in g
        let mut samples = vec![0.0; 10_000];
        samples[1234] = 0.1 * STANDARD_GRAVITY;
        samples[8765] = -0.2 * STANDARD_GRAVITY;
        let p = in_g(0.01, &samples);
        assert!(p.len() <= MAX_POINTS);
        let near = |t: f64, g: f64| {
            p.iter()
                .any(|&(a, b)| (a - t).abs() < 1e-12 && (b - g).abs() < 1e-15)
        };
        assert!(near(12.34, 0.1) && near(87.65, -0.2), "{:?}", &p[..4]);
        let peak = p.iter().fold(0.0_f64, |m, x| m.max(x.1.abs()));
        assert!((peak - 0.2).abs() < 1e-15);
        let short = in_g(0.5, &[STANDARD_GRAVITY, 0.0]);
        assert_eq!(short, [(0.0, 1.0), (0.5, 0.0)]);
    }
}

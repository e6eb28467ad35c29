//! What every figure shares, so that all of them — time histories, work-precision,
//! stability map, study plots — look alike: one palette (series colours, the reference in
//! black, one colour per stability class), the legend strip drawn *below* the plot area
//! (no legend box hides data), decade ranges for log axes, and the placeholder drawn when
//! a plot fails (a figure never fails a report).

use plotters::coord::Shift;
use plotters::prelude::*;
use rockslide_core::trace::Trace;
use rockslide_verify::suite::CaseResult;

/// The reference's colour: black, drawn wider than the runs.
pub(crate) const REFERENCE: RGBColor = RGBColor(0, 0, 0);
/// Light grid lines.
pub(crate) const GRID: RGBColor = RGBColor(238, 238, 238);
/// Markers and notes that are not data (e.g. the first lift-off line).
pub(crate) const NOTE: RGBColor = RGBColor(120, 120, 120);

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

/// The reference (black) and every run (the palette, in order) of a case, each with its
/// label and trace: the participants the report's overlay figures draw.
pub(crate) fn participants(r: &CaseResult) -> Vec<(String, &Trace, RGBColor)> {
    let mut lines: Vec<(String, &Trace, RGBColor)> = Vec::new();
    if let Ok(x) = &r.reference {
        lines.push((
            format!("reference ({})", x.solution.name()),
            &x.output,
            REFERENCE,
        ));
    }
    for (i, run) in r.runs.iter().enumerate() {
        lines.push((run.label(), &run.trace, palette(i)));
    }
    lines
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

pub(crate) fn failed_svg(width: u32, why: &str) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"40\"><text x=\"8\" y=\"24\">plot failed: {}</text></svg>",
        super::format::esc(why)
    )
}

/// Decade bounds around positive values.
pub(crate) fn log_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
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

/// Colour of a stability class.
pub(crate) fn class_colour(class: &str) -> RGBColor {
    match class {
        "accurate" => RGBColor(0x2c, 0xa0, 0x2c),
        "inaccurate" => RGBColor(0xff, 0x9f, 0x1c),
        "diverged" => RGBColor(0xd6, 0x27, 0x28),
        _ => RGBColor(0x55, 0x55, 0x55),
    }
}

/// Indices of a series of `n` samples (`value(i)`) to draw with at most `max_points`
/// points: every index when short, otherwise the minimum and the maximum of each of
/// `max_points / 2` buckets, in time order, so every peak survives the reduction.
pub(crate) fn extreme_indices(
    n: usize,
    max_points: usize,
    value: impl Fn(usize) -> f64,
) -> Vec<usize> {
    if n <= max_points {
        return (0..n).collect();
    }
    let buckets = max_points / 2;
    let mut out = Vec::with_capacity(max_points);
    for b in 0..buckets {
        let (lo, hi) = (b * n / buckets, ((b + 1) * n / buckets).min(n));
        if lo >= hi {
            continue;
        }
        let (mut imin, mut imax) = (lo, lo);
        for i in lo..hi {
            if value(i) < value(imin) {
                imin = i;
            }
            if value(i) > value(imax) {
                imax = i;
            }
        }
        out.push(imin.min(imax));
        if imin != imax {
            out.push(imin.max(imax));
        }
    }
    out
}

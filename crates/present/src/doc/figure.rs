//! What every figure shares, so that all of them — time histories, work-precision,
//! stability map, study plots — look alike: one palette (series colours, the reference in
//! black, one colour per stability class), the legend strip drawn *below* the plot area
//! (no legend box hides data), decade ranges for log axes, and the placeholder drawn when
//! a plot fails (a figure never fails a report).

use plotters::coord::Shift;
use plotters::prelude::*;
use rockslide_core::trace::Trace;
use rockslide_verify::analysis::envelope::Envelope;
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

/// One participant of an overlay figure: label, trace, colour, and — for a streamed run —
/// the per-slice extremes of every step, drawn instead of its kept rows.
pub(crate) type Participant<'a> = (String, &'a Trace, RGBColor, Option<&'a Envelope>);

/// The reference (black) and every run (the palette, in order) of a case, each with its
/// label and trace: the participants the report's overlay figures draw.
pub(crate) fn participants(r: &CaseResult) -> Vec<Participant<'_>> {
    let mut lines: Vec<Participant<'_>> = Vec::new();
    if let Ok(x) = &r.reference {
        lines.push((
            format!("reference ({})", x.solution.name()),
            &x.output,
            REFERENCE,
            None,
        ));
    }
    for (i, run) in r.runs.iter().enumerate() {
        lines.push((run.label(), &run.trace, palette(i), r.envelope(i)));
    }
    lines
}

/// (time, scale(value)) of channel `key` to draw: a streamed run's per-slice extremes
/// over every step when it has them, else the trace's samples reduced to a min/max pair
/// per bucket beyond `max_points` ([`extreme_indices`]).
pub(crate) fn channel_points(
    trace: &Trace,
    envelope: Option<&Envelope>,
    key: &str,
    scale: impl Fn(f64) -> f64,
    max_points: usize,
) -> Vec<(f64, f64)> {
    if let Some(points) = envelope.and_then(|e| e.points(key)) {
        return points.into_iter().map(|(t, v)| (t, scale(v))).collect();
    }
    let Some(col) = trace.column(key) else {
        return Vec::new();
    };
    extreme_indices(col.len(), max_points, |i| col[i])
        .into_iter()
        .map(|i| (trace.time[i], scale(col[i])))
        .collect()
}

/// One legend entry: label, colour, dashed line.
pub(crate) type Entry = (String, RGBColor, bool);

/// Height of a legend row, pixels.
const LEGEND_ROW: i32 = 18;
/// The legend's font size, pixels.
const LEGEND_FONT: f64 = 13.0;

/// A generous estimate of `label`'s width in the legend's sans-serif, pixels: 0.62 em a
/// character (wider than the average glyph), so that estimated boxes that do not touch
/// never touch on screen either.
pub(crate) fn label_width(label: &str) -> i32 {
    (label.chars().count() as f64 * LEGEND_FONT * 0.62).ceil() as i32
}

/// Where each legend entry goes in a strip `width` pixels wide: `(x, y)` of its swatch,
/// in rows of equal columns as wide as the widest entry (swatch, gap, label, margin), so
/// that no label runs into the next entry.
pub(crate) fn legend_layout(entries: &[Entry], width: u32) -> Vec<(i32, i32)> {
    let widest = entries
        .iter()
        .map(|(label, _, _)| 30 + label_width(label) + 16)
        .max()
        .unwrap_or(1);
    let available = (width as i32 - 20).max(1);
    let cols = (available / widest).max(1) as usize;
    let col_w = available / cols as i32;
    (0..entries.len())
        .map(|k| {
            (
                20 + (k % cols) as i32 * col_w,
                8 + (k / cols) as i32 * LEGEND_ROW,
            )
        })
        .collect()
}

/// Height in pixels of the legend strip of `entries` in a figure `width` pixels wide.
pub(crate) fn legend_height(entries: &[Entry], width: u32) -> u32 {
    let rows = legend_layout(entries, width)
        .last()
        .map_or(0, |&(_, y)| (y - 8) / LEGEND_ROW + 1);
    (rows * LEGEND_ROW) as u32 + 10
}

/// Draw a legend strip (a short line and the label per entry, in rows) on `area`.
pub(crate) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[Entry],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (w, _) = area.dim_in_pixel();
    for ((label, c, dashed), (x, y)) in entries.iter().zip(legend_layout(entries, w)) {
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

/// Colour of a limit line drawn over classed markers: blue, purple, brown, pink, cyan,
/// grey — never the green, orange, red or dark grey of the classes.
pub(crate) fn limit_colour(i: usize) -> RGBColor {
    const P: [RGBColor; 6] = [
        RGBColor(0x1f, 0x77, 0xb4),
        RGBColor(0x94, 0x67, 0xbd),
        RGBColor(0x8c, 0x56, 0x4b),
        RGBColor(0xe3, 0x77, 0xc2),
        RGBColor(0x17, 0xbe, 0xcf),
        RGBColor(0x9a, 0x9a, 0x9a),
    ];
    P[i % P.len()]
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

/// The same picture in fewer bytes. `plotters` writes every line as a `<polyline>` of
/// absolute integer points — a min/max pair per pixel column gives many repeated points
/// and straight runs — and every grid line as its own `<line>` with its attributes. This
/// rewrites, exactly (the same geometry, the same paint order):
/// - each polyline of integer points as a `<path>` with relative moves, after dropping
///   each point that repeats the one before it ([`reduced`]: a segment of no length, so
///   neither the shape, the joins nor a dash pattern's phase change);
/// - each run of consecutive `<line>` elements with the same attributes as `<line>`
///   elements with their coordinates only, in a `<g>` carrying the attributes (all but
///   an `opacity` other than 1, which stays on each line: a group's opacity would blend
///   the lines together).
///
/// Rendered by librsvg and by Chromium, every figure of the default run is the same
/// image pixel for pixel (docs/performance.md §2). Rewrites that would save more are left
/// out because Chromium's anti-aliasing is not exact under them (librsvg's is): a
/// `<path>` for a `<line>` (±2 of 255 levels along the grid), dropping the inner points
/// of a straight run — vertical (≤ 5 levels on ≤ 52 pixels of 7 of the default run's
/// figures, for 0.09 MB), horizontal (±3 levels on a few dozen pixels) or diagonal (up to
/// 46 levels on a few pixels).
///
/// Anything else (text, rectangles, circles, a polyline with non-integer points) is
/// passed through unchanged.
pub(crate) fn compact_svg(svg: &str) -> String {
    let mut out = String::with_capacity(svg.len() / 2);
    let mut grid = LineRun::default();
    for row in svg.split_inclusive('\n') {
        let element = row.trim_end_matches('\n');
        if let Some(line) = parse_line(element) {
            if !grid.accepts(&line) {
                grid.flush(&mut out);
            }
            grid.push(line);
            continue;
        }
        grid.flush(&mut out);
        match polyline_as_path(element) {
            Some(path) => {
                out.push_str(&path);
                out.push('\n');
            }
            None => out.push_str(row),
        }
    }
    grid.flush(&mut out);
    out
}

/// The points of a polyline without the points that repeat the one before them.
pub(crate) fn reduced(points: &[(i64, i64)]) -> Vec<(i64, i64)> {
    let mut out: Vec<(i64, i64)> = Vec::with_capacity(points.len());
    for &p in points {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    out
}

/// A path `d` drawing `points`: an absolute move to the first, then relative lines.
fn relative_d(points: &[(i64, i64)]) -> String {
    let mut d = String::with_capacity(4 * points.len() + 8);
    let Some(&(x0, y0)) = points.first() else {
        return d;
    };
    d.push('M');
    push_numbers(&mut d, &[x0, y0]);
    if points.len() > 1 {
        d.push('l');
        let mut first = true;
        for w in points.windows(2) {
            let (dx, dy) = (w[1].0 - w[0].0, w[1].1 - w[0].1);
            if !first && dx >= 0 {
                d.push(' ');
            }
            first = false;
            push_numbers(&mut d, &[dx, dy]);
        }
    }
    d
}

/// Numbers separated by a space, or by nothing before a minus sign; each in decimal as
/// `{n}` writes it (`itoa`, without the formatting machinery: a figure's paths are
/// thousands of them).
fn push_numbers(d: &mut String, numbers: &[i64]) {
    let mut digits = itoa::Buffer::new();
    for (k, &n) in numbers.iter().enumerate() {
        if k > 0 && n >= 0 {
            d.push(' ');
        }
        d.push_str(digits.format(n));
    }
}

/// `<polyline a="…" points="x,y x,y "/>` of integer points as `<path a="…" d="…"/>`.
fn polyline_as_path(element: &str) -> Option<String> {
    let rest = element.strip_prefix("<polyline ")?.strip_suffix("/>")?;
    let start = rest.find("points=\"")?;
    let (attributes, tail) = rest.split_at(start);
    let list = tail.strip_prefix("points=\"")?;
    let end = list.find('"')?;
    let (list, after) = (&list[..end], &list[end + 1..]);
    let points = list
        .split_ascii_whitespace()
        .map(|pair| {
            let (x, y) = pair.split_once(',')?;
            Some((x.parse().ok()?, y.parse().ok()?))
        })
        .collect::<Option<Vec<(i64, i64)>>>()?;
    Some(format!(
        "<path {attributes}d=\"{}\"{after}/>",
        relative_d(&reduced(&points))
    ))
}

/// One `<line>`: its attributes but the coordinates, and its ends.
struct GridLine<'a> {
    attributes: &'a str,
    from: (i64, i64),
    to: (i64, i64),
}

/// The attributes of a line split in those a group can carry and those each line keeps:
/// an `opacity="1"` is dropped (the default), another opacity stays on the line.
fn split_opacity(attributes: &str) -> (String, &str) {
    let Some(start) = attributes.find("opacity=\"") else {
        return (attributes.to_string(), "");
    };
    let end = attributes[start + 9..]
        .find('"')
        .map_or(attributes.len(), |e| start + 9 + e + 1);
    let opacity = &attributes[start..end];
    let rest = format!("{}{}", &attributes[..start], attributes[end..].trim_start());
    if opacity == "opacity=\"1\"" {
        (rest, "")
    } else {
        (rest, &attributes[start..(end + 1).min(attributes.len())])
    }
}

/// `<line a="…" x1="…" y1="…" x2="…" y2="…"/>` with integer coordinates, the coordinates
/// last (as `plotters` writes them).
fn parse_line(element: &str) -> Option<GridLine<'_>> {
    let rest = element.strip_prefix("<line ")?.strip_suffix("/>")?;
    let start = rest.find("x1=\"")?;
    let (attributes, coordinates) = rest.split_at(start);
    let mut values = [0_i64; 4];
    let mut tail = coordinates;
    for (k, name) in ["x1=\"", "y1=\"", "x2=\"", "y2=\""].iter().enumerate() {
        tail = tail.trim_start().strip_prefix(name)?;
        let end = tail.find('"')?;
        values[k] = tail[..end].parse().ok()?;
        tail = &tail[end + 1..];
    }
    tail.trim().is_empty().then_some(GridLine {
        attributes,
        from: (values[0], values[1]),
        to: (values[2], values[3]),
    })
}

/// Consecutive `<line>` elements of the same attributes, written in one group.
#[derive(Default)]
struct LineRun<'a> {
    lines: Vec<GridLine<'a>>,
}

impl<'a> LineRun<'a> {
    fn accepts(&self, line: &GridLine<'_>) -> bool {
        self.lines
            .first()
            .is_none_or(|first| first.attributes == line.attributes)
    }

    fn push(&mut self, line: GridLine<'a>) {
        self.lines.push(line);
    }

    fn flush(&mut self, out: &mut String) {
        use std::fmt::Write;
        let Some(first) = self.lines.first() else {
            return;
        };
        let (group, kept) = split_opacity(first.attributes);
        let single = self.lines.len() == 1;
        if !single {
            let _ = writeln!(out, "<g {}>", group.trim_end());
        }
        for l in &self.lines {
            let attributes = if single { first.attributes } else { kept };
            let _ = writeln!(
                out,
                "<line {attributes}x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>",
                l.from.0, l.from.1, l.to.0, l.to.1
            );
        }
        if !single {
            out.push_str("</g>\n");
        }
        self.lines.clear();
    }
}

/// One rendered figure.
#[derive(Debug, Clone)]
pub(crate) struct Figure {
    /// File stem (`relative-displacement`), unique within a case.
    pub id: String,
    /// Caption.
    pub caption: String,
    /// The SVG document.
    pub svg: String,
}

/// The opacity that marks a line to be dashed: plotters writes a colour's alpha as the
/// element's `opacity`, and no other element of a figure is drawn with this one.
pub(crate) const DASH_MARK: f64 = 0.999;

/// The lines drawn with [`DASH_MARK`] made opaque and dashed (6 on, 4 off, as plotters'
/// own dashed series): one SVG element per line instead of one per dash.
pub(crate) fn dash_marked(svg: &str) -> String {
    svg.replace(
        &format!("opacity=\"{DASH_MARK}\""),
        "opacity=\"1\" stroke-dasharray=\"6 4\"",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Legend entries as boxes (swatch and label, estimated generously) never touch one
    /// another, however long their labels: the stability map's limit lines and a force
    /// plot's participants included.
    #[test]
    fn legend_entries_never_overlap() {
        let labels = [
            "accurate",
            "inaccurate",
            "diverged",
            "not converged",
            "predictor-corrector/paper limit Δt/T = 0.0500",
            "fe/double limit Δt/T = 0.1000",
            "rapier/kinematic-ground limit Δt/T = 0.02500",
            "reference (Newmark rigid block, two-way)",
            "fe/single resistance T",
            "external/opensees-zeroLength μN",
        ];
        for width in [500_u32, 800, 1100] {
            let entries: Vec<Entry> = labels
                .iter()
                .map(|l| (l.to_string(), BLACK, false))
                .collect();
            let at = legend_layout(&entries, width);
            let boxes: Vec<(i32, i32, i32)> = at
                .iter()
                .zip(&labels)
                .map(|(&(x, y), l)| (y, x, x + 30 + label_width(l)))
                .collect();
            for (i, a) in boxes.iter().enumerate() {
                assert!(
                    a.2 <= width as i32,
                    "{width}: {} runs off the figure",
                    labels[i]
                );
                for (j, b) in boxes.iter().enumerate().skip(i + 1) {
                    let same_row = a.0 == b.0;
                    let apart = a.2 < b.1 || b.2 < a.1;
                    assert!(
                        !same_row || apart,
                        "{width}: \"{}\" runs into \"{}\"",
                        labels[i],
                        labels[j]
                    );
                }
            }
            let rows = boxes.iter().map(|b| b.0).max().unwrap();
            assert!(legend_height(&entries, width) as i32 >= rows + LEGEND_ROW);
        }
    }

    /// The stability map's limit lines use no colour of the classes they are drawn over.
    #[test]
    fn limit_lines_differ_from_every_class() {
        let classes = ["accurate", "inaccurate", "diverged", "not converged"].map(class_colour);
        for i in 0..12 {
            assert!(!classes.contains(&limit_colour(i)), "limit colour {i}");
        }
    }

    /// The points a path `d` written by [`relative_d`] draws, back in absolute pixels.
    fn points_of(d: &str) -> Vec<(i64, i64)> {
        let (start, moves) = d.trim_start_matches('M').split_once('l').unwrap_or((d, ""));
        let numbers = |s: &str| -> Vec<i64> {
            s.replace('-', " -")
                .split_ascii_whitespace()
                .map(|n| n.parse().unwrap())
                .collect()
        };
        let first = numbers(start.trim_start_matches('M'));
        let mut at = (first[0], first[1]);
        let mut out = vec![at];
        for pair in numbers(moves).chunks(2) {
            at = (at.0 + pair[0], at.1 + pair[1]);
            out.push(at);
        }
        out
    }

    #[test]
    fn numbers_are_written_as_formatting_writes_them() {
        let mut values = vec![0, 1, -1, 9, 10, -10, 99, 100, 12345, i64::MAX, i64::MIN];
        values.extend((-1200..1200).map(|k| k * 7));
        let mut d = String::new();
        push_numbers(&mut d, &values);
        let mut expected = String::new();
        for (k, n) in values.iter().enumerate() {
            if k > 0 && *n >= 0 {
                expected.push(' ');
            }
            expected.push_str(&format!("{n}"));
        }
        assert_eq!(d, expected);
    }

    #[test]
    fn repeated_points_are_dropped_and_every_other_kept() {
        let line = [
            (0, 0),
            (0, 0),
            (1, 1),
            (2, 2),
            (2, 5),
            (2, 3),
            (2, 3),
            (2, 1), // inside a column's run: kept (see `compact_svg`)
            (2, 0),
            (3, 0),
        ];
        let expected = [
            (0, 0),
            (1, 1),
            (2, 2),
            (2, 5),
            (2, 3),
            (2, 1),
            (2, 0),
            (3, 0),
        ];
        assert_eq!(reduced(&line), expected);
        assert_eq!(relative_d(&expected), "M0 0l1 1 1 1 0 3 0-2 0-2 0-1 1 0");
        assert_eq!(points_of(&relative_d(&expected)), expected);
        assert_eq!(reduced(&[(7, 7), (7, 7)]), [(7, 7)]);
        assert_eq!(relative_d(&[(7, -7)]), "M7-7");
    }

    #[test]
    fn grid_lines_share_their_attributes_in_a_group_but_a_partial_opacity() {
        let svg = "<line opacity=\"1\" stroke=\"#EEEEEE\" stroke-width=\"1\" x1=\"82\" y1=\"387\" x2=\"82\" y2=\"37\"/>\n\
                   <line opacity=\"1\" stroke=\"#EEEEEE\" stroke-width=\"1\" x1=\"97\" y1=\"387\" x2=\"97\" y2=\"37\"/>\n\
                   <line opacity=\"0.2\" stroke=\"#000000\" stroke-width=\"1\" x1=\"82\" y1=\"40\" x2=\"900\" y2=\"40\"/>\n\
                   <line opacity=\"0.2\" stroke=\"#000000\" stroke-width=\"1\" x1=\"82\" y1=\"80\" x2=\"900\" y2=\"80\"/>\n\
                   <line opacity=\"1\" stroke=\"#000000\" stroke-width=\"1\" x1=\"1\" y1=\"2\" x2=\"3\" y2=\"4\"/>\n";
        let expected = "<g stroke=\"#EEEEEE\" stroke-width=\"1\">\n\
                        <line x1=\"82\" y1=\"387\" x2=\"82\" y2=\"37\"/>\n\
                        <line x1=\"97\" y1=\"387\" x2=\"97\" y2=\"37\"/>\n\
                        </g>\n\
                        <g stroke=\"#000000\" stroke-width=\"1\">\n\
                        <line opacity=\"0.2\" x1=\"82\" y1=\"40\" x2=\"900\" y2=\"40\"/>\n\
                        <line opacity=\"0.2\" x1=\"82\" y1=\"80\" x2=\"900\" y2=\"80\"/>\n\
                        </g>\n\
                        <line opacity=\"1\" stroke=\"#000000\" stroke-width=\"1\" x1=\"1\" y1=\"2\" x2=\"3\" y2=\"4\"/>\n";
        assert_eq!(compact_svg(svg), expected);
    }

    #[test]
    fn a_constant_signal_is_one_point_per_pixel_column_and_the_figure_less_than_half_its_bytes() {
        // 2,000 samples of y = 0.25 drawn as plotters draws a figure: a polyline of 2,000
        // points (one per sample, mostly repeated pixels) and a grid of <line> elements;
        // compacted, the data line is one point per pixel column and the grid's
        // attributes are written once.
        let mut raw = String::new();
        {
            let root = SVGBackend::with_string(&mut raw, (1000, 440)).into_drawing_area();
            let mut chart = ChartBuilder::on(&root)
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..1.0, -1.0..1.0)
                .unwrap();
            chart
                .configure_mesh()
                .light_line_style(GRID)
                .draw()
                .unwrap();
            let signal = (0..2000).map(|i| (i as f64 / 1999.0, 0.25));
            chart
                .draw_series(LineSeries::new(signal, palette(0).stroke_width(1)))
                .unwrap();
            root.present().unwrap();
        }
        let data = |svg: &str| -> String {
            svg.lines()
                .find(|l| l.contains("stroke=\"#1F77B4\""))
                .unwrap()
                .to_string()
        };
        let before = data(&raw);
        assert_eq!(before.matches(',').count(), 2000, "one point per sample");
        let compact = compact_svg(&raw);
        let after = data(&compact);
        let d = &after[after.find(" d=\"").unwrap() + 4..];
        let ends = points_of(&d[..d.find('"').unwrap()]);
        // one point per pixel column (the samples are denser than the columns), all on
        // one row
        let columns = (ends[ends.len() - 1].0 - ends[0].0 + 1) as usize;
        assert!(columns > 800, "{ends:?}: across the plot");
        assert_eq!(ends.len(), columns, "{after}");
        assert!(ends.windows(2).all(|w| w[1] == (w[0].0 + 1, w[0].1)));
        // every grid line kept, the light grid's attributes once, on its group
        let lines = |svg: &str| svg.matches("<line").count();
        assert!(lines(&raw) > 10);
        assert_eq!(lines(&compact), lines(&raw));
        assert_eq!(
            compact.matches("stroke=\"#EEEEEE\"").count(),
            1,
            "{compact}"
        );
        assert!(
            compact.len() * 2 < raw.len(),
            "{} of {}",
            compact.len(),
            raw.len()
        );
    }
}

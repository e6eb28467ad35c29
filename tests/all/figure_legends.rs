//! The figures' legends, checked on the SVG files the shipped cases write: every case of
//! the default folders (`run`), the stability map (`stability`), a work-precision sweep
//! (`sweep`), the worked example with an external participant (`check`) and a small
//! study (`study`). Each legend entry is found as the figures draw it — a swatch (one
//! 24-pixel line or three 5-pixel dashes, 2 pixels wide, 6 pixels below the label's top)
//! written right before its label's `<text>` — and boxed: the label from its position,
//! its `dy` and its font size, with a width bound per character (below), the swatch from
//! its ends and stroke width. No two boxes overlap, every box is inside the figure, and no
//! plotted line (every other path, polyline and line, segment by segment) nor marker
//! crosses a box.

use std::path::{Path, PathBuf};
use std::process::Command;

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

/// Advance widths of printable ASCII (space to `~`), 1/1000 em: the larger of DejaVu Sans
/// and Liberation Sans (the `sans-serif` of Debian's Chromium and librsvg), rounded up,
/// read from the fonts' `hmtx` tables. Kerning only narrows a label, so a sum of these is
/// a bound on its width in either font.
const ASCII_ADVANCE: [u16; 95] = [
    318, 401, 460, 838, 637, 951, 780, 275, 391, 391, 500, 838, 318, 361, 318, 337, 637, 637, 637,
    637, 637, 637, 637, 637, 637, 637, 337, 337, 838, 838, 838, 557, 1016, 685, 687, 723, 771, 667,
    611, 778, 752, 295, 500, 667, 558, 863, 749, 788, 667, 788, 723, 667, 611, 732, 685, 989, 686,
    667, 686, 391, 337, 391, 838, 557, 500, 613, 635, 550, 635, 616, 353, 635, 634, 278, 278, 580,
    278, 975, 634, 612, 635, 635, 412, 521, 393, 634, 592, 818, 592, 592, 525, 637, 337, 637, 838,
];

/// The bound of a character's advance width, em: the table for ASCII, the same two fonts'
/// larger advance for the symbols the labels use, and 1.02 em (the widest glyph of either
/// font among these) for anything else.
fn advance(c: char) -> f64 {
    let thousandths = match c {
        ' '..='~' => ASCII_ADVANCE[c as usize - 32],
        'Δ' => 685,
        'μ' | 'σ' | 'θ' | 'β' | 'τ' | 'Σ' | '√' => 690,
        'π' => 690,
        'ω' | 'φ' | 'α' | 'γ' | 'λ' => 838,
        '±' | '×' | '≤' | '≥' | '−' => 838,
        '→' | '←' => 1000,
        '·' => 318,
        '²' | '³' => 401,
        '–' => 557,
        _ => 1020,
    };
    f64::from(thousandths) / 1000.0
}

/// Above and below the baseline, em: the larger ascent (DejaVu Sans, 0.928) and descent
/// (DejaVu Sans, 0.236) of the two fonts, rounded up.
const ASCENT: f64 = 0.93;
const DESCENT: f64 = 0.24;

/// An axis-aligned box, pixels.
#[derive(Debug, Clone, Copy)]
struct Area {
    left: f64,
    top: f64,
    right: f64,
    bottom: f64,
}

impl Area {
    fn overlaps(&self, o: &Area) -> bool {
        self.left < o.right && o.left < self.right && self.top < o.bottom && o.top < self.bottom
    }

    fn inside(&self, width: f64, height: f64) -> bool {
        self.left >= 0.0 && self.top >= 0.0 && self.right <= width && self.bottom <= height
    }

    /// Whether the segment a–b passes through the box's interior (Liang–Barsky clipping).
    fn crossed_by(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for (p, q) in [
            (-dx, a.0 - self.left),
            (dx, self.right - a.0),
            (-dy, a.1 - self.top),
            (dy, self.bottom - a.1),
        ] {
            if p == 0.0 {
                if q <= 0.0 {
                    return false;
                }
            } else {
                let t = q / p;
                if p < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
            }
        }
        t0 < t1
    }
}

/// What a figure draws, in paint order.
#[derive(Debug)]
enum Mark {
    /// A `<text>`: its anchor point, `dy` in em, font size, anchor and label.
    Text {
        x: f64,
        y: f64,
        dy_em: f64,
        size: f64,
        start_anchored: bool,
        label: String,
    },
    /// A path, polyline or line: its stroke width and points.
    Stroke { width: f64, points: Vec<(f64, f64)> },
    /// A marker.
    Circle { x: f64, y: f64, r: f64 },
}

/// One legend entry: its label and the boxes of its label and swatch pieces.
struct Entry {
    label: String,
    text: Area,
    swatches: Vec<Area>,
}

fn attribute(e: &BytesStart<'_>, name: &str) -> Option<String> {
    e.try_get_attribute(name)
        .expect("attribute parses")
        .map(|a| String::from_utf8_lossy(&a.value).into_owned())
}

fn number(e: &BytesStart<'_>, name: &str) -> Option<f64> {
    attribute(e, name).and_then(|v| v.trim_end_matches("px").parse().ok())
}

/// The points of a path's `d`: absolute and relative moves and lines (what the figures
/// write).
fn path_points(d: &str) -> Vec<(f64, f64)> {
    let mut tokens: Vec<String> = Vec::new();
    for c in d.chars() {
        match c {
            'M' | 'm' | 'L' | 'l' => tokens.push(c.to_string()),
            '-' => tokens.push("-".into()),
            c if c.is_ascii_digit() || c == '.' || c == 'e' => match tokens.last_mut() {
                Some(t) if t.chars().all(|x| x.is_ascii_digit() || "-.e".contains(x)) => t.push(c),
                _ => tokens.push(c.to_string()),
            },
            ' ' | ',' | '\n' => tokens.push(String::new()),
            other => panic!("path command {other:?} in {d:?}"),
        }
    }
    let mut points = Vec::new();
    let (mut relative, mut at) = (false, (0.0, 0.0));
    let mut pending: Option<f64> = None;
    for t in tokens.into_iter().filter(|t| !t.is_empty()) {
        match t.as_str() {
            "M" | "L" => relative = false,
            "m" | "l" => relative = true,
            n => {
                let v: f64 = n.parse().unwrap_or_else(|_| panic!("{n:?} in {d:?}"));
                match pending.take() {
                    None => pending = Some(v),
                    Some(x) => {
                        at = if relative && !points.is_empty() {
                            (at.0 + x, at.1 + v)
                        } else {
                            (x, v)
                        };
                        points.push(at);
                    }
                }
            }
        }
    }
    points
}

/// The figure's size and its marks.
fn marks(svg: &str) -> ((f64, f64), Vec<Mark>) {
    let mut reader = Reader::from_str(svg);
    let mut size = (0.0, 0.0);
    let mut out = Vec::new();
    let mut widths: Vec<f64> = vec![1.0]; // stroke width inherited from <g>
    let mut open_text: Option<Mark> = None;
    loop {
        let event = reader.read_event().expect("well-formed SVG");
        let element = match &event {
            Event::Start(e) | Event::Empty(e) => Some(e.clone()),
            _ => None,
        };
        if let Some(e) = element {
            let width = number(&e, "stroke-width").unwrap_or(*widths.last().unwrap());
            match e.name().as_ref() {
                b"svg" => size = (number(&e, "width").unwrap(), number(&e, "height").unwrap()),
                b"g" if matches!(event, Event::Start(_)) => widths.push(width),
                b"path" => out.push(Mark::Stroke {
                    width,
                    points: path_points(&attribute(&e, "d").unwrap()),
                }),
                b"polyline" => out.push(Mark::Stroke {
                    width,
                    points: attribute(&e, "points")
                        .unwrap()
                        .split_whitespace()
                        .map(|p| {
                            let (x, y) = p.split_once(',').unwrap();
                            (x.parse().unwrap(), y.parse().unwrap())
                        })
                        .collect(),
                }),
                b"line" => out.push(Mark::Stroke {
                    width,
                    points: vec![
                        (number(&e, "x1").unwrap(), number(&e, "y1").unwrap()),
                        (number(&e, "x2").unwrap(), number(&e, "y2").unwrap()),
                    ],
                }),
                b"circle" => out.push(Mark::Circle {
                    x: number(&e, "cx").unwrap(),
                    y: number(&e, "cy").unwrap(),
                    r: number(&e, "r").unwrap(),
                }),
                b"text" => {
                    let dy = attribute(&e, "dy").unwrap_or_default();
                    open_text = Some(Mark::Text {
                        x: number(&e, "x").unwrap(),
                        y: number(&e, "y").unwrap(),
                        dy_em: dy.strip_suffix("em").map_or(0.0, |v| v.parse().unwrap()),
                        size: number(&e, "font-size").unwrap(),
                        start_anchored: attribute(&e, "text-anchor").as_deref() == Some("start")
                            && attribute(&e, "transform").is_none(),
                        label: String::new(),
                    });
                }
                _ => {}
            }
        }
        match event {
            Event::Text(t) => {
                if let Some(Mark::Text { label, .. }) = open_text.as_mut() {
                    label.push_str(&t.decode().unwrap());
                }
            }
            Event::GeneralRef(r) => {
                if let Some(Mark::Text { label, .. }) = open_text.as_mut() {
                    let name = r.decode().unwrap();
                    label.push(match name.as_ref() {
                        "lt" => '<',
                        "gt" => '>',
                        "amp" => '&',
                        "quot" => '"',
                        "apos" => '\'',
                        other => panic!("entity {other}"),
                    });
                }
            }
            Event::End(e) if e.name().as_ref() == b"text" => {
                if let Some(Mark::Text {
                    x,
                    y,
                    dy_em,
                    size,
                    start_anchored,
                    label,
                }) = open_text.take()
                {
                    out.push(Mark::Text {
                        x,
                        y,
                        dy_em,
                        size,
                        start_anchored,
                        label: label.trim().to_string(),
                    });
                }
            }
            Event::End(e) if e.name().as_ref() == b"g" => {
                widths.pop();
            }
            Event::Eof => break,
            _ => {}
        }
    }
    (size, out)
}

/// A stroke that is a legend swatch of a label whose text starts at (`x`, `y`): a
/// horizontal 2-pixel line of 24 or 5 pixels, 6 pixels below `y`, ending before `x`.
fn swatch(mark: &Mark, x: f64, y: f64) -> Option<Area> {
    let Mark::Stroke { width, points } = mark else {
        return None;
    };
    let [a, b] = points.as_slice() else {
        return None;
    };
    let length = b.0 - a.0;
    let fits = *width == 2.0
        && a.1 == b.1
        && a.1 == y + 6.0
        && (length == 24.0 || length == 5.0)
        && b.0 <= x;
    fits.then(|| Area {
        left: a.0,
        top: a.1 - width / 2.0,
        right: b.0,
        bottom: a.1 + width / 2.0,
    })
}

/// The label's box: from its anchor, the baseline `dy` below it, the ascent and descent
/// and the width bound of its characters at its font size.
fn label_area(x: f64, y: f64, dy_em: f64, size: f64, label: &str) -> Area {
    let baseline = y + dy_em * size;
    Area {
        left: x,
        top: baseline - ASCENT * size,
        right: x + size * label.chars().map(advance).sum::<f64>(),
        bottom: baseline + DESCENT * size,
    }
}

/// The legend entries of a figure's marks, and the indices of the marks that are theirs.
fn legend(marks: &[Mark]) -> (Vec<Entry>, Vec<usize>) {
    let mut entries = Vec::new();
    let mut own = Vec::new();
    for (i, m) in marks.iter().enumerate() {
        let Mark::Text {
            x,
            y,
            dy_em,
            size,
            start_anchored: true,
            label,
        } = m
        else {
            continue;
        };
        let mut swatches = Vec::new();
        let mut j = i;
        while j > 0
            && let Some(area) = swatch(&marks[j - 1], *x, *y)
        {
            swatches.push(area);
            own.push(j - 1);
            j -= 1;
        }
        if !swatches.is_empty() {
            own.push(i);
            entries.push(Entry {
                label: label.clone(),
                text: label_area(*x, *y, *dy_em, *size, label),
                swatches,
            });
        }
    }
    (entries, own)
}

/// Every problem of one figure's legend, as sentences; and its entry count.
fn legend_problems(svg: &str) -> (Vec<String>, usize) {
    let ((width, height), marks) = marks(svg);
    let (entries, own) = legend(&marks);
    let mut problems = Vec::new();
    let boxes: Vec<(usize, &str, Area)> = entries
        .iter()
        .enumerate()
        .flat_map(|(k, e)| {
            std::iter::once((k, "label", e.text))
                .chain(e.swatches.iter().map(move |s| (k, "swatch", *s)))
        })
        .collect();
    for (n, (k, what, area)) in boxes.iter().enumerate() {
        let label = &entries[*k].label;
        if !area.inside(width, height) {
            problems.push(format!(
                "the {what} of \"{label}\" leaves the figure: {area:?}"
            ));
        }
        for (m, (l, other, b)) in boxes.iter().enumerate().skip(n + 1) {
            if area.overlaps(b) {
                let theirs = &entries[*l].label;
                problems.push(format!(
                    "the {what} of \"{label}\" overlaps the {other} of \"{theirs}\" ({n}, {m})"
                ));
            }
        }
        for (i, mark) in marks.iter().enumerate() {
            if own.contains(&i) {
                continue;
            }
            let crossed = match mark {
                Mark::Stroke { points, .. } => {
                    points.len() == 1 && area.crossed_by(points[0], points[0])
                        || points.windows(2).any(|s| area.crossed_by(s[0], s[1]))
                }
                Mark::Circle { x, y, r } => area.overlaps(&Area {
                    left: x - r,
                    top: y - r,
                    right: x + r,
                    bottom: y + r,
                }),
                Mark::Text { .. } => false,
            };
            if crossed {
                problems.push(format!("a plotted mark crosses the {what} of \"{label}\""));
            }
        }
    }
    (problems, entries.len())
}

/// `rockslide args… --quiet --out out` from the repository's root, which must pass.
fn rockslide(args: &[&str], out: &Path) {
    let o = Command::new(env!("CARGO_BIN_EXE_rockslide"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .args(["--quiet", "--out"])
        .arg(out)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn svg_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            svg_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "svg") {
            out.push(p);
        }
    }
}

/// A study of the paper's PEPO under the Loma Prieta record, two PGAs, both polarities,
/// written into `dir`: its grid file.
fn small_study(dir: &Path) -> PathBuf {
    let record = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cases/records/Loma_Prieta_1989_HSP-000.AT2")
        .display()
        .to_string();
    let base = format!(
        "name = \"legend-study-base\"\n[model]\nkind = \"oscillator\"\nmass = 1.0e6\ngravity = 9.81\n\
         [model.contact]\nkx = 9.8696e8\nkz = 3.94784e9\nmu = 0.2\n[excitation]\n\
         kind = \"ground-acceleration\"\nrecord = \"{record}\"\nscale_to_pga_g = 0.3\n[run]\n\
         duration = 40.0\ndt = 0.005\n[engines.predictor-corrector]\nvariants = [\"ground-accel\"]\n"
    );
    std::fs::write(dir.join("base.toml"), base).unwrap();
    let grid = dir.join("grid.toml");
    std::fs::write(
        &grid,
        format!(
            "title = \"legend check\"\nbase = \"base.toml\"\nrecords = [\"{record}\"]\n\
             pga_g = [0.2, 0.4]\npolarity = [1, -1]\ntail = 2.0\n"
        ),
    )
    .unwrap();
    grid
}

#[test]
fn legends_of_the_shipped_figures_overlap_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for args in [
        &[
            "run",
            "cases",
            "cases/records",
            "cases/vertical",
            "cases/spatial",
        ][..],
        &["stability"],
        &["sweep", "cases/pepo-mass-accel.toml"],
        &["check", "examples/external/pepo-external.toml"],
    ] {
        rockslide(args, &out);
    }
    let grid = small_study(dir.path());
    rockslide(&["study", grid.to_str().unwrap()], &out.join("study"));
    let mut files = Vec::new();
    svg_files(&out, &mut files);
    files.sort();
    let mut problems = Vec::new();
    let (mut figures, mut entries) = (0, 0);
    for f in &files {
        let svg = std::fs::read_to_string(f).unwrap();
        let (found, n) = legend_problems(&svg);
        let name = f.strip_prefix(&out).unwrap().display().to_string();
        // every figure but a record's (one line, no legend) has a legend
        if n == 0 && !name.ends_with("plot-record.svg") {
            problems.push(format!("{name}: no legend found"));
        }
        problems.extend(found.into_iter().map(|p| format!("{name}: {p}")));
        figures += 1;
        entries += n;
    }
    assert!(figures >= 150, "{figures} figures");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    eprintln!("{figures} figures, {entries} legend entries, none overlapping");
}

/// The checker itself: two labels that share a row overlap when the first is long, and a
/// curve through a label crosses it.
#[test]
fn the_legend_check_finds_an_overlap_and_a_crossing() {
    let entry = |x: i32, y: i32, label: &str| {
        format!(
            "<path fill=\"none\" stroke=\"#000000\" stroke-width=\"2\" d=\"M{x} {}l24 0\"/>\n\
             <text x=\"{}\" y=\"{y}\" dy=\"0.76em\" text-anchor=\"start\" font-family=\"sans-serif\" font-size=\"10\">\n{label}\n</text>\n",
            y + 6,
            x + 30
        )
    };
    let svg = |body: &str| {
        format!(
            "<svg width=\"600\" height=\"100\" xmlns=\"http://www.w3.org/2000/svg\">\n{body}</svg>\n"
        )
    };
    // "mmmmmmmmmm" is 10 × 0.975 em = 97.5 px at 10 px: from 50 to 147.5, into the second
    // entry's swatch at 140
    let near = svg(&(entry(20, 40, "mmmmmmmmmm") + &entry(140, 40, "b")));
    let (p, n) = legend_problems(&near);
    assert_eq!(n, 2);
    assert!(
        p.iter()
            .any(|p| p.contains("\"mmmmmmmmmm\" overlaps the swatch of \"b\"")),
        "{p:?}"
    );
    // moved to 160, the boxes are apart
    let apart = svg(&(entry(20, 40, "mmmmmmmmmm") + &entry(160, 40, "b")));
    assert_eq!(legend_problems(&apart), (vec![], 2));
    // a curve through the label's box (the text spans y 40 − 1.7 to 40 + 10)
    let crossed = format!(
        "{}<path fill=\"none\" stroke=\"#1F77B4\" stroke-width=\"1\" d=\"M60 0l0 90\"/>\n",
        entry(20, 40, "abc")
    );
    let (p, _) = legend_problems(&svg(&crossed));
    assert_eq!(p, ["a plotted mark crosses the label of \"abc\""]);
}

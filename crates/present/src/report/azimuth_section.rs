//! The case report's section of a case run at a set of azimuths
//! ([`rockslide_verify::azimuths::AzimuthSweep`]): what the set covers and which azimuth
//! governs, each participant's maxima over the set, the checks on those maxima, the
//! figures at every azimuth (one table per quantity, the governing row marked) and a plot
//! of peak sliding against azimuth. The rest of the report — traces, figures, checks — is
//! the governing azimuth's.

use plotters::prelude::*;

use crate::doc::figure::{GRID, NOTE, REFERENCE, draw_legend, failed_svg, legend_height, palette};
use crate::doc::format::pct;
use crate::doc::{Block, Cell, Table, Tone};
use rockslide_core::case::REFERENCE_LABEL;
use rockslide_core::response::{display_unit, show};
use rockslide_verify::azimuths::{AzimuthSweep, Figures, Maximum};
use rockslide_verify::check_record::CheckRecord;
use rockslide_verify::suite::CaseResult;

/// How one quantity is read off a participant's figures.
type Read = fn(&Figures) -> Option<f64>;
/// A line of the plot: label, colour, (azimuth, value) points.
type Series = (String, RGBColor, Vec<(f64, f64)>);

/// Figure size in pixels, before the legend.
const SIZE: (u32, u32) = (1000, 380);

/// The section, for a case with a set of azimuths (nothing otherwise).
pub(crate) fn case_blocks(r: &CaseResult) -> Vec<Block> {
    let Some(s) = r.azimuths.as_deref() else {
        return Vec::new();
    };
    let mut b = vec![Block::Heading(
        2,
        format!(
            "Azimuths of +x: {} from 0 to {}°",
            s.points.len(),
            s.span_deg
        ),
    )];
    b.push(Block::Para(summary(s)));
    b.push(Block::Table(maxima_table(s)));
    let elsewhere = s.governing_elsewhere();
    if !elsewhere.is_empty() {
        b.push(Block::List(
            elsewhere
                .iter()
                .map(|(p, a)| {
                    format!(
                        "{p}: its largest peak sliding is at {}, not at the {}'s {} — a different governing azimuth, which fails nothing while the maxima agree within the case's tolerance (checks below)",
                        degrees(*a),
                        s.basis,
                        degrees(s.governing_deg())
                    )
                })
                .collect(),
        ));
    }
    if !s.max_checks.is_empty() {
        b.push(Block::Heading(
            3,
            "Checks on the maxima over the set".into(),
        ));
        b.push(Block::Table(max_checks_table(&s.max_checks)));
    }
    b.push(Block::Figure {
        file: "plot-azimuths.svg".into(),
        caption: format!(
            "Peak sliding ({}) against the compass azimuth of +x, each participant; the governing azimuth {} marked.",
            s.peak_key,
            degrees(s.governing_deg())
        ),
        svg: draw(s),
    });
    let tables: [(&str, &str, Read); 3] = [
        ("Peak sliding", &s.peak_key, |f| f.peak_sliding),
        ("Residual sliding", &s.residual_key, |f| f.residual_sliding),
        ("Peak uplift", s.uplift_key.as_deref().unwrap_or(""), |f| {
            f.peak_uplift
        }),
    ];
    for (title, key, read) in tables {
        if key.is_empty() {
            continue;
        }
        b.push(Block::Heading(
            3,
            format!("{title} at each azimuth ({key}, {})", display_unit(key).0),
        ));
        b.push(Block::Table(azimuth_table(s, key, read)));
    }
    b
}

/// What was run and what governs, in a paragraph.
fn summary(s: &AzimuthSweep) -> String {
    let list: Vec<String> = s
        .points
        .iter()
        .map(|p| format!("{}", p.azimuth_deg))
        .collect();
    let failing = s.points.iter().filter(|p| !p.failures.is_empty()).count();
    let same = if same_everywhere(s) {
        " The basis's peak sliding is the same at every azimuth to 10⁻⁶ (a scene isotropic \
         in plan turns with the ground motion): the set changes nothing here, and round-off \
         picks the governing azimuth."
    } else {
        ""
    };
    format!(
        "Every participant ran at each compass azimuth of +x of x_azimuths_deg ({}°): {}. \
         The governing azimuth is {}, where the {} has its largest peak sliding; the \
         traces, figures and checks above, and the CSV and MCAP files, are at it. The gate \
         applies the case's tolerances at every azimuth ({} of {} with a failure) and to \
         the maxima over the set.{same}",
        list.join(", "),
        s.span_reason,
        degrees(s.governing_deg()),
        s.basis,
        failing,
        s.points.len()
    )
}

/// Whether the basis's peak sliding differs by less than 10⁻⁶ of itself over the set.
fn same_everywhere(s: &AzimuthSweep) -> bool {
    let Some(i) = s.participants.iter().position(|p| *p == s.basis) else {
        return false;
    };
    let peaks: Vec<f64> = s
        .points
        .iter()
        .filter_map(|p| p.figures[i].peak_sliding)
        .collect();
    let (lo, hi) = peaks.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &v| {
        (lo.min(v), hi.max(v))
    });
    s.points.len() > 1 && peaks.len() == s.points.len() && hi > 0.0 && hi - lo <= 1e-6 * hi
}

/// An azimuth in words, `45°`.
fn degrees(a: f64) -> String {
    format!("{a}°")
}

/// A value of `key` for people (4 significant digits in its display unit), `—` if none.
fn value(key: &str, v: Option<f64>) -> String {
    v.map_or_else(|| "—".to_string(), |v| show(key, v))
}

/// A maximum and its azimuth, `12.34 at 45°`.
fn maximum(key: &str, m: Option<Maximum>) -> String {
    m.map_or_else(
        || "—".to_string(),
        |m| format!("{} at {}", show(key, m.value), degrees(m.azimuth_deg)),
    )
}

/// Participant × (largest peak, residual, uplift, each with its azimuth).
fn maxima_table(s: &AzimuthSweep) -> Table {
    let unit = |k: &str| display_unit(k).0.to_string();
    let mut header = vec![
        "Participant".to_string(),
        format!("Largest peak sliding [{}]", unit(&s.peak_key)),
        format!("Largest residual sliding [{}]", unit(&s.residual_key)),
    ];
    if let Some(k) = &s.uplift_key {
        header.push(format!("Largest peak uplift [{}]", unit(k)));
    }
    let mut t = Table {
        numeric: vec![false; header.len()],
        header,
        rows: Vec::new(),
    };
    for m in &s.maxima {
        let mut row: Vec<Cell> = vec![
            m.participant.clone().into(),
            maximum(&s.peak_key, m.peak_sliding).into(),
            maximum(&s.residual_key, m.residual_sliding).into(),
        ];
        if let Some(k) = &s.uplift_key {
            row.push(maximum(k, m.peak_uplift).into());
        }
        t.rows.push(row);
    }
    t
}

/// The checks on the maxima: run, quantity, both maxima, Δ, tolerance, verdict.
fn max_checks_table(checks: &[CheckRecord]) -> Table {
    let mut t = Table {
        header: [
            "Quantity",
            "Run",
            "Against",
            "Maximum",
            "Basis",
            "Unit",
            "Δ %",
            "Tolerance",
            "Result",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![false, false, false, true, true, false, true, false, false],
        rows: Vec::new(),
    };
    for c in checks {
        let tone = match (c.verdict.as_str(), c.gated) {
            ("PASS", _) => Tone::Pass,
            (_, true) => Tone::Fail,
            (_, false) => Tone::Warn,
        };
        t.rows.push(vec![
            c.quantity.clone().into(),
            c.run.clone().into(),
            c.basis.clone().into(),
            value(&c.quantity, c.value).into(),
            value(&c.quantity, c.basis_value).into(),
            display_unit(&c.quantity).0.into(),
            pct(c.percent).into(),
            c.limit.clone().into(),
            Cell::toned(c.verdict.clone(), tone),
        ]);
    }
    t
}

/// Azimuth × participant of one quantity, each run's Δ against the reference beside it,
/// the azimuth's gate last; the governing row marked.
fn azimuth_table(s: &AzimuthSweep, key: &str, read: Read) -> Table {
    let has_reference = s.participants.first().map(String::as_str) == Some(REFERENCE_LABEL);
    let mut header = vec!["Azimuth of +x".to_string()];
    for p in &s.participants {
        header.push(p.clone());
        if has_reference && p != REFERENCE_LABEL {
            header.push("Δ %".into());
        }
    }
    header.push("Gate".into());
    let mut numeric = vec![true; header.len()];
    numeric[0] = false;
    *numeric.last_mut().expect("a gate column") = false;
    let mut t = Table {
        header,
        numeric,
        rows: Vec::new(),
    };
    for (i, p) in s.points.iter().enumerate() {
        let governs = i == s.governing;
        let label = if governs {
            Cell::toned(
                format!("{} (governing)", degrees(p.azimuth_deg)),
                Tone::Strong,
            )
        } else {
            degrees(p.azimuth_deg).into()
        };
        let mut row = vec![label];
        let reference = has_reference.then(|| read(&p.figures[0])).flatten();
        for f in &p.figures {
            let v = read(f);
            row.push(value(key, v).into());
            if has_reference && f.participant != REFERENCE_LABEL {
                let d = match (v, reference) {
                    (Some(v), Some(b)) => rockslide_verify::analysis::discrepancy_percent(v, b),
                    _ => None,
                };
                row.push(pct(d).into());
            }
        }
        row.push(if p.failures.is_empty() {
            Cell::toned("PASS", Tone::Pass)
        } else {
            Cell::toned(format!("FAIL ({})", p.failures.len()), Tone::Fail)
        });
        t.rows.push(row);
    }
    t
}

/// Peak sliding (display unit) against azimuth, a line and markers per participant (the
/// reference black and wider), the governing azimuth a grey vertical line.
fn draw(s: &AzimuthSweep) -> String {
    let (unit, factor) = display_unit(&s.peak_key);
    let series: Vec<Series> = s
        .participants
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let colour = if p == REFERENCE_LABEL {
                REFERENCE
            } else {
                let runs_before = usize::from(s.participants[0] == REFERENCE_LABEL);
                palette(i - runs_before)
            };
            let points = s
                .points
                .iter()
                .filter_map(|pt| Some((pt.azimuth_deg, pt.figures[i].peak_sliding? * factor)))
                .filter(|(_, v)| v.is_finite())
                .collect();
            (p.clone(), colour, points)
        })
        .collect();
    let top = series
        .iter()
        .flat_map(|(_, _, pts)| pts.iter().map(|p| p.1))
        .fold(0.0_f64, f64::max);
    let top = if top > 0.0 { 1.1 * top } else { 1.0 };
    let entries: Vec<(String, RGBColor, bool)> = series
        .iter()
        .map(|(l, c, _)| (l.clone(), *c, false))
        .collect();
    let legend = legend_height(&entries, SIZE.0);
    let governing = s.governing_deg();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (SIZE.0, SIZE.1 + legend)).into_drawing_area();
        let result = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
            root.fill(&WHITE)?;
            let (plot, strip) = root.split_vertically(SIZE.1);
            let mut chart = ChartBuilder::on(&plot)
                .caption("Peak sliding against the azimuth of +x", ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..s.span_deg, 0.0..top)?;
            chart
                .configure_mesh()
                .x_desc("compass azimuth of +x [°]")
                .y_desc(format!("peak sliding [{unit}]"))
                .label_style(("sans-serif", 13))
                .light_line_style(GRID)
                .draw()?;
            chart.draw_series(LineSeries::new(
                [(governing, 0.0), (governing, top)],
                NOTE.stroke_width(1),
            ))?;
            for (label, colour, points) in &series {
                let width = if label == REFERENCE_LABEL { 3 } else { 2 };
                chart.draw_series(LineSeries::new(
                    points.iter().copied(),
                    colour.stroke_width(width),
                ))?;
                chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))?;
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
    crate::doc::figure::compact_svg(&svg)
}

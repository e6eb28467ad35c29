//! The study summary as a document, built from the typed [`Study`]: provenance of the
//! grid and base case, the headline (largest sliding, engine agreement, ratios to the
//! rigid block) in sentences, one table row per point and run in display units, and the
//! figures. Wall times are in the result files but never here, so a sharded study merged
//! afterwards gives the same summary, byte for byte, as the study run in one go.

use super::figure::{residual_vs_pga, run_slug};
use crate::doc::{Block, Table};
use rockslide_core::case::record::STANDARD_GRAVITY;
use rockslide_verify::study::{Headline, Statistics, Study, headline, short_name, statistics};

/// A headline item as a sentence.
pub fn sentence(h: &Headline) -> String {
    match h {
        Headline::Largest {
            label,
            value,
            point,
        } => format!(
            "{label}: largest |residual sliding| {} mm — {} at PGA {:.3} g, μ = {}, polarity {:+}",
            rockslide_core::response::sig(value * 1000.0),
            short_name(&point.record),
            point.pga / STANDARD_GRAVITY,
            point.mu,
            point.point.polarity
        ),
        Headline::Against {
            label,
            quantity,
            basis,
            median,
            largest,
            points,
        } => format!(
            "{label} against {basis}, {}: median |Δ| {median:.2} %, largest {largest:.2} % over {points} points with |sliding| > 0.1 mm",
            quantity.name()
        ),
        Headline::OverRigid {
            label,
            median,
            min,
            max,
            points,
        } => format!(
            "{label} / newmark-rigid |residual sliding|: median {median:.2}, range {min:.2}–{max:.2} over {points} points with rigid-block sliding > 0.1 mm"
        ),
    }
}

/// One quantity's statistics over the study as a sentence.
pub fn statistics_sentence(s: &Statistics) -> String {
    let g = &s.governing;
    // lengths in cm, rotations in mrad
    let (unit, f) = if s.unit == "rad" {
        ("mrad", 1e3)
    } else {
        ("cm", 100.0)
    };
    format!(
        "{}: {} over {} points — mean {:.3} {unit}, median {:.3} {unit}, 84th percentile {:.3} {unit}, max {:.3} {unit} ({} at PGA {:.3} g, μ = {}, polarity {:+}{})",
        s.label,
        s.quantity,
        s.points,
        s.mean * f,
        s.median * f,
        s.p84 * f,
        s.max * f,
        short_name(&g.record),
        g.pga / STANDARD_GRAVITY,
        g.mu,
        g.point.polarity,
        governing_azimuths(s)
    )
}

/// The governing azimuth of a statistic, or every azimuth that reaches its maximum alike.
fn governing_azimuths(s: &Statistics) -> String {
    match s.governing_azimuths.as_slice() {
        [] => String::new(),
        [a] => format!(", +x at compass {a}°"),
        all => format!(
            ", +x at compass {}° alike (to {:.0e}: no azimuth governs)",
            all.iter()
                .map(|a| a.to_string())
                .collect::<Vec<_>>()
                .join("°, "),
            rockslide_verify::study::SAME_TO
        ),
    }
}

/// The headline of a study as sentences.
pub fn headline_sentences(c: &Study) -> Vec<String> {
    headline(c).iter().map(sentence).collect()
}

/// The first 12 hex digits of a SHA-256.
fn short(sha: &str) -> &str {
    &sha[..sha.len().min(12)]
}

/// The summary page of a study.
pub(crate) fn document(c: &Study) -> Vec<Block> {
    let mut b = vec![
        Block::Heading(1, format!("Study: {}", c.title)),
        provenance_facts(c),
        Block::Heading(2, "Headline".into()),
        Block::List(headline_sentences(c)),
        Block::Heading(2, "Statistics".into()),
        Block::List(statistics(c).iter().map(statistics_sentence).collect()),
        Block::Heading(2, "Runs".into()),
        Block::Table(runs_table(c)),
    ];
    b.extend(not_applicable_blocks(c));
    b.extend(figure_blocks(c));
    b
}

/// Where the study comes from: its grid and base case with their hashes, its size, the
/// rigid block it is measured against, the tool and commit.
fn provenance_facts(c: &Study) -> Block {
    Block::Facts(vec![
        (
            "grid".into(),
            format!("{} (sha256 {})", c.grid.path, short(&c.grid.sha256)),
        ),
        (
            "base case".into(),
            format!(
                "{} — {} (sha256 {})",
                c.base.path,
                c.base_title,
                short(&c.base.sha256)
            ),
        ),
        (
            "points".into(),
            format!("{}, runs: {}", c.results.len(), c.rows().count()),
        ),
        (
            "rigid block".into(),
            "Newmark 1965, ky = μ·g of the model, two-way sliding, exact for piecewise-linear records; sliding sign: mass minus ground".into(),
        ),
        ("tool".into(), crate::stamp::tool()),
        ("commit".into(), crate::stamp::COMMIT.into()),
    ])
}

/// One row per point and run: the point's record, PGA, μ and polarity, the run, its
/// status and its sliding in mm.
fn runs_table(c: &Study) -> Table {
    let mut t = Table::with_columns(&[
        ("point", false),
        ("record", false),
        ("PGA [g]", true),
        ("μ", true),
        ("pol.", true),
        ("run", false),
        ("status", false),
        ("residual sliding [mm]", true),
        ("peak abs. sliding [mm]", true),
    ]);
    let mm = |x: Option<f64>| {
        x.map_or_else(|| "—".into(), |v| rockslide_core::response::sig(v * 1000.0))
    };
    for (r, run) in c.rows() {
        t.rows.push(vec![
            r.point.id().into(),
            short_name(&r.record).into(),
            format!("{:.3}", r.pga / STANDARD_GRAVITY).into(),
            format!("{}", r.mu).into(),
            format!("{:+}", r.point.polarity).into(),
            format!("{}/{}", run.engine, run.variant).into(),
            run.status.clone().into(),
            mm(run.residual_resultant_sliding.or(run.residual_sliding)).into(),
            mm(run.peak_magnitude()).into(),
        ]);
    }
    t
}

/// The engines that did not apply to the study's scene, and why (none: no blocks).
fn not_applicable_blocks(c: &Study) -> Vec<Block> {
    let Some(first) = c.results.first() else {
        return Vec::new();
    };
    if first.not_applicable.is_empty() {
        return Vec::new();
    }
    vec![
        Block::Heading(2, "Engines not applicable".into()),
        Block::List(
            first
                .not_applicable
                .iter()
                .map(|(e, why)| format!("{e}: not applicable — {why}"))
                .collect(),
        ),
    ]
}

/// Residual sliding against PGA: every run, then each engine's with the rigid block when
/// the study ran more than one.
fn figure_blocks(c: &Study) -> Vec<Block> {
    let mut b = vec![Block::Figure {
        file: "residual-vs-pga.svg".into(),
        caption: "Residual sliding against PGA, every run of the study.".into(),
        svg: residual_vs_pga(c, None),
    }];
    let engines = c.engine_labels();
    if engines.len() > 1 {
        b.push(Block::Heading(
            2,
            "Per engine (with the rigid block)".into(),
        ));
        for l in engines {
            b.push(Block::Figure {
                file: format!("residual-vs-pga-{}.svg", run_slug(&l)),
                caption: format!("Residual sliding against PGA: {l}, with the rigid block."),
                svg: residual_vs_pga(c, Some(&l)),
            });
        }
    }
    b
}

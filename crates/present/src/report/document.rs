//! The content of a case's report, built once as [`Block`]s: the verdict, the design
//! quantities and notes first, then document control, the paper-style table, the
//! tolerance checks and invariants, the cross-code comparison, the whole-history errors,
//! the plots, each run's settings and findings, and provenance. The suite summary
//! (`suite_document`) shares its notes.

use super::attachments::Attachments;
use super::control::document_control;
use super::crosscode_tables::{cross_code_blocks, history_table};
use super::plots::figures;
use super::provenance::Provenance;
use super::response_tables::{checks_table, response_table};
use super::sections;
use crate::doc::{Block, Cell, Table, Tone};
use rockslide_core::case::Invariant;
use rockslide_verify::suite::CaseResult;
use rockslide_verify::verdict;

/// The blocks of one case's report.
pub(crate) fn case_document(r: &CaseResult, prov: &Provenance, att: &Attachments) -> Vec<Block> {
    let c = &r.case;
    let mut b = vec![Block::Heading(1, format!("{} — {}", c.name, c.title))];
    b.extend(verdict_blocks(r));
    b.extend(super::input_warnings::case_blocks(r));
    b.extend(super::design::case_design_blocks(r));
    b.extend(notes_blocks(std::slice::from_ref(r)));
    b.push(Block::Heading(2, "Document".into()));
    b.push(document_control(c, prov));
    b.push(case_facts(c));
    b.extend(response_blocks(r));
    b.extend(super::azimuth_section::case_blocks(r));

    if !r.checks.is_empty() {
        b.push(Block::Heading(2, "Tolerance checks".into()));
        b.push(Block::Table(checks_table(r)));
    }
    if !r.invariants.is_empty() {
        b.push(Block::Heading(
            2,
            "Physical invariants (every completed run, no reference)".into(),
        ));
        b.push(Block::Table(invariants_table(r)));
        b.push(Block::List(
            Invariant::ALL
                .iter()
                .map(|&k| format!("{k}: {}", rockslide_verify::invariants::meaning(k)))
                .collect(),
        ));
    }

    b.push(Block::Heading(2, "Cross-code comparison".into()));
    b.extend(cross_code_blocks(r));

    if r.reference.is_ok()
        && let Some(t) = history_table(r)
    {
        b.push(Block::Heading(
            2,
            "Whole-history error of the relative displacement against the reference".into(),
        ));
        b.push(Block::Table(t));
    }

    b.push(Block::Heading(2, "Time histories".into()));
    for f in figures(r) {
        b.push(Block::Figure {
            file: format!("plot-{}.svg", f.id),
            caption: f.caption,
            svg: f.svg,
        });
    }

    b.extend(sections::energy_blocks(r));
    b.extend(crate::sweep::case_section(r, att.sweep.as_ref()));

    b.extend(runs_blocks(r));

    b.push(Block::Heading(2, "Provenance".into()));
    b.push(Block::Facts(prov.lines(r)));
    b.push(Block::Details {
        summary: format!("case file {}", c.path.display()),
        text: c.text.clone(),
    });
    b
}

/// The case's facts: its source, requirement, records and scene.
fn case_facts(c: &rockslide_core::case::Case) -> Block {
    let mut facts = Vec::new();
    if !c.source.is_empty() {
        facts.push(("Source".to_string(), c.source.clone()));
    }
    if !c.requirement.is_empty() {
        facts.push(("Requirement".to_string(), c.requirement.clone()));
    }
    if let Some(rockslide_core::case::Signal::Record { label, .. }) = c.scene.excitation.signal() {
        facts.push(("Record".to_string(), label.clone()));
    }
    // a 3D scene's second horizontal component, along e₂
    if let Some(rockslide_core::case::Signal::Record { label, .. }) =
        c.scene.spatial().and_then(|s| s.second.as_ref())
    {
        facts.push((
            "Record, second component (along e₂)".to_string(),
            label.clone(),
        ));
    }
    if let Some(rockslide_core::case::Signal::Record { label, .. }) =
        c.scene.vertical.as_ref().map(|v| &v.signal)
    {
        facts.push(("Record, vertical (up)".to_string(), label.clone()));
    }
    facts.push((
        "Scene".into(),
        format!(
            "{} under {}, {} s",
            c.scene.model.kind(),
            c.scene.excitation.kind(),
            c.run.duration
        ),
    ));
    Block::Facts(facts)
}

/// The gate's verdict of the case and its failures, if any.
fn verdict_blocks(r: &CaseResult) -> Vec<Block> {
    let gated = r.checks.iter().filter(|c| c.gated).count();
    let failures = verdict::failures(std::slice::from_ref(r));
    let informative = r.checks.len() - gated;
    let mut b = vec![Block::Verdict {
        passed: failures.is_empty(),
        text: format!(
            "{}, {} failed; {}",
            count(gated, "gated check", "gated checks"),
            failures.len(),
            count(
                informative,
                "informative (not gated) check",
                "informative (not gated) checks"
            )
        ),
    }];
    if !failures.is_empty() {
        b.push(Block::List(
            failures.iter().map(|f| f.to_string()).collect(),
        ));
    }
    b
}

/// `1 case`, `2 cases`: a count with its noun.
pub(crate) fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The notes after the design quantities, each said once: what the cases declare known
/// (disagreements with their reason and evidence, invariant violations grouped per
/// declaration), then the informative checks outside their limit.
pub(super) fn notes_blocks(results: &[CaseResult]) -> Vec<Block> {
    let known = verdict::warnings(results);
    let informative = verdict::informative_notes(results);
    if known.is_empty() && informative.is_empty() {
        return Vec::new();
    }
    let mut b = vec![Block::Heading(2, "Notes".into())];
    if !known.is_empty() {
        b.push(Block::Para(
            "Known and declared in the case files (not gate failures; a declaration that stops holding fails the gate):".into(),
        ));
        b.push(Block::List(known));
    }
    if !informative.is_empty() {
        b.push(Block::Para(
            "Informative checks outside their limit (not gated: a known property of a method, reported rather than failed):".into(),
        ));
        b.push(Block::List(
            informative.iter().map(|f| f.to_string()).collect(),
        ));
    }
    b
}

/// The response quantities of every participant, with the table's notes and the reference.
fn response_blocks(r: &CaseResult) -> Vec<Block> {
    let mut b = Vec::new();
    b.push(Block::Heading(2, "Response quantities".into()));
    let (table, notes) = response_table(r);
    b.push(Block::Table(table));
    let mut foot = vec![
        "Δ % = 100·(run/reference − 1) (the SAP2000 verification convention); ✓ within a gated tolerance, ✗ outside it, (✗) outside an informative one; each run's tolerance is in the tolerance checks below.".to_string(),
    ];
    foot.extend(notes);
    match &r.reference {
        Ok(x) => foot.push(format!("Reference: {}.", x.solution.method())),
        Err(why) => foot.push(format!("Reference: none — {why}.")),
    }
    b.push(Block::List(foot));
    b
}

/// Each run's settings, solver statistics and findings.
fn runs_blocks(r: &CaseResult) -> Vec<Block> {
    let mut b = Vec::new();
    b.push(Block::Heading(
        2,
        "Runs: settings, solver statistics, findings".into(),
    ));
    for run in &r.runs {
        b.push(Block::Heading(3, run.label()));
        let mut facts = vec![("status".to_string(), run.status.to_string())];
        facts.extend(run.settings.iter().map(|s| (s.label(), setting_text(s))));
        facts.extend(
            run.stats
                .entries()
                .into_iter()
                .map(|(k, v)| (k.to_string(), v.to_string())),
        );
        facts.extend(
            run.findings
                .iter()
                .map(|f| ("finding".to_string(), f.clone())),
        );
        b.push(Block::Facts(facts));
    }
    b
}

/// A setting's value for people: numbers to six significant digits (`0.0000666667`,
/// `21.3542`, `-985973`), anything else as the engine words it.
fn setting_text(s: &rockslide_engine_api::Setting) -> String {
    use rockslide_engine_api::SettingValue;
    let readable = |x: &f64| {
        let rounded: f64 = format!("{x:.5e}").parse().unwrap_or(*x);
        format!("{rounded}")
    };
    match &s.value {
        SettingValue::Number(x) => readable(x),
        SettingValue::Numbers(xs) => xs.iter().map(readable).collect::<Vec<_>>().join(", "),
        _ => s.value_text(),
    }
}

/// One row per invariant and run: measured worst value, where, the engine's limit, verdict.
fn invariants_table(r: &CaseResult) -> Table {
    let mut t = Table::with_columns(&[
        ("Invariant", false),
        ("Run", false),
        ("Worst excess (0: never)", true),
        ("At t (s)", true),
        ("Limit", true),
        ("Verdict", false),
    ]);
    for i in &r.invariants {
        let verdict = match (i.holds(), &i.expected) {
            (true, _) => Cell::toned("PASS: holds", Tone::Pass),
            (false, Some((field, reason))) => {
                Cell::toned(format!("declared ({field})"), Tone::Warn).hint(reason.clone())
            }
            (false, None) => Cell::toned("FAIL", Tone::Fail),
        };
        t.rows.push(vec![
            Cell::plain(i.invariant.key()),
            Cell::plain(i.run.clone()),
            // a measure at or below zero never broke the law (compression −1: N ≥ M·g)
            Cell::plain(verdict::show_measure(i.worst.max(0.0))),
            Cell::plain(i.at.map_or("—".into(), |t| format!("{t:.4}"))),
            Cell::plain(verdict::show_measure(i.limit)),
            verdict,
        ]);
    }
    t
}

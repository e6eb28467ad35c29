//! The content of the suite summary, built once as [`Block`]s: the gate's verdict over
//! every case and its failures, the input warnings, the design quantities, the notes, one
//! row per case, the stability study and provenance. The cases' own reports follow it in
//! the HTML page (`pages`).

use super::attachments::Attachments;
use super::document::{count, notes_blocks};
use super::provenance::Provenance;
use super::response_tables::gated_failures;
use crate::doc::{Block, Cell, Table, Tone};
use rockslide_verify::suite::CaseResult;
use rockslide_verify::verdict;

/// The blocks of the suite summary (without the cases' own reports).
pub(crate) fn suite_document(
    results: &[CaseResult],
    prov: &Provenance,
    att: &Attachments,
) -> Vec<Block> {
    let mut b = vec![Block::Heading(1, "rockslide — verification suite".into())];
    b.extend(verdict_blocks(results));
    b.extend(super::input_warnings::suite_blocks(results));
    b.push(Block::Heading(2, "Design quantities".into()));
    b.push(Block::Table(super::design::suite_design_table(results)));
    b.push(Block::List(vec![format!(
        "Each case's basis (its reference, or its first run) and the largest difference of any participant from it on a design quantity; a difference beyond {} % is declared in the case file (its report gives the reason and the evidence) or fails the gate.",
        rockslide_verify::disagreement::DESIGN_PERCENT
    )]));
    b.extend(notes_blocks(results));
    b.push(Block::Heading(2, "Cases".into()));
    b.push(Block::Table(cases_table(results)));
    b.extend(crate::stability::suite_section(att.stability.as_ref()));
    b.push(Block::Heading(2, "Provenance".into()));
    b.push(provenance_facts(results, prov));
    b
}

/// The gate's verdict over every case, and every gate failure.
fn verdict_blocks(results: &[CaseResult]) -> Vec<Block> {
    let all = verdict::failures(results);
    let gated: usize = results
        .iter()
        .map(|r| r.checks.iter().filter(|c| c.gated).count())
        .sum();
    let mut b = vec![Block::Verdict {
        passed: all.is_empty(),
        text: format!(
            "{}, {}, {}",
            count(results.len(), "case", "cases"),
            count(gated, "gated check", "gated checks"),
            count(all.len(), "gate failure", "gate failures")
        ),
    }];
    if !all.is_empty() {
        b.push(Block::List(all.iter().map(|f| f.to_string()).collect()));
    }
    b
}

/// One row per case: its runs, the engines that do not apply, its reference, its checks
/// and failures, and its gate.
fn cases_table(results: &[CaseResult]) -> Table {
    let mut t = Table::with_columns(&[
        ("Case", false),
        ("Title", false),
        ("Runs", true),
        ("n/a", false),
        ("Reference", false),
        ("Checks", true),
        ("Failed", true),
        ("Informative fails", true),
        ("Gate", false),
    ]);
    for r in results {
        let failed = gated_failures(r);
        let na: Vec<String> = super::table::absent_engines(r)
            .into_iter()
            .map(|(e, _)| e)
            .collect();
        t.rows.push(vec![
            Cell::plain(r.case.name.clone()).link(r.case.name.clone()),
            Cell::plain(r.case.title.clone()),
            Cell::plain(r.runs.len().to_string()),
            Cell::toned(na.join(", "), Tone::Muted),
            Cell::plain(
                r.reference
                    .as_ref()
                    .map_or("none".to_string(), |x| x.solution.name().to_string()),
            ),
            Cell::plain(r.checks.len().to_string()),
            Cell::plain(failed.to_string()),
            Cell::plain(
                verdict::informative(std::slice::from_ref(r))
                    .len()
                    .to_string(),
            ),
            if failed == 0 {
                Cell::toned("PASS", Tone::Pass)
            } else {
                Cell::toned("FAIL", Tone::Fail)
            },
        ]);
    }
    t
}

/// The tool, commit, machine and date of the run, and every case file with its hash.
fn provenance_facts(results: &[CaseResult], prov: &Provenance) -> Block {
    Block::Facts(vec![
        ("tool".into(), prov.tool.clone()),
        ("commit".into(), prov.commit.clone()),
        ("machine".into(), prov.machine()),
        ("date".into(), prov.date.clone()),
        (
            "case files".into(),
            results
                .iter()
                .map(|r| format!("{} (sha256 {})", r.case.path.display(), r.case.sha256))
                .collect::<Vec<_>>()
                .join("; "),
        ),
    ])
}

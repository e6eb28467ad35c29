//! The case's numbers against their checks: the paper-style response table, each value
//! marked with its check's verdict (✓ within a gated tolerance, ✗ outside it, (✗) outside
//! an informative one), and the tolerance checks' table, one row per check.

use super::table::{Column, paper_table};
use crate::doc::format::{display_unit, pct, show};
use crate::doc::{Cell, Table, Tone};
use rockslide_verify::analysis::Verdict;
use rockslide_verify::suite::CaseResult;
use rockslide_verify::verdict;

fn tone_of(verdict: Verdict, gated: bool) -> Tone {
    match (verdict, gated) {
        (Verdict::Pass, _) => Tone::Pass,
        (_, true) => Tone::Fail,
        (_, false) => Tone::Warn,
    }
}

fn mark(verdict: Verdict, gated: bool) -> &'static str {
    match (verdict, gated) {
        (Verdict::Pass, _) => " ✓",
        (_, true) => " ✗",
        (_, false) => " (✗)",
    }
}

/// Gated checks of a case that failed.
pub(super) fn gated_failures(r: &CaseResult) -> usize {
    verdict::failures(std::slice::from_ref(r)).len()
}

/// The paper-style table, and the notes that go under it (engines that did not run, and
/// why; other programs' notes).
pub(super) fn response_table(r: &CaseResult) -> (Table, Vec<String>) {
    let t = paper_table(r);
    let mut header = vec!["Quantity".to_string(), "Unit".into()];
    let mut numeric = vec![false, false];
    if let Some(name) = &t.reference {
        header.push(name.clone());
        numeric.push(true);
    }
    let mut notes = Vec::new();
    for col in &t.columns {
        match col {
            Column::Run(i) => {
                let run = &r.runs[*i];
                let mut h = run.label();
                if !run.status.completed() {
                    h.push_str(&format!(" ({})", run.status.label()));
                }
                header.push(h);
                numeric.push(true);
                if t.reference.is_some() {
                    header.push("Δ %".into());
                    numeric.push(true);
                }
            }
            // Engines that did not run get no column (a column of "n/a" only hides the
            // numbers): the reason is listed right under the table.
            Column::Absent { engine, why } => {
                notes.push(format!("{engine}: not applicable — {why}"));
            }
        }
    }
    notes.extend(rockslide_verify::external::report_notes(r));
    // each run's tolerance is in the tolerance checks' table, one row per check
    header.push("Result".into());
    numeric.push(false);
    let mut rows = Vec::new();
    for row in &t.rows {
        let mut cells: Vec<Cell> = vec![row.label.into(), row.unit.into()];
        if t.reference.is_some() {
            cells.push(Cell::plain(
                row.reference.map_or("—".into(), |v| show(row.key, v)),
            ));
        }
        let mut k = 0;
        for col in &t.columns {
            match col {
                Column::Run(i) => {
                    let c = &row.cells[k];
                    k += 1;
                    let missing = rockslide_verify::external::missing_text(&r.runs[*i], row.key);
                    let value = c.value.map_or(missing.into(), |v| show(row.key, v));
                    cells.push(match (t.reference.is_some(), c.mark) {
                        // Without a reference, checks are against other runs: mark the value.
                        (false, Some((v, g))) => Cell::toned(value + mark(v, g), tone_of(v, g)),
                        _ => Cell::plain(value),
                    });
                    if t.reference.is_some() {
                        let mut text = pct(c.percent);
                        let tone = match c.mark {
                            Some((v, g)) => {
                                text.push_str(mark(v, g));
                                tone_of(v, g)
                            }
                            None => Tone::Plain,
                        };
                        cells.push(Cell::toned(text, tone));
                    }
                }
                Column::Absent { .. } => {}
            }
        }
        cells.push(Cell::toned(row.result.label(), row.result.tone()));
        rows.push(cells);
    }
    (
        Table {
            header,
            numeric,
            rows,
        },
        notes,
    )
}

/// The tolerance checks, one row per check.
pub(super) fn checks_table(r: &CaseResult) -> Table {
    let mut t = Table::with_columns(&[
        ("Quantity", false),
        ("Run", false),
        ("Against", false),
        ("Value", true),
        ("Basis", true),
        ("Unit", false),
        ("Δ %", true),
        ("Tolerance", false),
        ("Gated", false),
        ("Result", false),
    ]);
    for ch in &r.checks {
        t.rows.push(vec![
            ch.quantity.clone().into(),
            ch.run.clone().into(),
            ch.basis.clone().into(),
            ch.value
                .map_or("—".into(), |v| show(&ch.quantity, v))
                .into(),
            ch.basis_value
                .map_or("—".into(), |v| show(&ch.quantity, v))
                .into(),
            display_unit(&ch.quantity).0.into(),
            pct(ch.percent).into(),
            verdict::limit_text(r, ch).into(),
            (if ch.gated { "yes" } else { "no" }).into(),
            Cell::toned(ch.verdict.label(), tone_of(ch.verdict, ch.gated)),
        ]);
    }
    t
}

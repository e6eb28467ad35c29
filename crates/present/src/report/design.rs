//! What a reader sees first after the gate: the design quantities (peak and residual
//! sliding, uplift, rotation) of every participant with Δ % from the basis, for a case;
//! and for the suite, each case's basis values with its largest difference.

use crate::doc::format::{display_unit, pct, show};
use crate::doc::{Block, Cell, Table, Tone};
use rockslide_core::case::REFERENCE_LABEL;
use rockslide_core::case::{DESIGN_QUANTITIES, Model};
use rockslide_verify::analysis::{Responses, quantity_def};
use rockslide_verify::disagreement::{Disagreement, basis, design_disagreements};
use rockslide_verify::suite::CaseResult;

/// The design quantities some participant of the case has.
fn shown_quantities(r: &CaseResult) -> Vec<&'static str> {
    let reference = r.reference.as_ref().ok().map(|x| &x.responses);
    DESIGN_QUANTITIES
        .iter()
        .copied()
        .filter(|q| {
            reference.is_some_and(|x| x.contains_key(q))
                || r.run_responses.iter().any(|x| x.contains_key(q))
        })
        .collect()
}

fn heading(q: &str) -> String {
    let label = quantity_def(q).map_or(q, |d| d.label);
    let label = label
        .trim_end_matches(" (signed)")
        .trim_end_matches(" (abs)");
    format!("{label} [{}]", display_unit(q).0)
}

/// The tone of a Δ % cell: a declared disagreement warns, an undeclared one fails.
fn tone(found: &[Disagreement], run: &str, q: &str) -> Tone {
    match found.iter().find(|d| d.run == run && d.quantity == q) {
        Some(d) if d.declared.is_some() => Tone::Warn,
        Some(_) => Tone::Fail,
        None => Tone::Plain,
    }
}

/// One participant's row: its values and, for a run, Δ % from the basis.
fn row(
    label: &str,
    resp: &Responses,
    basis: Option<&Responses>,
    quantities: &[&'static str],
    found: &[Disagreement],
) -> Vec<Cell> {
    let mut cells = vec![Cell::plain(label)];
    for &q in quantities {
        let value = resp.get(q).copied();
        cells.push(Cell::plain(value.map_or("—".into(), |v| show(q, v))));
        let delta = match (value, basis.and_then(|b| b.get(q))) {
            (Some(v), Some(&b)) if b != 0.0 => Some(100.0 * (v / b - 1.0)),
            _ => None,
        };
        cells.push(match basis {
            None => Cell::toned("basis", Tone::Muted),
            Some(_) => Cell::toned(pct(delta), tone(found, label, q)),
        });
    }
    cells
}

/// The design quantities of a case: its heading, the table, and what the basis and the
/// sliding of a rocking body are.
pub(crate) fn case_design_blocks(r: &CaseResult) -> Vec<Block> {
    let quantities = shown_quantities(r);
    let Some((basis_label, basis_resp)) = basis(r) else {
        return Vec::new();
    };
    if quantities.is_empty() {
        return Vec::new();
    }
    let found = design_disagreements(r);
    let mut header = vec!["Participant".to_string()];
    for q in &quantities {
        header.extend([heading(q), "Δ %".into()]);
    }
    let numeric = std::iter::once(false)
        .chain(std::iter::repeat_n(true, 2 * quantities.len()))
        .collect();
    let mut rows = Vec::new();
    if let Ok(x) = &r.reference {
        rows.push(row(
            REFERENCE_LABEL,
            &x.responses,
            None,
            &quantities,
            &found,
        ));
    }
    for (run, resp) in r.runs.iter().zip(&r.run_responses) {
        let label = run.label();
        if !run.status.completed() {
            continue;
        }
        let against = (label != basis_label).then_some(basis_resp);
        rows.push(row(&label, resp, against, &quantities, &found));
    }
    let mut notes = vec![format!(
        "Δ % = 100·(run/{basis_label} − 1). A difference beyond {} % that no gated tolerance judges must be declared with its reason and evidence, or the gate fails.",
        rockslide_verify::disagreement::DESIGN_PERCENT
    )];
    if matches!(r.case.scene.model, Model::RockingBody(_)) {
        notes.push(ROCKING_SLIDING.to_string());
    }
    vec![
        Block::Heading(2, "Design quantities".into()),
        Block::Table(Table {
            header,
            numeric,
            rows,
        }),
        Block::List(notes),
    ]
}

/// What the sliding of a rocking body is, said where its numbers are.
const ROCKING_SLIDING: &str = "Sliding of a rocking body: the mean horizontal slip of its supports. A lifted support moves with the body, so during lift-off the sliding shows a transient of a few mm that returns on landing; its peak can be read off that transient. The residual sliding is not affected.";

/// One row per case: the gate, the basis and its design values, and the largest
/// difference of any participant from it (in its own cells: per cent, run, quantity).
pub(crate) fn suite_design_table(results: &[CaseResult]) -> Table {
    let mut header: Vec<String> = ["Case", "Gate", "Basis"].map(String::from).to_vec();
    header.extend(DESIGN_QUANTITIES.iter().map(|q| heading(q)));
    header.extend(["Largest Δ %".to_string(), "Where".into()]);
    let numeric = [false, false, false]
        .into_iter()
        .chain(DESIGN_QUANTITIES.iter().map(|_| true))
        .chain([true, false])
        .collect();
    let rows = results.iter().map(suite_row).collect();
    Table {
        header,
        numeric,
        rows,
    }
}

fn suite_row(r: &CaseResult) -> Vec<Cell> {
    let passed = r.gate_passed();
    let mut cells = vec![
        Cell::plain(r.case.name.clone()).link(r.case.name.clone()),
        if passed {
            Cell::toned("PASS", Tone::Pass)
        } else {
            Cell::toned("FAIL", Tone::Fail)
        },
    ];
    let Some((label, resp)) = basis(r) else {
        cells.push(Cell::toned("none", Tone::Muted));
        cells.extend(DESIGN_QUANTITIES.iter().map(|_| Cell::plain("—")));
        cells.extend([Cell::plain("—"), Cell::plain("")]);
        return cells;
    };
    cells.push(Cell::plain(label.clone()));
    for q in DESIGN_QUANTITIES {
        cells.push(Cell::plain(resp.get(q).map_or("—".into(), |&v| show(q, v))));
    }
    let largest = largest_difference(r, &label, resp);
    let found = design_disagreements(r);
    match largest {
        Some((p, run, q)) => {
            cells.push(Cell::toned(pct(Some(p)), tone(&found, &run, q)));
            cells.push(Cell::plain(format!("{run}, {}", heading(q))));
        }
        None => cells.extend([Cell::plain("—"), Cell::plain("")]),
    }
    cells
}

/// The largest |Δ %| of any completed run from the basis on a design quantity.
fn largest_difference(
    r: &CaseResult,
    basis_label: &str,
    basis: &Responses,
) -> Option<(f64, String, &'static str)> {
    let mut best: Option<(f64, String, &'static str)> = None;
    for (run, resp) in r.runs.iter().zip(&r.run_responses) {
        if !run.status.completed() || run.label() == basis_label {
            continue;
        }
        for &q in DESIGN_QUANTITIES {
            let (Some(&v), Some(&b)) = (resp.get(q), basis.get(q)) else {
                continue;
            };
            if b == 0.0 {
                continue;
            }
            let p = 100.0 * (v / b - 1.0);
            if best.as_ref().is_none_or(|(x, _, _)| p.abs() > x.abs()) {
                best = Some((p, run.label(), q));
            }
        }
    }
    best
}

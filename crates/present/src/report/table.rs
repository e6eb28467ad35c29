//! The paper-style table of a case, as data: response quantities as rows; one column per
//! engine run (value and Δ % against the reference), the reference, and one column per
//! engine that did not run, saying why ("not applicable — …"); then the tolerance and the PASS/FAIL
//! of the case's checks on that row. Markdown, HTML and CSV render the same table.

use crate::doc::Tone;
use rockslide_verify::analysis::{
    Check, QUANTITY_KEYS, Verdict, discrepancy_percent, quantity_def,
};
use rockslide_verify::registry::ENGINE_IDS;
use rockslide_verify::suite::CaseResult;

/// A column of the table after the reference.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Column {
    /// Run `i` of the case (index into `CaseResult::runs`).
    Run(usize),
    /// An engine that did not run, and why.
    Absent {
        /// Engine id.
        engine: String,
        /// Why it did not run.
        why: String,
    },
}

/// One run's entry in a row.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Cell {
    /// Value, SI (`None`: the run lacks the quantity or did not complete).
    pub value: Option<f64>,
    /// Discrepancy against the reference, %.
    pub percent: Option<f64>,
    /// Outcome of the checks on this run and quantity: worst verdict, and whether gated.
    pub mark: Option<(Verdict, bool)>,
}

/// One response quantity.
#[derive(Debug, Clone)]
pub(crate) struct Row {
    /// Quantity key.
    pub key: &'static str,
    /// Label.
    pub label: &'static str,
    /// Display unit.
    pub unit: &'static str,
    /// Reference value, SI.
    pub reference: Option<f64>,
    /// One per `Column::Run`, in column order (absent columns have no cell).
    pub cells: Vec<Cell>,
    /// The row's verdict: its gated checks' and its informative checks'.
    pub result: RowVerdict,
}

/// The verdict of one quantity's row: the worst of its gated checks and the worst of its
/// informative (ungated) ones, `None` where it has none.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RowVerdict {
    /// Worst gated verdict.
    pub gated: Option<Verdict>,
    /// Worst informative verdict.
    pub informative: Option<Verdict>,
}

impl RowVerdict {
    /// In words: `PASS`, `FAIL (info: PASS)`, `info: FAIL`, `—`.
    pub fn label(&self) -> String {
        match (self.gated, self.informative) {
            (Some(v), Some(Verdict::Pass) | None) => v.label().to_string(),
            (Some(v), Some(i)) => format!("{} (info: {})", v.label(), i.label()),
            (None, Some(i)) => format!("info: {}", i.label()),
            (None, None) => "—".into(),
        }
    }

    /// How the row reads at a glance: a gated failure (or a check that could not be
    /// evaluated) fails; a pass whose informative checks did not pass, or an informative
    /// check alone that did not pass, warns; a pass passes.
    pub fn tone(&self) -> Tone {
        match (self.gated, self.informative) {
            (Some(Verdict::Fail | Verdict::Missing), _) => Tone::Fail,
            (Some(Verdict::Pass), Some(Verdict::Pass) | None) => Tone::Pass,
            (Some(Verdict::Pass), Some(_)) => Tone::Warn,
            (None, Some(Verdict::Pass)) => Tone::Pass,
            (None, Some(_)) => Tone::Warn,
            (None, None) => Tone::Plain,
        }
    }
}

/// The paper-style table of one case.
#[derive(Debug, Clone)]
pub(crate) struct PaperTable {
    /// Columns after the reference.
    pub columns: Vec<Column>,
    /// Rows, in catalogue order, only quantities some participant has.
    pub rows: Vec<Row>,
    /// Reference column title, if the case has one.
    pub reference: Option<String>,
}

/// Why each known engine did not run for this case, in engine order (runs' engines first).
pub(crate) fn absent_engines(r: &CaseResult) -> Vec<(String, String)> {
    let mut ids: Vec<&str> = ENGINE_IDS.to_vec();
    for (e, _) in &r.not_applicable {
        if !ids.contains(e) {
            ids.push(e);
        }
    }
    let mut out = Vec::new();
    for id in ids {
        if r.runs.iter().any(|run| run.engine == id) {
            continue;
        }
        let why = if let Some((_, why)) = r.not_applicable.iter().find(|(e, _)| *e == id) {
            why.clone()
        } else if !r.case.engines.is_empty() && r.case.engine(id).is_none() {
            "not requested by the case (it names its engines)".to_string()
        } else if rockslide_verify::registry::all()
            .iter()
            .all(|e| e.id() != id)
        {
            "engine not in this build".to_string()
        } else {
            "no variant requested".to_string()
        };
        out.push((id.to_string(), why));
    }
    out
}

/// Worst outcome of a set of checks: FAIL/MISSING over PASS.
fn worst(checks: &[&Check]) -> Option<Verdict> {
    if checks.is_empty() {
        None
    } else if let Some(c) = checks.iter().find(|c| c.verdict != Verdict::Pass) {
        Some(c.verdict)
    } else {
        Some(Verdict::Pass)
    }
}

/// Build the table of a case.
pub(crate) fn paper_table(r: &CaseResult) -> PaperTable {
    let ref_resp = r.reference.as_ref().ok().map(|x| &x.responses);
    let mut columns: Vec<Column> = (0..r.runs.len()).map(Column::Run).collect();
    columns.extend(
        absent_engines(r)
            .into_iter()
            .map(|(engine, why)| Column::Absent { engine, why }),
    );
    let mut rows = Vec::new();
    for key in QUANTITY_KEYS {
        let present = ref_resp.is_some_and(|x| x.contains_key(key))
            || r.run_responses.iter().any(|x| x.contains_key(key));
        if !present {
            continue;
        }
        let d = quantity_def(key).expect("catalogue key");
        let reference = ref_resp.and_then(|x| x.get(key).copied());
        let checks: Vec<&Check> = r.checks.iter().filter(|c| c.quantity == *key).collect();
        let cells = r
            .runs
            .iter()
            .zip(&r.run_responses)
            .map(|(run, resp)| {
                let value = resp.get(key).copied().filter(|_| run.status.completed());
                let mine: Vec<&Check> = checks
                    .iter()
                    .copied()
                    .filter(|c| c.run == run.label())
                    .collect();
                let gated: Vec<&Check> = mine.iter().copied().filter(|c| c.gated).collect();
                let mark = match worst(&gated) {
                    Some(v) => Some((v, true)),
                    None => worst(&mine).map(|v| (v, false)),
                };
                Cell {
                    value,
                    percent: value
                        .zip(reference)
                        .and_then(|(v, b)| discrepancy_percent(v, b)),
                    mark,
                }
            })
            .collect();
        let gated: Vec<&Check> = checks.iter().copied().filter(|c| c.gated).collect();
        let informative: Vec<&Check> = checks.iter().copied().filter(|c| !c.gated).collect();
        let result = RowVerdict {
            gated: worst(&gated),
            informative: worst(&informative),
        };
        rows.push(Row {
            key,
            label: d.label,
            unit: d.display().0,
            reference,
            cells,
            result,
        });
    }
    PaperTable {
        columns,
        rows,
        reference: r
            .reference
            .as_ref()
            .ok()
            .map(|x| format!("Reference ({})", x.solution.name())),
    }
}

#[cfg(test)]
mod row_verdict_tests {
    use super::*;

    #[test]
    fn a_row_reads_from_its_verdicts_not_its_words() {
        let row = |gated, informative| RowVerdict { gated, informative };
        let (p, f, m) = (Verdict::Pass, Verdict::Fail, Verdict::Missing);
        let cases = [
            (row(Some(p), None), "PASS", Tone::Pass),
            (row(Some(p), Some(p)), "PASS", Tone::Pass),
            (row(Some(p), Some(f)), "PASS (info: FAIL)", Tone::Warn),
            (row(Some(f), Some(p)), "FAIL", Tone::Fail),
            (row(Some(m), Some(f)), "MISSING (info: FAIL)", Tone::Fail),
            (row(None, Some(p)), "info: PASS", Tone::Pass),
            (row(None, Some(m)), "info: MISSING", Tone::Warn),
            (row(None, None), "—", Tone::Plain),
        ];
        for (r, label, tone) in cases {
            assert_eq!((r.label().as_str(), r.tone()), (label, tone));
        }
    }
}

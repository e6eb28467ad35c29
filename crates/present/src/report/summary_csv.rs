//! The machine-readable summary: one CSV row per (case, run, response quantity) — SI
//! value, the reference's, Δ %, and the tolerance check on it if any (one row per check
//! when several apply) — plus one row per run for the whole-history error. Written per
//! case and for the suite, for spreadsheets and dashboards that track drift over commits.

use rockslide_core::case::REFERENCE_LABEL;
use rockslide_core::error::Error;
use rockslide_verify::analysis::quantity_def;
use rockslide_verify::suite::CaseResult;

use super::table::paper_table;

/// Column names of the summary CSV.
pub const SUMMARY_HEADER: &[&str] = &[
    "case",
    "quantity",
    "si_unit",
    "run",
    "dt_s",
    "status",
    "value",
    "reference",
    "delta_percent",
    "against",
    "basis_value",
    "tolerance",
    "gated",
    "verdict",
];

fn num(x: Option<f64>) -> String {
    x.map_or(String::new(), |v| format!("{v:?}"))
}

/// The summary rows of one case (without header).
pub(crate) fn case_rows(r: &CaseResult) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    let table = paper_table(r);
    for (i, run) in r.runs.iter().enumerate() {
        let label = run.label();
        for row in &table.rows {
            let cell = &row.cells[i];
            let unit = quantity_def(row.key).map_or("", |d| d.unit());
            let base = vec![
                r.case.name.clone(),
                row.key.to_string(),
                unit.to_string(),
                label.clone(),
                format!("{:?}", run.dt),
                run.status.label().to_string(),
                num(cell.value),
                num(row.reference),
                num(cell.percent),
            ];
            let checks: Vec<_> = r
                .checks
                .iter()
                .filter(|c| c.run == label && c.quantity == row.key)
                .collect();
            if checks.is_empty() {
                let mut v = base.clone();
                v.extend(std::iter::repeat_n(String::new(), 5));
                rows.push(v);
            }
            for c in checks {
                let mut v = base.clone();
                v.extend([
                    c.basis.clone(),
                    num(c.basis_value),
                    rockslide_verify::verdict::limit_text(r, c),
                    c.gated.to_string(),
                    c.verdict.label().to_string(),
                ]);
                rows.push(v);
            }
        }
        if let Some(Some(e)) = r.history_errors.get(i) {
            rows.push(vec![
                r.case.name.clone(),
                "history_nrms_rel_disp".into(),
                String::new(),
                label.clone(),
                format!("{:?}", run.dt),
                run.status.label().to_string(),
                num(Some(e.rms)),
                String::new(),
                String::new(),
                REFERENCE_LABEL.into(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
            ]);
        }
    }
    rows
}

/// The summary CSV of some cases, as bytes.
pub fn summary_csv(results: &[CaseResult]) -> Result<Vec<u8>, Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let err = |e: csv::Error| Error::Other(format!("summary CSV: {e}"));
    w.write_record(SUMMARY_HEADER).map_err(err)?;
    for r in results {
        for row in case_rows(r) {
            w.write_record(&row).map_err(err)?;
        }
    }
    w.into_inner()
        .map_err(|e| Error::Other(format!("summary CSV: {e}")))
}

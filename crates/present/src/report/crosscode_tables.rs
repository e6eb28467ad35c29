//! The cross-code comparison as tables: every participant against every other one on the
//! peak and on the history of the relative displacement (up to the first full lift-off as
//! well, for a scene that lifts off), every pair on every quantity, and each run's
//! whole-history error against the reference. The numbers come from `crosscode`.

use super::crosscode::{
    CrossCode, HISTORY_KEY, LIFTOFF_KEY, cross_code, normalised_rms, participants,
};
use crate::doc::format::{pct, ratio};
use crate::doc::{Block, Cell, Table, Tone};
use rockslide_verify::analysis::quantity_def;
use rockslide_verify::suite::CaseResult;

fn matrix(x: &CrossCode, values: &[Vec<Option<f64>>], f: impl Fn(Option<f64>) -> String) -> Table {
    let mut header = vec!["row vs column".to_string()];
    header.extend(x.labels.iter().cloned());
    let n = x.labels.len();
    Table {
        header,
        numeric: std::iter::once(false)
            .chain(std::iter::repeat_n(true, n))
            .collect(),
        rows: (0..n)
            .map(|i| {
                std::iter::once(Cell::plain(x.labels[i].clone()))
                    .chain((0..n).map(|j| {
                        if i == j {
                            Cell::toned("·", Tone::Muted)
                        } else {
                            Cell::plain(f(values[i][j]))
                        }
                    }))
                    .collect()
            })
            .collect(),
    }
}

/// Normalised RMS difference of the relative displacement of every participant against
/// every other one, up to the earlier first full lift-off of the two (`None` where neither
/// lifts off). Same definition as the whole-history matrix, on a shorter window.
fn liftoff_matrix(r: &CaseResult) -> (Vec<Vec<Option<f64>>>, Vec<Option<f64>>) {
    let ps = participants(r);
    let lift: Vec<Option<f64>> = ps
        .iter()
        .map(|p| p.responses.get(LIFTOFF_KEY).copied())
        .collect();
    let n = ps.len();
    let mut m = vec![vec![None; n]; n];
    for i in 0..n {
        for j in 0..n {
            if i == j {
                continue;
            }
            let until = match (lift[i], lift[j]) {
                (Some(a), Some(b)) => a.min(b),
                (Some(a), None) | (None, Some(a)) => a,
                (None, None) => continue,
            };
            m[i][j] = normalised_rms(ps[i].trace, ps[j].trace, HISTORY_KEY, until);
        }
    }
    (m, lift)
}

/// The cross-code section: the history matrices (up to the first full lift-off when the
/// scene lifts off, then the whole run), the peak matrix and every pair's differences.
pub(super) fn cross_code_blocks(r: &CaseResult) -> Vec<Block> {
    let x = cross_code(r);
    let mut b = Vec::new();
    if r.reference.is_err() {
        b.push(Block::Para(
            "No exact reference exists for this scene. The engines are therefore verified against each other (the matrices below, as the paper compares ANSYS with SAP2000) and against their own converged solutions (Δt → 0: the work-precision section below, from `rockslide sweep`).".into(),
        ));
    }
    if x.labels.len() < 2 {
        b.push(Block::Para(
            "Fewer than two participants completed: nothing to compare.".into(),
        ));
        return b;
    }
    b.push(Block::Para(format!(
        "Every participant (the reference, when there is one, and every run that completed) against every other one. Peaks: 100·(row/column − 1) of the peak relative displacement. History: RMS of the difference of the relative displacement, normalised by the column's peak over the same window; evaluated at the coarser trace's output times, the finer trace linearly interpolated there.{}",
        if x.lifts_off {
            " This scene lifts off: the airborne phase and the landing amplify small differences, so the history is compared first up to the first full lift-off (the part the engines must agree on), then over the whole run."
        } else {
            ""
        }
    )));
    if x.lifts_off {
        b.extend(liftoff_blocks(r, &x));
    }
    b.push(Block::Heading(
        3,
        format!("Whole history: normalised RMS difference of {HISTORY_KEY}"),
    ));
    b.push(Block::Table(matrix(&x, &x.nrms, ratio)));
    b.push(Block::Heading(
        3,
        "Peak relative displacement (abs), Δ %".into(),
    ));
    b.push(Block::Table(matrix(&x, &x.peak, pct)));
    b.push(Block::Heading(3, "Every pair, every quantity".into()));
    b.push(Block::Para(
        "One column per pair “compared vs basis”: Δ % = 100·(compared/basis − 1) for values, compared − basis in ms for event times.".into(),
    ));
    b.push(Block::Table(pairs_table(&x)));
    b
}

/// The cross-code history up to the first full lift-off: its heading, the window (each
/// participant's first full lift-off) and the matrix.
fn liftoff_blocks(r: &CaseResult, x: &CrossCode) -> Vec<Block> {
    let mut blocks = Vec::new();
    let (m, lift) = liftoff_matrix(r);
    blocks.push(Block::Heading(
        3,
        "Up to the first full lift-off: normalised RMS difference of the relative displacement"
            .into(),
    ));
    blocks.push(Block::Para(format!(
        "Window: from the start to the earlier first full lift-off of the two participants. First full lift-off: {}.",
        x.labels
            .iter()
            .zip(&lift)
            .map(|(l, t)| format!(
                "{l} {}",
                t.map_or("none".to_string(), |t| format!("{t:.4} s"))
            ))
            .collect::<Vec<_>>()
            .join(", ")
    )));
    blocks.push(Block::Table(matrix(x, &m, ratio)));
    blocks
}

/// Every pair, every quantity: one row per quantity some pair compares (Δ % for values,
/// Δ ms for event times), then the history nRMS rows; one column per pair.
fn pairs_table(x: &CrossCode) -> Table {
    // Quantities as rows and pairs as columns: the table stays as wide as the number of
    // pairs, however many quantities a scene has.
    let mut header = vec!["Quantity".to_string()];
    for p in &x.pairs {
        header.push(format!("{} vs {}", x.labels[p.b], x.labels[p.a]));
    }
    let numeric: Vec<bool> = std::iter::once(false)
        .chain(std::iter::repeat_n(true, x.pairs.len()))
        .collect();
    let mut rows = Vec::new();
    for (k, key) in x.keys.iter().enumerate() {
        // A quantity no pair could compare (e.g. a minimum that is zero everywhere) is
        // left out rather than shown as a row of dashes.
        if x.pairs.iter().all(|p| p.entries[k].is_none()) {
            continue;
        }
        let d = quantity_def(key).expect("catalogue key");
        let label = if d.is_time() {
            format!("{} Δt [ms]", d.label)
        } else {
            format!("{} Δ %", d.label)
        };
        let mut row: Vec<Cell> = vec![label.into()];
        for p in &x.pairs {
            row.push(Cell::plain(
                p.entries[k].map_or("—".into(), |v| format!("{v:+.2}")),
            ));
        }
        rows.push(row);
    }
    if x.lifts_off {
        let mut row: Vec<Cell> = vec![Cell::plain("nRMS to first lift-off")];
        row.extend(
            x.pairs
                .iter()
                .map(|p| Cell::plain(ratio(p.nrms_to_liftoff))),
        );
        rows.push(row);
    }
    let mut row: Vec<Cell> = vec![Cell::plain("History nRMS (whole run)")];
    row.extend(x.pairs.iter().map(|p| Cell::plain(ratio(p.nrms))));
    rows.push(row);
    Table {
        header,
        numeric,
        rows,
    }
}

/// The whole-history error of each run's relative displacement against the reference;
/// `None` without runs.
pub(super) fn history_table(r: &CaseResult) -> Option<Table> {
    if r.runs.is_empty() {
        return None;
    }
    let mut t = Table::with_columns(&[
        ("Run", false),
        ("dt [s]", true),
        ("max |Δ| / peak", true),
        ("RMS Δ / peak", true),
        ("status", false),
        ("wall time [ms]", true),
    ]);
    for (run, e) in r.runs.iter().zip(&r.history_errors) {
        t.rows.push(vec![
            run.label().into(),
            format!("{}", run.dt).into(),
            ratio(e.map(|e| e.max)).into(),
            ratio(e.map(|e| e.rms)).into(),
            run.status.to_string().into(),
            format!("{:.2}", run.wall_seconds * 1e3).into(),
        ]);
    }
    Some(t)
}

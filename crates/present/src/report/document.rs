//! The content of the reports, built once as [`Block`]s: for a case, the paper-style table,
//! the tolerance checks, the cross-code matrix, the whole-history errors, the plots, each
//! run's settings and findings, and provenance; for the suite, the verdict per case, the
//! gate failures, and (in HTML) every case in full.

use super::attachments::Attachments;
use super::crosscode::{
    CrossCode, HISTORY_KEY, LIFTOFF_KEY, PEAK_KEY, cross_code, normalised_rms, participants,
};
use super::plots::figures;
use super::provenance::Provenance;
use super::sections;
use super::table::{Column, paper_table};
use crate::doc::format::{display_unit, pct, ratio, show};
use crate::doc::{Block, Cell, Table, Tone};
use rockslide_core::case::Invariant;
use rockslide_verify::analysis::{Verdict, quantity_def};
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
fn gated_failures(r: &CaseResult) -> usize {
    verdict::failures(std::slice::from_ref(r)).len()
}

/// The paper-style table.
fn response_table(r: &CaseResult) -> (Table, Vec<String>) {
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

fn checks_table(r: &CaseResult) -> Table {
    let mut t = Table {
        header: [
            "Quantity",
            "Run",
            "Against",
            "Value",
            "Basis",
            "Unit",
            "Δ %",
            "Tolerance",
            "Gated",
            "Result",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![
            false, false, false, true, true, false, true, false, false, false,
        ],
        rows: Vec::new(),
    };
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

fn cross_code_blocks(r: &CaseResult) -> Vec<Block> {
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
    let _ = PEAK_KEY;
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

fn history_table(r: &CaseResult) -> Option<Table> {
    if r.runs.is_empty() {
        return None;
    }
    let mut t = Table {
        header: [
            "Run",
            "dt [s]",
            "max |Δ| / peak",
            "RMS Δ / peak",
            "status",
            "wall time [ms]",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![false, true, true, true, false, true],
        rows: Vec::new(),
    };
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

/// The blocks of one case's report.
/// SHA-256 of the inputs a case run reads: the case file's text and, for a recorded
/// motion, its samples as used (after scaling, f64 little-endian) and sample interval.
pub(crate) fn inputs_sha256(c: &rockslide_core::case::Case) -> String {
    use sha2::{Digest, Sha256};
    let mut h = Sha256::new();
    h.update(c.text.as_bytes());
    if let Some(rockslide_core::case::Signal::Record { dt, samples, .. }) =
        c.scene.excitation.signal()
    {
        h.update(dt.to_le_bytes());
        for x in samples.iter() {
            h.update(x.to_le_bytes());
        }
    }
    format!("{:x}", h.finalize())
}

/// The inputs' hash and the case file's, each once: the same hash when the case file is
/// the only input.
fn inputs_text(c: &rockslide_core::case::Case, inputs: &str) -> String {
    if inputs == c.sha256 {
        return format!("sha256 {inputs} (the case file {})", c.path.display());
    }
    format!(
        "sha256 {inputs} (the case file {} with the record's samples as used; the case file alone sha256 {})",
        c.path.display(),
        c.sha256
    )
}

/// The document ID of a case report: `RS-<case>-<12 hex of the inputs' SHA-256>`.
fn document_id(c: &rockslide_core::case::Case) -> String {
    format!("RS-{}-{}", c.name, &inputs_sha256(c)[..12])
}

/// The running header of a printed case report: its document ID and revision.
pub(crate) fn running_header(c: &rockslide_core::case::Case, prov: &Provenance) -> String {
    format!(
        "{} · {}, commit {}",
        document_id(c),
        prov.tool,
        short_commit(&prov.commit)
    )
}

/// The running header of the printed suite summary: what it is and its revision.
pub(crate) fn suite_header(prov: &Provenance) -> String {
    format!(
        "rockslide verification suite · {}, commit {}",
        prov.tool,
        short_commit(&prov.commit)
    )
}

fn short_commit(commit: &str) -> &str {
    commit.get(..12).unwrap_or(commit)
}

/// The document-control block of a case report: document ID `RS-<case>-<12 hex of the
/// inputs' SHA-256>` (the same inputs give the same ID), revision (the build stamp), date,
/// the inputs' hashes, and the prepared / checked / approved fields left to sign.
fn document_control(c: &rockslide_core::case::Case, prov: &Provenance) -> Block {
    let inputs = inputs_sha256(c);
    let blank = "________________  date ________".to_string();
    Block::Facts(vec![
        ("Document ID".into(), document_id(c)),
        (
            "Revision".into(),
            format!("{}, commit {}", prov.tool, prov.commit),
        ),
        ("Date".into(), prov.date.clone()),
        ("Inputs".into(), inputs_text(c, &inputs)),
        ("Prepared by".into(), blank.clone()),
        ("Checked by".into(), blank.clone()),
        ("Approved by".into(), blank),
    ])
}

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
fn notes_blocks(results: &[CaseResult]) -> Vec<Block> {
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
    let mut t = Table {
        header: [
            "Invariant",
            "Run",
            "Worst excess (0: never)",
            "At t (s)",
            "Limit",
            "Verdict",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![false, false, true, true, true, false],
        rows: Vec::new(),
    };
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

/// The blocks of the suite summary (without the cases' own reports).
pub(crate) fn suite_document(
    results: &[CaseResult],
    prov: &Provenance,
    att: &Attachments,
) -> Vec<Block> {
    let all = verdict::failures(results);
    let mut b = vec![Block::Heading(1, "rockslide — verification suite".into())];
    b.push(Block::Verdict {
        passed: all.is_empty(),
        text: format!(
            "{}, {}, {}",
            count(results.len(), "case", "cases"),
            count(
                results
                    .iter()
                    .map(|r| r.checks.iter().filter(|c| c.gated).count())
                    .sum::<usize>(),
                "gated check",
                "gated checks"
            ),
            count(all.len(), "gate failure", "gate failures")
        ),
    });
    if !all.is_empty() {
        b.push(Block::List(all.iter().map(|f| f.to_string()).collect()));
    }
    b.extend(super::input_warnings::suite_blocks(results));
    b.push(Block::Heading(2, "Design quantities".into()));
    b.push(Block::Table(super::design::suite_design_table(results)));
    b.push(Block::List(vec![format!(
        "Each case's basis (its reference, or its first run) and the largest difference of any participant from it on a design quantity; a difference beyond {} % is declared in the case file (its report gives the reason and the evidence) or fails the gate.",
        rockslide_verify::disagreement::DESIGN_PERCENT
    )]));
    b.extend(notes_blocks(results));
    b.push(Block::Heading(2, "Cases".into()));
    let mut t = Table {
        header: [
            "Case",
            "Title",
            "Runs",
            "n/a",
            "Reference",
            "Checks",
            "Failed",
            "Informative fails",
            "Gate",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![false, false, true, false, false, true, true, true, false],
        rows: Vec::new(),
    };
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
    b.push(Block::Table(t));
    b.extend(crate::stability::suite_section(att.stability.as_ref()));
    b.push(Block::Heading(2, "Provenance".into()));
    b.push(Block::Facts(vec![
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
    ]));
    b
}

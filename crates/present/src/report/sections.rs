//! Report sections about each method's consistency, beside the response tables
//! (`response_tables`): the energy audit of every run and of the reference (input work =
//! kinetic + strain + friction + damping, computed by `analysis::energy` from the trace).
//! The work-precision and stability sections are rendered from the typed results of
//! `sweep` and `stability` (`crate::sweep`, `crate::stability`).

use crate::doc::format::sig;
use crate::doc::{Block, Cell, Table};
use rockslide_engine_api::Arrangement;
use rockslide_verify::analysis::energy::{EnergySummary, audit};
use rockslide_verify::suite::CaseResult;

/// J → kJ, 4 significant digits.
fn kj(x: f64) -> String {
    sig(x / 1e3)
}

/// The energy audit of the reference and of every run.
pub(crate) fn energy_blocks(r: &CaseResult) -> Vec<Block> {
    let mut b = vec![Block::Heading(2, "Energy audit".into())];
    let mut audits: Vec<(String, Result<EnergySummary, String>)> = Vec::new();
    if let Ok(x) = &r.reference {
        audits.push((
            format!("reference ({})", x.solution.name()),
            audit(&x.trace, &r.case.scene, Arrangement::Single).map(|h| h.summary()),
        ));
    }
    for run in &r.runs {
        audits.push((
            run.label(),
            audit(&run.trace, &r.case.scene, run.arrangement).map(|h| h.summary()),
        ));
    }
    if audits.is_empty() {
        b.push(Block::Para("No run to audit.".into()));
        return b;
    }
    // One reason for all: say it once.
    if let Some(Err(first)) = audits.first().map(|a| &a.1)
        && audits
            .iter()
            .all(|(_, a)| a.as_ref().err().is_some_and(|w| w == first))
    {
        b.push(Block::Para(format!("Not audited: {first}.")));
        return b;
    }
    b.push(Block::Para(
        "Each trace is audited by the same independent arithmetic (`analysis::energy`), whatever engine wrote it: input work W = ∫F dx (plus the work of ground-velocity jumps) against kinetic ½Mv², strain ½R²/K, friction ∫R dxp and damping ∫C·v dx, all at the end of the run, in kJ. Balance error = E0 + W − (kinetic + strain + friction + damping): positive is energy the method lost, negative energy it created. Relative error = largest |balance error| over the run / largest energy. The reference's own audit is the floor set by the trapezoidal rule on its sampled trace.".into(),
    ));
    let mut t = Table::with_columns(&[
        ("Run", false),
        ("input E0 + W [kJ]", true),
        ("kinetic [kJ]", true),
        ("strain [kJ]", true),
        ("friction [kJ]", true),
        ("damping [kJ]", true),
        ("balance error at end [kJ]", true),
        ("relative error", true),
    ]);
    let mut skipped = Vec::new();
    for (label, a) in &audits {
        match a {
            Ok(e) => t.rows.push(vec![
                label.clone().into(),
                kj(e.supplied).into(),
                kj(e.kinetic).into(),
                kj(e.strain).into(),
                kj(e.friction).into(),
                kj(e.damping).into(),
                kj(e.end_error).into(),
                Cell::plain(format!("{:.2e}", e.relative_error)),
            ]),
            Err(why) => skipped.push(format!("{label}: not audited — {why}")),
        }
    }
    b.push(Block::Table(t));
    if !skipped.is_empty() {
        b.push(Block::List(skipped));
    }
    b
}

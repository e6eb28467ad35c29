//! The case files' plausibility warnings — valid values that are more likely a slip than
//! an intent, each with the likely mistake named (`PGA 3.92 g: was this in m/s²?`) — at
//! the top of a case's report and of the summary, right under the gate's verdict: the
//! console says them once when the case is loaded, the report keeps them with the numbers
//! they may have spoilt.

use crate::doc::Block;
use rockslide_core::case::plausibility::{Warning, warnings};
use rockslide_verify::suite::CaseResult;

const HEADING: &str = "Input warnings";

const LEAD: &str = "Values the case file accepts that look like mistakes (the runs went ahead with them as written): check each before reading the numbers.";

fn line(w: &Warning) -> String {
    format!("{}: {}", w.field, w.message)
}

/// The case's warnings under their heading; nothing when it has none.
pub(crate) fn case_blocks(r: &CaseResult) -> Vec<Block> {
    let found = warnings(&r.case);
    if found.is_empty() {
        return Vec::new();
    }
    vec![
        Block::Heading(2, HEADING.into()),
        Block::Para(LEAD.into()),
        Block::List(found.iter().map(line).collect()),
    ]
}

/// Every case's warnings, each once, named by its case; nothing when no case has one.
pub(crate) fn suite_blocks(results: &[CaseResult]) -> Vec<Block> {
    let lines: Vec<String> = results
        .iter()
        .flat_map(|r| {
            warnings(&r.case)
                .into_iter()
                .map(move |w| format!("{}: {}", r.case.name, line(&w)))
        })
        .collect();
    if lines.is_empty() {
        return Vec::new();
    }
    vec![
        Block::Heading(2, HEADING.into()),
        Block::Para(LEAD.into()),
        Block::List(lines),
    ]
}

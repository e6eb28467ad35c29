//! Markdown rendering of the report documents: GitHub-flavoured tables, figures as links
//! to the SVG files written beside the report, the case file in a collapsible block.
//! The content itself is built in `document.rs`.

use std::fmt::Write;

use super::attachments::Attachments;
use super::doc::{Block, Cell, Table, Tone};
use super::document::{case_document, suite_document};
use super::format::md_cell;
use super::provenance::Provenance;
use rockslide_verify::suite::CaseResult;

fn cell(c: &Cell) -> String {
    let mut t = md_cell(&c.text);
    if let Some(case) = &c.case_link {
        t = format!("[{t}]({case}/report.md)");
    }
    match c.tone {
        Tone::Fail | Tone::Strong => format!("**{t}**"),
        _ => t,
    }
}

fn table(s: &mut String, t: &Table) {
    debug_assert!(
        t.rows.iter().all(|r| r.len() == t.header.len()) && t.numeric.len() == t.header.len(),
        "table rows must match the header: {:?}",
        t.header
    );
    let _ = writeln!(
        s,
        "| {} |",
        t.header
            .iter()
            .map(|h| md_cell(h))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    let rule: Vec<&str> = t
        .numeric
        .iter()
        .map(|&n| if n { "---:" } else { "---" })
        .collect();
    let _ = writeln!(s, "|{}|", rule.join("|"));
    for row in &t.rows {
        let cells: Vec<String> = row.iter().map(cell).collect();
        let _ = writeln!(s, "| {} |", cells.join(" | "));
    }
    s.push('\n');
}

/// Render blocks as Markdown; figure links are prefixed with `figure_dir` (e.g. `case/`).
pub(crate) fn render(blocks: &[Block], figure_dir: &str) -> String {
    let mut s = String::new();
    for b in blocks {
        match b {
            Block::Heading(l, t) => {
                let _ = writeln!(s, "{} {t}\n", "#".repeat(*l as usize));
            }
            Block::Para(t) => {
                let _ = writeln!(s, "{t}\n");
            }
            Block::Verdict { passed, text } => {
                let v = if *passed { "PASS" } else { "FAIL" };
                let _ = writeln!(s, "**Gate: {v}** — {text}\n");
            }
            Block::Facts(f) => {
                for (k, v) in f {
                    let _ = writeln!(s, "- **{k}:** {v}");
                }
                s.push('\n');
            }
            Block::List(items) => {
                for i in items {
                    let _ = writeln!(s, "- {i}");
                }
                s.push('\n');
            }
            Block::Table(t) => table(&mut s, t),
            Block::Figure { file, caption, .. } => {
                let _ = writeln!(s, "![{file}]({figure_dir}{file})\n\n*{caption}*\n");
            }
            Block::Details { summary, text } => {
                let _ = writeln!(
                    s,
                    "<details><summary>{summary}</summary>\n\n```toml\n{}\n```\n\n</details>\n",
                    text.trim_end()
                );
            }
        }
    }
    s
}

/// The Markdown report of one case.
pub fn case_markdown(r: &CaseResult) -> String {
    render(
        &case_document(r, Provenance::current(), &Attachments::default()),
        "",
    )
}

/// The suite summary: the verdict per case, every gate failure, provenance.
pub fn suite_markdown(results: &[CaseResult]) -> String {
    render(
        &suite_document(results, Provenance::current(), &Attachments::default()),
        "",
    )
}

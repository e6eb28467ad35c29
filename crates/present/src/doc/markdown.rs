//! Markdown rendering of the document model: GitHub-flavoured tables, figures as links
//! to the SVG files written beside the page, the case file in a collapsible block.
//! The content itself is built by each page's document (`report/document.rs` and
//! `report/suite_document.rs`, the sweep, stability and study documents).

use std::fmt::Write;

use super::format::md_cell;
use super::model::{Block, Cell, Table, Tone};

/// Where a rendered page's links to other outputs point.
#[derive(Debug, Clone, PartialEq)]
pub enum Links {
    /// Relative to the page, which sits in the output folder (`<case>/report.md`).
    Relative,
    /// Absolute: the output folder's URL, e.g. from `ROCKSLIDE_REPORTS_URL`
    /// (`https://…/reports/<case>/report.html`).
    Absolute(String),
    /// No link (a page read where relative links cannot resolve, e.g. a GitHub step
    /// summary): the file's path from the repository root, as found in an uploaded
    /// artifact of the output folder (`reports/<case>/report.html`), in code font.
    Paths(String),
}

impl Links {
    /// `text` linked to `file` (a path inside the output folder).
    fn to(&self, text: &str, file: &str) -> String {
        match self {
            Links::Relative => format!("[{text}]({file})"),
            Links::Absolute(base) => format!("[{text}]({}/{file})", base.trim_end_matches('/')),
            Links::Paths(root) if root.is_empty() => format!("{text} (`{file}`)"),
            Links::Paths(root) => {
                format!("{text} (`{}/{file}`)", root.trim_end_matches('/'))
            }
        }
    }
    /// A figure: an image where a link resolves, else its path.
    fn figure(&self, file: &str) -> String {
        match self {
            Links::Paths(_) => self.to("figure", file),
            _ => format!("!{}", self.to(file, file)),
        }
    }
    /// The page of a case: Markdown beside the files, HTML on the web.
    fn case_page(&self, case: &str) -> String {
        match self {
            Links::Relative => format!("{case}/report.md"),
            _ => format!("{case}/report.html"),
        }
    }
}

fn cell(c: &Cell, links: &Links) -> String {
    let mut t = md_cell(&c.text);
    if let Some(case) = &c.case_link {
        t = links.to(&t, &links.case_page(case));
    }
    match c.tone {
        Tone::Fail | Tone::Strong => format!("**{t}**"),
        _ => t,
    }
}

fn table(s: &mut String, t: &Table, links: &Links) {
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
        let cells: Vec<String> = row.iter().map(|c| cell(c, links)).collect();
        let _ = writeln!(s, "| {} |", cells.join(" | "));
    }
    s.push('\n');
}

/// Render blocks as Markdown; figure links are prefixed with `figure_dir` (e.g. `case/`).
pub(crate) fn render(blocks: &[Block], figure_dir: &str) -> String {
    render_with(blocks, figure_dir, &Links::Relative)
}

/// Render blocks as Markdown with links to other outputs made as `links` says.
pub(crate) fn render_with(blocks: &[Block], figure_dir: &str, links: &Links) -> String {
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
            Block::Table(t) => table(&mut s, t, links),
            Block::Figure { file, caption, .. } => {
                let image = links.figure(&format!("{figure_dir}{file}"));
                let _ = writeln!(s, "{image}\n\n*{caption}*\n");
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

//! Self-contained HTML rendering of the document model: one file, inline CSS, the SVG
//! plots embedded inline — no scripts, fonts, images or style sheets fetched from anywhere,
//! so the page can be archived with a verification record and opened offline. Case names
//! in the suite table link to the case's section of the same page.

use std::fmt::Write;

use super::format::esc;
use super::model::{Block, Cell, Table, Tone};

const STYLE: &str = r#"
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 2rem auto; max-width: 1400px; padding: 0 1rem; color: #1b1b1b; line-height: 1.45; }
h1 { border-bottom: 2px solid #333; padding-bottom: .3rem; }
h2 { border-bottom: 1px solid #ccc; padding-bottom: .2rem; margin-top: 2rem; }
table { border-collapse: collapse; margin: .6rem 0 1rem; font-size: .88rem; display: block; max-width: 100%; overflow-x: auto; }
th, td { border: 1px solid #c8c8c8; padding: .25rem .5rem; vertical-align: top; }
th { background: #f0f0f0; text-align: left; }
td:first-child { white-space: nowrap; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.pass { background: #e3f4e1; color: #14531a; }
td.fail { background: #fbe0e0; color: #8a1010; font-weight: 600; }
td.warn { background: #fff4d6; color: #7a5200; }
td.muted { color: #888; font-style: italic; }
.verdict { display: inline-block; padding: .35rem .8rem; border-radius: 4px; font-weight: 600; }
.verdict.pass { background: #e3f4e1; color: #14531a; border: 1px solid #14531a; }
.verdict.fail { background: #fbe0e0; color: #8a1010; border: 1px solid #8a1010; }
figure { margin: 1rem 0 1.5rem; }
figure svg, figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: .88rem; color: #444; }
pre { background: #f6f6f6; padding: .6rem; overflow-x: auto; font-size: .82rem; }
section.case { border-top: 3px double #999; margin-top: 2.5rem; }
ul.facts li { margin: .1rem 0; }
@page { size: A4 landscape; margin: 14mm 10mm 12mm; }
@page { @bottom-right { content: "page " counter(page) " of " counter(pages); font: 8pt system-ui, sans-serif; color: #444; } }
.print-only { display: none; }
@media print {
  /* The case file in full (a closed <details> prints as its summary line alone). */
  details { display: none; }
  .print-only { display: block; }
  /* Every column on the page: tables shrink and wrap instead of scrolling. */
  body { margin: 0; max-width: none; padding: 0; font-size: 8.5pt; line-height: 1.25; }
  h1 { font-size: 14pt; margin: 0 0 .3rem; } h2 { font-size: 11pt; margin: .8rem 0 .3rem; } h3 { font-size: 9.5pt; margin: .5rem 0 .2rem; }
  table { display: table; overflow: visible; width: 100%; font-size: 7pt; table-layout: auto; }
  /* Words break only where one alone is wider than its column; a number never breaks
     inside itself (it may wrap at a space, before its unit or mark). */
  th, td { padding: .1rem .25rem; overflow-wrap: break-word; }
  td:first-child { white-space: normal; }
  td.num { white-space: normal; overflow-wrap: normal; word-break: keep-all; }
  tr, figure, .verdict, ul.facts { break-inside: avoid; page-break-inside: avoid; }
  h1, h2, h3, h4 { break-after: avoid; page-break-after: avoid; }
  /* Figures two to a row, two rows to a page: each at most half the width and a little
     under half the printable height. */
  figure { display: inline-block; vertical-align: top; width: 49%; margin: .2rem 0 .4rem; }
  figure svg, figure img { max-width: 100%; max-height: 80mm; width: auto; }
  figcaption { font-size: 7pt; }
  /* Lists of facts (settings, provenance) and the case file in columns. */
  ul.facts { columns: 3; column-gap: 6mm; font-size: 7pt; }
  ul.facts li { break-inside: avoid; }
  .print-only pre { columns: 2; column-gap: 6mm; font-size: 6pt; line-height: 1.15; }
  pre { white-space: pre-wrap; overflow: visible; font-size: 7pt; }
  details > summary { list-style: none; }
  td.pass, td.fail, td.warn, .verdict { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
}
"#;

/// A page-unique, URL-safe id for a case section.
fn anchor(case: &str) -> String {
    let id: String = case
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect();
    format!("case-{id}")
}

fn cell(s: &mut String, c: &Cell, numeric: bool) {
    let mut classes = Vec::new();
    if numeric {
        classes.push("num");
    }
    classes.push(match c.tone {
        Tone::Plain => "",
        Tone::Pass => "pass",
        Tone::Fail => "fail",
        Tone::Warn => "warn",
        Tone::Muted => "muted",
        Tone::Strong => "",
    });
    classes.retain(|c| !c.is_empty());
    let _ = write!(s, "<td");
    if !classes.is_empty() {
        let _ = write!(s, " class=\"{}\"", classes.join(" "));
    }
    if let Some(h) = &c.hint {
        let _ = write!(s, " title=\"{}\"", esc(h));
    }
    s.push('>');
    let text = match c.tone {
        Tone::Strong => format!("<b>{}</b>", esc(&c.text)),
        _ => esc(&c.text),
    };
    match &c.case_link {
        Some(case) => {
            let _ = write!(s, "<a href=\"#{}\">{text}</a>", anchor(case));
        }
        None => s.push_str(&text),
    }
    s.push_str("</td>");
}

fn table(s: &mut String, t: &Table) {
    debug_assert!(
        t.rows.iter().all(|r| r.len() == t.header.len()) && t.numeric.len() == t.header.len(),
        "table rows must match the header: {:?}",
        t.header
    );
    s.push_str("<table>\n<thead><tr>");
    for h in &t.header {
        let _ = write!(s, "<th>{}</th>", esc(h));
    }
    s.push_str("</tr></thead>\n<tbody>\n");
    for row in &t.rows {
        s.push_str("<tr>");
        for (i, c) in row.iter().enumerate() {
            cell(s, c, t.numeric.get(i).copied().unwrap_or(false));
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</tbody>\n</table>\n");
}

/// Inline form of an SVG document: the XML prolog dropped and the namespace declaration
/// removed (HTML parses inline `<svg>` into the SVG namespace by itself), so the page holds
/// no URL at all.
pub(crate) fn inline_svg(svg: &str) -> String {
    let body = match svg.find("<svg") {
        Some(i) => &svg[i..],
        None => svg,
    };
    body.replacen(" xmlns=\"http://www.w3.org/2000/svg\"", "", 1)
}

/// How a page shows its figures.
pub(crate) enum Figures {
    /// The SVG inline: the page is self-contained.
    Inline,
    /// An `<img>` of the figure's file, its name after this prefix (`""` beside the
    /// page, `"<case>/"` from the summary page).
    Linked(String),
}

/// Render blocks as HTML body content, figures inline.
pub(crate) fn render(blocks: &[Block]) -> String {
    render_with(blocks, &Figures::Inline)
}

/// Render blocks as HTML body content, figures shown as `figures` says.
pub(crate) fn render_with(blocks: &[Block], figures: &Figures) -> String {
    let mut s = String::new();
    for b in blocks {
        match b {
            Block::Heading(l, t) => {
                let _ = writeln!(s, "<h{l}>{}</h{l}>", esc(t));
            }
            Block::Para(t) => {
                let _ = writeln!(s, "<p>{}</p>", esc(t));
            }
            Block::Verdict { passed, text } => {
                let (c, v) = if *passed {
                    ("pass", "PASS")
                } else {
                    ("fail", "FAIL")
                };
                let _ = writeln!(
                    s,
                    "<p><span class=\"verdict {c}\">Gate: {v}</span> {}</p>",
                    esc(text)
                );
            }
            Block::Facts(f) => {
                s.push_str("<ul class=\"facts\">\n");
                for (k, v) in f {
                    let _ = writeln!(s, "<li><b>{}:</b> {}</li>", esc(k), esc(v));
                }
                s.push_str("</ul>\n");
            }
            Block::List(items) => {
                s.push_str("<ul>\n");
                for i in items {
                    let _ = writeln!(s, "<li>{}</li>", esc(i));
                }
                s.push_str("</ul>\n");
            }
            Block::Table(t) => table(&mut s, t),
            Block::Figure { caption, svg, file } => {
                let figure = match figures {
                    Figures::Inline => inline_svg(svg),
                    Figures::Linked(prefix) => format!(
                        "<img src=\"{}\" alt=\"{}\" loading=\"lazy\">",
                        esc(&format!("{prefix}{file}")),
                        esc(caption)
                    ),
                };
                let _ = writeln!(
                    s,
                    "<figure>\n{figure}\n<figcaption>{}</figcaption>\n</figure>",
                    esc(caption)
                );
            }
            Block::Details { summary, text } => {
                let _ = writeln!(
                    s,
                    "<details><summary>{}</summary><pre>{}</pre></details>\n<div class=\"print-only\"><p>{0}</p><pre>{1}</pre></div>",
                    esc(summary),
                    esc(text)
                );
            }
        }
    }
    s
}

/// A whole page around body content; printed, the title is its running header.
pub(crate) fn page(title: &str, body: &str) -> String {
    page_with_header(title, title, body)
}

/// A whole page around body content with `header` on every printed page (a CSS
/// paged-media margin box; "page X of Y" at the foot is the stylesheet's).
pub(crate) fn page_with_header(title: &str, header: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n<style>{STYLE}@page {{ @top-left {{ content: \"{}\"; font: 8pt system-ui, sans-serif; color: #444; }} }}\n</style>\n</head>\n<body>\n{body}</body>\n</html>\n",
        esc(title),
        css_string(header)
    )
}

/// Text as the inside of a CSS string: quotes and backslashes escaped, markup characters
/// as CSS escapes (the style element ends at `</`).
fn css_string(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '"' | '\\' | '<' | '>' | '&' | '\n' => {
                let _ = write!(out, "\\{:x} ", c as u32);
            }
            c => out.push(c),
        }
    }
    out
}

/// A case's rendered body as a section of the suite page (its anchor is the summary
/// table's link target).
pub(crate) fn case_section(case: &str, body: &str) -> String {
    format!(
        "<section class=\"case\" id=\"{}\">\n{body}</section>\n",
        anchor(case)
    )
}

/// The suite page: the summary, then every case's section; `header` on every printed page.
pub(crate) fn suite_page(blocks: &[Block], sections: &[String], header: &str) -> String {
    let mut body = render(blocks);
    for section in sections {
        body.push_str(section);
    }
    page_with_header("rockslide — verification suite", header, &body)
}

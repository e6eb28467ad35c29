//! The case and suite reports rendered whole, in Markdown and as self-contained HTML:
//! the report documents ([`super::document`], [`super::suite_document`]) through the
//! document model's renderers.

use std::path::Path;

use super::attachments::Attachments;
use super::control::{running_header, suite_header};
use super::document::case_document;
use super::provenance::Provenance;
use super::suite_document::suite_document;
use crate::doc::markdown::{Links, render, render_with};
use crate::doc::{Block, html};
use rockslide_verify::suite::CaseResult;

/// The Markdown report of one case.
pub fn case_markdown(r: &CaseResult) -> String {
    render(
        &case_document(r, Provenance::current(), &Attachments::default()),
        "",
    )
}

/// The suite summary: the verdict per case, every gate failure, provenance.
pub fn suite_markdown(results: &[CaseResult]) -> String {
    suite_markdown_with(results, &Links::Relative)
}

/// The suite summary with its links to the case pages and figures made as `links` says
/// (the GitHub step summary, read away from the output folder).
pub fn suite_markdown_with(results: &[CaseResult], links: &Links) -> String {
    render_with(
        &suite_document(results, Provenance::current(), &Attachments::default()),
        "",
        links,
    )
}

/// The self-contained HTML report of one case.
pub fn case_html(r: &CaseResult) -> String {
    let blocks = case_document(r, Provenance::current(), &Attachments::default());
    html::page_with_header(
        &format!("rockslide — {}", r.case.name),
        &running_header(&r.case, Provenance::current()),
        &html::render(&blocks),
    )
}

/// The self-contained HTML report of the suite: the summary, then every case in full.
pub fn suite_html(results: &[CaseResult]) -> String {
    suite_html_in(results, None)
}

/// The suite page, with the sweeps and the stability study found under `out` (when given).
pub(crate) fn suite_html_in(results: &[CaseResult], out: Option<&Path>) -> String {
    let att = out.map_or_else(Attachments::default, Attachments::for_suite);
    let blocks = suite_document(results, Provenance::current(), &att);
    let sections: Vec<String> = results.iter().map(|r| case_section_in(r, out)).collect();
    html::suite_page(&blocks, &sections, &suite_header(Provenance::current()))
}

/// A case's section of the suite page, figures inline, with its sweep found under `out`
/// (when given).
pub(crate) fn case_section_in(r: &CaseResult, out: Option<&Path>) -> String {
    let att = out.map_or_else(Attachments::default, |o| {
        Attachments::for_case(&o.join(&r.case.name))
    });
    let blocks: Vec<Block> = case_document(r, Provenance::current(), &att)
        .into_iter()
        .map(|b| b.demoted(1))
        .collect();
    html::case_section(&r.case.name, &html::render(&blocks))
}

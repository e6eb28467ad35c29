//! Reports: the verification document an engineer signs. For each case and for the whole
//! suite, Markdown and a self-contained HTML page (plots inline as SVG) and a summary CSV;
//! the content — paper-style table, tolerance checks, cross-code matrix, plots, settings,
//! provenance — is built once (`document`, `suite_document`) in the document model
//! (`crate::doc`) and rendered by its Markdown and HTML renderers (`pages`). The same model
//! renders the sweep, stability and study pages (`crate::sweep`, `crate::stability`,
//! `crate::study`). Every file is written atomically under the output folder.
//!
//! Table of contents:
//! - `document`: a case's report content; `suite_document`: the suite summary's;
//!   `control`: document ID, running headers and the control block; `design`: the design
//!   quantities first; `input_warnings`: the case files' likely mistakes, under the
//!   verdict;
//! - `table`: the paper-style table as data; `response_tables`: it and the tolerance
//!   checks as tables, marked with their verdicts; `crosscode`: pairwise discrepancies;
//!   `crosscode_tables`: their matrices and the whole-history errors;
//! - `plots`, `record_plot`, `vertical_plot`, `orbit_plot`: the figures (SVG);
//!   `sections`: the energy audit section; `provenance`: tool, commit, machine, date;
//!   `attachments`: the typed results of `sweep` and `stability` picked up from the output
//!   folder (never recomputed);
//! - `azimuth_section`: a case run at a set of azimuths (maxima, tables, plot);
//! - `pages`: the documents rendered; `summary_csv`: the summary CSV; `mcap_log`: the
//!   MCAP trace of a case run (Foxglove).

mod attachments;
mod azimuth_section;
mod control;
mod crosscode;
mod crosscode_tables;
mod design;
mod document;
mod input_warnings;
mod mcap_log;
mod orbit_plot;
mod pages;
mod plots;
mod provenance;
mod record_plot;
mod response_tables;
mod sections;
mod suite_document;
mod summary_csv;
mod table;
mod vertical_plot;

pub use crate::doc::markdown::Links;
pub use mcap_log::{case_trace_log, git_commit, write_case_mcap};
pub use pages::{case_html, case_markdown, suite_html, suite_markdown, suite_markdown_with};
pub use provenance::Provenance;
pub use summary_csv::{SUMMARY_HEADER, summary_csv};

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;
use rockslide_core::trace::Trace;
use rockslide_formats::{write_contacts_csv, write_csv};
use rockslide_verify::suite::CaseResult;
use rockslide_verify::timings;

use crate::doc::{self, html, markdown};

pub use rockslide_core::response::show_value;

/// Which files a case run writes. [`OutputSet::FULL`] (what `run` and `check` write, and
/// the default command with `--full-traces`) holds every trace as CSV and self-contained
/// pages; [`OutputSet::LEAN`] (the default command) leaves the traces to the MCAP file,
/// which holds every channel of every run (state, per-contact block, 3D view) at the same
/// rows, at most one every [`LEAN_FILE_STEP`], and has the pages link the figures written
/// beside them instead of embedding a second copy. The analysis, the checks, the tables
/// and the figures are the same in both: the file step is the files' alone, the case the
/// analysis reads is never changed for it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputSet {
    /// A CSV trace per engine run, its per-contact block and the reference's CSV trace.
    pub trace_csv: bool,
    /// HTML pages embed every figure (self-contained, offline); else they link
    /// `plot-*.svg` beside them (`<case>/plot-*.svg` from the summary page).
    pub inline_figures: bool,
    /// The trace files keep at most one row per this step, s (the first row, the first
    /// at or after each multiple, the last: [`Trace::output_rows`]); the case's
    /// `[run] output_dt` where coarser. `None`: the case's own step (every row without).
    pub file_step: Option<f64>,
}

/// The lean set's file step: 5 ms, unless the case's `[run] output_dt` is coarser. 200
/// rows a simulated second — the records' own sampling — is 400 points across a 2-s
/// case's Foxglove plot of 1,000-odd pixels and 200 frames a second in its 3D view; the
/// analysis, the checks and the figures use every step whatever the files keep.
pub const LEAN_FILE_STEP: f64 = 0.005;

impl OutputSet {
    /// Every file: CSV traces beside the MCAP file, self-contained pages.
    pub const FULL: OutputSet = OutputSet {
        trace_csv: true,
        inline_figures: true,
        file_step: None,
    };
    /// The MCAP file alone for traces, at most one row every [`LEAN_FILE_STEP`], pages
    /// linking their figures.
    pub const LEAN: OutputSet = OutputSet {
        trace_csv: false,
        inline_figures: false,
        file_step: Some(LEAN_FILE_STEP),
    };

    /// The step of `case`'s trace files: the coarser of its `[run] output_dt` and this
    /// set's file step (`None`: every row).
    pub fn file_step_of(&self, case: &rockslide_core::case::Case) -> Option<f64> {
        match (case.run.output_dt, self.file_step) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        }
    }
}

/// What writing a case left for the suite page.
#[derive(Debug, Clone)]
pub struct WrittenCase {
    /// The case's folder.
    pub dir: PathBuf,
    /// The case's section of the summary page (headings one level down), rendered once
    /// with the case page.
    section: String,
}

/// Write a case's outputs under `out/<case>/`: CSV traces (and each run's per-contact
/// block as `<engine>-<variant>-contacts.csv`, unless it only repeats the run's own
/// columns: [`rockslide_core::trace::ContactBlock::repeats`]), the MCAP log, the typed record
/// `result.json`, `report.md`, `report.html`, `summary.csv` and the plots as
/// `plot-*.svg`; returns the folder. Every file ([`OutputSet::FULL`]).
pub fn write_case_outputs(result: &CaseResult, out: &Path) -> Result<PathBuf, Error> {
    write_case_outputs_with(result, out, OutputSet::FULL).map(|w| w.dir)
}

/// [`write_case_outputs`] with the files of `set`.
pub fn write_case_outputs_with(
    result: &CaseResult,
    out: &Path,
    set: OutputSet,
) -> Result<WrittenCase, Error> {
    let name = &result.case.name;
    let dir = out.join(name);
    // The traces (the largest files) are written beside the pages, on another core.
    let (traces, pages) = rayon::join(
        || timings::time("traces", name, || write_case_traces(result, &dir, set)),
        || timings::time("pages", name, || write_case_pages(result, &dir, set)),
    );
    traces?;
    let section = pages?;
    Ok(WrittenCase { dir, section })
}

/// The traces of a case's files: every row, or the rows at the file step of `set`
/// ([`OutputSet::file_step_of`]); the analysis and figures always use every row.
fn file_traces<'a>(
    result: &'a CaseResult,
    set: OutputSet,
) -> (Vec<Cow<'a, Trace>>, Option<Cow<'a, Trace>>) {
    let step = set.file_step_of(&result.case);
    let at_output = |t| match step {
        Some(step) => Cow::Owned(Trace::at_output_step(t, step)),
        None => Cow::Borrowed(t),
    };
    let runs = result.runs.iter().map(|r| at_output(&r.trace)).collect();
    let reference = result.reference.as_ref().ok().map(|r| at_output(&r.output));
    (runs, reference)
}

/// A CSV trace per engine run (and its contacts) and of the reference, and the case's
/// MCAP file, written in parallel.
fn write_case_traces(result: &CaseResult, dir: &Path, set: OutputSet) -> Result<(), Error> {
    use rayon::prelude::*;
    let (runs, reference) = file_traces(result, set);
    let run_traces: Vec<&Trace> = runs.iter().map(|t| t.as_ref()).collect();
    let mut csv_files: Vec<(&Trace, PathBuf)> = result
        .runs
        .iter()
        .zip(&run_traces)
        .map(|(run, &trace)| {
            let file = dir.join(format!("{}-{}.csv", run.engine, run.variant));
            (trace, file)
        })
        .collect();
    if let (Ok(r), Some(trace)) = (&result.reference, &reference) {
        let file = dir.join(format!("reference-{}.csv", file_safe(r.solution.name())));
        csv_files.push((trace.as_ref(), file));
    }
    if !set.trace_csv {
        csv_files.clear();
    }
    let contact_files: Vec<(&rockslide_core::trace::ContactBlock, PathBuf)> = result
        .runs
        .iter()
        .zip(&run_traces)
        // a block that only repeats the run's columns (the predictor-corrector's one
        // contact) has no file of its own: its MCAP state messages carry it
        .filter(|(_, trace)| {
            set.trace_csv && !trace.contacts.is_empty() && !trace.contacts.repeats(trace)
        })
        .map(|(run, trace)| {
            let file = dir.join(format!("{}-{}-contacts.csv", run.engine, run.variant));
            (&trace.contacts, file)
        })
        .collect();
    let mcap_file = dir.join(format!("{}.mcap", result.case.name));
    let (csvs, mcap) = rayon::join(
        || {
            csv_files
                .par_iter()
                .map(|(trace, file)| write_csv(trace, file))
                .chain(
                    contact_files
                        .par_iter()
                        .map(|(block, file)| write_contacts_csv(block, file)),
                )
                .collect::<Result<Vec<()>, Error>>()
        },
        || {
            let reference = reference.as_ref().map(|t| t.as_ref());
            let step = set.file_step_of(&result.case);
            mcap_log::write_case_mcap_of(result, &run_traces, reference, step, &mcap_file)
        },
    );
    csvs?;
    mcap
}

/// The typed record, figures, `report.md`, `report.html` and `summary.csv` of a case;
/// returns its section of the summary page.
fn write_case_pages(result: &CaseResult, dir: &Path, set: OutputSet) -> Result<String, Error> {
    // The typed record of the result, for commands and tools that read numbers.
    rockslide_verify::record::CaseRecord::of(result).save(dir)?;
    // The sweep of this case, when `rockslide sweep` left one here: picked up, not rerun.
    let att = attachments::Attachments::for_case(dir);
    let blocks = document::case_document(result, Provenance::current(), &att);
    write_figures_and_markdown(&blocks, dir, "report.md")?;
    let figures = |prefix: &str| match set.inline_figures {
        true => html::Figures::Inline,
        false => html::Figures::Linked(prefix.to_string()),
    };
    let page = html::page_with_header(
        &format!("rockslide — {}", result.case.name),
        &control::running_header(&result.case, Provenance::current()),
        &html::render_with(&blocks, &figures("")),
    );
    write_atomically(&dir.join("report.html"), page.as_bytes())?;
    write_atomically(
        &dir.join("summary.csv"),
        &summary_csv(std::slice::from_ref(result))?,
    )?;
    let demoted: Vec<doc::Block> = blocks.into_iter().map(|b| b.demoted(1)).collect();
    let prefix = format!("{}/", result.case.name);
    Ok(html::case_section(
        &result.case.name,
        &html::render_with(&demoted, &figures(&prefix)),
    ))
}

/// A document's figures (`plot-*.svg`) and its Markdown rendering `md_file` in `dir`.
fn write_figures_and_markdown(
    blocks: &[doc::Block],
    dir: &Path,
    md_file: &str,
) -> Result<(), Error> {
    for b in blocks {
        if let doc::Block::Figure { file, svg, .. } = b {
            write_atomically(&dir.join(file), svg.as_bytes())?;
        }
    }
    write_atomically(&dir.join(md_file), markdown::render(blocks, "").as_bytes())
}

/// Write the suite's outputs under `out/`: `summary.md`, `summary.html` (every case in
/// full) and `summary.csv`, with the stability study (`out/stability/stability.json`) and
/// each case's sweep (`out/<case>/sweep.json`) when those commands left them there.
/// Returns the HTML path.
pub fn write_suite_outputs(results: &[CaseResult], out: &Path) -> Result<PathBuf, Error> {
    let sections: Vec<String> = results
        .iter()
        .map(|r| pages::case_section_in(r, Some(out)))
        .collect();
    write_suite_pages(results, &sections, out)
}

/// [`write_suite_outputs`] with the cases' sections already rendered by
/// [`write_case_outputs_with`] (in the order of `results`): no figure drawn twice.
pub fn write_suite_outputs_with(
    results: &[CaseResult],
    written: &[WrittenCase],
    out: &Path,
) -> Result<PathBuf, Error> {
    let sections: Vec<String> = written.iter().map(|w| w.section.clone()).collect();
    write_suite_pages(results, &sections, out)
}

/// The suite's pages around the cases' sections.
fn write_suite_pages(
    results: &[CaseResult],
    sections: &[String],
    out: &Path,
) -> Result<PathBuf, Error> {
    timings::time("summary", "all", || {
        let att = attachments::Attachments::for_suite(out);
        let blocks = suite_document::suite_document(results, Provenance::current(), &att);
        write_figures_and_markdown(&blocks, out, "summary.md")?;
        let html = out.join("summary.html");
        let page = html::suite_page(
            &blocks,
            sections,
            &control::suite_header(Provenance::current()),
        );
        write_atomically(&html, page.as_bytes())?;
        write_atomically(&out.join("summary.csv"), &summary_csv(results)?)?;
        Ok(html)
    })
}

/// A solution's name as a file-name part: letters, digits, `-` and `_` kept, every other
/// run of characters one `-` ("exact EPO (vertical)" → "exact-EPO-vertical").
fn file_safe(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    for c in name.chars() {
        if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
            out.push(c);
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    out.trim_matches('-').to_string()
}

#[cfg(test)]
mod tests;

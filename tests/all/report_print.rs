//! The reports on paper: the RPEPO report and a record case printed to PDF (A4
//! landscape) by headless Chromium, then read back with poppler's `pdfinfo` and
//! `pdftotext`. The RPEPO report fits in 10 pages; every page carries the running header
//! (document ID and revision) and "page X of Y"; every table column's heading is on paper.
//! Without Chromium or poppler the tests are listed as ignored, saying why; under `CI=true`
//! or `ROCKSLIDE_REQUIRE_CHROMIUM` (`.ci/run` installs both) their absence fails them.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{present_or_skip, rockslide};

/// The RPEPO report's page budget.
const RPEPO_MAX_PAGES: usize = 10;

/// The Chromium binary: `ROCKSLIDE_CHROMIUM` when it runs, else the first of Debian's and
/// upstream's names found on the PATH that runs.
fn chromium() -> Option<PathBuf> {
    if let Ok(p) = std::env::var("ROCKSLIDE_CHROMIUM") {
        return runs(&p, "--version").then(|| PathBuf::from(p));
    }
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|name| runs(name, "--version"))
        .map(PathBuf::from)
}

fn runs(program: &str, arg: &str) -> bool {
    Command::new(program)
        .arg(arg)
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Chromium and poppler, or why the test cannot run (a failure under `CI=true` or
/// `ROCKSLIDE_REQUIRE_CHROMIUM`).
fn printer(test: &str) -> Option<PathBuf> {
    let found = chromium().filter(|_| runs("pdfinfo", "-v") && runs("pdftotext", "-v"));
    let why =
        "headless Chromium and poppler-utils not found (apt-get install chromium poppler-utils)";
    present_or_skip(test, found.is_some(), "ROCKSLIDE_REQUIRE_CHROMIUM", why);
    found
}

/// Print `html` to `pdf` (A4 landscape, the page's own margin boxes, no browser header).
fn print(chromium: &Path, html: &Path, pdf: &Path, profile: &Path) {
    let out = Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-pdf-header-footer",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--print-to-pdf={}", pdf.display()))
        .arg(format!("file://{}", html.canonicalize().unwrap().display()))
        .output()
        .unwrap();
    assert!(
        pdf.is_file(),
        "chromium printed nothing: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The text of each page of `pdf`.
fn pages(pdf: &Path) -> Vec<String> {
    let out = Command::new("pdftotext")
        .arg(pdf)
        .arg("-")
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let mut pages: Vec<String> = text.split('\u{c}').map(str::to_string).collect();
    if pages.last().is_some_and(|p| p.trim().is_empty()) {
        pages.pop();
    }
    pages
}

/// Every `<th>` heading of the page, once each.
fn column_headings(html: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for piece in html.split("<th>").skip(1) {
        let heading = piece.split("</th>").next().unwrap_or_default();
        let heading = heading
            .replace("&amp;", "&")
            .replace("&lt;", "<")
            .replace("&gt;", ">");
        if !out.contains(&heading) {
            out.push(heading);
        }
    }
    out
}

/// Run `case` into `out`, print its report; its pages' text.
fn printed_report(chromium: &Path, case: &str, out: &Path) -> (Vec<String>, String) {
    let o = rockslide(&["run", case, "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let name = Path::new(case).file_stem().unwrap().to_str().unwrap();
    let html = out.join(name).join("report.html");
    let pdf = out.join(format!("{name}.pdf"));
    print(chromium, &html, &pdf, &out.join("chromium-profile"));
    (pages(&pdf), std::fs::read_to_string(&html).unwrap())
}

/// Each page has the running header (document ID, revision) and "page i of n"; every
/// table column's heading (each of its words) is printed.
fn assert_paper(case: &str, pages: &[String], html: &str) {
    let n = pages.len();
    for (i, text) in pages.iter().enumerate() {
        assert!(
            text.contains(&format!("RS-{case}-")) && text.contains("commit"),
            "{case}: page {} of {n} lacks the running header:\n{text}",
            i + 1
        );
        assert!(
            text.contains(&format!("page {} of {n}", i + 1)),
            "{case}: page {} lacks \"page {} of {n}\"",
            i + 1,
            i + 1
        );
    }
    let all: String = pages.join(" ");
    let words: Vec<&str> = all.split_whitespace().collect();
    for heading in column_headings(html) {
        for word in heading.split_whitespace() {
            assert!(
                words.contains(&word) || all.contains(word),
                "{case}: the column heading \"{heading}\" is not on paper (\"{word}\" missing)"
            );
        }
    }
}

#[test]
#[cfg_attr(
    not(live_chromium),
    ignore = "Chromium or poppler-utils not found (apt-get install chromium poppler-utils); ROCKSLIDE_REQUIRE_CHROMIUM=1 runs it"
)]
fn the_rpepo_report_prints_in_ten_pages_with_header_and_every_column() {
    let test = "the_rpepo_report_prints_in_ten_pages_with_header_and_every_column";
    let Some(chromium) = printer(test) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let (pages, html) = printed_report(&chromium, "cases/rpepo-mass-accel.toml", dir.path());
    assert!(
        pages.len() <= RPEPO_MAX_PAGES,
        "the RPEPO report prints on {} pages (at most {RPEPO_MAX_PAGES})",
        pages.len()
    );
    assert_paper("rpepo-mass-accel", &pages, &html);
    // the case file is printed in full: its last line is on paper
    let text = std::fs::read_to_string(crate::common::repo("cases/rpepo-mass-accel.toml")).unwrap();
    let last = text.lines().rev().find(|l| !l.trim().is_empty()).unwrap();
    let printed = pages.join(" ");
    assert!(
        last.split_whitespace().all(|w| printed.contains(w)),
        "the case file's last line is not on paper: {last}"
    );
}

#[test]
#[cfg_attr(
    not(live_chromium),
    ignore = "Chromium or poppler-utils not found (apt-get install chromium poppler-utils); ROCKSLIDE_REQUIRE_CHROMIUM=1 runs it"
)]
fn a_record_case_report_prints_with_header_and_every_column() {
    let test = "a_record_case_report_prints_with_header_and_every_column";
    let Some(chromium) = printer(test) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let (pages, html) =
        printed_report(&chromium, "cases/records/block-northridge.toml", dir.path());
    assert_paper("block-northridge", &pages, &html);
}

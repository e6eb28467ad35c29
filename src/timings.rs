//! `--timings`: the stages a command timed ([`rockslide_verify::timings`]) written as
//! `timings.json` (every span) and `timings.md` (a table per stage and per case) in the
//! output folder. Written only when asked: wall times differ from run to run, so they
//! are never part of the default outputs.

use std::fmt::Write as _;
use std::path::Path;

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;
use rockslide_verify::timings::Span;

/// The stages of a case, in the order of the table's columns.
const CASE_STAGES: &[&str] = &["engines", "reference", "analysis", "traces", "pages"];

/// The content of `timings.json`.
#[derive(serde::Serialize)]
struct Report<'a> {
    threads: usize,
    note: &'static str,
    spans: &'a [Span],
}

/// Write `timings.json` and `timings.md` into `folder`.
pub fn write(spans: &[Span], folder: &Path) -> Result<(), Error> {
    let report = Report {
        threads: rayon::current_num_threads(),
        note: "wall and process CPU (user + system) per span, s; spans overlap when stages run in parallel, so a span's CPU counts every thread: it is the span's own only with RAYON_NUM_THREADS=1",
        spans,
    };
    rockslide_verify::json::write(&folder.join("timings.json"), &report)?;
    write_atomically(&folder.join("timings.md"), markdown(spans).as_bytes())
}

/// The spans of `stage` (every subject), summed: (wall, cpu, count).
fn summed<'a>(spans: impl Iterator<Item = &'a Span>) -> (f64, f64, usize) {
    spans.fold((0.0, 0.0, 0), |(w, c, n), s| (w + s.wall, c + s.cpu, n + 1))
}

/// The Markdown report: whole stages, then one row per case.
fn markdown(spans: &[Span]) -> String {
    let mut s = format!(
        "# Stage timings\n\n{} worker threads. Wall and process CPU (user + system), s. \
         Stages run in parallel: the CPU of a span counts every thread while it ran, and is \
         its own only with `RAYON_NUM_THREADS=1`.\n\n",
        rayon::current_num_threads()
    );
    s.push_str("| stage | spans | wall, summed | CPU, summed | first start | last end |\n");
    s.push_str("|---|---:|---:|---:|---:|---:|\n");
    let mut stages: Vec<&str> = Vec::new();
    for span in spans {
        if !stages.contains(&span.stage) {
            stages.push(span.stage);
        }
    }
    for stage in stages {
        let of = || spans.iter().filter(move |s| s.stage == stage);
        let (wall, cpu, n) = summed(of());
        let first = of().map(|s| s.start).fold(f64::INFINITY, f64::min);
        let last = of().map(|s| s.start + s.wall).fold(0.0, f64::max);
        let _ = writeln!(
            s,
            "| {stage} | {n} | {wall:.3} | {cpu:.3} | {first:.3} | {last:.3} |"
        );
    }
    s.push_str("\n## Per case, wall s (CPU s)\n\n| case |");
    for stage in CASE_STAGES {
        let _ = write!(s, " {stage} |");
    }
    s.push_str("\n|---|");
    s.push_str(&"---:|".repeat(CASE_STAGES.len()));
    s.push('\n');
    let mut cases: Vec<&str> = spans
        .iter()
        .filter(|s| CASE_STAGES.contains(&s.stage))
        .map(|s| s.subject.as_str())
        .collect();
    cases.sort_unstable();
    cases.dedup();
    for case in cases {
        let _ = write!(s, "| {case} |");
        for stage in CASE_STAGES {
            let (wall, cpu, n) = summed(
                spans
                    .iter()
                    .filter(|s| s.stage == *stage && s.subject == case),
            );
            match n {
                0 => s.push_str(" — |"),
                _ => {
                    let _ = write!(s, " {wall:.3} ({cpu:.3}) |");
                }
            }
        }
        s.push('\n');
    }
    s
}

//! A suite of cases from the command line to the gate, shared by `run`, `check` and the
//! default command: the cases loaded and planned with their `--external` participants,
//! run and written in parallel, then each case's gate said, the suite's pages written
//! and (for `check`) the JUnit XML and exit code 1 when the gate fails.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use rockslide_core::case::Case;
use rockslide_core::error::{Error, InputError};
use rockslide_core::io::{inside, remove_stale_temporaries_under};
use rockslide_present::gate;
use rockslide_present::report::{
    OutputSet, WrittenCase, write_case_outputs_with, write_suite_outputs_with,
};
use rockslide_verify::registry;
use rockslide_verify::suite::{CaseResult, run_case};

use crate::input::{case_paths, load_all, plan_all};

/// Load, check and plan the cases a run names (all of the default case folders when
/// none), with `--external` participants; the output folder cleared of stale temporaries.
/// An empty list that `check` refuses (`gate`) is returned unplanned, for it to say so.
pub(crate) fn prepare_cases(
    args: &[PathBuf],
    out: &Path,
    external: &[String],
    gate: bool,
) -> Result<Vec<Case>, Error> {
    let mut cases = load_all(&case_paths(args)?)?;
    add_externals(&mut cases, external)?;
    if cases.is_empty() && gate {
        return Ok(cases);
    }
    let engines = registry::all();
    plan_all(&cases, &engines)?;
    remove_stale_temporaries_under(out)?;
    for case in &cases {
        inside(out, &case.name)?;
    }
    Ok(cases)
}

/// `--external LABEL=PATH` participants join the one case given.
fn add_externals(cases: &mut [Case], external: &[String]) -> Result<(), Error> {
    match cases {
        _ if external.is_empty() => Ok(()),
        [case] => Ok(rockslide_verify::external::add_from_command_line(
            case, external,
        )?),
        _ => Err(Error::Input(
            InputError::new(
                Path::new("--external"),
                "",
                format!(
                    "applies to one case, but {} cases were given; name one case file",
                    cases.len()
                ),
            )
            .into(),
        )),
    }
}

/// Run every case and write its outputs, cases in parallel across cores (each case's
/// engines in parallel inside it); results in the cases' order, whatever finished first.
pub(crate) fn run_and_write_all(
    cases: Vec<Case>,
    out: &Path,
    set: OutputSet,
) -> Vec<Result<(CaseResult, WrittenCase), Error>> {
    use rayon::prelude::*;
    cases
        .into_par_iter()
        .map(|case| {
            let mut result = run_case(case)?;
            let written = write_case_outputs_with(&result, out, set)?;
            // the suite's pages and the gate read no history: hold only the cases in flight
            result.release_histories();
            Ok((result, written))
        })
        .collect()
}

/// Say each case's gate, write the suite's pages and (with `junit`) the JUnit XML; exit
/// code 1 when the gate fails.
pub(crate) fn finish(
    outcomes: Vec<Result<(CaseResult, WrittenCase), Error>>,
    out: &Path,
    quiet: bool,
    junit: Option<&Path>,
) -> Result<ExitCode, Error> {
    let mut results: Vec<CaseResult> = Vec::new();
    let mut written: Vec<WrittenCase> = Vec::new();
    for outcome in outcomes {
        let (result, case_written) = outcome?;
        if !quiet {
            let name = &result.case.name;
            let passed = gate::failures(std::slice::from_ref(&result)).is_empty();
            let runs = result.runs.len();
            say!(
                "{name}: {runs} run{}, gate {} → {}",
                if runs == 1 { "" } else { "s" },
                if passed { "PASS" } else { "FAIL" },
                case_written.dir.join("report.html").display()
            );
        }
        results.push(result);
        written.push(case_written);
    }
    let html = write_suite_outputs_with(&results, &written, out)?;
    if !quiet {
        for w in rockslide_verify::verdict::warnings(&results) {
            say!("{w}");
        }
    }
    let failures = gate::failures(&results);
    for f in &failures {
        eprintln!("{f}");
        annotate(f);
    }
    if !quiet {
        for f in rockslide_verify::verdict::informative_notes(&results) {
            say!("{f}");
        }
    }
    let Some(junit) = junit else {
        if !quiet {
            say!("summary: {}", html.display());
        }
        return Ok(ExitCode::SUCCESS);
    };
    gate::write_junit(&results, junit)?;
    gate::write_step_summary(&results, out);
    if !quiet {
        say!(
            "gate: {} — {} failure(s); report {}, JUnit {}",
            if failures.is_empty() { "PASS" } else { "FAIL" },
            failures.len(),
            html.display(),
            junit.display()
        );
    }
    Ok(if failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// A GitHub Actions annotation for a gate failure (`::error file=…,title=…::…`), only when
/// run there (`GITHUB_ACTIONS=true`, as GitHub sets it).
fn annotate(f: &gate::Failure) {
    if std::env::var("GITHUB_ACTIONS").as_deref() != Ok("true") {
        return;
    }
    let file = f.field.split(": ").next().unwrap_or_default();
    let escape = |s: &str| {
        s.replace('%', "%25")
            .replace('\r', "%0D")
            .replace('\n', "%0A")
    };
    say!(
        "::error file={},title=rockslide {}::{}",
        escape(file).replace(',', "%2C").replace(':', "%3A"),
        escape(&f.case),
        escape(&f.to_string())
    );
}

//! The command line: clap definitions and what each command does. Exit codes: 0 success
//! (gate passed), 1 a gated discrepancy is out of tolerance, 2 bad input or an error.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::case::{discover, load_case};
use crate::engine;
use crate::error::{Error, InputErrors};
use crate::io::write_atomically;
use crate::report::{suite_markdown, write_case_outputs};
use crate::suite::{CaseResult, plan, run_case};

/// Cross-code verification of seismic sliding and rocking.
#[derive(Debug, Parser)]
#[command(name = "rockslide", version, about, long_about = None)]
pub struct Cli {
    /// What to do (default: run every case under `cases/` and write `reports/`).
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Print nothing but errors and failures.
    #[arg(long, short, global = true)]
    pub quiet: bool,
}

/// The commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run cases and write their traces and reports.
    Run {
        /// Case files or folders (default: `cases/`).
        cases: Vec<PathBuf>,
        /// Output folder.
        #[arg(long, short, default_value = "reports")]
        out: PathBuf,
    },
    /// List the cases and which engines apply to each.
    List {
        /// Case files or folders (default: `cases/`).
        cases: Vec<PathBuf>,
    },
    /// Run cases and gate on their tolerances: exit 1 if any gated check fails.
    Check {
        /// Case files or folders (default: `cases/`).
        cases: Vec<PathBuf>,
        /// Output folder for reports and traces.
        #[arg(long, short, default_value = "reports")]
        out: PathBuf,
    },
    /// Error against run time: a Δt ladder per engine and variant, with observed order,
    /// table and log-log plot in `<out>/<case>/sweep.{md,csv,svg}`.
    Sweep {
        /// Case files.
        cases: Vec<PathBuf>,
        /// Output folder.
        #[arg(long, short, default_value = "reports")]
        out: PathBuf,
        /// Rungs of the Δt ladder (from T/10 down, at least 3).
        #[arg(long, default_value_t = 8)]
        rungs: usize,
        /// Refinement ratio between rungs.
        #[arg(long, default_value_t = 2.0)]
        ratio: f64,
        /// Timed repeats per rung (median, min and max are reported).
        #[arg(long, default_value_t = 3)]
        repeats: usize,
        /// Worker threads (default: all cores).
        #[arg(long, short)]
        jobs: Option<usize>,
    },
    /// Run the stiff and extreme scenes and classify every run (accurate, inaccurate,
    /// diverged, not converged); map and stability limits in `<out>/stability/`.
    Stability {
        /// Case files or folders (default: `cases/stability/`).
        cases: Vec<PathBuf>,
        /// Output folder.
        #[arg(long, short, default_value = "reports")]
        out: PathBuf,
        /// Worker threads (default: all cores).
        #[arg(long, short)]
        jobs: Option<usize>,
    },
}

/// Run the command line; returns the process exit code.
pub fn main(cli: Cli) -> ExitCode {
    let result = match cli.command {
        None => run(&[], Path::new("reports"), cli.quiet, false),
        Some(Command::Run { cases, out }) => run(&cases, &out, cli.quiet, false),
        Some(Command::Check { cases, out }) => run(&cases, &out, cli.quiet, true),
        Some(Command::List { cases }) => list(&cases),
        Some(Command::Sweep {
            cases,
            out,
            rungs,
            ratio,
            repeats,
            jobs,
        }) => crate::sweep_cmd::sweep::command(
            &cases,
            &out,
            &crate::sweep_cmd::Options {
                rungs,
                ratio,
                repeats,
                jobs,
                quiet: cli.quiet,
            },
        ),
        Some(Command::Stability { cases, out, jobs }) => crate::sweep_cmd::stability::command(
            &cases,
            &out,
            &crate::sweep_cmd::Options {
                jobs,
                quiet: cli.quiet,
                ..Default::default()
            },
        ),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// Expand case arguments: files as given, folders to their `*.toml`, default `cases/`.
fn case_paths(args: &[PathBuf]) -> Result<Vec<PathBuf>, Error> {
    let args = if args.is_empty() {
        vec![PathBuf::from("cases")]
    } else {
        args.to_vec()
    };
    let mut out = Vec::new();
    for a in args {
        if a.is_dir() {
            out.extend(discover(&a).map_err(|e| Error::io(&a, e))?);
        } else {
            out.push(a);
        }
    }
    Ok(out)
}

/// Load every case first, so that all input errors are reported before any work.
fn load_all(paths: &[PathBuf]) -> Result<Vec<crate::case::Case>, Error> {
    let mut cases = Vec::new();
    let mut errors = Vec::new();
    for p in paths {
        match load_case(p) {
            Ok(c) => cases.push(c),
            Err(e) => errors.extend(e.0),
        }
    }
    if errors.is_empty() {
        Ok(cases)
    } else {
        Err(InputErrors(errors).into())
    }
}

fn run(args: &[PathBuf], out: &Path, quiet: bool, gate: bool) -> Result<ExitCode, Error> {
    let cases = load_all(&case_paths(args)?)?;
    let engines = engine::all();
    for c in &cases {
        plan(c, &engines)?;
    }
    let mut results: Vec<CaseResult> = Vec::new();
    for case in cases {
        let name = case.name.clone();
        let result = run_case(case)?;
        let dir = write_case_outputs(&result, out)?;
        if !quiet {
            println!(
                "{name}: {} runs, gate {} → {}",
                result.runs.len(),
                if result.gate_passed() { "PASS" } else { "FAIL" },
                dir.join("report.md").display()
            );
        }
        results.push(result);
    }
    write_atomically(&out.join("summary.md"), suite_markdown(&results).as_bytes())?;
    let failures: Vec<String> = results
        .iter()
        .flat_map(|r| {
            r.checks
                .iter()
                .filter(|c| c.gated && c.verdict != crate::analysis::Verdict::Pass)
                .map(move |c| {
                    format!(
                        "FAIL {}: {} of {} against {}: {} (tolerance {}) [{}]",
                        r.case.name,
                        c.quantity,
                        c.run,
                        c.basis,
                        c.percent.map_or_else(
                            || match (c.value, c.basis_value) {
                                (Some(v), Some(b)) => format!("difference {:.4e}", v - b),
                                _ => "missing".into(),
                            },
                            |p| format!("{p:+.3} %")
                        ),
                        c.limit,
                        c.field
                    )
                })
        })
        .collect();
    for f in &failures {
        eprintln!("{f}");
    }
    if gate && !failures.is_empty() {
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

fn list(args: &[PathBuf]) -> Result<ExitCode, Error> {
    let cases = load_all(&case_paths(args)?)?;
    let engines = engine::all();
    for c in &cases {
        println!("{} — {}", c.name, c.title);
        println!(
            "    {} under {}, {} s",
            c.scene.model.kind(),
            c.scene.excitation.kind(),
            c.run.duration
        );
        for e in &engines {
            let listed = c.engines.is_empty() || c.engine(e.id()).is_some();
            match e.variants(&c.scene) {
                Err(na) => println!("    {:<20} n/a — {}", e.id(), na.0),
                Ok(_) if !listed => println!("    {:<20} not requested by the case", e.id()),
                Ok(v) => {
                    let wanted = c
                        .engine(e.id())
                        .and_then(|r| r.variants.clone())
                        .unwrap_or_else(|| v.iter().map(|s| s.to_string()).collect());
                    println!(
                        "    {:<20} {} (dt {} s)",
                        e.id(),
                        wanted.join(", "),
                        c.dt_for(e.id())
                    );
                }
            }
        }
        match crate::reference::for_case(c) {
            Ok(r) => println!("    {:<20} {}", "reference", r.name()),
            Err(why) => println!("    {:<20} none — {why}", "reference"),
        }
    }
    Ok(ExitCode::SUCCESS)
}

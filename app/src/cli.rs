//! The command line: clap definitions and what each command does. Exit codes: 0 success
//! (gate passed), 1 a gated discrepancy is out of tolerance, 2 bad input or an error.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;

use clap::{Parser, Subcommand};

use crate::commands;

use rockslide_core::case::{discover, limits};
use rockslide_core::error::{Error, InputErrors};
use rockslide_core::io::{inside, remove_stale_temporaries_under};
use rockslide_present::gate;
use rockslide_present::report::{
    OutputSet, WrittenCase, write_case_outputs_with, write_suite_outputs_with,
};
use rockslide_verify::registry;
use rockslide_verify::registry::load_case;
use rockslide_verify::suite::{CaseResult, plan, run_case};
use rockslide_verify::sweep::stability::study;
use rockslide_verify::sweep::work_precision::sweep_case;
use rockslide_verify::timings;

/// Cross-code verification of seismic sliding and rocking.
#[derive(Debug, Parser)]
#[command(name = "rockslide", version, about, long_about = None)]
pub struct Cli {
    /// What to do (default: run every case in `cases/`, `cases/records/`, `cases/vertical/` and `cases/spatial/` and write `reports/`).
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Print nothing but errors and failures.
    #[arg(long, short, global = true)]
    pub quiet: bool,
    /// Also write the wall and CPU time of every stage (stability map, sweeps, each case's
    /// engines, reference, analysis, trace files and pages) as `timings.json` and
    /// `timings.md` in the output folder. Off by default: no other output changes.
    #[arg(long, global = true)]
    pub timings: bool,
    /// The default command only: write every trace as CSV too (each run, its per-contact
    /// block, the reference) and self-contained pages with every figure inline, as `run`
    /// and `check` do. By default the traces are in each case's MCAP file only and the
    /// pages link their figures.
    #[arg(long)]
    pub full_traces: bool,
}

/// The commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run cases and write their traces and reports.
    Run {
        /// Case files or folders (default: `cases/`, `cases/records/`, `cases/vertical/` and `cases/spatial/`).
        cases: Vec<PathBuf>,
        /// Output folder.
        #[arg(long, short, default_value = "reports")]
        out: PathBuf,
        /// Another program's results as a participant, `LABEL=PATH` (repeatable; one case):
        /// a rockslide trace CSV (any unit the catalogue knows) or MCAP file
        /// (`trace.mcap#/fe/single/state` when it has several state topics).
        #[arg(long = "external", value_name = "LABEL=PATH")]
        external: Vec<String>,
    },
    /// List the cases and which engines apply to each.
    List {
        /// Case files or folders (default: `cases/`, `cases/records/`, `cases/vertical/` and `cases/spatial/`).
        cases: Vec<PathBuf>,
    },
    /// Write a case's reference solution (exact or closed form) as a CSV trace.
    Reference {
        /// The case file.
        case: PathBuf,
        /// Sampling interval, s.
        #[arg(long, default_value_t = 0.001, allow_negative_numbers = true)]
        dt: f64,
        /// Output CSV file.
        #[arg(long, short)]
        out: PathBuf,
    },
    /// Run cases and gate on their tolerances: exit 0 when every gated check passes, 1 when
    /// any fails (one line per failure on stderr), 2 on bad input. Writes the reports and
    /// JUnit XML.
    Check {
        /// Case files or folders (default: `cases/`, `cases/records/`, `cases/vertical/` and `cases/spatial/`).
        cases: Vec<PathBuf>,
        /// Output folder for reports and traces.
        #[arg(long, short, default_value = "reports")]
        out: PathBuf,
        /// JUnit XML file for CI systems (default: `<out>/junit.xml`, i.e. `reports/junit.xml`).
        #[arg(long)]
        junit: Option<PathBuf>,
        /// Another program's results as a participant, `LABEL=PATH` (repeatable; one case):
        /// a rockslide trace CSV (any unit the catalogue knows) or MCAP file
        /// (`trace.mcap#/fe/single/state` when it has several state topics).
        #[arg(long = "external", value_name = "LABEL=PATH")]
        external: Vec<String>,
    },
    // --- records and studies (commands/study.rs; docs/records-and-studies.md) ---
    /// Run a study grid: one model under many records / PGAs / μ / polarities, resumable.
    Study {
        /// The grid file (TOML).
        grid: PathBuf,
        /// Output folder (result files in `<out>/runs/`, summary beside them).
        #[arg(long, short, default_value = "reports/study")]
        out: PathBuf,
        /// Run only shard K of N (0-based, e.g. `--shard $SLURM_ARRAY_TASK_ID/8`).
        #[arg(long)]
        shard: Option<String>,
        /// Do not run: merge the results found in `--from` folders into `--out` (as study-merge).
        #[arg(long)]
        merge: bool,
        /// With --merge: folders holding other shards' results.
        #[arg(long)]
        from: Vec<PathBuf>,
    },
    /// Merge the shards of a study into one summary.
    StudyMerge {
        /// The grid file the shards ran.
        grid: PathBuf,
        /// Output folder for the merged results and summary.
        #[arg(long, short, default_value = "reports/study")]
        out: PathBuf,
        /// Folders holding shards' results (each with a `runs/` folder); `--out` is always searched.
        #[arg(long)]
        from: Vec<PathBuf>,
    },
    /// Newmark rigid-block sliding on a record, both polarities; sliding in mm, block minus ground (the reports' convention).
    Newmark {
        /// The record (.AT2 or two-column CSV).
        record: PathBuf,
        /// Yield acceleration(s), g.
        #[arg(long, required = true, num_args = 1.., allow_negative_numbers = true)]
        ky: Vec<f64>,
        /// Unit of a CSV record: g, m/s2 or cm/s2.
        #[arg(long)]
        unit: Option<String>,
        /// Scale the record to this PGA first, g.
        #[arg(long, allow_negative_numbers = true)]
        pga: Option<f64>,
        /// Slide both ways (block on a level frictional base) instead of one way.
        #[arg(long)]
        two_way: bool,
        /// Also write the table as CSV.
        #[arg(long)]
        csv: Option<PathBuf>,
    },
    /// Check an MCAP trace and print its channels, metadata and attachments.
    TraceInfo {
        /// The `.mcap` file (`reports/<case>/<case>.mcap`).
        file: PathBuf,
    },
    /// Error against run time: a Δt ladder per engine and variant, with observed order;
    /// the typed result in `<out>/<case>/sweep.json`, table and log-log plot in
    /// `sweep.{md,html,csv,svg}`.
    Sweep {
        /// Case files.
        cases: Vec<PathBuf>,
        /// Output folder.
        #[arg(long, short, default_value = "reports")]
        out: PathBuf,
        /// Rungs of the Δt ladder (from T/10 down, at least 3).
        #[arg(long, default_value_t = 8, allow_negative_numbers = true)]
        rungs: usize,
        /// Refinement ratio between rungs.
        #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
        ratio: f64,
        /// Timed repeats per rung (median, min and max are reported).
        #[arg(long, default_value_t = 3, allow_negative_numbers = true)]
        repeats: usize,
        /// Worker threads (default: all cores).
        #[arg(long, short, allow_negative_numbers = true)]
        jobs: Option<usize>,
        /// Wall-time budget per engine variant, s (0: none); rungs beyond it are skipped.
        #[arg(long, default_value_t = rockslide_verify::sweep::DEFAULT_BUDGET, allow_negative_numbers = true)]
        budget: f64,
    },
    /// Run the stiff and extreme scenes and classify every run (accurate, inaccurate,
    /// diverged, not converged); the typed result, map and stability limits in
    /// `<out>/stability/`.
    Stability {
        /// Case files or folders (default: `cases/stability/`).
        cases: Vec<PathBuf>,
        /// Output folder.
        #[arg(long, short, default_value = "reports")]
        out: PathBuf,
        /// Worker threads (default: all cores).
        #[arg(long, short, allow_negative_numbers = true)]
        jobs: Option<usize>,
    },
    /// Write a case's scene as another program's input: `--to opensees` writes an
    /// OpenSeesPy script (and its record samples) into `<out>/<case>/` that records
    /// rockslide's own trace CSV (read back with `--external opensees=…`).
    Export {
        /// The case file.
        case: PathBuf,
        /// The program to write for.
        #[arg(long, value_enum)]
        to: Target,
        /// Output folder.
        #[arg(long, short, default_value = "exports")]
        out: PathBuf,
    },
}

/// Programs `rockslide export` writes for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Target {
    /// OpenSeesPy (Python) script.
    Opensees,
}

impl Command {
    /// The folder `--timings` writes into: the command's output folder.
    fn timings_folder(&self) -> Option<&Path> {
        match self {
            Command::Run { out, .. } | Command::Check { out, .. } => Some(out),
            other => other.output_folder(),
        }
    }

    /// The output folder a command writes many files into (stale temporaries of an
    /// interrupted run there are removed first); `run` and `check` clear theirs themselves.
    fn output_folder(&self) -> Option<&Path> {
        match self {
            Command::Sweep { out, .. }
            | Command::Stability { out, .. }
            | Command::Study { out, .. }
            | Command::StudyMerge { out, .. } => Some(out),
            _ => None,
        }
    }
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

/// Run the command line; returns the process exit code.
pub fn main(cli: Cli) -> ExitCode {
    if !cli.timings {
        return dispatch(cli);
    }
    rockslide_verify::timings::enable();
    let folder = cli
        .command
        .as_ref()
        .map_or(Some(Path::new("reports")), Command::timings_folder)
        .map(Path::to_path_buf);
    let code = rockslide_verify::timings::time("total", "all", || dispatch(cli));
    if let Some(folder) = folder
        && let Err(e) = crate::timings::write(&rockslide_verify::timings::take(), &folder)
    {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    code
}

/// Run one command; returns the process exit code.
fn dispatch(cli: Cli) -> ExitCode {
    let set = match cli.full_traces {
        true => OutputSet::FULL,
        false => OutputSet::LEAN,
    };
    if cli.full_traces && cli.command.is_some() {
        eprintln!(
            "error: --full-traces applies to the default command only (run and check write every trace)"
        );
        return ExitCode::from(2);
    }
    let stale = cli
        .command
        .as_ref()
        .and_then(Command::output_folder)
        .map_or(Ok(0), remove_stale_temporaries_under);
    let result = match stale.map(|_| cli.command) {
        Err(e) => Err(e),
        Ok(None) => run_everything(Path::new("reports"), cli.quiet, set),
        Ok(Some(Command::Run {
            cases,
            out,
            external,
        })) => run(&cases, &out, cli.quiet, None, &external),
        Ok(Some(Command::Check {
            cases,
            out,
            junit,
            external,
        })) => {
            let junit = junit.unwrap_or_else(|| out.join("junit.xml"));
            run(&cases, &out, cli.quiet, Some(&junit), &external)
        }
        Ok(Some(Command::List { cases })) => list(&cases),
        Ok(Some(Command::Reference { case, dt, out })) => write_reference(&case, dt, &out),
        Ok(Some(Command::Study {
            grid,
            out,
            shard,
            merge,
            from,
        })) => commands::study::run(&grid, &out, shard.as_deref(), merge, &from, cli.quiet),
        Ok(Some(Command::StudyMerge { grid, out, from })) => {
            commands::study::run(&grid, &out, None, true, &from, cli.quiet)
        }
        Ok(Some(Command::Newmark {
            record,
            ky,
            unit,
            pga,
            two_way,
            csv,
        })) => commands::study::newmark(rockslide_verify::study::NewmarkArgs {
            record,
            ky,
            unit,
            pga,
            two_way,
            csv,
        }),
        Ok(Some(Command::TraceInfo { file })) => rockslide_formats::mcap_info(&file).map(|s| {
            let _ = std::io::Write::write_all(&mut std::io::stdout().lock(), s.as_bytes());
            ExitCode::SUCCESS
        }),
        Ok(Some(Command::Sweep {
            cases,
            out,
            rungs,
            ratio,
            repeats,
            jobs,
            budget,
        })) => check_ladder(rungs, ratio)
            .and_then(|()| check_budget(budget))
            .and_then(|()| {
                commands::sweep::run(
                    &cases,
                    &out,
                    &rockslide_verify::sweep::Options {
                        rungs,
                        ratio,
                        repeats,
                        jobs: bounded_jobs(jobs),
                        quiet: cli.quiet,
                        budget: (budget > 0.0).then_some(budget),
                    },
                )
            }),
        Ok(Some(Command::Export { case, to, out })) => {
            commands::export::run(&case, to, &out, cli.quiet)
        }
        Ok(Some(Command::Stability { cases, out, jobs })) => commands::stability::run(
            &cases,
            &out,
            &rockslide_verify::sweep::Options {
                jobs: bounded_jobs(jobs),
                quiet: cli.quiet,
                ..Default::default()
            },
        ),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            for line in e.to_string().lines() {
                eprintln!("error: {line}");
            }
            ExitCode::from(2)
        }
    }
}

/// Largest number of rungs of a sweep's Δt ladder.
const MAX_RUNGS: usize = 30;
/// Largest refinement between the first and the last rung (`ratio^(rungs-1)`).
const MAX_REFINEMENT: f64 = 1e7;

/// The Δt ladder stays within [`MAX_RUNGS`] and [`MAX_REFINEMENT`] (checked before work).
fn check_ladder(rungs: usize, ratio: f64) -> Result<(), Error> {
    if rungs > MAX_RUNGS {
        return Err(Error::Other(format!(
            "--rungs is {rungs}, but the limit is {MAX_RUNGS}"
        )));
    }
    let refinement = ratio.powf(rungs.saturating_sub(1) as f64);
    if ratio > 1.0 && (refinement.is_nan() || refinement > MAX_REFINEMENT) {
        return Err(Error::Other(format!(
            "--ratio {ratio:e} over {rungs} rungs refines Δt by {refinement:.3e}; the limit is \
             {MAX_REFINEMENT:.0e}"
        )));
    }
    Ok(())
}

/// `--budget`: 0 means none, a positive number is seconds; anything else is an error.
fn check_budget(budget: f64) -> Result<(), Error> {
    if budget >= 0.0 && budget.is_finite() {
        return Ok(());
    }
    Err(Error::Other(format!(
        "--budget is {budget} s, but must be >= 0 (0: no budget)"
    )))
}

/// Every case's engine options and variants checked against the engines (what `run`
/// checks before any work), all problems reported together.
fn plan_all(
    cases: &[rockslide_core::case::Case],
    engines: &[Box<dyn rockslide_engine_api::Engine>],
) -> Result<(), Error> {
    let errors: Vec<_> = cases
        .iter()
        .filter_map(|c| plan(c, engines).err())
        .flat_map(|e| e.0)
        .collect();
    if errors.is_empty() {
        Ok(())
    } else {
        Err(InputErrors(errors).into())
    }
}

/// One case loaded and checked as `run` checks it (engine options, variants).
fn load_planned(path: &Path) -> Result<rockslide_core::case::Case, Error> {
    let case = load_case(path)?;
    plan_all(std::slice::from_ref(&case), &registry::all())?;
    Ok(case)
}

/// Worker threads: a request above [`limits::MAX_JOBS`] is lowered to it (0 stays, and
/// is refused by the options' own check).
fn bounded_jobs(jobs: Option<usize>) -> Option<usize> {
    jobs.map(|j| j.min(limits::MAX_JOBS))
}

/// The default command: the complete document. Stability map of `cases/stability/`,
/// work-precision sweeps of the oscillator cases (cheap: each has an exact reference and
/// runs in seconds per engine), and every case in `cases/`, `cases/records/` and
/// `cases/vertical/`, all three at once on every core. A case whose report shows a sweep
/// is written once its sweep is; the others as soon as they are run. Output order is the
/// cases' order, whatever finished first.
fn run_everything(out: &Path, quiet: bool, set: OutputSet) -> Result<ExitCode, Error> {
    use rayon::prelude::*;
    let options = rockslide_verify::sweep::Options {
        quiet,
        repeats: DEFAULT_RUN_REPEATS,
        budget: Some(DEFAULT_RUN_SWEEP_BUDGET),
        ..Default::default()
    };
    let stability_folder = Path::new("cases/stability");
    let stability_cases = match stability_folder.is_dir() {
        true => load_all(&case_paths_or(&[stability_folder.to_path_buf()], "")?)?,
        false => Vec::new(),
    };
    if stability_folder.is_dir() && stability_cases.is_empty() {
        return Err(Error::Other("stability: no case files found".into()));
    }
    // Sweeps of the top-level oscillators only: a record case's Δt ladder is minutes long.
    let oscillators: Vec<rockslide_core::case::Case> = load_all(&case_paths_or(&[], "cases")?)?
        .into_iter()
        .filter(|c| matches!(c.scene.model, rockslide_core::case::Model::Oscillator(_)))
        .collect();
    // the lean set's file step is the output set's (`OutputSet::file_step`): the cases
    // are analysed as written
    let cases = prepare_cases(&[], out, &[], false)?;
    let swept: Vec<&str> = oscillators.iter().map(|c| c.name.as_str()).collect();
    // One pool, longest first: a task starts in the order it was spawned (FIFO). The
    // costliest cases first, one per core (their longest runs set the critical path: they
    // start at t = 0), then the stability map (many short runs; run before most case
    // results are held, its memory is freed early — run last it raised the peak RSS from
    // 524 to 735 MB), then the other cases by estimated cost, then the sweeps (short runs
    // that fill the cores' gaps at the end).
    let order = longest_first(&cases);
    let case_slots: Vec<Slot<(CaseResult, Option<WrittenCase>)>> =
        cases.iter().map(|_| Mutex::new(None)).collect();
    let sweep_slots: Vec<Slot<_>> = oscillators.iter().map(|_| Mutex::new(None)).collect();
    let stability_slot: Slot<Option<_>> = Mutex::new(None);
    let mut cases: Vec<Option<rockslide_core::case::Case>> = cases.into_iter().map(Some).collect();
    rayon::scope_fifo(|s| {
        let (stability_cases, options, swept) = (&stability_cases, &options, &swept);
        let spawn_case = |i: usize, case: Option<rockslide_core::case::Case>| {
            let slot = &case_slots[i];
            s.spawn_fifo(move |_| {
                let Some(case) = case else { return };
                let write_now = !swept.contains(&case.name.as_str());
                let outcome = run_case(case).map_err(Error::from).and_then(|mut result| {
                    let written = write_now
                        .then(|| write_case_outputs_with(&result, out, set))
                        .transpose()?;
                    if written.is_some() {
                        result.release_histories();
                    }
                    Ok((result, written))
                });
                fill(slot, outcome);
            });
        };
        let first = rayon::current_num_threads().min(order.len());
        for &i in &order[..first] {
            spawn_case(i, cases[i].take());
        }
        let slot = &stability_slot;
        s.spawn_fifo(move |_| {
            let outcome = (!stability_cases.is_empty())
                .then(|| timings::time("stability", "all", || study(stability_cases, options)))
                .transpose();
            fill(slot, outcome);
        });
        for &i in &order[first..] {
            spawn_case(i, cases[i].take());
        }
        for (c, slot) in oscillators.iter().zip(&sweep_slots) {
            s.spawn_fifo(move |_| {
                fill(
                    slot,
                    timings::time("sweep", &c.name, || sweep_case(c, options)),
                );
            });
        }
    });
    let stability = taken(stability_slot);
    let sweeps: Result<Vec<_>, Error> = sweep_slots.into_iter().map(taken).collect();
    let outcomes: Vec<Result<_, Error>> = case_slots.into_iter().map(taken).collect();
    if let Some(r) = stability? {
        commands::stability::write(&r, out, quiet)?;
    }
    for r in &sweeps? {
        commands::sweep::write(r, out, quiet)?;
    }
    // the swept cases' pages show their sweep: written now that it is there
    let written: Vec<Result<(CaseResult, WrittenCase), Error>> = outcomes
        .into_par_iter()
        .map(|outcome| {
            let (result, written) = outcome?;
            let written = match written {
                Some(w) => w,
                None => write_case_outputs_with(&result, out, set)?,
            };
            Ok((result, written))
        })
        .collect();
    finish(written, out, quiet, None)
}

/// A task's outcome, filled once by the task that computes it.
type Slot<T> = Mutex<Option<Result<T, Error>>>;

/// Store a task's outcome in its slot.
fn fill<T>(slot: &Slot<T>, outcome: Result<T, Error>) {
    *slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(outcome);
}

/// A slot's outcome once its task has run (an error if the task never filled it).
fn taken<T>(slot: Slot<T>) -> Result<T, Error> {
    slot.into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .unwrap_or_else(|| {
            Err(Error::Other(
                "a task of the default run did not finish".into(),
            ))
        })
}

/// Relative CPU cost of one time step of a run, in units of 0.1 µs, from the default
/// run's single-thread CPU per case (docs/performance.md §2): the predictor-corrector
/// 0.06 µs, fe 0.2–1.1 µs; rapier about 2 µs on a mass (the oscillator) and 25 µs on a
/// body with corners (block, rocking body: contact manifolds, substeps), twice that with
/// a moving kinematic ground (its contacts are rebuilt every step).
fn step_weight(engine: &str, variant: &str, model: &rockslide_core::case::Model) -> f64 {
    use rockslide_core::case::Model;
    match engine {
        "rapier" => {
            let body = match model {
                Model::Oscillator(_) => 20.0,
                Model::RockingBody(_) | Model::RigidBlock(_) => 250.0,
            };
            match variant {
                "kinematic-ground" => 2.0 * body,
                _ => body,
            }
        }
        "fe" => 6.0,
        _ => 1.0,
    }
}

/// A case's estimated cost: Σ over its planned runs of steps × the run's step weight.
fn estimated_cost(
    case: &rockslide_core::case::Case,
    engines: &[Box<dyn rockslide_engine_api::Engine>],
) -> f64 {
    plan(case, engines).map_or(0.0, |p| {
        p.runs
            .iter()
            .map(|r| {
                case.run.duration / r.dt * step_weight(r.engine, &r.variant, &case.scene.model)
            })
            .sum()
    })
}

/// The cases' indices, costliest first (ties: the cases' order).
fn longest_first(cases: &[rockslide_core::case::Case]) -> Vec<usize> {
    let engines = registry::all();
    let costs: Vec<f64> = cases.iter().map(|c| estimated_cost(c, &engines)).collect();
    let mut order: Vec<usize> = (0..cases.len()).collect();
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]));
    order
}

/// Timed repeats of each sweep rung in the default command: one. The timing of a run is
/// reported as measured once; `rockslide sweep` (3 repeats by default) gives medians.
const DEFAULT_RUN_REPEATS: usize = 1;

/// Wall-time budget of one engine variant's sweep in the default command, s. Only rapier
/// on the rocking RPEPO scenes reaches it (its finer rungs cost seconds each); those rungs
/// are skipped and the sweep page says so. `rockslide sweep` keeps the full budget
/// ([`rockslide_verify::sweep::DEFAULT_BUDGET`]).
const DEFAULT_RUN_SWEEP_BUDGET: f64 = 3.0;

/// The folders `run`, `check` and `list` read when given no case: the top-level cases and
/// the record cases. `cases/stability/` is not among them: its scenes are meant to break
/// engines and are classified by `rockslide stability`, not gated.
const DEFAULT_CASE_FOLDERS: &[&str] =
    &["cases", "cases/records", "cases/vertical", "cases/spatial"];

/// Expand case arguments: files as given, folders to their `*.toml`; with none, every
/// folder of [`DEFAULT_CASE_FOLDERS`] that exists (`cases/` itself must).
fn case_paths(args: &[PathBuf]) -> Result<Vec<PathBuf>, Error> {
    if !args.is_empty() {
        return case_paths_or(args, "cases");
    }
    let mut out = case_paths_or(&[], DEFAULT_CASE_FOLDERS[0])?;
    for folder in &DEFAULT_CASE_FOLDERS[1..] {
        if Path::new(folder).is_dir() {
            out.extend(case_paths_or(&[], folder)?);
        }
    }
    Ok(out)
}

/// Expand case arguments: files as given, folders to their `*.toml`, default `default`.
pub(crate) fn case_paths_or(args: &[PathBuf], default: &str) -> Result<Vec<PathBuf>, Error> {
    let args = if args.is_empty() {
        vec![PathBuf::from(default)]
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
pub(crate) fn load_all(paths: &[PathBuf]) -> Result<Vec<rockslide_core::case::Case>, Error> {
    let mut cases = Vec::new();
    let mut errors = Vec::new();
    for p in paths {
        match load_case(p) {
            Ok(c) => cases.push(c),
            Err(e) => errors.extend(e.0),
        }
    }
    if let Err(e) = rockslide_core::case::slug::check_unique(&cases) {
        errors.extend(e.0);
    }
    if errors.is_empty() {
        Ok(cases)
    } else {
        Err(InputErrors(errors).into())
    }
}

/// Run every case and write its outputs, cases in parallel across cores (each case's
/// engines in parallel inside it); results in the cases' order, whatever finished first.
fn run_and_write_all(
    cases: Vec<rockslide_core::case::Case>,
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

/// Load, check and plan the cases a run names (all of [`DEFAULT_CASE_FOLDERS`] when
/// none), with `--external` participants; the output folder cleared of stale temporaries.
/// `None` for an empty list that `check` refuses (said on stderr).
fn prepare_cases(
    args: &[PathBuf],
    out: &Path,
    external: &[String],
    gate: bool,
) -> Result<Vec<rockslide_core::case::Case>, Error> {
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

/// Run the cases, write every report; with `junit` (the `check` command), also write the
/// JUnit XML and return exit code 1 when the gate fails.
fn run(
    args: &[PathBuf],
    out: &Path,
    quiet: bool,
    junit: Option<&Path>,
    external: &[String],
) -> Result<ExitCode, Error> {
    let cases = prepare_cases(args, out, external, junit.is_some())?;
    if cases.is_empty() && junit.is_some() {
        let shown: Vec<String> = args.iter().map(|a| a.display().to_string()).collect();
        eprintln!(
            "FAIL checks nothing: no case file (*.toml) in {}",
            if shown.is_empty() {
                DEFAULT_CASE_FOLDERS.join(", ")
            } else {
                shown.join(", ")
            }
        );
        return Ok(ExitCode::from(1));
    }
    finish(
        run_and_write_all(cases, out, OutputSet::FULL),
        out,
        quiet,
        junit,
    )
}

/// Say each case's gate, write the suite's pages and (with `junit`) the JUnit XML; exit
/// code 1 when the gate fails.
fn finish(
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
            say!(
                "{name}: {} runs, gate {} → {}",
                result.runs.len(),
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
        for f in gate::informative(&results) {
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

/// `--external LABEL=PATH` participants join the one case given.
fn add_externals(
    cases: &mut [rockslide_core::case::Case],
    external: &[String],
) -> Result<(), Error> {
    match cases {
        _ if external.is_empty() => Ok(()),
        [case] => Ok(rockslide_verify::external::add_from_command_line(
            case, external,
        )?),
        _ => Err(Error::Input(
            rockslide_core::error::InputError::new(
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

fn list(args: &[PathBuf]) -> Result<ExitCode, Error> {
    let cases = load_all(&case_paths(args)?)?;
    let engines = registry::all();
    plan_all(&cases, &engines)?;
    for c in &cases {
        say!("{} — {}", c.name, c.title);
        say!(
            "    {} under {}, {} s",
            c.scene.model.kind(),
            c.scene.excitation.kind(),
            c.run.duration
        );
        for e in &engines {
            let listed = c.engines.is_empty() || c.engine(e.id()).is_some();
            match e.variants(&c.scene) {
                Err(na) => say!("    {:<20} n/a — {}", e.id(), na.0),
                Ok(_) if !listed => say!("    {:<20} not requested by the case", e.id()),
                Ok(v) => {
                    let wanted = c
                        .engine(e.id())
                        .and_then(|r| r.variants.clone())
                        .unwrap_or_else(|| v.iter().map(|s| s.to_string()).collect());
                    say!(
                        "    {:<20} {} (dt {} s)",
                        e.id(),
                        wanted.join(", "),
                        c.dt_for(e.id())
                    );
                }
            }
        }
        match rockslide_reference::for_case(c) {
            Ok(r) => say!("    {:<20} {}", "reference", r.name()),
            Err(why) => say!("    {:<20} none — {why}", "reference"),
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn write_reference(path: &Path, dt: f64, out: &Path) -> Result<ExitCode, Error> {
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(Error::Other(format!(
            "--dt is {dt} s, but must be > 0 (and finite)"
        )));
    }
    let case = load_planned(path)?;
    limits::check_steps(case.run.duration, dt)
        .map_err(|why| Error::Other(format!("--dt {why}")))?;
    let solution = rockslide_reference::for_case(&case)
        .map_err(|why| Error::Other(format!("{}: no reference: {why}", path.display())))?;
    let n = rockslide_engine_api::step_count(case.run.duration, dt);
    let times: Vec<f64> = (0..=n).map(|i| i as f64 * dt).collect();
    let trace = rockslide_reference::sample(solution.as_ref(), &times);
    rockslide_formats::write_csv(&trace, out)?;
    say!("{}: {} → {}", case.name, solution.method(), out.display());
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// rockslide shall start the default run's costliest cases first: a case's cost is
    /// Σ steps × step weight over its planned runs.
    #[test]
    fn the_record_cases_with_rapier_bodies_are_scheduled_first() {
        let paths: Vec<PathBuf> = [
            "cases/pepo-mass-accel.toml",
            "cases/records/pepo-loma-prieta.toml",
            "cases/records/rpepo-loma-prieta.toml",
            "cases/records/block-northridge.toml",
        ]
        .iter()
        .map(PathBuf::from)
        .collect();
        let cases = load_all(&paths).unwrap();
        let engines = registry::all();
        // RPEPO, 60 s at 1 ms: fe single and double (6 each) and rapier's applied-force
        // supports on a body (250)
        assert_eq!(
            estimated_cost(&cases[2], &engines),
            60_000.0 * (6.0 + 6.0 + 250.0)
        );
        // block, 22 s at 1 ms: rapier's kinematic ground (500) and inertial force (250)
        assert_eq!(
            estimated_cost(&cases[3], &engines),
            22_000.0 * (500.0 + 250.0)
        );
        assert_eq!(longest_first(&cases), [3, 2, 1, 0]);
    }
}

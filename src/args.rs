//! The command line's definitions (clap): the global flags, the commands and each
//! command's arguments, nothing else. What a command does is in `commands/`, one file per
//! command; `cli.rs` hands each parsed command to its file.

use std::path::{Path, PathBuf};

use clap::{Args, Parser, Subcommand};

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
    Run(RunArgs),
    /// List the cases and which engines apply to each.
    List(ListArgs),
    /// Write a case's reference solution (exact or closed form) as a CSV trace.
    Reference(ReferenceArgs),
    /// Run cases and gate on their tolerances: exit 0 when every gated check passes, 1 when
    /// any fails (one line per failure on stderr), 2 on bad input. Writes the reports and
    /// JUnit XML.
    Check(CheckArgs),
    // --- records and studies (commands/study.rs; docs/records-and-studies.md) ---
    /// Run a study grid: one model under many records / PGAs / μ / polarities, resumable.
    Study(StudyArgs),
    /// Merge the shards of a study into one summary.
    StudyMerge(StudyMergeArgs),
    /// Newmark rigid-block sliding on a record, both polarities; sliding in mm, block minus ground (the reports' convention).
    Newmark(NewmarkArgs),
    /// Check an MCAP trace and print its channels, metadata and attachments.
    TraceInfo(TraceInfoArgs),
    /// Error against run time: a Δt ladder per engine and variant, with observed order;
    /// the typed result in `<out>/<case>/sweep.json`, table and log-log plot in
    /// `sweep.{md,html,csv,svg}`.
    Sweep(SweepArgs),
    /// Run the stiff and extreme scenes and classify every run (accurate, inaccurate,
    /// diverged, not converged); the typed result, map and stability limits in
    /// `<out>/stability/`.
    Stability(StabilityArgs),
    /// Write a case's scene as another program's input into `<out>/<case>/`: `--to
    /// opensees` an OpenSeesPy script (and its record samples) that records rockslide's
    /// own trace CSV (read back with `--external opensees=…`); `--to calculix` a CalculiX
    /// `.inp` deck whose `.dat` output rockslide reads (`[engines.calculix]` runs it);
    /// `--to ansys` an ANSYS APDL deck of the paper's CONTA178 models that writes
    /// rockslide's CSV (not executed by rockslide).
    Export(ExportArgs),
}

/// `rockslide run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Case files or folders (default: `cases/`, `cases/records/`, `cases/vertical/` and `cases/spatial/`).
    pub cases: Vec<PathBuf>,
    /// Output folder.
    #[arg(long, short, default_value = "reports")]
    pub out: PathBuf,
    /// Another program's results as a participant, `LABEL=PATH` (repeatable; one case):
    /// a rockslide trace CSV (any unit the catalogue knows) or MCAP file
    /// (`trace.mcap#/fe/single/state` when it has several state topics).
    #[arg(long = "external", value_name = "LABEL=PATH")]
    pub external: Vec<String>,
}

/// `rockslide list`.
#[derive(Debug, Args)]
pub struct ListArgs {
    /// Case files or folders (default: `cases/`, `cases/records/`, `cases/vertical/` and `cases/spatial/`).
    pub cases: Vec<PathBuf>,
}

/// `rockslide reference`.
#[derive(Debug, Args)]
pub struct ReferenceArgs {
    /// The case file.
    pub case: PathBuf,
    /// Sampling interval, s.
    #[arg(long, default_value_t = 0.001, allow_negative_numbers = true)]
    pub dt: f64,
    /// Output CSV file.
    #[arg(long, short)]
    pub out: PathBuf,
}

/// `rockslide check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Case files or folders (default: `cases/`, `cases/records/`, `cases/vertical/` and `cases/spatial/`).
    pub cases: Vec<PathBuf>,
    /// Output folder for reports and traces.
    #[arg(long, short, default_value = "reports")]
    pub out: PathBuf,
    /// JUnit XML file for CI systems (default: `<out>/junit.xml`, i.e. `reports/junit.xml`).
    #[arg(long)]
    pub junit: Option<PathBuf>,
    /// Another program's results as a participant, `LABEL=PATH` (repeatable; one case):
    /// a rockslide trace CSV (any unit the catalogue knows) or MCAP file
    /// (`trace.mcap#/fe/single/state` when it has several state topics).
    #[arg(long = "external", value_name = "LABEL=PATH")]
    pub external: Vec<String>,
}

/// `rockslide study`.
#[derive(Debug, Args)]
pub struct StudyArgs {
    /// The grid file (TOML).
    pub grid: PathBuf,
    /// Output folder (result files in `<out>/runs/`, summary beside them).
    #[arg(long, short, default_value = "reports/study")]
    pub out: PathBuf,
    /// Run only shard K of N (0-based, e.g. `--shard $SLURM_ARRAY_TASK_ID/8`).
    #[arg(long)]
    pub shard: Option<String>,
    /// Do not run: merge the results found in `--from` folders into `--out` (as study-merge).
    #[arg(long)]
    pub merge: bool,
    /// With --merge: folders holding other shards' results.
    #[arg(long)]
    pub from: Vec<PathBuf>,
}

/// `rockslide study-merge`.
#[derive(Debug, Args)]
pub struct StudyMergeArgs {
    /// The grid file the shards ran.
    pub grid: PathBuf,
    /// Output folder for the merged results and summary.
    #[arg(long, short, default_value = "reports/study")]
    pub out: PathBuf,
    /// Folders holding shards' results (each with a `runs/` folder); `--out` is always searched.
    #[arg(long)]
    pub from: Vec<PathBuf>,
}

/// `rockslide newmark`.
#[derive(Debug, Args)]
pub struct NewmarkArgs {
    /// The record (.AT2 or two-column CSV).
    pub record: PathBuf,
    /// Yield acceleration(s), g.
    #[arg(long, required = true, num_args = 1.., allow_negative_numbers = true)]
    pub ky: Vec<f64>,
    /// Unit of a CSV record: g, m/s2 or cm/s2.
    #[arg(long)]
    pub unit: Option<String>,
    /// Scale the record to this PGA first, g.
    #[arg(long, allow_negative_numbers = true)]
    pub pga: Option<f64>,
    /// Slide both ways (block on a level frictional base) instead of one way.
    #[arg(long)]
    pub two_way: bool,
    /// Also write the table as CSV.
    #[arg(long)]
    pub csv: Option<PathBuf>,
}

/// `rockslide trace-info`.
#[derive(Debug, Args)]
pub struct TraceInfoArgs {
    /// The `.mcap` file (`reports/<case>/<case>.mcap`).
    pub file: PathBuf,
}

/// `rockslide sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// Case files.
    pub cases: Vec<PathBuf>,
    /// Output folder.
    #[arg(long, short, default_value = "reports")]
    pub out: PathBuf,
    /// Rungs of the Δt ladder (from T/10 down, at least 3).
    #[arg(long, default_value_t = 8, allow_negative_numbers = true)]
    pub rungs: usize,
    /// Refinement ratio between rungs.
    #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
    pub ratio: f64,
    /// Timed repeats per rung (median, min and max are reported).
    #[arg(long, default_value_t = 3, allow_negative_numbers = true)]
    pub repeats: usize,
    /// Worker threads (default: all cores).
    #[arg(long, short, allow_negative_numbers = true)]
    pub jobs: Option<usize>,
    /// Wall-time budget per engine variant, s (0: none); rungs beyond it are skipped.
    #[arg(long, default_value_t = rockslide_verify::sweep::DEFAULT_BUDGET, allow_negative_numbers = true)]
    pub budget: f64,
}

/// `rockslide stability`.
#[derive(Debug, Args)]
pub struct StabilityArgs {
    /// Case files or folders (default: `cases/stability/`).
    pub cases: Vec<PathBuf>,
    /// Output folder.
    #[arg(long, short, default_value = "reports")]
    pub out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long, short, allow_negative_numbers = true)]
    pub jobs: Option<usize>,
}

/// `rockslide export`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// The case file.
    pub case: PathBuf,
    /// The program to write for.
    #[arg(long, value_enum)]
    pub to: Target,
    /// Output folder.
    #[arg(long, short, default_value = "exports")]
    pub out: PathBuf,
}

/// Programs `rockslide export` writes for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Target {
    /// OpenSeesPy (Python) script.
    Opensees,
    /// CalculiX (`ccx`) input deck.
    Calculix,
    /// ANSYS Mechanical APDL input deck (not executed by rockslide).
    Ansys,
    /// Abaqus/Standard input deck and its results script (not executed by rockslide).
    Abaqus,
}

impl Command {
    /// The folder `--timings` writes into: the command's output folder.
    pub(crate) fn timings_folder(&self) -> Option<&Path> {
        match self {
            Command::Run(RunArgs { out, .. }) | Command::Check(CheckArgs { out, .. }) => Some(out),
            other => other.output_folder(),
        }
    }

    /// The output folder a command writes many files into (stale temporaries of an
    /// interrupted run there are removed first); `run` and `check` clear theirs themselves.
    pub(crate) fn output_folder(&self) -> Option<&Path> {
        match self {
            Command::Sweep(SweepArgs { out, .. })
            | Command::Stability(StabilityArgs { out, .. })
            | Command::Study(StudyArgs { out, .. })
            | Command::StudyMerge(StudyMergeArgs { out, .. }) => Some(out),
            _ => None,
        }
    }
}

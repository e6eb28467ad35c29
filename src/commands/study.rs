//! `rockslide study <grid>` (optionally one shard `K/N` of it, or `--merge`), and the
//! merge that `study-merge` runs too. A study runs its points (resumable, one result file
//! per point under `<out>/runs/`); unsharded or merged, the results are gathered into the
//! typed `<out>/study.json` and rendered as `summary.{md,html,csv}` and figures.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use rockslide_core::error::Error;
use rockslide_present::study::{headline_sentences, write_summary};
use rockslide_verify::study::{
    Study, StudyOptions, StudyOutcome, collect, load_grid, run_study, runs_dir,
};

use crate::args::StudyArgs;

/// Parse a shard `K/N` (0-based K < N, as Slurm's `--array=0-(N-1)` and Kubernetes'
/// `JOB_COMPLETION_INDEX` count).
pub fn parse_shard(s: &str) -> Result<(usize, usize), String> {
    let (k, n) = s
        .split_once('/')
        .ok_or_else(|| format!("shard \"{s}\" must be K/N, e.g. 0/8"))?;
    let k: usize = k
        .trim()
        .parse()
        .map_err(|_| format!("shard \"{s}\": K must be a whole number"))?;
    let n: usize = n
        .trim()
        .parse()
        .map_err(|_| format!("shard \"{s}\": N must be a whole number"))?;
    if n == 0 || k >= n {
        return Err(format!(
            "shard \"{s}\": need 0 ≤ K < N (shards are numbered from 0)"
        ));
    }
    Ok((k, n))
}

/// Save the gathered study as `study.json` and write its summary into `out`.
fn write(study: &Study, out: &Path, quiet: bool) -> Result<(), Error> {
    study.save(out)?;
    write_summary(study, out)?;
    if !quiet {
        for h in headline_sentences(study) {
            say!("  {h}");
        }
        say!("summary: {}", out.join("summary.md").display());
    }
    Ok(())
}

/// `rockslide study`: run (the shard of) a grid, then — unsharded — gather and write the
/// summary. Returns the outcome for callers that count.
pub fn study_command(
    grid_path: &Path,
    out: &Path,
    shard: Option<(usize, usize)>,
    quiet: bool,
) -> Result<StudyOutcome, Error> {
    let grid = load_grid(grid_path)?;
    let start = std::time::Instant::now();
    let outcome = run_study(
        &grid,
        &StudyOptions {
            out: out.to_path_buf(),
            shard,
            progress: !quiet,
        },
    )?;
    let secs = start.elapsed().as_secs_f64();
    if !quiet {
        let shard_text = shard.map_or_else(String::new, |(k, n)| format!(" (shard {k}/{n})"));
        say!(
            "{}{shard_text}: {} of {} points assigned, {} run now ({} engine runs, {:.2} s, {:.1} runs/s), {} already done",
            grid.title,
            outcome.assigned,
            outcome.points,
            outcome.executed,
            outcome.runs,
            secs,
            if secs > 0.0 {
                outcome.runs as f64 / secs
            } else {
                0.0
            },
            outcome.skipped
        );
    }
    match shard {
        Some(_) => {
            if !quiet {
                say!(
                    "results in {}; when every shard is done: rockslide study-merge {} --out {} [--from <shard folders>]",
                    runs_dir(out).display(),
                    grid_path.display(),
                    out.display()
                );
            }
        }
        None => write(&collect(&grid, &[], out)?, out, quiet)?,
    }
    Ok(outcome)
}

/// `rockslide study-merge`: gather the shards' results into `out` and write the summary.
pub fn merge_command(
    grid_path: &Path,
    out: &Path,
    from: &[PathBuf],
    quiet: bool,
) -> Result<Study, Error> {
    let grid = load_grid(grid_path)?;
    let study = collect(&grid, from, out)?;
    if !quiet {
        let folders: Vec<String> = from.iter().map(|f| f.display().to_string()).collect();
        say!(
            "{}: merged {} points into {}{}",
            grid.title,
            study.results.len(),
            out.display(),
            if folders.is_empty() {
                String::new()
            } else {
                format!(" from {}", folders.join(", "))
            }
        );
    }
    write(&study, out, quiet)?;
    Ok(study)
}

/// The `study` command for the command line (exit code 0 on success); with `--merge`, as
/// `study-merge`.
pub fn run(args: &StudyArgs, quiet: bool) -> Result<ExitCode, Error> {
    let (grid, out, from) = (&args.grid, &args.out, &args.from);
    if args.merge {
        if args.shard.is_some() {
            return Err(Error::Other(
                "--merge and --shard do not go together".into(),
            ));
        }
        merge_command(grid, out, from, quiet)?;
    } else {
        let shard = args
            .shard
            .as_deref()
            .map(parse_shard)
            .transpose()
            .map_err(Error::Other)?;
        study_command(grid, out, shard, quiet)?;
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_are_k_of_n_from_zero() {
        assert_eq!(parse_shard("0/8"), Ok((0, 8)));
        assert_eq!(parse_shard(" 7 / 8 "), Ok((7, 8)));
        assert!(parse_shard("8/8").unwrap_err().contains("0 ≤ K < N"));
        assert!(parse_shard("1/0").is_err());
        assert!(parse_shard("3").unwrap_err().contains("K/N"));
        assert!(parse_shard("a/2").is_err());
    }
}

//! The command line's input, read and checked before any work: case arguments expanded to
//! files, every case loaded and planned against the engines with all problems reported
//! together, worker-thread requests bounded.

use std::path::{Path, PathBuf};

use rockslide_core::case::{Case, discover, limits};
use rockslide_core::error::{Error, InputErrors};
use rockslide_engine_api::Engine;
use rockslide_verify::registry::{self, load_case};
use rockslide_verify::suite::plan;

/// The folders `run`, `check` and `list` read when given no case: the top-level cases and
/// the record cases. `cases/stability/` is not among them: its scenes are meant to break
/// engines and are classified by `rockslide stability`, not gated.
pub(crate) const DEFAULT_CASE_FOLDERS: &[&str] =
    &["cases", "cases/records", "cases/vertical", "cases/spatial"];

/// Expand case arguments: files as given, folders to their `*.toml`; with none, every
/// folder of [`DEFAULT_CASE_FOLDERS`] that exists (`cases/` itself must), found from the
/// current folder or, run from inside a checkout, from the nearest parent that has them.
pub(crate) fn case_paths(args: &[PathBuf]) -> Result<Vec<PathBuf>, Error> {
    if !args.is_empty() {
        return case_paths_or(args, "cases");
    }
    let root = checkout_root();
    // in the current folder the paths stay as written (`cases/x.toml`), as reports show them
    let at = |f: &str| match &root {
        Some(r) => r.join(f),
        None => PathBuf::from(f),
    };
    let first = at(DEFAULT_CASE_FOLDERS[0]);
    let mut out = case_paths_or(&[], &first.to_string_lossy())?;
    for folder in &DEFAULT_CASE_FOLDERS[1..] {
        let folder = at(folder);
        if folder.is_dir() {
            out.extend(case_paths_or(&[], &folder.to_string_lossy())?);
        }
    }
    Ok(out)
}

/// Where the default cases are read from when not from the current folder: the nearest
/// parent with `cases/` and `Cargo.toml` (run from a subfolder of the checkout). `None`:
/// the current folder (which has `cases/`, or its absence is reported).
pub(crate) fn checkout_root() -> Option<PathBuf> {
    if Path::new(DEFAULT_CASE_FOLDERS[0]).is_dir() {
        return None;
    }
    let cwd = std::env::current_dir().ok()?;
    cwd.ancestors()
        .skip(1)
        .find(|d| d.join(DEFAULT_CASE_FOLDERS[0]).is_dir() && d.join("Cargo.toml").is_file())
        .map(Path::to_path_buf)
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

/// Load every case first, so that all input errors are reported before any work; each
/// case's plausibility warnings (likely mistakes in valid values) go to stderr.
pub(crate) fn load_all(paths: &[PathBuf]) -> Result<Vec<Case>, Error> {
    let mut cases = Vec::new();
    let mut errors = Vec::new();
    for p in paths {
        match load_case(p) {
            Ok(c) => {
                for w in rockslide_core::case::plausibility::warnings(&c) {
                    eprintln!("{w}");
                }
                cases.push(c)
            }
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

/// Every case's engine options and variants checked against the engines (what `run`
/// checks before any work), all problems reported together.
pub(crate) fn plan_all(cases: &[Case], engines: &[Box<dyn Engine>]) -> Result<(), Error> {
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
pub(crate) fn load_planned(path: &Path) -> Result<Case, Error> {
    let case = load_case(path)?;
    plan_all(std::slice::from_ref(&case), &registry::all())?;
    Ok(case)
}

/// Worker threads: a request above [`limits::MAX_JOBS`] is lowered to it (0 stays, and
/// is refused by the options' own check).
pub(crate) fn bounded_jobs(jobs: Option<usize>) -> Option<usize> {
    jobs.map(|j| j.min(limits::MAX_JOBS))
}

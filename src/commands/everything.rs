//! The default command (`rockslide` with no command): the complete document. The
//! stability map of `cases/stability/`, the work-precision sweeps of the top-level
//! oscillator cases (cheap: each has an exact reference and runs in seconds per engine),
//! and every case of the default case folders, all three at once on every core in one
//! pool, the costliest cases first (`schedule.rs`). A case whose report shows a
//! sweep is written once its sweep is; the others as soon as they are run. Output order
//! is the cases' order, whatever finished first.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;

use rockslide_core::case::{Case, Model};
use rockslide_core::error::Error;
use rockslide_present::report::{OutputSet, WrittenCase, write_case_outputs_with};
use rockslide_verify::suite::{CaseResult, run_case};
use rockslide_verify::sweep::stability::study;
use rockslide_verify::sweep::work_precision::sweep_case;
use rockslide_verify::sweep::{Options, StabilityResult, SweepResult};
use rockslide_verify::timings;

use crate::commands::{stability, sweep};
use crate::input::{case_paths_or, checkout_root, load_all};
use crate::schedule::longest_first;
use crate::suite_run::{finish, prepare_cases};

/// Timed repeats of each sweep rung in the default command: one. The timing of a run is
/// reported as measured once; `rockslide sweep` (3 repeats by default) gives medians.
const DEFAULT_RUN_REPEATS: usize = 1;

/// Wall-time budget of one engine variant's sweep in the default command, s. Only rapier
/// on the rocking RPEPO scenes reaches it (its finer rungs cost seconds each); those rungs
/// are skipped and the sweep page says so. `rockslide sweep` keeps the full budget
/// ([`rockslide_verify::sweep::DEFAULT_BUDGET`]).
const DEFAULT_RUN_SWEEP_BUDGET: f64 = 3.0;

/// Run everything into `out` and write every page.
pub fn run(out: &Path, quiet: bool, set: OutputSet) -> Result<ExitCode, Error> {
    let options = Options {
        quiet,
        repeats: DEFAULT_RUN_REPEATS,
        budget: Some(DEFAULT_RUN_SWEEP_BUDGET),
        ..Default::default()
    };
    let work = load(out)?;
    let done = compute(work, &options, out, set);
    write(done, out, quiet, set)
}

/// What the default run computes, loaded and checked before any work.
struct Work {
    /// The scenes of `cases/stability/` (none when the folder is missing).
    stability: Vec<Case>,
    /// The top-level oscillator cases, which are swept.
    oscillators: Vec<Case>,
    /// Every case of the default case folders, planned.
    cases: Vec<Case>,
}

/// Load the stability scenes, the oscillators to sweep and the cases to run.
fn load(out: &Path) -> Result<Work, Error> {
    // from a subfolder of the checkout, its cases (as `run` finds them)
    let at = |f: &str| checkout_root().map_or_else(|| PathBuf::from(f), |r| r.join(f));
    let stability_folder = at("cases/stability");
    let stability = match stability_folder.is_dir() {
        true => load_all(&case_paths_or(std::slice::from_ref(&stability_folder), "")?)?,
        false => Vec::new(),
    };
    if stability_folder.is_dir() && stability.is_empty() {
        return Err(Error::Other("stability: no case files found".into()));
    }
    // Sweeps of the top-level oscillators only: a record case's Δt ladder is minutes long.
    let oscillators: Vec<Case> = load_all(&case_paths_or(&[], &at("cases").to_string_lossy())?)?
        .into_iter()
        .filter(|c| matches!(c.scene.model, Model::Oscillator(_)))
        .collect();
    // the lean set's file step is the output set's (`OutputSet::file_step`): the cases
    // are analysed as written
    let cases = prepare_cases(&[], out, &[], false)?;
    Ok(Work {
        stability,
        oscillators,
        cases,
    })
}

/// A case's outcome in the pool: its result, and its written pages unless it waits for
/// its sweep.
type CaseOutcome = (CaseResult, Option<WrittenCase>);

/// What the pool computed, each in its inputs' order.
struct Done {
    stability: Result<Option<StabilityResult>, Error>,
    sweeps: Vec<Result<SweepResult, Error>>,
    cases: Vec<Result<CaseOutcome, Error>>,
}

/// One pool, longest first: a task starts in the order it was spawned (FIFO). The
/// costliest cases first, one per core (their longest runs set the critical path: they
/// start at t = 0), then the stability map (many short runs; run before most case
/// results are held, its memory is freed early — run last it raised the peak RSS from
/// 524 to 735 MB), then the other cases by estimated cost, then the sweeps (short runs
/// that fill the cores' gaps at the end).
fn compute(work: Work, options: &Options, out: &Path, set: OutputSet) -> Done {
    let Work {
        stability: stability_cases,
        oscillators,
        cases,
    } = work;
    let swept: Vec<&str> = oscillators.iter().map(|c| c.name.as_str()).collect();
    let order = longest_first(&cases);
    let case_slots: Vec<Slot<CaseOutcome>> = cases.iter().map(|_| Mutex::new(None)).collect();
    let sweep_slots: Vec<Slot<SweepResult>> =
        oscillators.iter().map(|_| Mutex::new(None)).collect();
    let stability_slot: Slot<Option<StabilityResult>> = Mutex::new(None);
    let mut cases: Vec<Option<Case>> = cases.into_iter().map(Some).collect();
    rayon::scope_fifo(|s| {
        let (stability_cases, swept) = (&stability_cases, &swept);
        let spawn_case = |i: usize, case: Option<Case>| {
            let slot = &case_slots[i];
            s.spawn_fifo(move |_| {
                let Some(case) = case else { return };
                let write_now = !swept.contains(&case.name.as_str());
                fill(slot, run_one(case, write_now, out, set));
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
    Done {
        stability: taken(stability_slot),
        sweeps: sweep_slots.into_iter().map(taken).collect(),
        cases: case_slots.into_iter().map(taken).collect(),
    }
}

/// Run one case; write its outputs now (`write_now`, then its histories are released) or
/// once its sweep is there.
fn run_one(case: Case, write_now: bool, out: &Path, set: OutputSet) -> Result<CaseOutcome, Error> {
    run_case(case).map_err(Error::from).and_then(|mut result| {
        let written = write_now
            .then(|| write_case_outputs_with(&result, out, set))
            .transpose()?;
        if written.is_some() {
            result.release_histories();
        }
        Ok((result, written))
    })
}

/// Write the stability map, the sweeps, the pages of the cases that waited for their
/// sweep, then the suite's pages.
fn write(done: Done, out: &Path, quiet: bool, set: OutputSet) -> Result<ExitCode, Error> {
    use rayon::prelude::*;
    let sweeps: Result<Vec<_>, Error> = done.sweeps.into_iter().collect();
    if let Some(r) = done.stability? {
        stability::write(&r, out, quiet)?;
    }
    for r in &sweeps? {
        sweep::write(r, out, quiet)?;
    }
    // the swept cases' pages show their sweep: written now that it is there
    let written: Vec<Result<(CaseResult, WrittenCase), Error>> = done
        .cases
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

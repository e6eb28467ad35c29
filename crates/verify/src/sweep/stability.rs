//! `rockslide stability`: the stiff and extreme scenes (`cases/stability/*.toml`) run by
//! every applicable engine and variant at Δt/T from 1/100 to 1 (beyond T/2), each run
//! classified as accurate, inaccurate, diverged (with its time) or not converged, and for
//! each engine variant the practical stability limit in Δt/T: the ladder brackets the
//! first divergence, then bisection on the scenes that diverged there narrows it.
//!
//! The result, [`StabilityResult`], is written as `<out>/stability/stability.json`
//! ([`StabilityResult::save`]) and read back by the suite report
//! ([`StabilityResult::load`]); `rockslide-present` renders its map and limits. The same
//! scenes give the same `stability.json` byte for byte, whatever the number of workers:
//! the worker count and the wall time of each run ([`StabilityTiming`]) are saved apart,
//! in `stability-timing.json`.

use std::collections::BTreeSet;
use std::path::Path;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::Options;
use super::plan::{Series, applicable, characteristic_period, fine_grid};
use crate::analysis::energy::{EnergySummary, audit};
use crate::analysis::history_difference;
use crate::analysis::stability::{Class, Criteria, classify};
use crate::analysis::sweep::{exact_channel_cached, resample_channel};
use crate::registry;
use crate::run::{Timed, guarded};
use rockslide_core::case::Case;
use rockslide_core::error::{Error, InputErrors};
use rockslide_core::trace::q;
use rockslide_engine_api::{Engine, Variant};
use rockslide_reference::ExactSolution;

/// Between a row label's case and series ([`StabilityRun::row_label`]).
const ROW_SEPARATOR: &str = " · ";

/// Folder of the study in the output folder, and the typed result's file name in it.
pub const DIR: &str = "stability";
/// File name of the typed result in [`DIR`].
pub const FILE: &str = "stability.json";
/// File name of the timing part in [`DIR`] (worker count, wall times).
pub const TIMING_FILE: &str = "stability-timing.json";

/// The Δt/T ladder every stability scene is run at: from T/100 to T (beyond T/2).
pub const DT_OVER_T: &[f64] = &[0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0];

/// Bisection steps refining a stability limit (bracket shrinks by 2¹²).
const BISECTIONS: usize = 12;

/// One classified run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StabilityRun {
    /// Case name.
    pub case: String,
    /// `engine/variant`.
    pub series: String,
    /// Time step, s.
    pub dt: f64,
    /// Δt / T.
    pub dt_over_t: f64,
    /// The class.
    pub class: Class,
    /// Max error of the primary displacement, normalised by its peak, against the basis.
    #[serde(with = "crate::json::real_opt")]
    pub error: Option<f64>,
    /// Energy audit, or why there is none.
    pub energy: Result<EnergySummary, String>,
}

impl StabilityRun {
    /// Row label of the map: `case · engine/variant`.
    pub fn row_label(&self) -> String {
        format!("{}{ROW_SEPARATOR}{}", self.case, self.series)
    }

    /// Whether this run belongs to the map's row `label` ([`Self::row_label`]), compared
    /// without building the label: the map's table and figure ask once per run and row.
    pub fn is_row(&self, label: &str) -> bool {
        label
            .strip_prefix(self.case.as_str())
            .and_then(|rest| rest.strip_prefix(ROW_SEPARATOR))
            == Some(self.series.as_str())
    }
}

/// The stability limit of one engine variant.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Limit {
    /// `engine/variant`.
    pub label: String,
    /// Smallest ladder Δt/T at which some scene diverged, and the scenes that did.
    pub first_diverged: Option<(f64, Vec<String>)>,
    /// Largest ladder Δt/T below that at which no scene diverged.
    pub stable_up_to: Option<f64>,
    /// Bisection bracket (stable Δt/T, diverged Δt/T) and the scene that set it.
    pub refined: Option<(f64, f64, String)>,
    /// Largest ladder Δt/T up to which every run of every scene was accurate.
    pub accurate_up_to: Option<f64>,
}

impl Limit {
    /// The practical limit in Δt/T: the bisection bracket's midpoint, else the first
    /// diverging rung.
    pub fn limit(&self) -> Option<f64> {
        match (&self.refined, &self.first_diverged) {
            (Some((lo, hi, _)), _) => Some(0.5 * (lo + hi)),
            (None, Some((x, _))) => Some(*x),
            _ => None,
        }
    }
}

/// A scene of the study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Scene {
    /// Case name.
    pub name: String,
    /// Case title.
    pub title: String,
    /// Characteristic period T, s.
    pub period: f64,
    /// What errors are measured against, in words.
    pub basis: String,
}

/// An engine that does not apply to a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NotApplicable {
    /// Case name.
    pub scene: String,
    /// Engine id.
    pub engine: String,
    /// Why.
    pub why: String,
}

/// The whole study: the typed result of `rockslide stability`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StabilityResult {
    /// The scenes.
    pub cases: Vec<Scene>,
    /// Every run, scene by scene, series by series, Δt ascending.
    pub runs: Vec<StabilityRun>,
    /// One per engine variant.
    pub limits: Vec<Limit>,
    /// Engines that do not apply to a scene.
    pub not_applicable: Vec<NotApplicable>,
    /// The classification criteria.
    pub criteria: Criteria,
    /// Worker count and wall times: saved apart from the result (`stability-timing.json`),
    /// so that `stability.json` depends on the scenes and the build only.
    #[serde(skip)]
    pub timing: StabilityTiming,
}

/// The wall-clock side of a stability study: how many workers ran it and how long each
/// run took. Differs between reruns and thread counts, unlike the rest of the result.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct StabilityTiming {
    /// Worker threads used.
    pub threads: usize,
    /// Wall time of each run, s, in the order of [`StabilityResult::runs`].
    pub runs: Vec<RunTime>,
}

/// The wall time of one run of the ladder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunTime {
    /// Case name.
    pub case: String,
    /// `engine/variant`.
    pub series: String,
    /// Δt / T.
    pub dt_over_t: f64,
    /// Wall time, s ("NaN" when the run was not timed).
    #[serde(with = "crate::json::real")]
    pub seconds: f64,
}

impl StabilityResult {
    /// The Δt/T ladder every scene was run at.
    pub fn ladder(&self) -> &'static [f64] {
        DT_OVER_T
    }

    /// Write `stability.json` and its timing part, `stability-timing.json`, into `dir`
    /// (`<out>/stability/`).
    pub fn save(&self, dir: &Path) -> Result<(), Error> {
        crate::json::write(&dir.join(FILE), self)?;
        crate::json::write(&dir.join(TIMING_FILE), &self.timing)
    }

    /// Read `stability.json` from `dir`: `None` when there is none, else the result or
    /// why it could not be read. The timing part is read too when it is there and
    /// readable (it is not needed to render the result).
    pub fn load(dir: &Path) -> Option<Result<StabilityResult, String>> {
        let path = dir.join(FILE);
        path.exists().then(|| {
            let mut r: StabilityResult = crate::json::read(&path)?;
            r.timing = crate::json::read(&dir.join(TIMING_FILE)).unwrap_or_default();
            Ok(r)
        })
    }

    /// Row labels of the map, in order.
    pub fn rows(&self) -> Vec<String> {
        let mut seen = BTreeSet::new();
        self.runs
            .iter()
            .map(|r| r.row_label())
            .filter(|l| seen.insert(l.clone()))
            .collect()
    }
}

/// What a scene's runs are measured against when it has an exact reference: the solution,
/// sampled at each run's rows, and the peak of its primary displacement that normalises
/// the errors. The map reads nothing else of the reference, so it is not sampled on a fine
/// grid as a trace, nor are its other response quantities computed.
pub struct ExactBasis {
    /// The solution.
    pub solution: Box<dyn ExactSolution>,
    /// Peak |relative displacement|, m: the solution's exact value where it knows one,
    /// else the largest sample on the fine grid of [`fine_grid`] (`None`: the solution
    /// has no relative displacement).
    pub peak: Option<f64>,
}

/// The exact basis of a case, or why there is none.
pub fn exact_basis(case: &Case) -> Result<ExactBasis, String> {
    let solution = rockslide_reference::for_case(case)?;
    let key = "peak_relative_displacement";
    let exact = solution
        .exact_quantities()
        .into_iter()
        .rfind(|(k, _)| *k == key)
        .map(|(_, v)| v);
    let peak = exact.or_else(|| grid_peak(solution.as_ref(), case.run.duration));
    Ok(ExactBasis { solution, peak })
}

/// Largest |relative displacement| of `solution` on the fine uniform grid over
/// `duration`, the same times and fold as a sampled trace's peak (`None` without the
/// channel). Nothing is kept but the running maximum.
fn grid_peak(solution: &dyn ExactSolution, duration: f64) -> Option<f64> {
    let channels = solution.channels();
    let j = channels.iter().position(|c| c.key == q::REL_DISP.key)?;
    let n = fine_grid(duration);
    let mut row = vec![0.0; channels.len()];
    let mut peak = 0.0_f64;
    for i in 0..=n {
        solution.eval(duration * i as f64 / n as f64, &mut row);
        peak = peak.max(row[j].abs());
    }
    Some(peak)
}

/// What one run is classified from: its class, its error against the basis and its
/// energy audit.
type Classified = (Class, Option<f64>, Result<EnergySummary, String>);

/// Whether one run diverged: all a bisection step needs (the error against the basis
/// only separates accurate from inaccurate, so it is not computed).
fn diverged(case: &Case, timed: &Timed, criteria: &Criteria) -> bool {
    classify_run(case, timed, None, None, criteria, &mut None)
        .0
        .diverged()
}

/// Max error of a completed run's primary displacement against the reference (normalised
/// by the reference's peak), else against `own` (by the peak of its samples at the run's
/// rows); `None` without a basis or the channel. `sampled` keeps the reference at the
/// last rows it was sampled at (the other runs of the rung share them).
fn error_against(
    trace: &rockslide_core::trace::Trace,
    reference: Option<&ExactBasis>,
    own: Option<&rockslide_core::trace::Trace>,
    sampled: &mut Option<rockslide_core::trace::Trace>,
) -> Option<f64> {
    let key = q::REL_DISP.key;
    match (reference, own) {
        (Some(r), _) => {
            let at = exact_channel_cached(sampled, r.solution.as_ref(), key, &trace.time)?;
            // Normalise by the reference's true peak, not by the peak of its samples at
            // the run's rows: at Δt = T those can all sit near a zero of the response and
            // inflate the error by orders.
            let sampled = at
                .column(key)
                .map_or(0.0, |c| c.iter().fold(0.0_f64, |m, v| m.max(v.abs())));
            let peak = r.peak.map_or(sampled, |p| p.abs().max(sampled));
            history_difference(trace, at, key).map(|e| {
                if peak > 0.0 {
                    e.0 * sampled / peak
                } else {
                    e.0
                }
            })
        }
        (None, Some(b)) => {
            let at = resample_channel(b, key, &trace.time)?;
            history_difference(trace, &at, key).map(|e| e.0)
        }
        _ => None,
    }
}

/// Classify one run on `case` at `dt` against the reference (or `own`, the
/// series' finest run, when there is no reference); `sampled`: the reference at the rung's
/// rows, kept between the runs of one rung ([`exact_channel_cached`]).
fn classify_run(
    case: &Case,
    timed: &Timed,
    reference: Option<&ExactBasis>,
    own: Option<&rockslide_core::trace::Trace>,
    criteria: &Criteria,
    sampled: &mut Option<rockslide_core::trace::Trace>,
) -> Classified {
    match &timed.run {
        Err(panic) => (
            classify(
                Err(panic),
                &rockslide_core::trace::Trace::default(),
                None,
                None,
                criteria,
            ),
            None,
            Err("no trace: the engine panicked".into()),
        ),
        Ok(run) => {
            let energy = audit(&run.trace, &case.scene, run.arrangement);
            let error = if run.status.completed() {
                error_against(&run.trace, reference, own, sampled)
            } else {
                None
            };
            // (An absolute energy ceiling, `Criteria::energy_ceiling`, is not used here:
            // the paper's Eq 12 route is *given* spurious energy by its own input — the
            // balance closes — and must not count as a numerical blow-up.)
            let class = classify(
                Ok(&run.status),
                &run.trace,
                energy.as_ref().ok(),
                error,
                criteria,
            );
            (class, error, energy.map(|h| h.summary()))
        }
    }
}

/// Run and classify every scene.
pub fn study(cases: &[Case], opts: &Options) -> Result<StabilityResult, Error> {
    opts.validate()?;
    let cases: &[Case] = &cases
        .iter()
        .map(registry::for_stability)
        .collect::<Vec<_>>();
    let criteria = Criteria::default();
    let engines = registry::all();
    let (plans, not_applicable) = plan_series(cases, &engines)?;
    let periods: Vec<f64> = cases.iter().map(|c| characteristic_period(c).0).collect();
    let (timed, references, threads) = run_ladders(cases, &engines, &plans, &periods, opts)?;
    let (runs, times) = classify_all(cases, &plans, &timed, &references, &periods, &criteria);
    let limits = limits_of(&plans, &engines, cases, &periods, &runs, &criteria);
    Ok(StabilityResult {
        cases: scenes(cases, &references, &periods),
        runs,
        limits,
        not_applicable,
        criteria,
        timing: StabilityTiming {
            threads,
            runs: times,
        },
    })
}

/// The series (engine variants) that apply to each scene, and the engines that do not
/// apply to one (with why); every scene's input errors at once.
fn plan_series(
    cases: &[Case],
    engines: &[Box<dyn Engine>],
) -> Result<(Vec<Vec<Series>>, Vec<NotApplicable>), Error> {
    let mut plans = Vec::new();
    let mut not_applicable = Vec::new();
    let mut errors = Vec::new();
    for c in cases {
        match applicable(c, engines) {
            Ok((series, na)) => {
                not_applicable.extend(na.into_iter().map(|(engine, why)| NotApplicable {
                    scene: c.name.clone(),
                    engine,
                    why,
                }));
                plans.push(series);
            }
            Err(e) => errors.extend(e.0),
        }
    }
    if !errors.is_empty() {
        return Err(InputErrors(errors).into());
    }
    Ok((plans, not_applicable))
}

/// A scene's exact basis, or why it has none.
type Basis = Result<ExactBasis, String>;

/// Every series of every scene run at every rung of the ladder (in parallel, guarded),
/// beside every scene's exact basis: the runs in scene, series, rung order, the bases,
/// and the threads used.
fn run_ladders(
    cases: &[Case],
    engines: &[Box<dyn Engine>],
    plans: &[Vec<Series>],
    periods: &[f64],
    opts: &Options,
) -> Result<(Vec<Timed>, Vec<Basis>, usize), Error> {
    let tasks: Vec<(usize, &Series, f64)> = plans
        .iter()
        .enumerate()
        .flat_map(|(ci, series)| {
            let t = periods[ci];
            series
                .iter()
                .flat_map(move |s| DT_OVER_T.iter().map(move |x| (ci, s, x * t)))
        })
        .collect();
    let bar = crate::progress::bar(tasks.len(), !opts.quiet, "runs", "stability");
    let (timed, references, threads) = opts.install(tasks.len(), || {
        let (timed, references) = rayon::join(
            || {
                tasks
                    .par_iter()
                    .map(|(ci, s, dt)| {
                        let r = guarded(engines[s.engine].as_ref(), &cases[*ci], s.variant, *dt, 1);
                        bar.inc(1);
                        r
                    })
                    .collect::<Vec<_>>()
            },
            || cases.par_iter().map(exact_basis).collect::<Vec<_>>(),
        );
        (timed, references, rayon::current_num_threads())
    })?;
    bar.finish_and_clear();
    let timed: Vec<Timed> = timed
        .into_iter()
        .collect::<Result<_, _>>()
        .map_err(InputErrors::from)?;
    Ok((timed, references, threads))
}

/// Every run classified against its scene's basis (the exact reference, else the finest
/// completed run of its series), with its wall time.
fn classify_all(
    cases: &[Case],
    plans: &[Vec<Series>],
    timed: &[Timed],
    references: &[Basis],
    periods: &[f64],
    criteria: &Criteria,
) -> (Vec<StabilityRun>, Vec<RunTime>) {
    let mut runs = Vec::new();
    let mut times = Vec::new();
    let mut k = 0;
    for (ci, series) in plans.iter().enumerate() {
        let case = &cases[ci];
        let reference = references[ci].as_ref().ok();
        // The reference at each rung's rows, shared by the runs of the rung.
        let mut sampled: Vec<Option<rockslide_core::trace::Trace>> = vec![None; DT_OVER_T.len()];
        for s in series {
            let block = &timed[k..k + DT_OVER_T.len()];
            k += DT_OVER_T.len();
            // Without a reference, the finest completed run of the series is the basis.
            let own = if reference.is_none() {
                block
                    .iter()
                    .find_map(|t| t.run.as_ref().ok().filter(|r| r.status.completed()))
                    .map(|r| &r.trace)
            } else {
                None
            };
            for ((t, x), at) in block.iter().zip(DT_OVER_T).zip(&mut sampled) {
                let (class, error, energy) = classify_run(case, t, reference, own, criteria, at);
                runs.push(StabilityRun {
                    case: case.name.clone(),
                    series: s.label(),
                    dt: x * periods[ci],
                    dt_over_t: *x,
                    class,
                    error,
                    energy,
                });
                times.push(RunTime {
                    case: case.name.clone(),
                    series: s.label(),
                    dt_over_t: *x,
                    seconds: t.seconds.first().copied().unwrap_or(f64::NAN),
                });
            }
        }
    }
    (runs, times)
}

/// The stability limit of each engine variant (in first-seen order), over every scene.
fn limits_of(
    plans: &[Vec<Series>],
    engines: &[Box<dyn Engine>],
    cases: &[Case],
    periods: &[f64],
    runs: &[StabilityRun],
    criteria: &Criteria,
) -> Vec<Limit> {
    let mut labels: Vec<(String, usize, Variant)> = Vec::new();
    for series in plans {
        for s in series {
            if !labels.iter().any(|l| l.0 == s.label()) {
                labels.push((s.label(), s.engine, s.variant));
            }
        }
    }
    labels
        .iter()
        .map(|(label, ei, variant)| {
            limit_of(
                label,
                engines[*ei].as_ref(),
                *variant,
                cases,
                periods,
                runs,
                criteria,
            )
        })
        .collect()
}

/// Each scene with its period and what its runs are measured against.
fn scenes(cases: &[Case], references: &[Basis], periods: &[f64]) -> Vec<Scene> {
    cases
        .iter()
        .zip(references)
        .zip(periods)
        .map(|((c, r), t)| {
            let basis = match r {
                Ok(r) => format!("exact reference: {}", r.solution.name()),
                Err(_) => "own finest run (no exact reference)".into(),
            };
            Scene {
                name: c.name.clone(),
                title: c.title.clone(),
                period: *t,
                basis,
            }
        })
        .collect()
}

/// Bracket the first divergence of one engine variant on the ladder, then bisect it on
/// every scene that diverged there (in parallel; the smallest bracket wins). Bisection
/// assumes that once a scene diverges, larger steps diverge too.
#[allow(clippy::too_many_arguments)]
fn limit_of(
    label: &str,
    engine: &dyn Engine,
    variant: Variant,
    cases: &[Case],
    periods: &[f64],
    runs: &[StabilityRun],
    criteria: &Criteria,
) -> Limit {
    let mine: Vec<&StabilityRun> = runs.iter().filter(|r| r.series == label).collect();
    let first = mine
        .iter()
        .filter(|r| r.class.diverged())
        .map(|r| r.dt_over_t)
        .fold(f64::INFINITY, f64::min);
    let accurate_up_to = DT_OVER_T
        .iter()
        .take_while(|&&x| {
            mine.iter()
                .filter(|r| r.dt_over_t == x)
                .all(|r| r.class == Class::Accurate)
        })
        .last()
        .copied();
    if !first.is_finite() {
        return Limit {
            label: label.into(),
            first_diverged: None,
            stable_up_to: DT_OVER_T.last().copied(),
            refined: None,
            accurate_up_to,
        };
    }
    let diverged_cases: Vec<String> = mine
        .iter()
        .filter(|r| r.class.diverged() && r.dt_over_t == first)
        .map(|r| r.case.clone())
        .collect();
    let stable = DT_OVER_T.iter().copied().rfind(|&x| x < first);
    let refined = stable.and_then(|lo0| {
        let scenes: Vec<(&Case, f64)> = diverged_cases
            .iter()
            .filter_map(|name| {
                let ci = cases.iter().position(|c| &c.name == name)?;
                Some((&cases[ci], periods[ci]))
            })
            .collect();
        let bisection = Bisection {
            engine,
            variant,
            criteria,
            bracket: (lo0, first),
        };
        bisection
            .together(&scenes)
            .unwrap_or_else(|| bisection.each(&scenes))
    });
    Limit {
        label: label.into(),
        first_diverged: Some((first, diverged_cases)),
        stable_up_to: stable,
        refined,
        accurate_up_to,
    }
}

/// The bisection of one engine variant's stability limit in Δt/T, from the ladder's
/// bracket (the largest stable rung, the first diverged rung), on the scenes that
/// diverged there. Its result is the smallest bracket [`BISECTIONS`] halvings give on any
/// scene, and the first such scene in the scenes' order.
struct Bisection<'a> {
    engine: &'a dyn Engine,
    variant: Variant,
    criteria: &'a Criteria,
    bracket: (f64, f64),
}

impl Bisection<'_> {
    /// Whether `case` (period `t`) diverges at Δt/T = `x`; `None` when the engine refuses
    /// the input.
    fn diverges(&self, case: &Case, t: f64, x: f64) -> Option<bool> {
        let timed = guarded(self.engine, case, self.variant, x * t, 1).ok()?;
        Some(diverged(case, &timed, self.criteria))
    }

    /// Every scene bisected on its own, in parallel: each scene's own bracket, the
    /// smallest upper end wins (the first scene on a tie). A scene whose run the engine
    /// refuses drops out.
    fn each(&self, scenes: &[(&Case, f64)]) -> Option<(f64, f64, String)> {
        scenes
            .par_iter()
            .filter_map(|&(case, t)| {
                let (mut lo, mut hi) = self.bracket;
                for _ in 0..BISECTIONS {
                    let mid = 0.5 * (lo + hi);
                    if self.diverges(case, t, mid)? {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                Some((lo, hi, case.name.clone()))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The result of [`Self::each`] with fewer runs: the scenes are bisected in step, one
    /// shared bracket. At a midpoint where some scenes diverge, the others drop out: their
    /// own brackets would stay above the midpoint while the diverged ones end at or below
    /// it, so they cannot set the smallest bracket. `None` when the engine refuses a run
    /// (then a dropped scene could still have won: [`Self::each`] decides).
    fn together(&self, scenes: &[(&Case, f64)]) -> Option<Option<(f64, f64, String)>> {
        let mut alive: Vec<(&Case, f64)> = scenes.to_vec();
        let (mut lo, mut hi) = self.bracket;
        for _ in 0..BISECTIONS {
            if alive.is_empty() {
                break;
            }
            let mid = 0.5 * (lo + hi);
            let diverged: Vec<bool> = alive
                .par_iter()
                .map(|&(case, t)| self.diverges(case, t, mid))
                .collect::<Option<_>>()?;
            if diverged.contains(&true) {
                hi = mid;
                let mut keep = diverged.iter();
                alive.retain(|_| *keep.next().expect("one flag a scene"));
            } else {
                lo = mid;
            }
        }
        Some(alive.first().map(|(case, _)| (lo, hi, case.name.clone())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run belongs to the row its label names and to no other, the label never built.
    #[test]
    fn a_run_is_in_the_row_of_its_label_only() {
        let run = StabilityRun {
            case: "mu-large".into(),
            series: "fe/single".into(),
            dt: 0.01,
            dt_over_t: 0.05,
            class: Class::Accurate,
            error: None,
            energy: Err(String::new()),
        };
        assert!(run.is_row(&run.row_label()));
        assert!(run.is_row("mu-large · fe/single"));
        for other in [
            "mu-large · fe/double",
            "mu-large · fe/single ",
            "mu-larg · fe/single",
            "mu-large  fe/single",
            "mu-large · ",
            "",
        ] {
            assert!(!run.is_row(other), "{other:?}");
        }
    }

    /// The stability scenes shipped with the repository.
    fn scenes(names: &[&str]) -> Vec<Case> {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/stability");
        names
            .iter()
            .map(|n| registry::load_case(&dir.join(format!("{n}.toml"))).expect("a shipped case"))
            .collect()
    }

    /// The map's peak is the one the case reports measure: the solution's exact value, else
    /// the peak of the fine-grid trace `solve_reference` samples, bit for bit.
    #[test]
    fn the_exact_basis_peak_is_the_sampled_references_peak() {
        let cases = scenes(&[
            "explicit-limit",
            "mu-large",
            "stiff-ratio-1e4",
            "rocking-10g",
        ]);
        let mut compared = 0;
        for case in &cases {
            let (Ok(basis), Ok(full)) = (exact_basis(case), crate::suite::solve_reference(case))
            else {
                continue;
            };
            let sampled = full.responses.get("peak_relative_displacement").copied();
            assert_eq!(
                basis.peak.map(f64::to_bits),
                sampled.map(f64::to_bits),
                "{}",
                case.name
            );
            compared += 1;
        }
        assert!(
            compared >= 3,
            "only {compared} scenes have an exact reference"
        );
    }

    /// Bisecting the scenes in step and dropping those that cannot win gives the bracket
    /// and scene of bisecting every scene on its own: here the predictor-corrector, whose
    /// limit 1/π is reached on the undamped `explicit-limit` and not on the others.
    #[test]
    fn bisecting_together_gives_the_bracket_of_bisecting_each() {
        let cases = scenes(&["mu-large", "explicit-limit", "long-run"]);
        let engines = registry::all();
        let pc = engines
            .iter()
            .find(|e| e.id() == "predictor-corrector")
            .expect("registered");
        let scenes: Vec<(&Case, f64)> = cases
            .iter()
            .map(|c| (c, characteristic_period(c).0))
            .collect();
        let bisection = Bisection {
            engine: pc.as_ref(),
            variant: pc.variants(&cases[0].scene).expect("applies")[0],
            criteria: &Criteria::default(),
            bracket: (0.3, 0.4),
        };
        let each = bisection.each(&scenes).expect("a limit");
        let together = bisection.together(&scenes).expect("no refused run");
        assert_eq!(together, Some(each.clone()));
        assert!(each.0 < 1.0 / std::f64::consts::PI && 1.0 / std::f64::consts::PI < each.1);
    }
}

//! Running a study: every point of a grid (or of one shard of it) in parallel with rayon,
//! a progress bar on a terminal, one result file per point written atomically as soon as
//! the point is done. A point whose result file exists with the same hash is skipped, so
//! an interrupted study resumes where it stopped; the counts of executed and skipped
//! points are returned (deterministic counters, not times).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::grid::{Grid, GridPoint};
use crate::analysis::responses;
use crate::registry;
use crate::run::{Outcome, guarded};
use crate::suite::plan;
use rockslide_core::case::{Excitation, Model, Signal};
use rockslide_core::error::{Error, InputErrors};
use rockslide_core::io::write_atomically;
use rockslide_reference::EpoRecord;
use rockslide_reference::newmark_record::{Sliding, rigid_block};

/// One engine run of a point, reduced to the numbers a study tabulates (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    /// Engine id (`newmark-rigid` for the rigid-block reference).
    pub engine: String,
    /// Variant.
    pub variant: String,
    /// Time step, s.
    pub dt: f64,
    /// `completed`, `diverged`, `not converged`, `panicked`, with the reason when not
    /// completed.
    pub status: String,
    /// Sliding at the end of the run, m (mass minus ground, the PEPO's xp).
    #[serde(with = "crate::json::real_opt")]
    pub residual_sliding: Option<f64>,
    /// Largest |sliding| during the run, m.
    #[serde(with = "crate::json::real_opt")]
    pub peak_abs_sliding: Option<f64>,
    /// Largest |relative displacement|, m.
    #[serde(with = "crate::json::real_opt")]
    pub peak_relative_displacement: Option<f64>,
    /// Number of slip episodes (the exact references count them; engines leave it empty).
    #[serde(default)]
    pub slip_episodes: Option<u64>,
    /// Total distance slid, m (sum of |slip| over the episodes; exact references only).
    #[serde(default)]
    #[serde(with = "crate::json::real_opt")]
    pub total_slid: Option<f64>,
    /// First slip onset, s.
    #[serde(default)]
    #[serde(with = "crate::json::real_opt")]
    pub slip_start: Option<f64>,
    /// Last slip stop, s.
    #[serde(default)]
    #[serde(with = "crate::json::real_opt")]
    pub slip_end: Option<f64>,
    /// Steps taken (deterministic counter).
    pub steps: u64,
    /// Wall time of the run, s (informative only: never in summaries).
    #[serde(with = "crate::json::real")]
    pub wall_seconds: f64,
    /// Largest resultant sliding |p| in plan, m (3D scenes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[serde(with = "crate::json::real_opt")]
    pub peak_resultant_sliding: Option<f64>,
    /// Resultant sliding |p| in plan at the end of the run, m (3D scenes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[serde(with = "crate::json::real_opt")]
    pub residual_resultant_sliding: Option<f64>,
    /// Largest uplift, m (a rocking body's supports; the oscillator's flights in the
    /// plan reference).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[serde(with = "crate::json::real_opt")]
    pub peak_uplift: Option<f64>,
    /// Largest |rotation|, rad (a rocking body).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[serde(with = "crate::json::real_opt")]
    pub peak_rotation: Option<f64>,
}

impl RunSummary {
    /// A run with a status and no numbers yet.
    fn empty(engine: &str, variant: &str, dt: f64, status: String) -> Self {
        RunSummary {
            engine: engine.into(),
            variant: variant.into(),
            dt,
            status,
            residual_sliding: None,
            peak_abs_sliding: None,
            peak_relative_displacement: None,
            slip_episodes: None,
            total_slid: None,
            slip_start: None,
            slip_end: None,
            steps: 0,
            wall_seconds: f64::NAN,
            peak_resultant_sliding: None,
            residual_resultant_sliding: None,
            peak_uplift: None,
            peak_rotation: None,
        }
    }

    /// |residual sliding|: the resultant in plan for a 3D scene, else along x, m.
    pub fn residual_magnitude(&self) -> Option<f64> {
        self.residual_resultant_sliding
            .or(self.residual_sliding.map(f64::abs))
    }

    /// Peak |sliding|: the resultant in plan for a 3D scene, else along x, m.
    pub fn peak_magnitude(&self) -> Option<f64> {
        self.peak_resultant_sliding.or(self.peak_abs_sliding)
    }
}

/// The result file of one grid point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PointResult {
    /// Hash of everything that shaped the result ([`Grid::point_hash`]).
    pub hash: String,
    /// The point.
    pub point: GridPoint,
    /// Record name as written in the grid.
    pub record: String,
    /// PGA it ran at, m/s².
    pub pga: f64,
    /// Factor applied to the record as recorded (× polarity excluded).
    pub scale_factor: f64,
    /// Friction coefficient it ran with (∞ for no slip, written `"inf"`).
    #[serde(with = "crate::json::real")]
    pub mu: f64,
    /// The excitation's label (file, scaling, polarity, resampling note).
    pub excitation: String,
    /// Engines that do not apply to the model, with why.
    pub not_applicable: Vec<(String, String)>,
    /// One entry per engine run, then the rigid block when the grid asks for it.
    pub runs: Vec<RunSummary>,
}

/// What a study invocation did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StudyOutcome {
    /// Points in the grid.
    pub points: usize,
    /// Points this invocation was responsible for (its shard).
    pub assigned: usize,
    /// Points run now.
    pub executed: usize,
    /// Points skipped because a matching result existed.
    pub skipped: usize,
    /// Engine runs made now (rigid-block runs included).
    pub runs: usize,
}

/// Options of a study invocation.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyOptions {
    /// Output folder: result files go to `<out>/runs/`.
    pub out: PathBuf,
    /// Shard `(k, n)`, 0-based k < n; `None` = the whole grid.
    pub shard: Option<(usize, usize)>,
    /// Show a progress bar (still hidden when stderr is not a terminal or `CI` is set).
    pub progress: bool,
}

/// Folder of the per-point result files.
pub fn runs_dir(out: &Path) -> PathBuf {
    out.join("runs")
}

/// Path of a point's result file.
pub fn result_path(out: &Path, p: &GridPoint) -> PathBuf {
    runs_dir(out).join(format!("{}.json", p.id()))
}

/// Read a result file if it exists and parses.
pub fn read_result(path: &Path) -> Option<PointResult> {
    let text = std::fs::read_to_string(path).ok()?;
    serde_json::from_str(&text).ok()
}

/// Whether `r` is the result of point `p` of `grid`: its hash and its point both match.
pub fn matches(grid: &Grid, r: &PointResult, p: &GridPoint) -> bool {
    r.hash == grid.point_hash(p) && r.point == *p
}

/// Whether a point already has a result matching it in `out`.
pub fn is_done(grid: &Grid, out: &Path, p: &GridPoint) -> bool {
    read_result(&result_path(out, p)).is_some_and(|r| matches(grid, &r, p))
}

/// Run the grid's points (or those of one shard) that have no matching result yet.
pub fn run_study(grid: &Grid, opts: &StudyOptions) -> Result<StudyOutcome, Error> {
    let assigned: Vec<&GridPoint> = match opts.shard {
        Some((k, n)) => grid.shard(k, n),
        None => grid.points.iter().collect(),
    };
    // Check the base case's engine plan once, before any work.
    let engines = registry::all();
    plan(&grid.base, &engines)?;
    let todo: Vec<&GridPoint> = assigned
        .iter()
        .copied()
        .filter(|p| !is_done(grid, &opts.out, p))
        .collect();
    let executed = AtomicUsize::new(0);
    let runs = AtomicUsize::new(0);
    let pb = crate::progress::bar(todo.len(), opts.progress, "points", "study");
    let results: Vec<Result<(), Error>> = todo
        .par_iter()
        .map(|p| {
            let result = run_point(grid, p, &engines)?;
            runs.fetch_add(result.runs.len(), Ordering::Relaxed);
            let json = serde_json::to_string_pretty(&result)
                .map_err(|e| Error::Other(format!("cannot serialise {}: {e}", p.id())))?;
            write_atomically(&result_path(&opts.out, p), json.as_bytes())?;
            executed.fetch_add(1, Ordering::Relaxed);
            pb.inc(1);
            Ok(())
        })
        .collect();
    pb.finish_and_clear();
    for r in results {
        r?;
    }
    Ok(StudyOutcome {
        points: grid.points.len(),
        assigned: assigned.len(),
        executed: executed.into_inner(),
        skipped: assigned.len() - todo.len(),
        runs: runs.into_inner(),
    })
}

/// The study's anchor: the PEPO's exact solution under the point's record (ground
/// acceleration piecewise linear between samples) when the model is a planar oscillator
/// with no vertical component, the plan-motion reference for a 3D scene. A point the
/// exact reference cannot solve gets a status saying why.
fn exact_summary(case: &rockslide_core::case::Case) -> Option<RunSummary> {
    if case.scene.spatial().is_some() {
        return Some(plan_summary(case));
    }
    let Model::Oscillator(osc) = &case.scene.model else {
        return None;
    };
    // The planar record solution: no vertical component, no plan motion.
    if case.scene.vertical().is_some() {
        return None;
    }
    let start = Instant::now();
    let dt = match case.scene.excitation.signal() {
        Some(Signal::Record { dt, .. }) => *dt,
        _ => return None,
    };
    let exact = match EpoRecord::for_excitation(osc, &case.scene.excitation, case.run.duration) {
        Ok(exact) => exact,
        Err(why) => {
            return Some(RunSummary {
                wall_seconds: start.elapsed().as_secs_f64(),
                ..RunSummary::empty(
                    EXACT,
                    "epo-record",
                    dt,
                    format!("no exact reference: {why}"),
                )
            });
        }
    };
    let (_, _, _, residual) = exact.state(case.run.duration);
    Some(RunSummary {
        residual_sliding: Some(residual + 0.0),
        peak_abs_sliding: Some(exact.peak_abs_slip()),
        peak_relative_displacement: Some(exact.peak_abs_u),
        slip_episodes: Some(exact.slips.len() as u64),
        total_slid: Some(exact.total_slid()),
        slip_start: exact.slips.first().map(|s| s.start),
        slip_end: exact.slips.last().map(|s| s.end),
        wall_seconds: start.elapsed().as_secs_f64(),
        ..RunSummary::empty(EXACT, "epo-record", dt, "completed".into())
    })
}

/// The plan-motion reference of a 3D point (the oscillator or the block on a friction
/// cone, with N(t) and the oscillator's flights under a vertical component), its
/// resultant sliding and peak uplift.
fn plan_summary(case: &rockslide_core::case::Case) -> RunSummary {
    let start = Instant::now();
    let dt = rockslide_reference::bidirectional::DEFAULT_STEP;
    let variant = match case.scene.model {
        Model::RigidBlock(_) => "plan-block",
        _ => "plan-epo",
    };
    match rockslide_reference::bidirectional::for_case(case) {
        Err(why) => RunSummary {
            wall_seconds: start.elapsed().as_secs_f64(),
            ..RunSummary::empty(EXACT, variant, dt, format!("no exact reference: {why}"))
        },
        Ok(solution) => {
            let q = solution.exact_quantities();
            let get = |k: &str| q.iter().find(|(key, _)| *key == k).map(|(_, v)| *v);
            RunSummary {
                peak_resultant_sliding: get("peak_resultant_sliding"),
                residual_resultant_sliding: get("residual_resultant_sliding"),
                peak_uplift: get("peak_uplift").or(Some(0.0)),
                wall_seconds: start.elapsed().as_secs_f64(),
                ..RunSummary::empty(EXACT, variant, dt, "completed".into())
            }
        }
    }
}

/// Engine id of the exact reference in a study.
pub const EXACT: &str = "exact";

/// Run every engine the base case asks for on one point, and the rigid block.
pub fn run_point(
    grid: &Grid,
    p: &GridPoint,
    engines: &[Box<dyn rockslide_engine_api::Engine>],
) -> Result<PointResult, Error> {
    let case = grid.point_case(p)?;
    let planned = plan(&case, engines)?;
    let mut runs = Vec::new();
    for pr in &planned.runs {
        runs.push(engine_summary(&case, engines, pr)?);
    }
    if let Some(exact) = exact_summary(&case) {
        runs.push(exact);
    }
    let excitation_signal = case.scene.excitation.signal();
    if grid.newmark {
        runs.extend(newmark_summary(&case)?);
    }
    let rec = &grid.records[p.record];
    let pga = grid.pga(p);
    Ok(PointResult {
        hash: grid.point_hash(p),
        point: p.clone(),
        record: rec.name.clone(),
        pga,
        scale_factor: pga / rec.record.pga(),
        mu: grid.mu(p),
        excitation: match excitation_signal {
            Some(Signal::Record { label, .. }) => label.clone(),
            _ => String::new(),
        },
        not_applicable: planned
            .not_applicable
            .into_iter()
            .map(|(e, why)| (e.to_string(), why))
            .collect(),
        runs,
    })
}

/// One planned engine run of a point, guarded and timed, summarised from its responses;
/// a panic is a result, recorded with its message and no numbers.
fn engine_summary(
    case: &rockslide_core::case::Case,
    engines: &[Box<dyn rockslide_engine_api::Engine>],
    pr: &crate::plan::PlannedRun,
) -> Result<RunSummary, Error> {
    let engine = engines
        .iter()
        .find(|e| e.id() == pr.engine)
        .expect("planned engines exist");
    let timed = guarded(engine.as_ref(), case, pr.variant, pr.dt, 1).map_err(InputErrors::from)?;
    let wall = timed.seconds.first().copied().unwrap_or(f64::NAN);
    let status = Outcome::of(&timed.run).to_string();
    let Ok(run) = timed.run else {
        // A panic is a result: recorded with its message, no numbers.
        return Ok(RunSummary {
            wall_seconds: wall,
            ..RunSummary::empty(pr.engine, pr.variant.name, pr.dt, status)
        });
    };
    let resp = responses(&run.trace);
    let peak_abs_sliding = match (resp.get("peak_sliding"), resp.get("min_sliding")) {
        (Some(a), Some(b)) => Some(a.abs().max(b.abs())),
        _ => None,
    };
    Ok(RunSummary {
        engine: run.engine.to_string(),
        variant: run.variant.clone(),
        dt: run.dt,
        status,
        residual_sliding: resp.get("residual_sliding").copied(),
        peak_abs_sliding,
        peak_relative_displacement: resp.get("peak_relative_displacement").copied(),
        slip_episodes: None,
        total_slid: None,
        slip_start: resp.get("slip_start").copied(),
        slip_end: resp.get("slip_end").copied(),
        steps: run.stats.steps,
        wall_seconds: wall,
        peak_resultant_sliding: resp.get("peak_resultant_sliding").copied(),
        residual_resultant_sliding: resp.get("residual_resultant_sliding").copied(),
        peak_uplift: resp.get("peak_uplift").copied(),
        peak_rotation: resp.get("peak_rotation").copied(),
    })
}

/// Newmark's rigid block (two-way, on a level frictional base) on the point's record,
/// when its excitation is a record and its model has a yield acceleration.
fn newmark_summary(case: &rockslide_core::case::Case) -> Result<Option<RunSummary>, Error> {
    let (Some(Signal::Record { dt, samples, .. }), Some(ky)) = (
        case.scene.excitation.signal(),
        yield_acceleration(&case.scene.model),
    ) else {
        return Ok(None);
    };
    let is_ground = matches!(case.scene.excitation, Excitation::GroundAcceleration(_));
    let start = Instant::now();
    // Level frictional base: sliding both ways. The tail lets it come to rest.
    let tail = case.run.duration - dt * (samples.len() - 1) as f64;
    let sign = if is_ground { 1.0 } else { -1.0 };
    let acc: Vec<f64> = samples.iter().map(|a| sign * a).collect();
    let r = rigid_block(*dt, &acc, ky, Sliding::TwoWay, tail.max(0.0))
        .map_err(|why| Error::Other(format!("rigid block: {why}")))?;
    let u = r.residual();
    // Convert SLAMMER's u (ground relative to block) to mass minus ground: −u.
    let peak = r.peak_abs;
    Ok(Some(RunSummary {
        engine: "newmark-rigid".into(),
        variant: "two-way".into(),
        dt: *dt,
        status: "completed".into(),
        residual_sliding: Some(-u + 0.0), // + 0.0: no "-0" in tables
        peak_abs_sliding: Some(peak),
        peak_relative_displacement: None,
        slip_episodes: Some(r.episodes() as u64),
        total_slid: Some(r.total_slid()),
        slip_start: r.slides.first().map(|s| s.start),
        slip_end: r.slides.last().map(|s| s.end),
        steps: r.disp.len().saturating_sub(1) as u64,
        wall_seconds: start.elapsed().as_secs_f64(),
        ..RunSummary::empty("", "", *dt, String::new())
    }))
}

/// Newmark's yield acceleration of a model on a level frictional base, μ·g (m/s²); `None`
/// when it never slides (μ = ∞) or has no gravity.
pub fn yield_acceleration(model: &Model) -> Option<f64> {
    let (mu, g) = match model {
        Model::Oscillator(o) => (o.contact.mu, o.gravity),
        Model::RockingBody(r) => (r.contact.mu, r.gravity),
        Model::RigidBlock(b) => (b.mu, b.gravity),
    };
    let ky = mu * g;
    (ky.is_finite() && ky > 0.0).then_some(ky)
}

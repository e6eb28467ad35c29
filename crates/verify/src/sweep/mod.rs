//! The `sweep` and `stability` commands: many engine runs of one scene at many time
//! steps, in parallel on all cores, each timed over repeats and guarded so that a run
//! that blows up — even one that panics — is a result and never loses the others.
//!
//! - [`sweep`]: error against run time (work-precision) of every applicable engine and
//!   variant over a Δt ladder, with the observed order of accuracy.
//! - [`stability`]: the stiff and extreme scenes of `cases/stability/`, each run
//!   classified, and each engine's practical stability limit in Δt/T.
//! - `plot`: the SVG figures of both.
//!
//! The arithmetic (errors, orders, classes, energy) lives in [`crate::analysis`]; this
//! module runs engines and writes outputs. It is generic over [`crate::registry::all`]:
//! an engine added there is swept and classified without a change here.

mod plot;
pub mod stability;
pub mod work_precision;

use std::io::IsTerminal;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

use rockslide_core::case::{Case, Model};
use rockslide_core::error::{Error, InputError, InputErrors};
use rockslide_engine_api::{Engine, Run};

/// Settings shared by both commands.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Number of rungs of the sweep's Δt ladder (≥ 3), from T/10 down.
    pub rungs: usize,
    /// Refinement ratio between rungs (> 1).
    pub ratio: f64,
    /// Timed repeats of each run (≥ 1); the median, min and max are reported.
    pub repeats: usize,
    /// Worker threads (`None`: all cores).
    pub jobs: Option<usize>,
    /// No progress bar.
    pub quiet: bool,
    /// Sweep only: wall-time budget per engine variant, s (all repeats of all its rungs).
    /// Rungs are run coarse to fine; a rung whose projected cost (the previous rung's
    /// time scaled by its step count) would overrun the budget is run once instead of
    /// `repeats` times, and skipped — with every finer rung — when even one run would.
    /// The first three rungs always run (an order needs three). `None`: no budget.
    pub budget: Option<f64>,
}

/// Default wall-time budget of one engine variant in a sweep, s: rapier at 16 substeps
/// costs about 0.1–0.2 ms per step, so its finest PEPO rungs (T/1280: 6400 steps) take
/// about a second each; a rocking body's cost ten times that.
pub const DEFAULT_BUDGET: f64 = 20.0;

impl Default for Options {
    fn default() -> Self {
        Options {
            rungs: 8,
            ratio: 2.0,
            repeats: 3,
            jobs: None,
            quiet: false,
            budget: Some(DEFAULT_BUDGET),
        }
    }
}

impl Options {
    /// Check the ranges; the message names the option.
    pub fn validate(&self) -> Result<(), Error> {
        if self.rungs < 3 {
            return Err(Error::Other(format!(
                "--rungs is {}, but must be at least 3 (an order needs three solutions)",
                self.rungs
            )));
        }
        if !(self.ratio > 1.0 && self.ratio.is_finite()) {
            return Err(Error::Other(format!(
                "--ratio is {}, but must be a finite number above 1",
                self.ratio
            )));
        }
        if self.repeats == 0 {
            return Err(Error::Other("--repeats must be at least 1".into()));
        }
        if let Some(b) = self.budget
            && (b.is_nan() || b <= 0.0)
        {
            return Err(Error::Other(format!(
                "--budget is {b} s, but must be a positive number of seconds"
            )));
        }
        if self.jobs == Some(0) {
            return Err(Error::Other("--jobs must be at least 1".into()));
        }
        Ok(())
    }

    /// Run `f` on a pool of `jobs` threads (or rayon's global pool on all cores).
    pub fn install<T: Send>(&self, f: impl FnOnce() -> T + Send) -> Result<T, Error> {
        match self.jobs {
            None => Ok(f()),
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map(|p| p.install(f))
                .map_err(|e| Error::Other(format!("cannot start {n} worker threads: {e}"))),
        }
    }
}

/// The scene's characteristic period T, s, and how it was obtained. The sweep's ladder
/// starts at T/10 (the paper's advice Δt < T/10) and the stability map is in Δt/T.
pub fn characteristic_period(case: &Case) -> (f64, String) {
    let tau = 2.0 * std::f64::consts::PI;
    match &case.scene.model {
        Model::Oscillator(o) => (
            o.period(),
            "T = 2π·√(M/Kx) of the oscillator (single element; the double element's series stiffness is the same by design)".into(),
        ),
        Model::RockingBody(r) => {
            // Shear (n·Kx) in series with rocking (Kz·Σxᵢ²/h²): SPEC §1.1, ωX = 10π.
            let n = r.supports as f64;
            let k_shear = n * r.contact.kx;
            let k_rock = r.contact.kz * r.support_positions().iter().map(|x| x * x).sum::<f64>()
                / (r.cm_height * r.cm_height);
            let k = 1.0 / (1.0 / k_shear + 1.0 / k_rock);
            (
                tau * (r.mass / k).sqrt(),
                "T = 2π/ωX, shear stiffness n·Kx in series with rocking stiffness Kz·Σxᵢ²/h²"
                    .into(),
            )
        }
        Model::RigidBlock(_) => match case.scene.excitation.signal() {
            Some(rockslide_core::case::Signal::SinePulse { omega, .. }) => (
                tau / omega,
                "rigid block: no elastic period; T = 2π/θ of the excitation".into(),
            ),
            _ => (
                case.run.duration / 10.0,
                "rigid block under a record or free: T = duration/10 (no natural period)".into(),
            ),
        },
    }
}

/// One engine variant to run.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Index into the engine list.
    pub engine: usize,
    /// Engine id.
    pub engine_id: &'static str,
    /// Variant.
    pub variant: String,
}

impl Series {
    /// `engine/variant`.
    pub fn label(&self) -> String {
        format!("{}/{}", self.engine_id, self.variant)
    }
}

/// Every engine and variant that applies to the case — whether or not the case file
/// names the engine (a sweep is about the methods, the case's step does not matter) —
/// restricted to the variants the case asks for where it names some. Returns the series
/// and the engines that do not apply, with why.
#[allow(clippy::type_complexity)]
pub fn applicable(
    case: &Case,
    engines: &[Box<dyn Engine>],
) -> Result<(Vec<Series>, Vec<(&'static str, String)>), InputErrors> {
    let mut series = Vec::new();
    let mut not_applicable = Vec::new();
    let mut errors: Vec<InputError> = Vec::new();
    for (i, e) in engines.iter().enumerate() {
        errors.extend(e.check_options(case));
        match e.variants(&case.scene) {
            Err(na) => not_applicable.push((e.id(), na.0)),
            Ok(available) => {
                let wanted: Vec<String> = case
                    .engine(e.id())
                    .and_then(|r| r.variants.clone())
                    .unwrap_or_else(|| available.iter().map(|s| s.to_string()).collect());
                for v in wanted {
                    if available.contains(&v.as_str()) {
                        series.push(Series {
                            engine: i,
                            engine_id: e.id(),
                            variant: v,
                        });
                    }
                }
            }
        }
    }
    if errors.is_empty() {
        Ok((series, not_applicable))
    } else {
        Err(InputErrors(errors))
    }
}

/// One run, repeated and timed.
#[derive(Debug, Clone)]
pub struct Timed {
    /// The first repeat's run, or the message of a panic caught around the engine.
    pub run: Result<Run, String>,
    /// Wall time of each repeat, s.
    pub seconds: Vec<f64>,
    /// Whether every repeat gave a bit-identical trace.
    pub deterministic: bool,
}

impl Timed {
    /// (median, min, max) of the wall times, s.
    pub fn time_stats(&self) -> (f64, f64, f64) {
        let mut s = self.seconds.clone();
        if s.is_empty() {
            return (f64::NAN, f64::NAN, f64::NAN);
        }
        s.sort_by(f64::total_cmp);
        let n = s.len();
        let median = if n % 2 == 1 {
            s[n / 2]
        } else {
            0.5 * (s[n / 2 - 1] + s[n / 2])
        };
        (median, s[0], s[n - 1])
    }
}

/// Run `engine` on `case` at `dt`, `repeats` times. A panic inside the engine is caught
/// (last resort: engines report divergence as a `RunStatus`) and returned as the run's
/// outcome; an input error stops the command.
pub fn run_timed(
    engine: &dyn Engine,
    case: &Case,
    variant: &str,
    dt: f64,
    repeats: usize,
) -> Result<Timed, InputError> {
    let mut seconds = Vec::with_capacity(repeats);
    let mut first: Option<Run> = None;
    let mut deterministic = true;
    for _ in 0..repeats.max(1) {
        let start = Instant::now();
        let outcome = catch_unwind(AssertUnwindSafe(|| engine.run(case, variant, dt)));
        let elapsed = start.elapsed().as_secs_f64();
        match outcome {
            Err(payload) => {
                return Ok(Timed {
                    run: Err(panic_message(payload.as_ref())),
                    seconds,
                    deterministic,
                });
            }
            Ok(Err(e)) => return Err(e),
            Ok(Ok(mut run)) => {
                seconds.push(elapsed);
                match &first {
                    Some(f) => deterministic &= same_bits(&f.trace, &run.trace),
                    None => {
                        run.wall_seconds = elapsed;
                        first = Some(run);
                    }
                }
            }
        }
    }
    Ok(Timed {
        run: Ok(first.expect("at least one repeat")),
        seconds,
        deterministic,
    })
}

/// Whether two traces are bit-identical (NaN equals NaN of the same bits).
fn same_bits(a: &rockslide_core::trace::Trace, b: &rockslide_core::trace::Trace) -> bool {
    let eq = |x: &[f64], y: &[f64]| {
        x.len() == y.len() && x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits())
    };
    a.channels == b.channels
        && eq(&a.time, &b.time)
        && a.columns.len() == b.columns.len()
        && a.columns.iter().zip(&b.columns).all(|(x, y)| eq(x, y))
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "panic with a non-text payload".into()
    }
}

/// A progress bar on a terminal; hidden with `--quiet`, when `CI` is set or when stderr
/// is not a terminal.
pub fn progress(total: usize, quiet: bool, what: &str) -> ProgressBar {
    let hidden = quiet || std::env::var_os("CI").is_some() || !std::io::stderr().is_terminal();
    if hidden {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total as u64);
    if let Ok(style) =
        ProgressStyle::with_template("{msg:>12} [{bar:40}] {pos}/{len} runs ({elapsed}, eta {eta})")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_string());
    bar
}

/// `x` in engineering notation with 3 significant digits, `—` when absent.
pub(crate) fn sci(x: Option<f64>) -> String {
    match x {
        Some(v) if v.is_finite() => format!("{v:.3e}"),
        Some(v) => format!("{v}"),
        None => "—".into(),
    }
}

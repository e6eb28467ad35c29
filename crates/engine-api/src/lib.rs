//! # rockslide-engine-api — the interface every engine implements
//!
//! [`Engine`], the outcome of a run ([`Run`], [`RunStatus`]: divergence and non-convergence
//! are values) and why an engine does not apply ([`NotApplicable`]). Engine crates depend on
//! this crate and `rockslide-core` only — never on each other or on the references — so a
//! bug in one cannot hide in another; the crate graph enforces it.

#![warn(missing_docs)]

use std::any::Any;

pub use rockslide_core::case::Arrangement;
use rockslide_core::case::{Case, EngineOptions, Invariant, Scene};
use rockslide_core::error::InputError;
use rockslide_core::trace::{ContactBlock, ContactState, Trace};
use serde::{Deserialize, Serialize};

/// Why an engine cannot represent a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct NotApplicable(pub String);

/// How a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum RunStatus {
    /// Ran to the end of the case.
    Completed,
    /// The solution blew up (NaN/Inf or energy growth) at `time`.
    Diverged {
        /// Simulation time, s.
        time: f64,
        /// What was seen.
        reason: String,
    },
    /// An iterative solver did not converge at `time`.
    NotConverged {
        /// Simulation time, s.
        time: f64,
        /// Residual and iteration count, in words.
        reason: String,
    },
}

impl RunStatus {
    /// Whether the run reached the end.
    pub fn completed(&self) -> bool {
        matches!(self, RunStatus::Completed)
    }
    /// One-word label.
    pub fn label(&self) -> &'static str {
        match self {
            RunStatus::Completed => "completed",
            RunStatus::Diverged { .. } => "diverged",
            RunStatus::NotConverged { .. } => "not converged",
        }
    }
}

impl std::fmt::Display for RunStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunStatus::Completed => write!(f, "completed"),
            RunStatus::Diverged { time, reason } => {
                write!(f, "diverged at t = {time:.6} s: {reason}")
            }
            RunStatus::NotConverged { time, reason } => {
                write!(f, "not converged at t = {time:.6} s: {reason}")
            }
        }
    }
}

/// What a solver did during a run, counted deterministically (no times): the same case gives
/// the same numbers on every machine. Fields an engine has no notion of stay `None`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SolverStats {
    /// Time steps taken.
    pub steps: u64,
    /// Solver substeps per time step (rapier).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub substeps_per_step: Option<u64>,
    /// Equilibrium (Newton) iterations over all steps (fe).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub newton_iterations: Option<u64>,
    /// Most equilibrium iterations in one step (fe).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_step_iterations: Option<u64>,
    /// Iterations of the static preload before t = 0 (fe).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub static_iterations: Option<u64>,
    /// Failed steps cut into smaller ones and retried (fe).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step_cuts: Option<u64>,
    /// Steps accepted with the residual at the round-off floor rather than the tolerance (fe).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roundoff_accepted: Option<u64>,
}

impl SolverStats {
    /// Only `steps` known: the statistics of an engine without an iterative solver.
    pub fn steps(steps: u64) -> Self {
        SolverStats {
            steps,
            ..Self::default()
        }
    }

    /// The statistics an engine recorded, as (label, value) for tables and metadata, in a
    /// fixed order; unknown fields are left out.
    pub fn entries(&self) -> Vec<(&'static str, u64)> {
        let optional = [
            ("substeps per step", self.substeps_per_step),
            ("Newton iterations", self.newton_iterations),
            ("max iterations in a step", self.max_step_iterations),
            ("static preload iterations", self.static_iterations),
            ("step cuts", self.step_cuts),
            ("steps accepted at round-off", self.roundoff_accepted),
        ];
        std::iter::once(("steps", self.steps))
            .chain(optional.into_iter().filter_map(|(k, v)| v.map(|v| (k, v))))
            .collect()
    }
}

/// One way an engine runs a scene: its name (as in case files, trace channels and
/// reports: `single`, `kinematic-ground`, …) and what it models.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Variant {
    /// Name, unique within its engine.
    pub name: &'static str,
    /// How its supports carry the base reaction.
    pub arrangement: Arrangement,
}

impl Variant {
    /// A variant on single contact elements.
    pub const fn single(name: &'static str) -> Variant {
        Variant {
            name,
            arrangement: Arrangement::Single,
        }
    }
    /// A variant on the double element.
    pub const fn double(name: &'static str) -> Variant {
        Variant {
            name,
            arrangement: Arrangement::Double,
        }
    }
}

impl std::fmt::Display for Variant {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

/// One setting that shaped a run, as its engine states it: a name, the unit its value is in,
/// and a typed value, which the report renders ([`Setting::label`], [`Setting::value_text`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// What it is (`dt`, `integrator`, `substeps`, …).
    pub name: String,
    /// The unit of a numeric value (`s`, `N·s/m`), `None` where it has none.
    pub unit: Option<&'static str>,
    /// Its value.
    pub value: SettingValue,
}

/// The value of a [`Setting`].
#[derive(Debug, Clone, PartialEq)]
pub enum SettingValue {
    /// A number, shown in its shortest round-trip form.
    Number(f64),
    /// A number shown to a fixed number of decimals.
    Rounded {
        /// The value.
        value: f64,
        /// Decimals shown.
        decimals: usize,
    },
    /// Several numbers of one kind (a tuple of parameters), shown `a, b, c`.
    Numbers(Vec<f64>),
    /// A count.
    Count(u64),
    /// A switch: `on` or `off`.
    Switch(bool),
    /// One of the values an option can take, or a named model.
    Choice(&'static str),
    /// A model or a rule described in words.
    Text(String),
}

impl Setting {
    /// A number in `unit`.
    pub fn number(name: &str, unit: &'static str, value: f64) -> Setting {
        Setting::new(name, Some(unit), SettingValue::Number(value))
    }
    /// A dimensionless number shown to `decimals` decimals.
    pub fn rounded(name: &str, value: f64, decimals: usize) -> Setting {
        Setting::new(name, None, SettingValue::Rounded { value, decimals })
    }
    /// A count.
    pub fn count(name: &str, value: u64) -> Setting {
        Setting::new(name, None, SettingValue::Count(value))
    }
    /// A switch.
    pub fn switch(name: &str, on: bool) -> Setting {
        Setting::new(name, None, SettingValue::Switch(on))
    }
    /// One of an option's values, or a named model.
    pub fn choice(name: &str, value: &'static str) -> Setting {
        Setting::new(name, None, SettingValue::Choice(value))
    }
    /// Words.
    pub fn text(name: &str, value: impl Into<String>) -> Setting {
        Setting::new(name, None, SettingValue::Text(value.into()))
    }
    /// A setting of any value.
    pub fn new(name: &str, unit: Option<&'static str>, value: SettingValue) -> Setting {
        Setting {
            name: name.to_string(),
            unit,
            value,
        }
    }
    /// Its name with its unit, as a table shows it: `dt [s]`.
    pub fn label(&self) -> String {
        match self.unit {
            Some(u) => format!("{} [{u}]", self.name),
            None => self.name.clone(),
        }
    }
    /// Its value as a table shows it.
    pub fn value_text(&self) -> String {
        match &self.value {
            SettingValue::Number(x) => format!("{x}"),
            SettingValue::Rounded { value, decimals } => format!("{value:.decimals$}"),
            SettingValue::Numbers(xs) => {
                let shown: Vec<String> = xs.iter().map(|x| format!("{x}")).collect();
                shown.join(", ")
            }
            SettingValue::Count(n) => n.to_string(),
            SettingValue::Switch(on) => if *on { "on" } else { "off" }.into(),
            SettingValue::Choice(c) => (*c).into(),
            SettingValue::Text(t) => t.clone(),
        }
    }
}

/// The outcome of one engine run: its trace, how it ended, and what it ran with.
#[derive(Debug, Clone)]
pub struct Run {
    /// Engine id.
    pub engine: &'static str,
    /// Variant name.
    pub variant: String,
    /// How the run's supports carry the base reaction (its variant's).
    pub arrangement: Arrangement,
    /// Time step, s.
    pub dt: f64,
    /// Every setting that shaped the result — recorded in all outputs.
    pub settings: Vec<Setting>,
    /// What the solver did, counted deterministically (steps, iterations, substeps).
    pub stats: SolverStats,
    /// Things the engine measured about itself worth reporting (Eq. 9 change, eigenfrequencies).
    pub findings: Vec<String>,
    /// Time histories.
    pub trace: Trace,
    /// How it ended.
    pub status: RunStatus,
    /// Wall time of the run, s (filled by the caller; not part of the physics).
    pub wall_seconds: f64,
}

impl Run {
    /// `engine/variant`.
    pub fn label(&self) -> String {
        format!("{}/{}", self.engine, self.variant)
    }
}

/// A simulation method.
pub trait Engine: Send + Sync {
    /// Id as in case files.
    fn id(&self) -> &'static str;
    /// One line saying what it is.
    fn description(&self) -> &'static str;
    /// The variants this engine can run for a scene, or why it cannot run it at all.
    fn variants(&self, scene: &Scene) -> Result<Vec<Variant>, NotApplicable>;
    /// This engine's options in `case`, parsed and validated into the engine's own type
    /// (every problem located). The registry parses them once, when the case is loaded
    /// and again after a sweep's or a stability map's change to them, and keeps them with
    /// the case ([`Case::parsed_options`]); the engine reads them back on every run
    /// ([`parsed_options`]). `None`: the engine has no options.
    fn parse_options(&self, case: &Case) -> Result<Option<EngineOptions>, Vec<InputError>> {
        let _ = case;
        Ok(None)
    }
    /// Whether the engine models plan motion (a bidirectional, 3D scene: `Scene::spatial`).
    /// The registry refuses a spatial scene for every engine that does not, so that no
    /// 2D engine silently runs the planar part of a 3D scene.
    fn models_plan_motion(&self) -> bool {
        false
    }
    /// This engine's tolerance on a physical invariant, in the invariant's own measure
    /// (measured on the shipped cases, with margin). By default the contact law held to
    /// round-off ([`Invariant::round_off_limit`]).
    fn invariant_limit(&self, invariant: Invariant) -> f64 {
        invariant.round_off_limit()
    }
    /// Relative CPU cost of one time step of `variant` on `scene`, in units of 0.1 µs of
    /// single-thread CPU: what the default run's scheduler orders cases by (costliest
    /// first). An estimate, measured once; by default 1.
    fn step_cost(&self, scene: &Scene, variant: Variant) -> f64 {
        let _ = (scene, variant);
        1.0
    }
    /// The case as a work-precision sweep runs it: what the engine sets for itself where
    /// the case is silent (so that a rung's run time is the method's own), each change
    /// stated in words for the sweep's report. By default nothing.
    fn for_sweep(&self, case: &mut Case) -> Vec<String> {
        let _ = case;
        Vec::new()
    }
    /// The case one rung of a sweep runs at time step `dt`, where it differs from the case
    /// as the sweep runs it (e.g. the engine's own step made `dt`); `None`: unchanged.
    fn at_rung(&self, case: &Case, dt: f64) -> Option<Case> {
        let _ = (case, dt);
        None
    }
    /// The case as the stability map runs it: the engine stepping at the map's time step,
    /// so that its rows show the method's own stability limit, not a step rule's. By
    /// default unchanged.
    fn for_stability(&self, case: &mut Case) {
        let _ = case;
    }
    /// Run one variant (one of those [`Engine::variants`] declared for the case's scene)
    /// at time step `dt`. Divergence is a [`RunStatus`], never a panic.
    fn run(&self, case: &Case, variant: Variant, dt: f64) -> Result<Run, InputError>;
    /// Run one variant at time step `dt`, handing every row to `sink` as it is computed
    /// instead of keeping it: the returned run's trace holds the layout (channels, contact
    /// names and compliances) and no rows. By default the engine runs whole and its rows
    /// are forwarded ([`forward_rows`]), so an engine that does not stream natively still
    /// can be streamed (its memory then grows with the run as before); an engine that
    /// streams natively holds no trace.
    fn run_streaming(
        &self,
        case: &Case,
        variant: Variant,
        dt: f64,
        sink: &mut dyn StepSink,
    ) -> Result<Run, InputError> {
        let mut run = self.run(case, variant, dt)?;
        forward_rows(&run.trace, sink);
        run.trace = layout_of(&run.trace);
        Ok(run)
    }
    /// Whether [`Engine::run_streaming`] is native: the engine holds no trace while it
    /// streams (by default it runs whole and forwards the rows).
    fn streams_natively(&self) -> bool {
        false
    }
    /// Values one row of this variant records (time, channels and the contact block's
    /// fields), when the engine knows it before running; `None`: not declared (the
    /// memory and disk estimates then count every quantity of the catalogue).
    fn recorded_values(&self, case: &Case, variant: Variant) -> Option<usize> {
        let _ = (case, variant);
        None
    }
}

/// The variant of `available` (an engine's declared variants) named `name`, as a case file
/// names it.
pub fn declared(available: &[Variant], name: &str) -> Option<Variant> {
    available.iter().find(|v| v.name == name).copied()
}

/// Engine `id`'s options as the registry parsed them when the case was loaded
/// ([`Engine::parse_options`]), or, for a case read without the registry, parsed now by
/// `parse` (its first problem returned).
pub fn parsed_options<T: Any + Clone>(
    case: &Case,
    id: &str,
    parse: impl FnOnce(&Case) -> Result<T, Vec<InputError>>,
) -> Result<T, InputError> {
    match case.parsed_options.get::<T>(id) {
        Some(options) => Ok(options.clone()),
        None => parse(case).map_err(|mut errors| errors.remove(0)),
    }
}

/// Where a streamed run sends its rows ([`Engine::run_streaming`]), one step at a time.
pub trait StepSink {
    /// Before the first row: the run's layout, a trace with its channels and its contact
    /// block's names and compliances, and no rows.
    fn begin(&mut self, layout: &Trace);
    /// One row: time, s; values in channel order; each contact's state in contact order
    /// (empty when the run has no per-contact block).
    fn row(&mut self, t: f64, values: &[f64], contacts: &[ContactState]);
}

/// Keeps every row in a trace sized for the run up front (no reallocation in the time
/// loop): how an engine that streams natively makes a whole run ([`Engine::run`]) from
/// the same loop that feeds a caller's sink.
#[derive(Debug, Default)]
pub struct TraceSink {
    /// The rows so far, under the run's layout.
    pub trace: Trace,
    /// Rows the trace is sized for.
    rows: usize,
}

impl TraceSink {
    /// A sink for a run of `rows` rows.
    pub fn sized(rows: usize) -> Self {
        Self {
            trace: Trace::default(),
            rows,
        }
    }
}

impl StepSink for TraceSink {
    fn begin(&mut self, layout: &Trace) {
        self.trace = Trace::with_channels(&layout.channels, self.rows);
        let names: Vec<&str> = layout.contacts.names.iter().map(String::as_str).collect();
        self.trace.contacts =
            ContactBlock::with_contacts(&names, &layout.contacts.compliance, self.rows);
    }

    #[inline]
    fn row(&mut self, t: f64, values: &[f64], contacts: &[ContactState]) {
        self.trace.push(t, values);
        self.trace.contacts.push(t, contacts);
    }
}

/// The layout of a trace: its channels and its contact block's names and compliances,
/// without rows (a contact block whose rows are not the trace's rows is kept whole).
pub fn layout_of(trace: &Trace) -> Trace {
    let mut layout = Trace::with_channels(&trace.channels, 0);
    layout.contacts = trace.contacts.clone();
    if trace.contacts.len() == trace.len() {
        layout.contacts.time = Vec::new();
        layout.contacts.values = Vec::new();
    }
    layout
}

/// Hand every row of a whole trace to `sink`, as a streaming engine would have: the
/// contact states with each row when the block has the trace's rows, else none.
pub fn forward_rows(trace: &Trace, sink: &mut dyn StepSink) {
    sink.begin(&layout_of(trace));
    let per_row = trace.contacts.len() == trace.len();
    let mut values = vec![0.0; trace.channels.len()];
    let mut states: Vec<ContactState> = Vec::with_capacity(trace.contacts.count());
    for (i, &t) in trace.time.iter().enumerate() {
        for (v, column) in values.iter_mut().zip(&trace.columns) {
            *v = column[i];
        }
        states.clear();
        if per_row {
            states.extend((0..trace.contacts.count()).map(|c| trace.contacts.at(i, c)));
        }
        sink.row(t, &values, &states);
    }
}

/// Number of steps covering `duration` at `dt` (the last step may end past it by < dt/2).
pub fn step_count(duration: f64, dt: f64) -> usize {
    (duration / dt - 1e-9).ceil().max(1.0) as usize
}

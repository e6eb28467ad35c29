//! The validated case: SI units, every field present and in range, the scene saying what
//! it needs. This is what engines, references and reports read.

pub use super::invariant::INVARIANT_KEYS;
use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;
use std::sync::Arc;

use super::external::{EXTERNAL_VARIANT, External};
use super::locate::Locator;
use super::signal::Signal;
use crate::error::InputError;

/// One contact element (CONTA178-like): tangential and normal penalty stiffness, friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Horizontal (sticking) stiffness, N/m.
    pub kx: f64,
    /// Vertical stiffness in compression, N/m (no tension).
    pub kz: f64,
    /// Coulomb friction coefficient (may be `f64::INFINITY`: never slips).
    pub mu: f64,
}

/// Two contact elements in series through a massless intermediate node: element 1 from
/// the ground (it slides), element 2 to the structure (μ = ∞, elastic).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoubleContact {
    /// Element 1, ground to intermediate node.
    pub lower: Contact,
    /// Element 2, intermediate node to structure.
    pub upper: Contact,
}

impl DoubleContact {
    /// Series stiffnesses (kx, kz) of the two elements, N/m.
    pub fn series(&self) -> (f64, f64) {
        let s = |a: f64, b: f64| a * b / (a + b);
        (
            s(self.lower.kx, self.upper.kx),
            s(self.lower.kz, self.upper.kz),
        )
    }
}

/// A mass on one base contact, sliding only (the paper's PEPO; with μ = ∞ a linear SDOF).
#[derive(Debug, Clone, PartialEq)]
pub struct Oscillator {
    /// Mass, kg.
    pub mass: f64,
    /// Gravity, m/s² (sets the normal force M·g).
    pub gravity: f64,
    /// Viscous damping as a fraction of critical, 2·ζ·M·ω.
    pub damping_ratio: f64,
    /// The single-element arrangement.
    pub contact: Contact,
    /// The double-element arrangement, when the case defines one.
    pub double: Option<DoubleContact>,
}

impl Oscillator {
    /// Natural circular frequency √(Kx/M), rad/s.
    pub fn omega(&self) -> f64 {
        (self.contact.kx / self.mass).sqrt()
    }
    /// Natural period, s.
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.omega()
    }
    /// Normal force M·g, N.
    pub fn normal_force(&self) -> f64 {
        self.mass * self.gravity
    }
    /// Friction limit Ru = μ·M·g, N (infinite when μ is).
    pub fn friction_limit(&self) -> f64 {
        self.contact.mu * self.normal_force()
    }
    /// Viscous damping coefficient C = 2ζMω, N·s/m.
    pub fn damping(&self) -> f64 {
        2.0 * self.damping_ratio * self.mass * self.omega()
    }
}

/// A rigid body on a rigid massless base with equally spaced supports (the paper's RPEPO).
#[derive(Debug, Clone, PartialEq)]
pub struct RockingBody {
    /// Translational mass (X and Z), kg.
    pub mass: f64,
    /// Gravity, m/s².
    pub gravity: f64,
    /// Height of the centre of mass above the base centre O, m.
    pub cm_height: f64,
    /// Half-width of the base, m.
    pub half_width: f64,
    /// Number of supports, equally spaced from −b to +b.
    pub supports: usize,
    /// Rotational inertia about the centre of mass, kg·m² (the paper's model has none;
    /// a small stated value keeps the airborne phase determinate).
    pub rotational_inertia: f64,
    /// Each support as a single element.
    pub contact: Contact,
    /// Each support as two elements in series, when defined.
    pub double: Option<DoubleContact>,
}

impl RockingBody {
    /// Support abscissae x_i = −b + 2b·i/(n−1), m.
    pub fn support_positions(&self) -> Vec<f64> {
        let n = self.supports;
        (0..n)
            .map(|i| -self.half_width + 2.0 * self.half_width * i as f64 / (n - 1) as f64)
            .collect()
    }
    /// Weight M·g, N.
    pub fn weight(&self) -> f64 {
        self.mass * self.gravity
    }
}

/// A rigid block on a rigid ground, no elasticity (Newmark's sliding block, Housner's
/// rocking block).
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBlock {
    /// Mass, kg.
    pub mass: f64,
    /// Gravity, m/s².
    pub gravity: f64,
    /// Half-width b, m.
    pub half_width: f64,
    /// Half-height h, m (centre of mass at the block's centre).
    pub half_height: f64,
    /// Friction coefficient at the base.
    pub mu: f64,
    /// Initial tilt about the right corner, rad (0: resting flat).
    pub initial_tilt: f64,
}

/// The structure of a scene.
#[derive(Debug, Clone, PartialEq)]
pub enum Model {
    /// Sliding-only mass on an elastic-plastic contact (PEPO, linear SDOF).
    Oscillator(Oscillator),
    /// Rigid body on ten elastic-plastic supports (RPEPO).
    RockingBody(RockingBody),
    /// Rigid block on a rigid ground (Newmark, Housner).
    RigidBlock(RigidBlock),
}

impl Model {
    /// The model's kind as written in case files.
    pub fn kind(&self) -> &'static str {
        match self {
            Model::Oscillator(_) => "oscillator",
            Model::RockingBody(_) => "rocking-body",
            Model::RigidBlock(_) => "rigid-block",
        }
    }
    /// Whether the scene has rotation (a rotation channel makes sense).
    pub fn has_rotation(&self) -> bool {
        !matches!(self, Model::Oscillator(_))
    }
    /// Whether the scene has geometry to draw in 3D.
    pub fn has_geometry(&self) -> bool {
        !matches!(self, Model::Oscillator(_))
    }
    /// Total mass, kg.
    pub fn mass(&self) -> f64 {
        match self {
            Model::Oscillator(o) => o.mass,
            Model::RockingBody(r) => r.mass,
            Model::RigidBlock(b) => b.mass,
        }
    }
}

/// What drives the scene.
#[derive(Debug, Clone, PartialEq)]
pub enum Excitation {
    /// Free response from the initial state.
    None,
    /// Horizontal acceleration applied to the mass: force M·a(t), m/s².
    MassAcceleration(Signal),
    /// Horizontal ground displacement xg(t), m.
    GroundDisplacement(Signal),
    /// Horizontal ground acceleration ag(t), m/s² (records).
    GroundAcceleration(Signal),
}

impl Excitation {
    /// The kind as written in case files.
    pub fn kind(&self) -> &'static str {
        match self {
            Excitation::None => "none",
            Excitation::MassAcceleration(_) => "mass-acceleration",
            Excitation::GroundDisplacement(_) => "ground-displacement",
            Excitation::GroundAcceleration(_) => "ground-acceleration",
        }
    }
    /// The signal, if any.
    pub fn signal(&self) -> Option<&Signal> {
        match self {
            Excitation::None => None,
            Excitation::MassAcceleration(s)
            | Excitation::GroundDisplacement(s)
            | Excitation::GroundAcceleration(s) => Some(s),
        }
    }
    /// Whether the ground moves.
    pub fn moves_ground(&self) -> bool {
        matches!(
            self,
            Excitation::GroundDisplacement(_) | Excitation::GroundAcceleration(_)
        )
    }
}

/// Model plus excitation: what every engine must simulate.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The structure.
    pub model: Model,
    /// What drives it.
    pub excitation: Excitation,
    /// The vertical ground acceleration, when the case gives one (`[excitation.vertical]`).
    pub vertical: Option<Vertical>,
    /// Plan motion (a bidirectional, 3D scene), when the case gives any of its keys:
    /// `excitation.azimuth_deg`, `[excitation.y]`, `model.half_depth`, `model.support_rows`,
    /// `model.rotational_inertia_{x,y,z}`. `None`: a planar scene, as before.
    pub spatial: Option<super::spatial::Spatial>,
}

impl Scene {
    /// The vertical component, if any.
    pub fn vertical(&self) -> Option<&Vertical> {
        self.vertical.as_ref()
    }
    /// The plan-motion part, if the scene is bidirectional (3D).
    pub fn spatial(&self) -> Option<&super::spatial::Spatial> {
        self.spatial.as_ref()
    }
}

/// How the normal force follows a vertical ground motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NormalForce {
    /// The contact's vertical stiffness Kz and the mass form a linear oscillator driven by
    /// a_v: M·δ'' + Kz·δ = M·(g + a_v), N = Kz·δ (compression only).
    Dynamic,
    /// A rigid vertical contact: N = M·(g + a_v(t)) at every instant (never below zero).
    QuasiStatic,
}

impl NormalForce {
    /// The name as written in case files (`normal_force = "…"`).
    pub fn name(self) -> &'static str {
        match self {
            NormalForce::Dynamic => "dynamic",
            NormalForce::QuasiStatic => "quasi-static",
        }
    }
}

/// A vertical ground acceleration a_v(t), m/s², **positive upward**: in the frame of the
/// ground the effective gravity is g + a_v(t), so quasi-statically N = M·(g + a_v).
#[derive(Debug, Clone, PartialEq)]
pub struct Vertical {
    /// a_v(t), m/s² (a sine pulse or a record, as the horizontal signal).
    pub signal: Signal,
    /// How the normal force follows it.
    pub normal_force: NormalForce,
}

impl Vertical {
    /// Effective gravity g + a_v(t), m/s².
    pub fn effective_gravity(&self, gravity: f64, t: f64) -> f64 {
        gravity + self.signal.value(t)
    }
}

/// Run length and default step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSettings {
    /// Simulated time, s: the end of the run, when every trace and the exact reference
    /// are read. The case's `duration` when it is a multiple of `dt`; otherwise the first
    /// step after it (n·dt, n = ⌈duration/dt⌉), which every engine at `dt` runs to.
    pub duration: f64,
    /// The duration the case wrote, s (differs from `duration` when it was not a multiple
    /// of `dt`: a warning says so).
    pub asked_duration: f64,
    /// Default time step, s (an engine section may override it).
    pub dt: f64,
    /// Time step of the trace files written (CSV, MCAP), s; `None`: every step. The
    /// analysis, plots and checks always use every step.
    pub output_dt: Option<f64>,
}

/// An engine option value, as written in the case file.
#[derive(Debug, Clone, PartialEq)]
pub enum OptionValue {
    /// A number.
    Number(f64),
    /// A string.
    Text(String),
    /// A boolean.
    Bool(bool),
}

/// An engine's section of the case: its step, its variants, its own options.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EngineRequest {
    /// Time step for this engine, s (default: the run's).
    pub dt: Option<f64>,
    /// Variants to run (default: all that apply).
    pub variants: Option<Vec<String>>,
    /// Engine-specific options, validated by the engine.
    pub options: BTreeMap<String, OptionValue>,
}

/// What a tolerance compares against.
#[derive(Debug, Clone, PartialEq)]
pub enum ToleranceBasis {
    /// The exact or closed-form reference.
    Reference,
    /// Another engine run, `engine/variant`.
    Run(String),
}

/// A gated (or informative) limit on one discrepancy.
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerance {
    /// Response quantity key (`peak_relative_displacement`, `slip_end`, ...).
    pub quantity: String,
    /// Which runs it applies to: `engine` or `engine/variant`; `None` = all.
    pub runs: Option<String>,
    /// What the runs are compared with.
    pub basis: ToleranceBasis,
    /// Limit on |discrepancy| in percent, if given.
    pub percent: Option<f64>,
    /// Limit on |difference| in the quantity's SI unit, if given.
    pub absolute: Option<f64>,
    /// Whether `check` fails on it (default true).
    pub gate: bool,
    /// Where it is in the case file (`tolerance[i]`), for messages.
    pub field: String,
}

impl Tolerance {
    /// Whether this tolerance applies to the run `engine/variant`.
    pub fn applies_to(&self, engine: &str, variant: &str) -> bool {
        match &self.runs {
            None => true,
            Some(r) => match r.split_once('/') {
                Some((e, v)) => e == engine && v == variant,
                None => r == engine,
            },
        }
    }
}

/// How a run is declared to end when it is not meant to complete.
#[derive(Debug, Clone, PartialEq)]
pub struct ExpectedOutcome {
    /// Engine id.
    pub engine: String,
    /// Variant; `None` = every variant of the engine.
    pub variant: Option<String>,
    /// `diverged` or `not converged` (the run status label).
    pub status: String,
    /// Why, in words.
    pub reason: Option<String>,
    /// Where it is in the case file (`expected_outcome[i]`).
    pub field: String,
}

impl ExpectedOutcome {
    /// Whether this declaration is about the run `engine/variant`.
    pub fn applies_to(&self, engine: &str, variant: &str) -> bool {
        self.engine == engine && self.variant.as_deref().is_none_or(|v| v == variant)
    }
}

/// An engine's known violation of a physical invariant on this case: still measured and
/// reported with its size, but not a gate failure.
#[derive(Debug, Clone, PartialEq)]
pub struct ExpectedViolation {
    /// Engine id.
    pub engine: String,
    /// Invariant key (`friction_bound`, `compression`, `stick_slip`, `dissipation`,
    /// `energy_balance`).
    pub invariant: String,
    /// Why it is accepted, in words (with the measured size).
    pub reason: String,
    /// Where it is in the case file (`expected_violation[i]`).
    pub field: String,
}

/// The design quantities (the report's first table; a disagreement on one beyond what the
/// case accepts fails the gate unless declared).
pub const DESIGN_QUANTITIES: &[&str] = &[
    "peak_sliding",
    "residual_sliding",
    "peak_uplift",
    "peak_rotation",
];

/// Two participants known to differ on a design quantity beyond what is acceptable
/// (`[[expected_disagreement]]`): shown at the top of the report with its reason and
/// evidence instead of failing the gate.
#[derive(Debug, Clone, PartialEq)]
pub struct ExpectedDisagreement {
    /// Design quantity key (`residual_sliding`).
    pub quantity: String,
    /// The run, `engine/variant` or an engine id (every variant).
    pub runs: String,
    /// What it is compared with: `reference` (also when not given) or a run label.
    pub against: String,
    /// Why the difference is accepted.
    pub reason: String,
    /// What shows it (a convergence study, a finding), in words.
    pub evidence: String,
    /// Where it is in the case file (`expected_disagreement[i]`).
    pub field: String,
}

impl ExpectedDisagreement {
    /// Whether this declaration is about `quantity` of run `label` against `basis`.
    pub fn covers(&self, quantity: &str, label: &str, basis: &str) -> bool {
        let run_matches = self.runs == label || label.split('/').next() == Some(&*self.runs);
        self.quantity == quantity && run_matches && self.against == basis
    }
}

/// Run statuses an `[[expected_outcome]]` may name.
pub const EXPECTED_STATUSES: &[&str] = &["diverged", "not converged"];

/// A validated case file.
#[derive(Debug, Clone)]
pub struct Case {
    /// Short name (file stem unless given), used for output folders.
    pub name: String,
    /// One-line title.
    pub title: String,
    /// Where the scene comes from (paper section, textbook).
    pub source: String,
    /// The requirement it checks ("rockslide shall ...").
    pub requirement: String,
    /// Path of the case file.
    pub path: PathBuf,
    /// SHA-256 of the case file's bytes, hex.
    pub sha256: String,
    /// The case file's text (attached to traces and reports).
    pub text: String,
    /// The scene.
    pub scene: Scene,
    /// Run length and default step.
    pub run: RunSettings,
    /// Engine sections by engine id, in file order of ids.
    pub engines: BTreeMap<String, EngineRequest>,
    /// Tolerances, in file order.
    pub tolerances: Vec<Tolerance>,
    /// Runs declared not to complete (`[[expected_outcome]]`), in file order.
    pub expected_outcomes: Vec<ExpectedOutcome>,
    /// Invariant violations declared known (`[[expected_violation]]`), in file order.
    pub expected_violations: Vec<ExpectedViolation>,
    /// Design-quantity disagreements declared known (`[[expected_disagreement]]`).
    pub expected_disagreements: Vec<ExpectedDisagreement>,
    /// Locates fields of the file for error messages.
    pub locator: Locator,
    /// Other programs' results taking part like engines (`[[external]]`, `--external`).
    pub externals: Vec<External>,
    /// Each engine's options parsed once into its own type when the case is loaded
    /// through the registry (empty for a case read without it).
    pub parsed_options: super::ParsedOptions,
    /// The set of azimuths a station case runs at (`x_azimuths_deg`); its scene is at the
    /// set's first ([`Case::at_azimuth`] gives the others).
    pub azimuths: Option<AzimuthSet>,
}

/// The azimuths a case is run at and how to project its station at any of them
/// ([`Case::at_azimuth`]).
#[derive(Debug, Clone)]
pub struct AzimuthSet {
    /// Compass azimuths of +x, degrees clockwise from north, in the case file's order.
    pub degrees: Vec<f64>,
    /// What the set must span to cover every direction.
    pub coverage: Coverage,
    /// The station's prepared channels, projected at each azimuth.
    pub(crate) projection: Arc<dyn AzimuthProjection>,
}

/// A station's ground motion projected on the scene's axes with +x at any compass
/// azimuth: what a case with a set keeps. The station's reading implements it (the very
/// projection a case with one `x_azimuth_deg` uses).
pub(crate) trait AzimuthProjection: fmt::Debug + Send + Sync {
    /// The ground motion with +x at compass azimuth `degrees`.
    fn at(&self, degrees: f64) -> AzimuthSignals;
}

/// A station's ground motion on the scene's axes at one azimuth.
pub(crate) struct AzimuthSignals {
    /// Along +x.
    pub x: Signal,
    /// Along +y, when the station drives y.
    pub y: Option<Signal>,
    /// Upward, when the station drives z.
    pub vertical: Option<Vertical>,
}

/// What a set of azimuths spans, following the axes the station drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coverage {
    /// Both horizontals drive x and y: 0 up to 180° (a + 180° is a mirrored).
    Plan,
    /// One horizontal drives x: 0 up to 360° (a + 180° is the other polarity).
    Axis,
}

impl Coverage {
    /// The span of azimuths that covers every direction, degrees (180 or 360).
    pub fn span_deg(self) -> f64 {
        match self {
            Coverage::Plan => 180.0,
            Coverage::Axis => 360.0,
        }
    }

    /// Why the span is what it is, in words.
    pub fn reason(self) -> &'static str {
        match self {
            Coverage::Plan => {
                "the station drives x and y: an azimuth a + 180° inverts both horizontals, \
                 which mirrors the motion and leaves the resultant sliding and uplift as at a"
            }
            Coverage::Axis => {
                "the station drives x alone: an azimuth a + 180° is the other polarity, \
                 which changes the sign of the residual sliding, so both are in the set"
            }
        }
    }
}

impl Case {
    /// Add an external participant: tolerances `against` its bare label compare with its
    /// run (`<label>/external`).
    pub fn add_external(&mut self, external: External) {
        let bare = ToleranceBasis::Run(external.label.clone());
        for t in &mut self.tolerances {
            if t.basis == bare {
                t.basis = ToleranceBasis::Run(format!("{}/{EXTERNAL_VARIANT}", external.label));
            }
        }
        self.externals.push(external);
    }
}

impl Case {
    /// The time step an engine runs with by default.
    pub fn dt_for(&self, engine: &str) -> f64 {
        self.engines
            .get(engine)
            .and_then(|r| r.dt)
            .unwrap_or(self.run.dt)
    }

    /// An engine's section, if the case has one.
    pub fn engine(&self, engine: &str) -> Option<&EngineRequest> {
        self.engines.get(engine)
    }

    /// A located error about a field of this case.
    pub fn field_error(&self, field: &str, reason: impl Into<String>) -> InputError {
        self.locator.error(field, reason)
    }

    /// Number option of an engine section, with its default; an error names the field.
    pub fn engine_number(&self, engine: &str, key: &str, default: f64) -> Result<f64, InputError> {
        match self.engine(engine).and_then(|r| r.options.get(key)) {
            None => Ok(default),
            Some(OptionValue::Number(x)) => Ok(*x),
            Some(_) => {
                Err(self.field_error(&format!("engines.{engine}.{key}"), "must be a number"))
            }
        }
    }

    /// Text option of an engine section, checked against the allowed values.
    pub fn engine_text(
        &self,
        engine: &str,
        key: &str,
        default: &str,
        allowed: &[&str],
    ) -> Result<String, InputError> {
        match self.engine(engine).and_then(|r| r.options.get(key)) {
            None => Ok(default.to_string()),
            Some(OptionValue::Text(s)) if allowed.contains(&s.as_str()) => Ok(s.clone()),
            Some(_) => Err(self.field_error(
                &format!("engines.{engine}.{key}"),
                format!("must be one of {}", quoted(allowed)),
            )),
        }
    }

    /// Boolean option of an engine section.
    pub fn engine_bool(&self, engine: &str, key: &str, default: bool) -> Result<bool, InputError> {
        match self.engine(engine).and_then(|r| r.options.get(key)) {
            None => Ok(default),
            Some(OptionValue::Bool(b)) => Ok(*b),
            Some(_) => {
                Err(self.field_error(&format!("engines.{engine}.{key}"), "must be true or false"))
            }
        }
    }
}

/// `["a", "b"]` → `"a", "b"`.
pub(crate) fn quoted(items: &[&str]) -> String {
    items
        .iter()
        .map(|s| format!("\"{s}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

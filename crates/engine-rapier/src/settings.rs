//! The rigid-body engine's options (`[engines.rapier]` in a case file), each with its
//! unit, valid range and default, and how they map onto rapier's `IntegrationParameters`.
//! Every value is echoed into `Run::settings`, so an output always says what it ran with.

use rapier3d_f64::prelude::{FrictionModel, IntegrationParameters, SpringCoefficients};

use rockslide_core::case::{Case, Excitation, Model, Oscillator, Signal};
use rockslide_core::error::InputError;
use rockslide_engine_api::{Setting, SettingValue};

/// The engine's id, as in `[engines.rapier]`.
pub(crate) const ID: &str = "rapier";

/// How an oscillator's elastic-plastic contact is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OscillatorContact {
    /// `"joint-limit"` (default): the mass joined straight to the ground by a spring joint
    /// whose force rapier caps at μ·N, in series with a massless slider (no foot body).
    JointLimit,
    /// `"foot"`: a spring joint to a light foot body that slides on the ground with
    /// rapier's contact friction (the foot's inertia joins the oscillator).
    Foot,
    /// `"computed-supports"` (rocking body only): the supports' springs and Coulomb law
    /// computed by the engine from the body's pose after each rapier step and applied to
    /// the rapier body as an external force and torque for the next one; rapier
    /// integrates a single body with no joints and no colliders.
    ComputedSupports,
}

/// How rapier's own step is chosen from the output step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepRule {
    /// `"scene"` (default): the scene's step rule (oscillator accuracy, rocking mode,
    /// block slip estimate) divides the output step into several rapier steps.
    Scene,
    /// `"none"`: one rapier step per output step, whatever the scene; what the stability
    /// map runs, so that it shows rapier's own stability limit.
    None,
}

/// What one rapier run uses besides the time step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RapierSettings {
    /// `substeps`: solver substeps per step (rapier's `num_solver_iterations`), 1…1000,
    /// default 4 (rapier's default).
    pub substeps: usize,
    /// `pgs_iterations`: Gauss–Seidel sweeps per substep (`num_internal_pgs_iterations`),
    /// 1…1000, default 1 (8 for a rocking body on feet, [`FOOT_ROCKING_SWEEPS`]).
    pub pgs_iterations: usize,
    /// `friction_model`: `"simplified"` (one Coulomb constraint per manifold plus a twist
    /// constraint; rapier's default and ours: measured to give exactly the scene's μ) or
    /// `"coulomb"` (one constraint per contact point; measured to give an effective μ
    /// about 13 % low on a sliding block — see docs/rapier-engine.md).
    pub friction: FrictionModel,
    /// `foot_mass_ratio`: mass of each foot body over the structure's mass, in (0, 1),
    /// default 1e-2 (scenes with elasticity only).
    pub foot_mass_ratio: f64,
    /// `contact_hz`: natural frequency of the contact softness, Hz, applied to contacts
    /// with moving and with fixed bodies alike; default `None` = rapier's defaults
    /// (30 Hz against moving bodies, 60 Hz against fixed ones), 1000 Hz for a rocking body.
    pub contact_hz: Option<f64>,
    /// `contact_damping_ratio`: damping ratio of the contact softness, default 10 (rapier's).
    pub contact_damping_ratio: f64,
    /// `contact_model`: the elastic-plastic supports: `"joint-limit"` (an oscillator's
    /// default), `"computed-supports"` (a rocking body's default; rocking body only) or
    /// `"foot"`.
    pub oscillator_contact: OscillatorContact,
    /// `accuracy`: the relative accuracy the joint-limit oscillator's rapier step is
    /// chosen for (residual sliding and peak |u| against the exact solution), in
    /// [1e-4, 0.2]; default 0.01.
    pub accuracy: f64,
    /// `step_rule`: `"scene"` (default) or `"none"` (one rapier step per output step).
    pub step_rule: StepRule,
}

/// How the joint-limit oscillator is stepped: rapier steps of `dt_inner` (the output
/// step divided by `stride`), chosen from the scene and the accuracy target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OscillatorSteps {
    /// rapier steps per output step.
    pub stride: usize,
    /// rapier's step, s.
    pub dt_inner: f64,
    /// The largest step the accuracy target allows, s.
    pub dt_max: f64,
    /// The shortest period the step must resolve (structure or sine pulse), s.
    pub period: f64,
    /// Whether the excitation (a shorter pulse period, or a record step below the
    /// period rule) sets `dt_max` rather than the structure's period.
    pub excitation_limits: bool,
}

/// Error constant of the joint-limit oscillator's step rule: residual sliding error
/// ≈ C·(Δt/T)², measured on the Northridge PEPO (1.9 % at Δt/T = 0.025, 0.34–0.48 % at
/// 0.0125, 0.06 % at 0.005: second order); the rule uses 10 C, a safety factor for
/// records whose residual is small against their peak (docs/rapier-engine.md).
const STEP_ERROR_CONSTANT: f64 = 300.0;

/// Gauss–Seidel sweeps per substep of a rocking body on feet (`contact_model = "foot"`):
/// with fewer, the loaded feet creep under zero horizontal load.
pub const FOOT_ROCKING_SWEEPS: usize = 8;

/// More rapier steps per output step than this is outside what the engine runs.
pub const MAX_STRIDE: usize = 10_000;

impl OscillatorSteps {
    /// rapier's step for an oscillator scene: Δt ≤ T_min·√(ε/300), where T_min is the
    /// shorter of the structure's period 2π/ω and a sine pulse's period, and Δt ≤ a
    /// record's sample step (every sample of the piecewise-linear record is a step
    /// boundary's neighbour; the ground tables integrate it exactly in between); the
    /// output step is divided into the fewest equal steps that satisfy both.
    pub fn for_scene(osc: &Oscillator, excitation: &Excitation, dt: f64, accuracy: f64) -> Self {
        let (period, excitation_limits) = shortest_period(osc, excitation);
        let signal = excitation.signal();
        let mut dt_max = period * (accuracy / STEP_ERROR_CONSTANT).sqrt();
        let mut excitation_limits = excitation_limits;
        if let Some(Signal::Record { dt: rdt, .. }) = signal
            && *rdt < dt_max
        {
            dt_max = *rdt;
            excitation_limits = true;
        }
        let stride = ((dt / dt_max * (1.0 - 1e-12)).ceil() as usize).clamp(1, MAX_STRIDE);
        Self {
            stride,
            dt_inner: dt / stride as f64,
            dt_max,
            period,
            excitation_limits,
        }
    }

    /// The accuracy target whose step rule gives rapier steps of `dt` on this scene,
    /// ε = 300·(Δt/T_min)² (the rule inverted), within the accepted range
    /// [[`ACCURACY_MIN`], [`ACCURACY_MAX`]]: what `rockslide sweep` runs each rung at, so
    /// that its ladder is the rule's own steps (a rung coarser than the loosest target's
    /// step, T_min/38.7, is still divided by the rule).
    pub fn accuracy_for_step(osc: &Oscillator, excitation: &Excitation, dt: f64) -> f64 {
        let (period, _) = shortest_period(osc, excitation);
        (STEP_ERROR_CONSTANT * (dt / period).powi(2)).clamp(ACCURACY_MIN, ACCURACY_MAX)
    }

    /// The same scene stepped without the rule (`step_rule = "none"`): one rapier step
    /// per output step, `dt_max` still the rule's, so that [`Self::within_target`] says
    /// whether the output step happens to meet it.
    pub fn at_output_step(self, dt: f64) -> Self {
        Self {
            stride: 1,
            dt_inner: dt,
            ..self
        }
    }

    /// Whether the chosen step meets the accuracy target (false only when the stride
    /// would exceed [`MAX_STRIDE`]).
    pub fn within_target(&self) -> bool {
        self.dt_inner <= self.dt_max * (1.0 + 1e-12)
    }
}

/// The shortest period the oscillator's step must resolve, s: the structure's 2π/ω, or a
/// sine pulse's period when shorter (then `true`: the excitation sets it).
fn shortest_period(osc: &Oscillator, excitation: &Excitation) -> (f64, bool) {
    let structure = osc.period();
    match excitation.signal() {
        Some(Signal::SinePulse { omega, .. }) if 2.0 * std::f64::consts::PI / omega < structure => {
            (2.0 * std::f64::consts::PI / omega, true)
        }
        _ => (structure, false),
    }
}

/// The tightest `accuracy` a case may ask for.
pub const ACCURACY_MIN: f64 = 1e-4;

/// The loosest `accuracy` a case may ask for.
pub const ACCURACY_MAX: f64 = 0.2;

/// Contact natural frequency of the rigid block on a moving kinematic ground under a
/// record, Hz (rapier's default for a contact with a moving body is 30 Hz). The soft
/// contact lets the block sink g/ω² (0.28 mm at 30 Hz) and tilt under the friction's
/// moment, and the tilt's back and forth counts as sliding: measured on the Northridge
/// block at 1 ms and one substep, residual −0.85 % at 30 Hz, −0.12 % at 120 Hz, −0.07 %
/// at 240 Hz, −0.06 % at 1000 Hz (total slid +1.05, +0.83, +0.84, +0.85 %); at 0.5 ms
/// 240 and 480 Hz agree within 0.04 % of the slid on all fifteen record runs.
pub const KINEMATIC_BLOCK_CONTACT_HZ: f64 = 240.0;

/// Whether a run is the plane rigid block on a kinematic ground under a recorded ground
/// acceleration: the scene whose solver defaults [`RapierSettings::for_run`] sets, and
/// whose step the block's step rule chooses.
pub(crate) fn kinematic_block_on_record(case: &Case, kinematic_ground: bool) -> bool {
    kinematic_ground
        && case.scene.spatial().is_none()
        && matches!(case.scene.model, Model::RigidBlock(_))
        && matches!(
            case.scene.excitation,
            Excitation::GroundAcceleration(Signal::Record { .. })
        )
}

/// The `[engines.rapier]` options of a case parsed once, as the settings of its runs on a
/// kinematic ground and of its other runs ([`RapierSettings::for_run`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RapierOptions {
    /// The settings of a run on a kinematic ground.
    pub kinematic_ground: RapierSettings,
    /// The settings of every other run (inertial force, applied force, fixed ground).
    pub other: RapierSettings,
}

impl RapierOptions {
    /// Read and validate the case's options; every problem is returned, located.
    pub fn parse(case: &Case) -> Result<Self, Vec<InputError>> {
        Ok(Self {
            kinematic_ground: RapierSettings::for_run(case, true)?,
            other: RapierSettings::for_run(case, false)?,
        })
    }

    /// The case's options as the registry parsed them when it was loaded (parsed now for
    /// a case read without it), or the first problem with them.
    pub(crate) fn of(case: &Case) -> Result<Self, InputError> {
        rockslide_engine_api::parsed_options(case, ID, Self::parse)
    }

    /// The settings of a run on a kinematic ground or not.
    pub fn of_run(&self, kinematic_ground: bool) -> RapierSettings {
        if kinematic_ground {
            self.kinematic_ground
        } else {
            self.other
        }
    }
}

impl Default for RapierSettings {
    fn default() -> Self {
        Self {
            substeps: 4,
            pgs_iterations: 1,
            friction: FrictionModel::Simplified,
            foot_mass_ratio: 1e-2,
            contact_hz: None,
            contact_damping_ratio: 10.0,
            oscillator_contact: OscillatorContact::JointLimit,
            accuracy: 0.01,
            step_rule: StepRule::Scene,
        }
    }
}

impl RapierSettings {
    /// The settings of one run of the case, on a kinematic ground or not: the case's
    /// options over the defaults of its model ([`Self::for_model`]), and for the plane
    /// rigid block on a kinematic ground under a record ([`kinematic_block_on_record`])
    /// one substep per rapier step and [`KINEMATIC_BLOCK_CONTACT_HZ`] contacts. A
    /// kinematic ground's velocity changes once per step, and friction can absorb only
    /// μ·N·Δt/substeps of that change in the first substep: with several substeps the
    /// stuck block slips behind the ground every step (measured on the Northridge block at
    /// 1 ms: total slid +1.05 % at 1 substep, +1.83 % at 2, +2.87 % at 4, +3.74 % at 8).
    pub fn for_run(case: &Case, kinematic_ground: bool) -> Result<Self, Vec<InputError>> {
        let model = Self::for_model(&case.scene.model);
        let defaults = if kinematic_block_on_record(case, kinematic_ground) {
            Self {
                substeps: 1,
                contact_hz: Some(KINEMATIC_BLOCK_CONTACT_HZ),
                ..model
            }
        } else {
            model
        };
        Self::with_defaults(case, defaults)
    }

    /// The case's options read and validated over the defaults `d`: the numbers, the
    /// named choices, the model's defaults where an option is not given, then the keys
    /// no option has (every error in that order).
    fn with_defaults(case: &Case, d: Self) -> Result<Self, Vec<InputError>> {
        let mut errors = Vec::new();
        let n = Numbers::read(case, &d, &mut errors);
        let friction = friction_model(case, &mut errors);
        let oscillator_contact = contact_model(case, &d, &mut errors);
        let step_rule = step_rule(case, &mut errors);
        let (substeps, pgs) = contact_defaults(case, oscillator_contact, n.substeps, n.pgs);
        unknown_options(case, &mut errors);
        if !errors.is_empty() {
            return Err(errors);
        }
        Ok(Self {
            substeps: substeps as usize,
            pgs_iterations: pgs as usize,
            friction,
            foot_mass_ratio: n.foot,
            contact_hz: if n.has_hz { Some(n.hz) } else { d.contact_hz },
            contact_damping_ratio: n.zeta,
            oscillator_contact,
            accuracy: n.accuracy,
            step_rule,
        })
    }

    /// Defaults for a model. A rocking body on feet (`contact_model = "foot"`) carries
    /// its vertical load through ten spring joints into light feet on the ground: there the ground must be far stiffer than a support
    /// (rapier's default 60 Hz contact under a 1 t foot carrying W/10 sinks about as much
    /// as the support spring Kz deflects, and its damping ratio of 10 in series with the
    /// spring eats the response), and the coupled joint–friction system needs several
    /// Gauss–Seidel sweeps to converge (with 1 sweep the loaded feet creep under zero
    /// horizontal load; [`FOOT_ROCKING_SWEEPS`]). Measured (docs/rapier-engine.md):
    /// contact 1000 Hz vs 3000 Hz change peak uplift and rotation by < 2 %; 8 vs 16
    /// sweeps by < 0.5 %. The default joint-limit supports have no contacts and need one
    /// sweep (1, 2 and 8 agree within 1e-5 on the RPEPO).
    /// An oscillator with the joint-limit contact (the default) takes one substep: its
    /// error is the output-step subdivision's ([`OscillatorSteps`]), and substeps cost
    /// as much as steps without moving the slider.
    pub fn for_model(model: &Model) -> Self {
        match model {
            Model::Oscillator(_) => Self {
                substeps: 1,
                ..Self::default()
            },
            Model::RockingBody(_) => Self {
                contact_hz: Some(1000.0),
                oscillator_contact: OscillatorContact::ComputedSupports,
                ..Self::default()
            },
            _ => Self::default(),
        }
    }

    /// The `contact_model` name of the model's default.
    fn contact_model_name(&self) -> &'static str {
        match self.oscillator_contact {
            OscillatorContact::JointLimit => "joint-limit",
            OscillatorContact::Foot => "foot",
            OscillatorContact::ComputedSupports => COMPUTED_SUPPORTS,
        }
    }

    /// rapier's integration parameters for step `dt`.
    pub fn integration_parameters(&self, dt: f64) -> IntegrationParameters {
        let mut p = IntegrationParameters {
            dt,
            num_solver_iterations: self.substeps,
            num_internal_pgs_iterations: self.pgs_iterations,
            friction_model: self.friction,
            ..IntegrationParameters::default()
        };
        // Friction in the bias pass makes stuck bodies creep; keep it off.
        p.friction_in_bias_pass = false;
        // No continuous collision detection: no body of these scenes moves a sizeable part
        // of its size in one step, so CCD never clamps a motion, and with it on rapier still
        // checks every dynamic body each step. Measured off: every shipped rapier case's
        // traces and responses bit for bit as with it, 4.8 % fewer instructions per RPEPO
        // step (docs/rapier-engine.md, "Cost").
        p.max_ccd_substeps = 0;
        match self.contact_hz {
            Some(hz) => {
                let s = SpringCoefficients::new(hz, self.contact_damping_ratio);
                p.contact_softness = s;
                p.static_contact_softness = s;
            }
            None => {
                p.contact_softness.damping_ratio = self.contact_damping_ratio;
                p.static_contact_softness.damping_ratio = self.contact_damping_ratio;
            }
        }
        p
    }

    /// (name, value) pairs for `Run::settings`.
    pub fn describe(&self, dt: f64) -> Vec<Setting> {
        let p = self.integration_parameters(dt);
        let friction = match self.friction {
            FrictionModel::Coulomb => "Coulomb (one constraint per contact point)",
            FrictionModel::Simplified => "Simplified (one per manifold + twist)",
        };
        let softness = |s: SpringCoefficients<f64>| {
            SettingValue::Numbers(vec![s.natural_frequency, s.damping_ratio])
        };
        vec![
            Setting::number("dt", "s", dt),
            Setting::count("substeps", self.substeps as u64),
            Setting::count(
                "solver iterations (PGS per substep)",
                self.pgs_iterations as u64,
            ),
            Setting::new(
                "contact softness (moving body)",
                Some("Hz, ζ"),
                softness(p.contact_softness),
            ),
            Setting::new(
                "contact softness (fixed body)",
                Some("Hz, ζ"),
                softness(p.static_contact_softness),
            ),
            Setting::choice("friction model", friction),
            Setting::text(
                "friction combine",
                "both colliders carry the scene's μ (rule Average → μ)",
            ),
            Setting::text("restitution", "0 (both colliders, rule Min)"),
            Setting::text("sleeping", "disabled"),
            Setting::text(
                "continuous collision detection",
                "off (max_ccd_substeps = 0: no body moves a sizeable part of itself in a step)",
            ),
        ]
    }
}

/// Option keys the engine accepts.
pub const KEYS: &[&str] = &[
    "substeps",
    "pgs_iterations",
    "friction_model",
    "foot_mass_ratio",
    "contact_hz",
    "contact_damping_ratio",
    "contact_model",
    "accuracy",
    "step_rule",
];

/// The numeric options of a case as read over the defaults (a value out of range is
/// reported and replaced by its default).
struct Numbers {
    substeps: f64,
    pgs: f64,
    foot: f64,
    hz: f64,
    has_hz: bool,
    accuracy: f64,
    zeta: f64,
}

impl Numbers {
    /// Read every numeric option over the defaults `d`, then check that the counts are
    /// whole and a given `contact_hz` positive.
    fn read(case: &Case, d: &RapierSettings, errors: &mut Vec<InputError>) -> Self {
        let mut number = |key: &str, default: f64, lo: f64, hi: f64, what: &str| {
            engine_number(case, errors, key, default, (lo, hi), what)
        };
        let substeps = number(
            "substeps",
            d.substeps as f64,
            1.0,
            1000.0,
            "a whole number from 1 to 1000",
        );
        let pgs = number(
            "pgs_iterations",
            d.pgs_iterations as f64,
            1.0,
            1000.0,
            "a whole number from 1 to 1000",
        );
        let foot = number(
            "foot_mass_ratio",
            d.foot_mass_ratio,
            1e-9,
            0.999,
            "a mass ratio between 1e-9 and 0.999",
        );
        let hz = number("contact_hz", 0.0, 0.0, 1e9, "a frequency in Hz, positive");
        let accuracy = number(
            "accuracy",
            d.accuracy,
            ACCURACY_MIN,
            ACCURACY_MAX,
            "a relative accuracy from 1e-4 to 0.2",
        );
        let zeta = number(
            "contact_damping_ratio",
            d.contact_damping_ratio,
            0.0,
            1e6,
            "a damping ratio, zero or positive",
        );
        let whole = |x: f64| x.fract() == 0.0;
        for (key, x) in [("substeps", substeps), ("pgs_iterations", pgs)] {
            if !whole(x) {
                errors.push(case.field_error(
                    &format!("engines.{ID}.{key}"),
                    format!("is {x}, but must be a whole number"),
                ));
            }
        }
        let has_hz = has_option(case, "contact_hz");
        if has_hz && hz <= 0.0 {
            errors.push(case.field_error(
                &format!("engines.{ID}.contact_hz"),
                "must be a positive frequency in Hz",
            ));
        }
        Self {
            substeps,
            pgs,
            foot,
            hz,
            has_hz,
            accuracy,
            zeta,
        }
    }
}

/// Whether the case gives the option `key` of this engine.
fn has_option(case: &Case, key: &str) -> bool {
    case.engine(ID).is_some_and(|r| r.options.contains_key(key))
}

/// The number option `key` (`default` when not given) within `lo..=hi`; otherwise an
/// error saying it must be `what`, and the default.
fn engine_number(
    case: &Case,
    errors: &mut Vec<InputError>,
    key: &str,
    default: f64,
    (lo, hi): (f64, f64),
    what: &str,
) -> f64 {
    match case.engine_number(ID, key, default) {
        Ok(x) if x.is_finite() && x >= lo && x <= hi => x,
        Ok(x) => {
            errors.push(case.field_error(
                &format!("engines.{ID}.{key}"),
                format!("is {x}, but must be {what}"),
            ));
            default
        }
        Err(e) => {
            errors.push(e);
            default
        }
    }
}

/// `friction_model`: rapier's `"simplified"` (default) or `"coulomb"` friction.
fn friction_model(case: &Case, errors: &mut Vec<InputError>) -> FrictionModel {
    match case.engine_text(
        ID,
        "friction_model",
        "simplified",
        &["simplified", "coulomb"],
    ) {
        Ok(s) if s == "coulomb" => FrictionModel::Coulomb,
        Ok(_) => FrictionModel::Simplified,
        Err(e) => {
            errors.push(e);
            FrictionModel::Simplified
        }
    }
}

/// `contact_model`'s name for the supports the engine computes itself.
const COMPUTED_SUPPORTS: &str = "computed-supports";

/// The former name of [`COMPUTED_SUPPORTS`], which is also the name of the mass-acceleration
/// variant: still read, with a located note in the run's findings
/// ([`former_contact_model_name`]).
const FORMER_COMPUTED_SUPPORTS: &str = "applied-force";

/// `contact_model` over the model's default: `"computed-supports"` (or its former name)
/// is refused but for a rocking body.
fn contact_model(
    case: &Case,
    d: &RapierSettings,
    errors: &mut Vec<InputError>,
) -> OscillatorContact {
    match case.engine_text(
        ID,
        "contact_model",
        d.contact_model_name(),
        &[
            "joint-limit",
            "foot",
            COMPUTED_SUPPORTS,
            FORMER_COMPUTED_SUPPORTS,
        ],
    ) {
        Ok(s) if s == "foot" => OscillatorContact::Foot,
        Ok(s) if s == COMPUTED_SUPPORTS || s == FORMER_COMPUTED_SUPPORTS => {
            if !matches!(case.scene.model, Model::RockingBody(_)) {
                errors.push(case.field_error(
                    &format!("engines.{ID}.contact_model"),
                    format!("is \"{s}\", which is built for a rocking body only; use \"joint-limit\" or \"foot\""),
                ));
            }
            OscillatorContact::ComputedSupports
        }
        Ok(_) => OscillatorContact::JointLimit,
        Err(e) => {
            errors.push(e);
            OscillatorContact::JointLimit
        }
    }
}

/// A located note when the case names the computed supports by their former name
/// (`contact_model = "applied-force"`, the name of the mass-acceleration variant too).
pub(crate) fn former_contact_model_name(case: &Case) -> Option<String> {
    let named = case.engine_text(ID, "contact_model", "", &[FORMER_COMPUTED_SUPPORTS]);
    (named.ok()? == FORMER_COMPUTED_SUPPORTS).then(|| {
        case.field_error(
            &format!("engines.{ID}.contact_model"),
            format!("\"{FORMER_COMPUTED_SUPPORTS}\" is the former name of \"{COMPUTED_SUPPORTS}\" (read as it; \"{FORMER_COMPUTED_SUPPORTS}\" names the mass-acceleration variant): write \"{COMPUTED_SUPPORTS}\""),
        )
        .to_string()
    })
}

/// `step_rule`: `"scene"` (default) or `"none"`.
fn step_rule(case: &Case, errors: &mut Vec<InputError>) -> StepRule {
    match case.engine_text(ID, "step_rule", "scene", &["scene", "none"]) {
        Ok(s) if s == "none" => StepRule::None,
        Ok(_) => StepRule::Scene,
        Err(e) => {
            errors.push(e);
            StepRule::Scene
        }
    }
}

/// Substeps and Gauss–Seidel sweeps where the case gives none: the contact model's.
fn contact_defaults(
    case: &Case,
    contact: OscillatorContact,
    substeps: f64,
    pgs: f64,
) -> (f64, f64) {
    let substeps = match contact {
        OscillatorContact::Foot if !has_option(case, "substeps") => {
            RapierSettings::default().substeps as f64
        }
        // Applied forces are held over the whole rapier step: substeps add nothing.
        OscillatorContact::ComputedSupports if !has_option(case, "substeps") => 1.0,
        _ => substeps,
    };
    // The rocking body's feet need 8 sweeps (their loaded contacts creep with 1); the
    // joint-limit supports are as accurate with 1 (docs/rapier-engine.md).
    let pgs = if contact == OscillatorContact::Foot
        && matches!(case.scene.model, Model::RockingBody(_))
        && !has_option(case, "pgs_iterations")
    {
        FOOT_ROCKING_SWEEPS as f64
    } else {
        pgs
    };
    (substeps, pgs)
}

/// An error for every option of this engine that is not one of [`KEYS`].
fn unknown_options(case: &Case, errors: &mut Vec<InputError>) {
    if let Some(r) = case.engine(ID) {
        for key in r.options.keys() {
            if !KEYS.contains(&key.as_str()) {
                errors.push(case.field_error(
                    &format!("engines.{ID}.{key}"),
                    format!(
                        "unknown option of the rapier engine; options are {}",
                        KEYS.join(", ")
                    ),
                ));
            }
        }
    }
}

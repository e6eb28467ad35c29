//! Engine 2: an implicit penalty finite-element contact model.
//! CONTA178-like contact elements (compression-only normal penalty, tangential penalty
//! capped by μ times the element's own normal force, slip by return mapping) join the
//! ground, massless intermediate nodes and a rigid body (point mass at the centre of
//! mass, rigid massless base with supports, exact or small-rotation kinematics). Time
//! stepping is Newmark average acceleration or HHT-α with Newton–Raphson on the
//! consistent tangent; gravity is a static preload. Single- and double-element
//! arrangements of the paper's PEPO and RPEPO (AL-Shawaf & Rahman, Figs 1 and 7).
//!
//! - `element`: the element trait and the contact element of both dimensions
//!   (trial/commit).
//! - `series`: double supports condensed into one series-equivalent element, and the
//!   node's exact equilibrium, in both dimensions.
//! - `model`: the one model of both dimensions, generic over the `Dimension` (plane or
//!   space): body, nodes, supports; assembly; the condensed Newton solve.
//! - `stepper`: static preload and the time loop.
//! - `space`: the engine on a bidirectional (3D) scene.
//! - `modes`: the model's own eigenfrequencies.
//! - `options`: the `[engines.fe]` options.
//! - `simulate`: one run: build the model, integrate, gather settings and findings.
//! - `run_parts`: what a run states alike in either dimension (variant, errors, solver
//!   statistics, integrator settings).
//! - `recording`: the trace channels and the row handed to a sink at every step (the
//!   engine streams natively: a whole run is the same loop into a trace sized up front).
//! - `energy`: the energy bookkeeping of rocking runs.
//! - `findings`: eigenfrequencies, self-checks and sensitivity reported as findings.
//! - `variant`: the variants (single, double).
//! - `vertical`: vertical ground motion as an inertial load.
//! - `whole_run`: the sink of a whole run (rows kept row-major, split into columns once).

#![warn(missing_docs)]

mod element;
mod energy;
mod findings;
mod lu;
mod model;
mod modes;
mod options;
mod recording;
mod run_parts;
mod series;
mod simulate;
pub mod space;
mod stepper;
pub mod variant;
mod vertical;
mod whole_run;

pub use element::{
    ConeContact, ConeState, Contact, Contact178, ContactState, Element, Status, Tangential,
};
pub use model::{Dimension, Model, Plane, PlaneKinematics, Space, default_rotational_inertia};
pub use modes::{Modes, eigenfrequencies};
pub use options::{FeOptions, Integrator, Kinematics, Newton, OPTION_KEYS};
pub use simulate::{simulate, simulate_into};

use std::sync::Arc;

use rockslide_core::case::{Case, EngineOptions, Model as SceneModel, OptionValue, Scene};
use rockslide_core::error::InputError;
use rockslide_engine_api::{
    Arrangement, Engine, NotApplicable, Run, StepSink, Variant, parsed_options,
};

/// The penalty FE contact engine.
pub struct Fe;

impl Engine for Fe {
    fn id(&self) -> &'static str {
        options::ID
    }

    fn description(&self) -> &'static str {
        "implicit penalty FE model: CONTA178-like contact elements, rigid body, Newmark/HHT with Newton–Raphson"
    }

    fn variants(&self, scene: &Scene) -> Result<Vec<Variant>, NotApplicable> {
        vertical::check(scene)?;
        let names = match scene.spatial() {
            Some(s) => space::variants(scene, s)?,
            None => planar_variants(scene)?,
        };
        Ok(names.into_iter().map(variant::declared).collect())
    }

    fn parse_options(&self, case: &Case) -> Result<Option<EngineOptions>, Vec<InputError>> {
        parse_options(case).map(|o| Some(Arc::new(o) as EngineOptions))
    }

    /// Newton on a small system: 0.2–1.1 µs a step on the default run's cases.
    fn step_cost(&self, _scene: &Scene, _variant: Variant) -> f64 {
        6.0
    }

    /// The rotational-inertia and P-Delta sensitivity reruns (four extra runs of a rocking
    /// body) only feed the report: a sweep switches them off unless the case sets them.
    fn for_sweep(&self, case: &mut Case) -> Vec<String> {
        let section = case.engines.entry(self.id().to_string()).or_default();
        if section.options.contains_key(options::SENSITIVITY) {
            return Vec::new();
        }
        section
            .options
            .insert(options::SENSITIVITY.into(), OptionValue::Bool(false));
        vec![format!(
            "`[engines.fe] {} = false`: the FE engine's rotational-inertia and P-Delta sensitivity reruns (four extra runs of a rocking body) are not part of the method's cost",
            options::SENSITIVITY
        )]
    }

    fn run(&self, case: &Case, variant: Variant, dt: f64) -> Result<Run, InputError> {
        simulate(case, variant.name, dt, &options(case)?)
    }

    fn run_streaming(
        &self,
        case: &Case,
        variant: Variant,
        dt: f64,
        sink: &mut dyn StepSink,
    ) -> Result<Run, InputError> {
        simulate_into(case, variant.name, dt, &options(case)?, sink)
    }

    fn streams_natively(&self) -> bool {
        true
    }

    fn recorded_values(&self, case: &Case, variant: Variant) -> Option<usize> {
        simulate::recorded_values(case, variant.name, &options(case).ok()?)
    }

    fn models_plan_motion(&self) -> bool {
        true
    }
}

/// The variants of a planar scene: single, and double where the scene has the double element.
fn planar_variants(scene: &Scene) -> Result<Vec<&'static str>, NotApplicable> {
    let double = match &scene.model {
        SceneModel::Oscillator(o) => o.double.is_some(),
        SceneModel::RockingBody(r) => r.double.is_some(),
        SceneModel::RigidBlock(_) => {
            return Err(NotApplicable(
            "the penalty FE model needs contact stiffnesses, and a rigid block on a rigid ground has none (penalty stiffness would be a modelling choice, not the scene)".into(),
        ));
        }
    };
    Ok(if double {
        vec![variant::SINGLE, variant::DOUBLE]
    } else {
        vec![variant::SINGLE]
    })
}

/// How the variant named `variant` carries the base reaction.
fn arrangement(variant: &str) -> Arrangement {
    variant::declared(variant).arrangement
}

/// The case's `[engines.fe]` options as parsed when it was loaded, or the first error in
/// them.
fn options(case: &Case) -> Result<FeOptions, InputError> {
    parsed_options(case, options::ID, parse_options)
}

/// The case's `[engines.fe]` options parsed, or every problem with them.
fn parse_options(case: &Case) -> Result<FeOptions, Vec<InputError>> {
    let (opts, errors) = FeOptions::parse(case);
    if errors.is_empty() {
        Ok(opts)
    } else {
        Err(errors)
    }
}

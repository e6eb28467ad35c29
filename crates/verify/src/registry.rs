//! The one registry of engines: input validation (which `[engines.<id>]` a case may name),
//! `list`, and every command that runs engines ask it. It is also the one gate on
//! bidirectional (3D) scenes: an engine that does not model plan motion
//! ([`Engine::models_plan_motion`]) is "not applicable" to a spatial scene, never run on
//! its planar part.

use std::path::Path;

use rockslide_core::case::{Case, Scene};
use rockslide_core::error::{InputError, InputErrors};
use rockslide_engine_api::{Engine, NotApplicable, Run, StepSink};

/// Ids of every engine, as written in case files (`[engines.<id>]`), in report column order.
pub const ENGINE_IDS: &[&str] = &["predictor-corrector", "fe", "rapier"];

/// Sections a case may have under `[engines.<id>]`: the engines, and `opensees` (the
/// live OpenSees participant, [`crate::opensees`]: exported, run and read back).
pub const CASE_SECTION_IDS: &[&str] = &["predictor-corrector", "fe", "rapier", "opensees"];

/// Every engine, in report column order (the order of [`ENGINE_IDS`]), each behind the
/// spatial gate ([`PlanGate`]).
pub fn all() -> Vec<Box<dyn Engine>> {
    vec![
        Box::new(PlanGate(rockslide_engine_pc::PredictorCorrector)),
        Box::new(PlanGate(rockslide_engine_fe::Fe)),
        Box::new(PlanGate(rockslide_engine_rapier::Rapier)),
    ]
}

/// Why an engine that models motion in one vertical plane does not run a 3D scene.
pub fn plan_motion_refusal(engine: &str) -> NotApplicable {
    NotApplicable(format!(
        "bidirectional (3D) scene is not modelled in {engine}"
    ))
}

/// An engine behind the spatial gate: a scene with plan motion (`Scene::spatial`) is not
/// applicable unless the engine models it; everything else is the engine's own answer.
pub struct PlanGate<E>(pub E);

impl<E: Engine> PlanGate<E> {
    /// The case's scene refused, located, when it is spatial and the engine is planar.
    fn admit(&self, case: &Case) -> Result<(), InputError> {
        if case.scene.spatial.is_some() && !self.0.models_plan_motion() {
            return Err(case.field_error("excitation", plan_motion_refusal(self.0.id()).0));
        }
        Ok(())
    }
}

impl<E: Engine> Engine for PlanGate<E> {
    fn id(&self) -> &'static str {
        self.0.id()
    }
    fn description(&self) -> &'static str {
        self.0.description()
    }
    fn variants(&self, scene: &Scene) -> Result<Vec<&'static str>, NotApplicable> {
        if scene.spatial.is_some() && !self.0.models_plan_motion() {
            return Err(plan_motion_refusal(self.0.id()));
        }
        self.0.variants(scene)
    }
    fn check_options(&self, case: &Case) -> Vec<InputError> {
        self.0.check_options(case)
    }
    fn models_plan_motion(&self) -> bool {
        self.0.models_plan_motion()
    }
    fn run(&self, case: &Case, variant: &str, dt: f64) -> Result<Run, InputError> {
        self.admit(case)?;
        self.0.run(case, variant, dt)
    }
    fn run_streaming(
        &self,
        case: &Case,
        variant: &str,
        dt: f64,
        sink: &mut dyn StepSink,
    ) -> Result<Run, InputError> {
        self.admit(case)?;
        self.0.run_streaming(case, variant, dt, sink)
    }
    fn streams_natively(&self) -> bool {
        self.0.streams_natively()
    }
    fn recorded_values(&self, case: &Case, variant: &str) -> Option<usize> {
        self.0.recorded_values(case, variant)
    }
}

/// Read and validate a case file against the registry's engines.
pub fn load_case(path: &Path) -> Result<Case, InputErrors> {
    rockslide_formats::load_case(path, CASE_SECTION_IDS)
}

/// Validate a case from its text against the registry's engines.
pub fn parse_case(path: &Path, text: &str) -> Result<Case, InputErrors> {
    rockslide_formats::parse_case(path, text, CASE_SECTION_IDS)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_ids_are_the_engines_in_order() {
        let ids: Vec<&str> = super::all().iter().map(|e| e.id()).collect();
        assert_eq!(ids, super::ENGINE_IDS);
    }
}

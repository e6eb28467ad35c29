//! The one registry of engines: input validation (which `[engines.<id>]` a case may name),
//! `list`, and every command that runs engines ask it. It is also the one gate on
//! bidirectional (3D) scenes: an engine that does not model plan motion
//! ([`Engine::models_plan_motion`]) is "not applicable" to a spatial scene, never run on
//! its planar part.

use std::path::Path;

use rockslide_core::case::{Case, EngineOptions, Invariant, Scene};
use rockslide_core::error::{InputError, InputErrors};
use rockslide_engine_api::{Engine, NotApplicable, Run, StepSink, Variant};

/// Ids of every engine, as written in case files (`[engines.<id>]`), in report column order.
pub const ENGINE_IDS: &[&str] = &["predictor-corrector", "fe", "rapier"];

/// Sections a case may have under `[engines.<id>]`: the engines, `opensees` (the live
/// OpenSees participant, [`crate::opensees`]) and `calculix` (the live CalculiX
/// participant, [`crate::calculix`]): each exported, run and read back.
pub const CASE_SECTION_IDS: &[&str] = &[
    "predictor-corrector",
    "fe",
    "rapier",
    "opensees",
    "calculix",
];

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
    fn variants(&self, scene: &Scene) -> Result<Vec<Variant>, NotApplicable> {
        if scene.spatial.is_some() && !self.0.models_plan_motion() {
            return Err(plan_motion_refusal(self.0.id()));
        }
        self.0.variants(scene)
    }
    fn parse_options(&self, case: &Case) -> Result<Option<EngineOptions>, Vec<InputError>> {
        self.0.parse_options(case)
    }
    fn models_plan_motion(&self) -> bool {
        self.0.models_plan_motion()
    }
    fn run(&self, case: &Case, variant: Variant, dt: f64) -> Result<Run, InputError> {
        self.admit(case)?;
        self.0.run(case, variant, dt)
    }
    fn run_streaming(
        &self,
        case: &Case,
        variant: Variant,
        dt: f64,
        sink: &mut dyn StepSink,
    ) -> Result<Run, InputError> {
        self.admit(case)?;
        self.0.run_streaming(case, variant, dt, sink)
    }
    fn streams_natively(&self) -> bool {
        self.0.streams_natively()
    }
    fn recorded_values(&self, case: &Case, variant: Variant) -> Option<usize> {
        self.0.recorded_values(case, variant)
    }
    fn invariant_limit(&self, invariant: Invariant) -> f64 {
        self.0.invariant_limit(invariant)
    }
    fn step_cost(&self, scene: &Scene, variant: Variant) -> f64 {
        self.0.step_cost(scene, variant)
    }
    fn for_sweep(&self, case: &mut Case) -> Vec<String> {
        let notes = self.0.for_sweep(case);
        reparse_options(&self.0, case);
        notes
    }
    fn at_rung(&self, case: &Case, dt: f64) -> Option<Case> {
        let mut case = self.0.at_rung(case, dt)?;
        reparse_options(&self.0, &mut case);
        Some(case)
    }
    fn for_stability(&self, case: &mut Case) {
        self.0.for_stability(case);
        reparse_options(&self.0, case);
    }
}

/// The engine's options parsed again after its own change to them (a sweep's, a rung's,
/// the stability map's); options it cannot parse are dropped, so that its run parses
/// them itself and reports the located problem.
fn reparse_options<E: Engine + ?Sized>(engine: &E, case: &mut Case) {
    let parsed = engine.parse_options(case).ok().flatten();
    case.parsed_options.set(engine.id(), parsed);
}

/// Problems with engine `e`'s options in `case`: none for a case whose options were parsed
/// when it was loaded through the registry, else those the engine finds now (a case
/// read without the registry).
pub fn option_problems(case: &Case, e: &dyn Engine) -> Vec<InputError> {
    if case.parsed_options.contains(e.id()) {
        return Vec::new();
    }
    e.parse_options(case).err().unwrap_or_default()
}

/// The registered engine with this id.
pub fn engine(id: &str) -> Option<Box<dyn Engine>> {
    all().into_iter().find(|e| e.id() == id)
}

/// The engine whose completed run is the basis of another program's default checks when a
/// case has no reference: the penalty FE model, the contact model those programs share.
pub const EXTERNAL_BASIS_ENGINE: &str = "fe";

/// The tolerance on `invariant` of the run of engine `id`: the engine's own
/// ([`Engine::invariant_limit`]), or round-off for a run no registered engine made
/// (another program's results).
pub fn invariant_limit(id: &str, invariant: Invariant) -> f64 {
    engine(id).map_or(invariant.round_off_limit(), |e| {
        e.invariant_limit(invariant)
    })
}

/// The case as a work-precision sweep runs it: every engine's own changes
/// ([`Engine::for_sweep`]), in registry order, with each stated in words.
pub fn for_sweep(case: &Case) -> (Case, Vec<String>) {
    let mut case = case.clone();
    let notes = all().iter().flat_map(|e| e.for_sweep(&mut case)).collect();
    (case, notes)
}

/// The case as the stability map runs it: every engine stepping at the map's time step
/// ([`Engine::for_stability`]).
pub fn for_stability(case: &Case) -> Case {
    let mut case = case.clone();
    for e in all() {
        e.for_stability(&mut case);
    }
    case
}

/// Read and validate a case file against the registry's engines: its sections and each
/// engine's options ([`Engine::check_options`]), every error located.
pub fn load_case(path: &Path) -> Result<Case, InputErrors> {
    rockslide_formats::load_case(path, CASE_SECTION_IDS).and_then(with_valid_options)
}

/// Validate a case from its text against the registry's engines.
pub fn parse_case(path: &Path, text: &str) -> Result<Case, InputErrors> {
    rockslide_formats::parse_case(path, text, CASE_SECTION_IDS).and_then(with_valid_options)
}

/// The case with each engine's options parsed into the engine's type, or every problem
/// found with its engine sections: each engine's options (whether or not it applies to
/// the scene), variants asked of an engine that does not
/// apply, and the OpenSees participant's settings and export — the one validation every
/// command that reads a case goes through.
fn with_valid_options(mut case: Case) -> Result<Case, InputErrors> {
    let mut errors: Vec<InputError> = Vec::new();
    for e in all() {
        match e.parse_options(&case) {
            Ok(parsed) => case.parsed_options.set(e.id(), parsed),
            Err(problems) => errors.extend(problems),
        }
    }
    errors.extend(variants_of_inapplicable(&case));
    if let Err(e) = crate::opensees::prepare(&case) {
        errors.extend(e.0);
    }
    if errors.is_empty() {
        Ok(case)
    } else {
        Err(InputErrors(errors))
    }
}

/// `engines.<id>.variants` naming variants of an engine that does not apply to the
/// scene (a planar engine on a 3D scene): nothing could check them, so they are refused.
fn variants_of_inapplicable(case: &Case) -> Vec<InputError> {
    all()
        .iter()
        .filter_map(|e| {
            let asked = case.engine(e.id())?.variants.as_ref()?;
            let why = e.variants(&case.scene).err()?;
            (!asked.is_empty()).then(|| {
                case.field_error(
                    &format!("engines.{}.variants", e.id()),
                    format!(
                        "names {} of {}, which does not apply to this scene ({}): remove them",
                        asked.join(", "),
                        e.id(),
                        why.0
                    ),
                )
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An engine option out of its range is refused when the case is read, located, not
    /// when a command plans its runs.
    #[test]
    fn engine_options_are_checked_at_load() {
        let text = "[model]\nkind = \"oscillator\"\nmass = 1000.0\ngravity = 10.0\n[model.contact]\nkx = 1.0e6\nkz = 4.0e6\nmu = 0.5\n[excitation]\nkind = \"mass-acceleration\"\nshape = \"sine-pulse\"\namplitude = 1.0\nomega = 10.0\ncycles = 0.5\n[run]\nduration = 1.0\ndt = 0.01\n[engines.rapier]\nstep_rule = \"sometimes\"\n";
        let err = parse_case(Path::new("t.toml"), text)
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("t.toml:19:13: engines.rapier.step_rule"),
            "{err}"
        );
    }
    #[test]
    fn the_ids_are_the_engines_in_order() {
        let ids: Vec<&str> = super::all().iter().map(|e| e.id()).collect();
        assert_eq!(ids, super::ENGINE_IDS);
    }
}

//! The one registry of engines: input validation (which `[engines.<id>]` a case may name),
//! `list`, and every command that runs engines ask it.

use std::path::Path;

use rockslide_core::case::Case;
use rockslide_core::error::InputErrors;
use rockslide_engine_api::Engine;

/// Ids of every engine, as written in case files (`[engines.<id>]`), in report column order.
pub const ENGINE_IDS: &[&str] = &["predictor-corrector", "fe", "rapier"];

/// Sections a case may have under `[engines.<id>]`: the engines, and `opensees` (the
/// live OpenSees participant, [`crate::opensees`]: exported, run and read back).
pub const CASE_SECTION_IDS: &[&str] = &["predictor-corrector", "fe", "rapier", "opensees"];

/// Every engine, in report column order (the order of [`ENGINE_IDS`]).
pub fn all() -> Vec<Box<dyn Engine>> {
    vec![
        Box::new(rockslide_engine_pc::PredictorCorrector),
        Box::new(rockslide_engine_fe::Fe),
        Box::new(rockslide_engine_rapier::Rapier),
    ]
}

/// Read and validate a case file against the registry's engines.
pub fn load_case(path: &Path) -> Result<Case, InputErrors> {
    rockslide_core::case::load_case(path, CASE_SECTION_IDS)
}

/// Validate a case from its text against the registry's engines.
pub fn parse_case(path: &Path, text: &str) -> Result<Case, InputErrors> {
    rockslide_core::case::parse_case(path, text, CASE_SECTION_IDS)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_ids_are_the_engines_in_order() {
        let ids: Vec<&str> = super::all().iter().map(|e| e.id()).collect();
        assert_eq!(ids, super::ENGINE_IDS);
    }
}

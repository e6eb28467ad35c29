//! The default run's cost scheduler: each case's cost estimated from its planned runs, so
//! that the costliest cases start first (their longest runs set the critical path).

use rockslide_core::case::Case;
use rockslide_engine_api::Engine;
use rockslide_verify::registry;
use rockslide_verify::suite::plan;

/// A case's estimated cost: Σ over its planned runs of steps × the engine's cost of one
/// step of that variant on the scene ([`Engine::step_cost`]).
fn estimated_cost(case: &Case, engines: &[Box<dyn Engine>]) -> f64 {
    plan(case, engines).map_or(0.0, |p| {
        p.runs
            .iter()
            .map(|r| {
                let engine = engines.iter().find(|e| e.id() == r.engine);
                let step = engine.map_or(1.0, |e| e.step_cost(&case.scene, r.variant));
                case.run.duration / r.dt * step
            })
            .sum()
    })
}

/// The cases' indices, costliest first (ties: the cases' order).
pub(crate) fn longest_first(cases: &[Case]) -> Vec<usize> {
    let engines = registry::all();
    let costs: Vec<f64> = cases.iter().map(|c| estimated_cost(c, &engines)).collect();
    let mut order: Vec<usize> = (0..cases.len()).collect();
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]));
    order
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use super::*;
    use crate::input::load_all;

    /// rockslide shall start the default run's costliest cases first: a case's cost is
    /// Σ steps × step weight over its planned runs.
    #[test]
    fn the_record_cases_with_rapier_bodies_are_scheduled_first() {
        let paths: Vec<PathBuf> = [
            "cases/pepo-mass-accel.toml",
            "cases/records/pepo-loma-prieta.toml",
            "cases/records/rpepo-loma-prieta.toml",
            "cases/records/block-northridge.toml",
        ]
        .iter()
        .map(PathBuf::from)
        .collect();
        let cases = load_all(&paths).unwrap();
        let engines = registry::all();
        // RPEPO, 60 s at 1 ms: fe single and double (6 each) and rapier's applied-force
        // supports on a body (250)
        assert_eq!(
            estimated_cost(&cases[2], &engines),
            60_000.0 * (6.0 + 6.0 + 250.0)
        );
        // block, 22 s at 1 ms: rapier's kinematic ground (500) and inertial force (250)
        assert_eq!(
            estimated_cost(&cases[3], &engines),
            22_000.0 * (500.0 + 250.0)
        );
        assert_eq!(longest_first(&cases), [3, 2, 1, 0]);
    }
}

//! Invariants that must hold for any input: rockslide's resistance law and predictor-
//! corrector keep |R| ≤ μN, never do negative friction work, and stay deterministic.

use crate::common;

use proptest::prelude::*;
use rockslide::engine::predictor_corrector::resistance;
use rockslide::engine::predictor_corrector::variant as pc_variant;
use rockslide::engine::{Engine, predictor_corrector::PredictorCorrector};

proptest! {
    /// Paper Eqs 7–8: |R| ≤ Ru, and a change of slip has the sign of R (friction work ≥ 0).
    #[test]
    fn resistance_law_is_bounded_and_dissipative(x in -1.0..1.0f64, xp in -1.0..1.0f64, k in 1.0..1e9f64, ru in 0.0..1e6f64) {
        let (r, xp_new) = resistance(x, xp, k, ru);
        prop_assert!(r.abs() <= ru);
        prop_assert!((xp_new - xp) * r >= 0.0);
        // the elastic part is R/K, up to the rounding of x − xp (|x|·ε, times K)
        if xp_new != xp {
            let rounding = 4.0 * f64::EPSILON * k * (x.abs() + xp.abs() + xp_new.abs());
            prop_assert!(((x - xp_new) * k - r).abs() <= rounding);
        }
    }

    /// The whole predictor-corrector under any friction coefficient and pulse amplitude:
    /// |R| ≤ μMg at every step and the slip never moves against the resistance.
    #[test]
    fn predictor_corrector_respects_friction(mu in 0.01..2.0f64, amp in 0.1..10.0f64) {
        let case = common::case_with("pepo-mass-accel", "amplitude = 1.0 ", &format!("amplitude = {amp} "));
        let case = {
            let text = case.text.replacen("mu = 0.5\n", &format!("mu = {mu}\n"), 1);
            rockslide::case::parse_case(&case.path, &text).unwrap()
        };
        let run = PredictorCorrector.run(&case, pc_variant::PAPER, 1e-3).unwrap();
        let r = run.trace.column("resistance").unwrap();
        let xp = run.trace.column("slide").unwrap();
        let ru = mu * 1.0e6 * 1.0;
        for i in 1..r.len() {
            prop_assert!(r[i].abs() <= ru * (1.0 + 1e-12));
            prop_assert!((xp[i] - xp[i - 1]) * r[i] >= 0.0);
        }
    }
}

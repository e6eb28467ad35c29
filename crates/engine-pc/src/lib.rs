//! Engine 1: the paper's predictor-corrector for a single-degree-of-freedom elastic-plastic
//! oscillator, literally (AL-Shawaf & Rahman, "Verification of Seismic Stability
//! Modeling"): average acceleration (Eqs 3–5), one predicting and one correcting pass
//! (steps 1–6), the resistance law of Eqs 7–8, the Eq 9 convergence measure, and for
//! support motion the paper's Eq 12 route beside a consistent ground-acceleration route.

#![warn(missing_docs)]

mod options;
mod resistance;
mod stepper;
mod vertical;

pub use resistance::resistance;
pub use stepper::{GroundRoute, PcSettings, simulate, simulate_streaming, simulate_with_vertical};
pub use vertical::NormalStepper;

use std::sync::Arc;

use rockslide_core::case::{Case, EngineOptions, Excitation, Model, Scene};
use rockslide_core::error::InputError;
use rockslide_engine_api::{Engine, NotApplicable, Run, StepSink, Variant, parsed_options};

/// The paper's spreadsheet method.
pub struct PredictorCorrector;

/// The variants, each a constant the engine matches on.
pub mod variant {
    use rockslide_engine_api::Variant;

    /// Mass acceleration (or free response): the method as the paper states it.
    pub const PAPER: Variant = Variant::single("paper");
    /// Support displacement by the paper's Eq 12: effective ground displacement
    /// xg − xp, differentiated twice by finite differences.
    pub const EQ12: Variant = Variant::single("eq12");
    /// Eq 12 with the slip counted once (only through xg-eff, the resistance curve not
    /// shifted): what the paper's spreadsheet most plausibly did.
    pub const EQ12_SLIP_ONCE: Variant = Variant::single("eq12-slip-once");
    /// Support motion as ground acceleration in relative coordinates (ground-velocity
    /// jumps applied as impulses): the consistent route.
    pub const GROUND_ACCEL: Variant = Variant::single("ground-accel");
}

impl Engine for PredictorCorrector {
    fn id(&self) -> &'static str {
        options::ID
    }

    fn description(&self) -> &'static str {
        "the paper's predictor-corrector SDOF method (average acceleration, one predicting and one correcting pass)"
    }

    fn variants(&self, scene: &Scene) -> Result<Vec<Variant>, NotApplicable> {
        match &scene.model {
            Model::Oscillator(_) => {}
            other => {
                return Err(NotApplicable(format!(
                    "the predictor-corrector solves the paper's oscillator (one horizontal degree of freedom on an elastic-plastic contact); a {} is another model",
                    other.kind()
                )));
            }
        }
        Ok(match scene.excitation {
            Excitation::None | Excitation::MassAcceleration(_) => vec![variant::PAPER],
            Excitation::GroundDisplacement(_) => vec![
                variant::EQ12,
                variant::EQ12_SLIP_ONCE,
                variant::GROUND_ACCEL,
            ],
            Excitation::GroundAcceleration(_) => vec![variant::GROUND_ACCEL],
        })
    }

    fn parse_options(&self, case: &Case) -> Result<Option<EngineOptions>, Vec<InputError>> {
        options::parse(case).map(|o| Some(Arc::new(o) as EngineOptions))
    }

    fn run(&self, case: &Case, variant: Variant, dt: f64) -> Result<Run, InputError> {
        let (osc, settings) = prepare(case, variant, dt)?;
        Ok(simulate_with_vertical(
            osc,
            &case.scene.excitation,
            case.scene.vertical(),
            &settings,
            variant.name,
        ))
    }

    fn run_streaming(
        &self,
        case: &Case,
        variant: Variant,
        dt: f64,
        sink: &mut dyn StepSink,
    ) -> Result<Run, InputError> {
        let (osc, settings) = prepare(case, variant, dt)?;
        Ok(simulate_streaming(
            osc,
            &case.scene.excitation,
            case.scene.vertical(),
            &settings,
            variant.name,
            sink,
        ))
    }

    fn streams_natively(&self) -> bool {
        true
    }

    fn recorded_values(&self, case: &Case, _variant: Variant) -> Option<usize> {
        // time, the sliding channels (ground displacement when the ground moves), the
        // Eq 9 change, N(t) under vertical motion; one contact's four fields
        let channels = 6
            + usize::from(case.scene.excitation.moves_ground())
            + 1
            + usize::from(case.scene.vertical().is_some());
        Some(1 + channels + 4)
    }
}

/// The oscillator and the settings of one run, or the located reason it cannot run.
fn prepare(
    case: &Case,
    variant: Variant,
    dt: f64,
) -> Result<(&rockslide_core::case::Oscillator, PcSettings), InputError> {
    parsed_options::<options::PcOptions>(case, options::ID, options::parse)?;
    let Model::Oscillator(osc) = &case.scene.model else {
        return Err(case.field_error("model.kind", "the predictor-corrector needs an oscillator"));
    };
    let route = match variant {
        variant::EQ12 => GroundRoute::Eq12,
        variant::EQ12_SLIP_ONCE => GroundRoute::Eq12SlipOnce,
        _ => GroundRoute::GroundAcceleration,
    };
    let settings = PcSettings {
        dt,
        duration: case.run.duration,
        route,
    };
    Ok((osc, settings))
}

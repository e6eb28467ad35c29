//! What a sweep or a stability study runs: the scene's characteristic period T (the
//! ladders are in Δt/T) and every engine variant that applies to the scene.

use rockslide_core::case::{Case, Model, Signal};
use rockslide_core::error::{InputError, InputErrors};
use rockslide_engine_api::{Engine, Variant, declared};

use crate::registry::option_problems;

/// The scene's characteristic period T, s, and how it was obtained. The sweep's ladder
/// starts at T/10 (the paper's advice Δt < T/10) and the stability map is in Δt/T.
pub fn characteristic_period(case: &Case) -> (f64, String) {
    let tau = 2.0 * std::f64::consts::PI;
    match &case.scene.model {
        Model::Oscillator(o) => (
            o.period(),
            "T = 2π·√(M/Kx) of the oscillator (single element; the double element's series stiffness is the same by design)".into(),
        ),
        Model::RockingBody(r) => {
            // Shear (n·Kx) in series with rocking (Kz·Σxᵢ²/h²): the paper's RPEPO, ωX = 10π.
            let n = r.supports as f64;
            let k_shear = n * r.contact.kx;
            let k_rock = r.contact.kz * r.support_positions().iter().map(|x| x * x).sum::<f64>()
                / (r.cm_height * r.cm_height);
            let k = 1.0 / (1.0 / k_shear + 1.0 / k_rock);
            (
                tau * (r.mass / k).sqrt(),
                "T = 2π/ωX, shear stiffness n·Kx in series with rocking stiffness Kz·Σxᵢ²/h²"
                    .into(),
            )
        }
        Model::RigidBlock(_) => match case.scene.excitation.signal() {
            Some(Signal::SinePulse { omega, .. }) => (
                tau / omega,
                "rigid block: no elastic period; T = 2π/θ of the excitation".into(),
            ),
            _ => (
                case.run.duration / 10.0,
                "rigid block under a record or free: T = duration/10 (no natural period)".into(),
            ),
        },
    }
}

/// One engine variant to run.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Index into the engine list.
    pub engine: usize,
    /// Engine id.
    pub engine_id: &'static str,
    /// Variant, as the engine declared it.
    pub variant: Variant,
}

impl Series {
    /// `engine/variant`.
    pub fn label(&self) -> String {
        format!("{}/{}", self.engine_id, self.variant)
    }
}

/// An engine that does not apply to a scene, and why.
pub type NotApplicable = (String, String);

/// Every engine and variant that applies to the case — whether or not the case file
/// names the engine (a sweep is about the methods, the case's step does not matter) —
/// restricted to the variants the case asks for where it names some. Returns the series
/// and the engines that do not apply, with why.
pub fn applicable(
    case: &Case,
    engines: &[Box<dyn Engine>],
) -> Result<(Vec<Series>, Vec<NotApplicable>), InputErrors> {
    let mut series = Vec::new();
    let mut not_applicable = Vec::new();
    let mut errors: Vec<InputError> = Vec::new();
    for (i, e) in engines.iter().enumerate() {
        errors.extend(option_problems(case, e.as_ref()));
        match e.variants(&case.scene) {
            Err(na) => not_applicable.push((e.id().to_string(), na.0)),
            Ok(available) => {
                let asked = case.engine(e.id()).and_then(|r| r.variants.as_deref());
                let wanted = match asked {
                    Some(names) => names
                        .iter()
                        .filter_map(|n| declared(&available, n))
                        .collect(),
                    None => available,
                };
                series.extend(wanted.into_iter().map(|variant| Series {
                    engine: i,
                    engine_id: e.id(),
                    variant,
                }));
            }
        }
    }
    if errors.is_empty() {
        Ok((series, not_applicable))
    } else {
        Err(InputErrors(errors))
    }
}

/// The fine grid a reference is sampled on, shared with the case run.
pub use crate::reference::fine_grid;

//! The FE engine's options (`[engines.fe]` in a case file): integrator, Newton presets,
//! kinematics, P-Delta, rotational inertia. Each field says its unit and valid range; the
//! paper's Newton tolerances are one named preset.

use rockslide_core::case::Case;
use rockslide_core::error::InputError;

/// The engine's id, as in `[engines.fe]` and in every run it makes.
pub(crate) const ID: &str = "fe";

/// The option that switches the rotational-inertia and P-Delta sensitivity reruns.
pub(crate) const SENSITIVITY: &str = "sensitivity";

/// Every option key the engine understands.
pub const OPTION_KEYS: &[&str] = &[
    "integrator",
    "alpha",
    "newton",
    "max_iterations",
    "max_step_cuts",
    "kinematics",
    "p_delta",
    "rotational_inertia",
    SENSITIVITY,
];

/// Time integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// Newmark average acceleration (β = 1/4, γ = 1/2): second order, no dissipation.
    Newmark,
    /// Hilber–Hughes–Taylor α (Hilber, Hughes & Taylor 1977): α in [−1/3, 0],
    /// β = (1 − α)²/4, γ = 1/2 − α; damps modes with ω·Δt ≫ 1.
    Hht {
        /// α, in [−1/3, 0].
        alpha: f64,
    },
}

impl Integrator {
    /// (α, β, γ) in the HHT convention (α = 0 for Newmark).
    pub fn parameters(&self) -> (f64, f64, f64) {
        match *self {
            Integrator::Newmark => (0.0, 0.25, 0.5),
            Integrator::Hht { alpha } => (alpha, (1.0 - alpha).powi(2) / 4.0, 0.5 - alpha),
        }
    }
    /// The method's name, as a report states it.
    pub fn label(&self) -> &'static str {
        match self {
            Integrator::Newmark => "Newmark average acceleration",
            Integrator::Hht { .. } => "HHT-α",
        }
    }

    /// Name as in case files.
    pub fn name(&self) -> &'static str {
        match self {
            Integrator::Newmark => "newmark",
            Integrator::Hht { .. } => "hht",
        }
    }
}

/// Newton–Raphson convergence control. A step has converged when both the residual
/// force and the latest displacement correction are small (ANSYS-style criteria).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Newton {
    /// Preset name.
    pub preset: &'static str,
    /// ‖residual‖ ≤ force_tol · (‖external‖ + ‖internal‖ + ‖inertial‖) of the body.
    pub force_tol: f64,
    /// ‖latest correction‖ ≤ displacement_tol · ‖displacement increment of the step‖.
    pub displacement_tol: f64,
    /// Equilibrium iterations allowed per step before the run is declared not converged.
    pub max_iterations: usize,
    /// A failing step is cut in halves and retried down to Δt/2^max_step_cuts (0: never
    /// cut; the run ends at the first step Newton cannot finish).
    pub max_step_cuts: u32,
}

impl Newton {
    /// The paper's ANSYS defaults: 0.5 % on forces, 5 % on displacements (paper, RPEPO
    /// and PEPO FE runs; ANSYS NEQIT default 25 iterations).
    pub const PAPER: Newton = Newton {
        preset: "paper",
        force_tol: 5e-3,
        displacement_tol: 5e-2,
        max_iterations: 25,
        max_step_cuts: 4,
    };
    /// Verification preset: converged to round-off for these scenes.
    pub const TIGHT: Newton = Newton {
        preset: "tight",
        force_tol: 1e-9,
        displacement_tol: 1e-9,
        max_iterations: 50,
        max_step_cuts: 4,
    };
}

/// Rigid-body kinematics of the support points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kinematics {
    /// Exact finite rotation: points move by (R(θ) − I)·d. Gravity acting through the
    /// rotation (P-Delta) is part of it.
    Exact,
    /// Linearised rotation, u = (X − θ·dz, Z + θ·dx): what the paper's programs used.
    SmallRotation,
}

impl Kinematics {
    /// Name as in case files.
    pub fn name(&self) -> &'static str {
        match self {
            Kinematics::Exact => "exact",
            Kinematics::SmallRotation => "small-rotation",
        }
    }
}

/// Everything the FE engine runs with, beyond the scene and the time step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeOptions {
    /// Time integrator.
    pub integrator: Integrator,
    /// Newton control.
    pub newton: Newton,
    /// Kinematics of a rocking body.
    pub kinematics: Kinematics,
    /// P-Delta: second-order rotation terms (always on with exact kinematics; with small
    /// rotation, adds the −θ²/2 terms so gravity acts through the rotation).
    pub p_delta: bool,
    /// Rotational inertia override, kg·m² (> 0); `None`: the case's value, or when that
    /// is 0 the engine's stated default (see `model::default_rotational_inertia`).
    pub rotational_inertia: Option<f64>,
    /// For rocking bodies, rerun with I/10, 10·I and the paper's kinematics and report the
    /// differences as findings.
    pub sensitivity: bool,
}

impl Default for FeOptions {
    fn default() -> Self {
        Self {
            integrator: Integrator::Newmark,
            newton: Newton::TIGHT,
            kinematics: Kinematics::Exact,
            p_delta: true,
            rotational_inertia: None,
            sensitivity: true,
        }
    }
}

impl FeOptions {
    /// Read and validate the case's `[engines.fe]` options; every problem is returned.
    pub fn parse(case: &Case) -> (FeOptions, Vec<InputError>) {
        let mut errors = unknown_keys(case);
        let mut o = FeOptions::default();
        let field = |k: &str| format!("engines.{ID}.{k}");
        let mut take = |r: Result<(), InputError>| {
            if let Err(e) = r {
                errors.push(e);
            }
        };
        take((|| {
            let name = case.engine_text(ID, "integrator", "newmark", &["newmark", "hht"])?;
            let has_alpha = case
                .engine(ID)
                .is_some_and(|r| r.options.contains_key("alpha"));
            let alpha = case.engine_number(ID, "alpha", -0.05)?;
            if name == "hht" {
                if !(-1.0 / 3.0..=0.0).contains(&alpha) {
                    return Err(case.field_error(
                        &field("alpha"),
                        format!("is {alpha}, but must be between −1/3 and 0 (HHT-α)"),
                    ));
                }
                o.integrator = Integrator::Hht { alpha };
            } else if has_alpha {
                return Err(
                    case.field_error(&field("alpha"), "applies only with integrator = \"hht\"")
                );
            }
            Ok(())
        })());
        take((|| {
            let preset = case.engine_text(ID, "newton", "tight", &["paper", "tight"])?;
            o.newton = if preset == "paper" {
                Newton::PAPER
            } else {
                Newton::TIGHT
            };
            let m = case.engine_number(ID, "max_iterations", o.newton.max_iterations as f64)?;
            if !((1.0..=1000.0).contains(&m) && m.fract() == 0.0) {
                return Err(case.field_error(
                    &field("max_iterations"),
                    format!("is {m}, but must be a whole number from 1 to 1000"),
                ));
            }
            o.newton.max_iterations = m as usize;
            let cuts =
                case.engine_number(ID, "max_step_cuts", f64::from(o.newton.max_step_cuts))?;
            if !((0.0..=10.0).contains(&cuts) && cuts.fract() == 0.0) {
                return Err(case.field_error(
                    &field("max_step_cuts"),
                    format!("is {cuts}, but must be a whole number from 0 to 10 (Δt/2^10 at most)"),
                ));
            }
            o.newton.max_step_cuts = cuts as u32;
            Ok(())
        })());
        take((|| {
            let k = case.engine_text(ID, "kinematics", "exact", &["exact", "small-rotation"])?;
            o.kinematics = if k == "exact" {
                Kinematics::Exact
            } else {
                Kinematics::SmallRotation
            };
            o.p_delta = case.engine_bool(ID, "p_delta", true)?;
            if o.kinematics == Kinematics::Exact && !o.p_delta {
                return Err(case.field_error(
                    &field("p_delta"),
                    "cannot be false with kinematics = \"exact\": finite rotation includes gravity acting through the rotation; use kinematics = \"small-rotation\" to leave it out",
                ));
            }
            Ok(())
        })());
        take((|| {
            if case
                .engine(ID)
                .is_some_and(|r| r.options.contains_key("rotational_inertia"))
            {
                let i = case.engine_number(ID, "rotational_inertia", 0.0)?;
                if !(i > 0.0 && i.is_finite()) {
                    return Err(case.field_error(
                        &field("rotational_inertia"),
                        format!("is {i}, but must be positive and finite, in kg·m²"),
                    ));
                }
                o.rotational_inertia = Some(i);
            }
            o.sensitivity = case.engine_bool(ID, SENSITIVITY, true)?;
            Ok(())
        })());
        (o, errors)
    }
}

/// An error for every option of the case's `[engines.fe]` the engine does not know.
fn unknown_keys(case: &Case) -> Vec<InputError> {
    let Some(req) = case.engine(ID) else {
        return Vec::new();
    };
    let unknown = req
        .options
        .keys()
        .filter(|k| !OPTION_KEYS.contains(&k.as_str()));
    unknown
        .map(|k| {
            case.field_error(
                &format!("engines.{ID}.{k}"),
                format!(
                    "unknown option of the fe engine; its options are {}",
                    OPTION_KEYS.join(", ")
                ),
            )
        })
        .collect()
}

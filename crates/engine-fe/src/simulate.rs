//! Running one variant of a scene: build the model from the scene, integrate it
//! (`recording`), and gather what the run used and found (`findings`) into a [`Run`].

use super::findings::{Findings, findings};
use super::model::{Model, default_rotational_inertia};
use super::options::{FeOptions, Integrator};
use super::recording::run_model;
use super::variant;
use rockslide_core::case::{Case, DoubleContact, Model as SceneModel};
use rockslide_core::error::InputError;
use rockslide_engine_api::{Run, SolverStats};

/// Run `variant` of the case's scene at time step `dt` with `opts`.
pub fn simulate(case: &Case, variant: &str, dt: f64, opts: &FeOptions) -> Result<Run, InputError> {
    let (model, double, inertia_note) = build_model(case, variant, opts)?;
    let rocking = model.body.rotation;
    let (trace, status, counters, check) = run_model(case, model.clone(), dt, opts);
    let settings = settings(case, dt, opts, rocking, double.is_some(), inertia_note);
    let findings = findings(&Findings {
        case,
        model: &model,
        double: double.as_ref(),
        opts,
        dt,
        trace: &trace,
        status: &status,
        counters,
        check,
    });
    Ok(Run {
        engine: "fe",
        variant: variant.to_string(),
        dt,
        settings,
        stats: SolverStats {
            steps: counters.steps,
            substeps_per_step: None,
            newton_iterations: Some(counters.iterations),
            max_step_iterations: Some(counters.max_step_iterations),
            static_iterations: Some(counters.static_iterations),
            step_cuts: Some(counters.step_cuts),
            roundoff_accepted: Some(counters.roundoff_accepted),
        },
        findings,
        trace,
        status,
        wall_seconds: 0.0,
    })
}

/// The model of `variant`, its double arrangement if any, and where its rotational inertia
/// came from (empty for an oscillator).
fn build_model(
    case: &Case,
    variant: &str,
    opts: &FeOptions,
) -> Result<(Model, Option<DoubleContact>, String), InputError> {
    let scene = &case.scene;
    let want_double = match variant {
        variant::SINGLE => false,
        variant::DOUBLE => true,
        other => {
            return Err(case.field_error(
                "engines.fe.variants",
                format!("\"{other}\" is not a variant of fe; variants: single, double"),
            ));
        }
    };
    let no_double = || {
        case.field_error(
            "model.double",
            "is required for the fe engine's \"double\" variant",
        )
    };
    let mut inertia_note = String::new();
    let (model, double): (Model, Option<DoubleContact>) = match &scene.model {
        SceneModel::Oscillator(o) => {
            let d = if want_double {
                Some(o.double.ok_or_else(no_double)?)
            } else {
                None
            };
            (Model::oscillator(o, d.as_ref()), d)
        }
        SceneModel::RockingBody(r) => {
            let d = if want_double {
                Some(r.double.ok_or_else(no_double)?)
            } else {
                None
            };
            let inertia = match (opts.rotational_inertia, r.rotational_inertia) {
                (Some(i), _) => {
                    inertia_note = format!("{i} kg·m² (engines.fe.rotational_inertia)");
                    i
                }
                (None, i) if i > 0.0 => {
                    inertia_note = format!("{i} kg·m² (model.rotational_inertia)");
                    i
                }
                _ => {
                    let i = default_rotational_inertia(r);
                    inertia_note = format!(
                        "{i:.2} kg·m² (engine default for a case giving 0: 0.01 % of a uniform block 2b × 2h, 1e-4·M(b² + h²)/3)"
                    );
                    i
                }
            };
            (
                Model::rocking(r, d.as_ref(), inertia, opts.kinematics, opts.p_delta),
                d,
            )
        }
        SceneModel::RigidBlock(_) => {
            return Err(case.field_error(
                "model.kind",
                "the fe engine does not run rigid blocks (no contact stiffness)",
            ));
        }
    };
    Ok((model, double, inertia_note))
}

/// Every setting that shaped the run, as (name, value).
fn settings(
    case: &Case,
    dt: f64,
    opts: &FeOptions,
    rocking: bool,
    double: bool,
    inertia_note: String,
) -> Vec<(String, String)> {
    let scene = &case.scene;
    let (alpha, beta, gamma) = opts.integrator.parameters();
    let mut settings: Vec<(String, String)> = vec![
        ("dt [s]".into(), format!("{dt}")),
        (
            "integrator".into(),
            match opts.integrator {
                Integrator::Newmark => "Newmark average acceleration".into(),
                Integrator::Hht { .. } => "HHT-α".into(),
            },
        ),
        (
            "α, β, γ".into(),
            format!("{alpha}, {beta:.6}, {gamma:.6}"),
        ),
        (
            "Newton".into(),
            format!(
                "preset \"{}\": force {:.1e} (relative), displacement {:.1e} (relative), at most {} iterations per step, failing steps cut down to Δt/{}; consistent tangent",
                opts.newton.preset,
                opts.newton.force_tol,
                opts.newton.displacement_tol,
                opts.newton.max_iterations,
                1u32 << opts.newton.max_step_cuts
            ),
        ),
        (
            "gravity".into(),
            "static preload: the run starts from equilibrium under M·g".into(),
        ),
        (
            "ground motion".into(),
            match &scene.excitation {
                rockslide_core::case::Excitation::GroundDisplacement(_) => {
                    "ground node moved (prescribed displacement, absolute coordinates); outputs relative to the ground".into()
                }
                rockslide_core::case::Excitation::GroundAcceleration(_) => {
                    "relative coordinates: force −M·ag on the body, ground fixed".into()
                }
                _ => "none".into(),
            },
        ),
    ];
    settings.extend(super::vertical::describe(scene));
    if rocking {
        settings.push(("kinematics".into(), opts.kinematics.name().into()));
        settings.push((
            "P-Delta".into(),
            if opts.p_delta { "on" } else { "off" }.into(),
        ));
        settings.push(("rotational inertia".into(), inertia_note));
    }
    if double {
        settings.push((
            "element 2".into(),
            "bonded normal (series with the compression-only element 1 transmits the same forces; keeps the massless node determinate when element 1 opens)".into(),
        ));
    }

    settings
}

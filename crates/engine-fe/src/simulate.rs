//! Running one variant of a scene, planar or bidirectional (`space`): build the model
//! from the scene, integrate it (`recording`), and gather what the run used and found
//! (`findings`) into a [`Run`]. The rows go to a [`StepSink`] as they are recorded: a
//! whole run ([`simulate`]) keeps them in a `WholeRun` sized up front (`whole_run`), a
//! streamed run ([`simulate_into`]) hands them on and holds none (what the findings read
//! of the rows is a running summary).

use super::findings::{Findings, Summarised, findings};
use super::model::{Model, Plane, default_rotational_inertia};
use super::options::FeOptions;
use super::recording::{RowSink, Rows, run_model};
use super::run_parts::{integrator_settings, is_double, no_double, rigid_block, solver_stats};
use super::space;
use super::whole_run::WholeRun;
use rockslide_core::case::{Case, DoubleContact, Model as SceneModel};
use rockslide_core::error::InputError;
use rockslide_engine_api::{Run, Setting, StepSink, step_count};

/// Run `variant` of the case's scene at time step `dt` with `opts`: the whole run, its
/// trace sized for the run up front.
pub fn simulate(case: &Case, variant: &str, dt: f64, opts: &FeOptions) -> Result<Run, InputError> {
    let mut rows = WholeRun::sized(step_count(case.run.duration, dt) + 1);
    let mut run = match case.scene.spatial() {
        Some(s) => space::simulate_space_into(case, s, variant, dt, opts, &mut rows)?,
        None => simulate_with(case, variant, dt, opts, &mut rows)?,
    };
    run.trace = rows.into_trace();
    Ok(run)
}

/// Run `variant` of the case's scene at time step `dt` with `opts`, handing the layout
/// and every recorded row to `sink`: the returned run's trace is the layout (channels,
/// contact names and compliances) without rows.
pub fn simulate_into<S: StepSink + ?Sized>(
    case: &Case,
    variant: &str,
    dt: f64,
    opts: &FeOptions,
    sink: &mut S,
) -> Result<Run, InputError> {
    match case.scene.spatial() {
        Some(s) => space::simulate_space_into(case, s, variant, dt, opts, sink),
        None => simulate_with(case, variant, dt, opts, &mut Rows::new(sink)),
    }
}

/// Values one row of `variant` of the case's scene records (time, channels, the
/// contacts' fields), or `None` when the variant does not build.
pub(crate) fn recorded_values(case: &Case, variant: &str, opts: &FeOptions) -> Option<usize> {
    if let Some(s) = case.scene.spatial() {
        return space::recorded_values_space(case, s, variant);
    }
    let (model, _, _) = build_model(case, variant, opts).ok()?;
    Some(super::recording::values_per_row(
        &super::recording::layout_of_model(case, &model),
    ))
}

/// [`simulate_into`] for the recorder's own sink: the whole run's, or any [`StepSink`]
/// through [`Rows`].
fn simulate_with<S: RowSink + ?Sized>(
    case: &Case,
    variant: &str,
    dt: f64,
    opts: &FeOptions,
    sink: &mut S,
) -> Result<Run, InputError> {
    let (model, double, inertia_note) = build_model(case, variant, opts)?;
    let rocking = model.body.rotation;
    // The sensitivity findings compare the run's headline numbers with its alternatives':
    // read as the rows go by, only where they are reported.
    let (status, counters, check, summary) = if rocking && opts.sensitivity {
        let mut summarised = Summarised::new(sink);
        let (status, counters, check) = run_model(case, model.clone(), dt, opts, &mut summarised);
        (status, counters, check, Some(summarised.summary))
    } else {
        let (status, counters, check) = run_model(case, model.clone(), dt, opts, sink);
        (status, counters, check, None)
    };
    let settings = settings(case, dt, opts, rocking, double.is_some(), inertia_note);
    let findings = findings(&Findings {
        case,
        model: &model,
        double: double.as_ref(),
        opts,
        dt,
        summary: summary.as_ref(),
        status: &status,
        counters,
        check,
    });
    Ok(Run {
        engine: crate::options::ID,
        variant: variant.to_string(),
        arrangement: crate::arrangement(variant),
        dt,
        settings,
        stats: solver_stats(&counters),
        findings,
        trace: super::recording::layout_of_model(case, &model),
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
) -> Result<(Model<Plane>, Option<DoubleContact>, String), InputError> {
    let scene = &case.scene;
    let want_double = is_double(case, variant)?;
    let no_double = || no_double(case);
    let mut inertia_note = String::new();
    let (model, double): (Model<Plane>, Option<DoubleContact>) = match &scene.model {
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
        SceneModel::RigidBlock(_) => return Err(rigid_block(case)),
    };
    Ok((model, double, inertia_note))
}

/// Every setting that shaped the run.
fn settings(
    case: &Case,
    dt: f64,
    opts: &FeOptions,
    rocking: bool,
    double: bool,
    inertia_note: String,
) -> Vec<Setting> {
    let scene = &case.scene;
    let mut settings = integrator_settings(dt, opts);
    settings.extend([
        Setting::text(
            "Newton",
            format!(
                "preset \"{}\": force {:.1e} (relative), displacement {:.1e} (relative), at most {} iterations per step, failing steps cut down to Δt/{}; consistent tangent",
                opts.newton.preset,
                opts.newton.force_tol,
                opts.newton.displacement_tol,
                opts.newton.max_iterations,
                1u32 << opts.newton.max_step_cuts
            ),
        ),
        Setting::text(
            "gravity",
            "static preload: the run starts from equilibrium under M·g",
        ),
        Setting::text(
            "ground motion",
            match &scene.excitation {
                rockslide_core::case::Excitation::GroundDisplacement(_) => {
                    "ground node moved (prescribed displacement, absolute coordinates); outputs relative to the ground"
                }
                rockslide_core::case::Excitation::GroundAcceleration(_) => {
                    "relative coordinates: force −M·ag on the body, ground fixed"
                }
                _ => "none",
            },
        ),
    ]);
    settings.extend(super::vertical::describe(scene));
    if rocking {
        settings.push(Setting::choice("kinematics", opts.kinematics.name()));
        settings.push(Setting::switch("P-Delta", opts.p_delta));
        settings.push(Setting::text("rotational inertia", inertia_note));
    }
    if double {
        settings.push(Setting::text(
            "element 2",
            "bonded normal (series with the compression-only element 1 transmits the same forces; keeps the massless node determinate when element 1 opens)",
        ));
    }

    settings
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recording::run_whole;
    use crate::variant;
    use std::path::Path;

    fn case(name: &str) -> Case {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../cases")
            .join(name);
        rockslide_core::case::load_case(&path, &["predictor-corrector", "fe", "rapier", "opensees"])
            .expect("a shipped case")
    }

    /// Largest difference of every channel between the double arrangement run with its
    /// supports condensed into series equivalents and run with the nodes as Newton
    /// unknowns, relative to the channel's largest magnitude; and the run's Newton
    /// iterations (condensed, uncondensed).
    fn condensed_against_nodes(name: &str) -> (f64, (u64, u64)) {
        let case = case(name);
        let (opts, errors) = FeOptions::parse(&case);
        assert!(errors.is_empty());
        let (model, _, _) = build_model(&case, variant::DOUBLE, &opts).expect("builds");
        assert!(model.condensed && !model.equivalents.is_empty());
        let mut nodes = model.clone();
        nodes.condensed = false;

        let dt = 1e-3;
        let (a, sa, ca, _) = run_whole(&case, model, dt, &opts);
        let (b, sb, cb, _) = run_whole(&case, nodes, dt, &opts);
        assert!(sa.completed() && sb.completed());
        let mut worst = 0.0_f64;
        for (x, y) in a.columns.iter().zip(&b.columns) {
            let scale = y.iter().fold(0.0_f64, |m, v| m.max(v.abs())).max(1e-300);
            let diff = x
                .iter()
                .zip(y)
                .fold(0.0_f64, |m, (u, v)| m.max((u - v).abs()));
            worst = worst.max(diff / scale);
        }
        (worst, (ca.iterations, cb.iterations))
    }

    /// The sliding oscillator's scalar step (`stepper::slider`) against the general step
    /// on the same single-arrangement model (`condensed = false` takes the general
    /// assembly and Newton step): every channel, the contact block and the Newton
    /// counters the same bits, on a pulse, a moving ground and a damped SDOF.
    #[test]
    fn slider_step_is_the_general_step_bit_for_bit() {
        for name in [
            "pepo-mass-accel.toml",
            "pepo-ground-disp.toml",
            "linear-sdof.toml",
        ] {
            let case = case(name);
            let (opts, errors) = FeOptions::parse(&case);
            assert!(errors.is_empty());
            let (model, _, _) = build_model(&case, variant::SINGLE, &opts).expect("builds");
            assert!(model.is_slider(), "{name}");
            let mut general = model.clone();
            general.condensed = false;
            assert!(!general.is_slider());
            let (a, sa, ca, _) = run_whole(&case, model, 1e-3, &opts);
            let (b, sb, cb, _) = run_whole(&case, general, 1e-3, &opts);
            assert!(sa.completed() && sb.completed(), "{name}");
            assert_eq!(ca, cb, "{name}");
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            for (x, y) in a.columns.iter().zip(&b.columns) {
                assert_eq!(bits(x), bits(y), "{name}");
            }
            assert_eq!(bits(&a.contacts.values), bits(&b.contacts.values), "{name}");
        }
    }

    /// Peaks of the RPEPO double, condensed and with node unknowns: peak sliding and peak
    /// rotation agree to round-off amplified by the run (measured 8.9e-11 and 3.3e-12
    /// relative). Later the traces part (final sliding 1.89 against 3.24 mm): the node
    /// model itself ends at 4.76 mm when the mass changes by 4e-16 (docs/fe-engine.md).
    #[test]
    fn condensed_rpepo_double_peaks_match_the_node_model() {
        let case = case("rpepo-mass-accel.toml");
        let (opts, _) = FeOptions::parse(&case);
        let (model, _, _) = build_model(&case, variant::DOUBLE, &opts).expect("builds");
        let mut nodes = model.clone();
        nodes.condensed = false;
        let peaks = |m: Model<Plane>| {
            let (trace, status, _, _) = run_whole(&case, m, 1e-3, &opts);
            assert!(status.completed());
            let peak = |key: &str| {
                let column = trace.column(key).expect("a channel");
                column.iter().fold(0.0_f64, |a, v| a.max(v.abs()))
            };
            (peak("slide"), peak("rotation"))
        };
        let ((slide, rotation), (slide_n, rotation_n)) = (peaks(model), peaks(nodes));
        eprintln!(
            "peak sliding {slide:e} against {slide_n:e}, rotation {rotation:e} against {rotation_n:e}"
        );
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        assert!(
            rel(slide, slide_n) <= 1e-10,
            "{slide:e} against {slide_n:e}"
        );
        assert!(
            rel(rotation, rotation_n) <= 5e-12,
            "{rotation:e} against {rotation_n:e}"
        );
    }

    #[test]
    fn condensed_pepo_double_is_the_node_model_to_round_off() {
        // Measured: the body's motion identical bit for bit, with the same 1900 Newton
        // iterations; the tangential force 2.8e-13 of its peak (1.4e-7 N of 5e5 N): the
        // node model recomputes it as kx1·(δ1x − s1), kx1 = 1.01e11 N/m times the round-off
        // of δ1x, where the equivalent gives ks·(δtx − s1) directly.
        let (pepo, iterations) = condensed_against_nodes("pepo-mass-accel.toml");
        eprintln!("largest difference {pepo:e} of a channel's peak, iterations {iterations:?}");
        assert!(pepo <= 3e-13, "{pepo:e}");
        assert_eq!(iterations, (1900, 1900));
    }

    /// The RPEPO double's force and condensed tangent, condensed and with node unknowns,
    /// at body positions and element-1 slips that put supports open, sticking and
    /// slipping: (largest relative difference of force, of tangent; supports seen open,
    /// sticking, slipping).
    fn rpepo_states() -> (f64, f64, [usize; 3]) {
        use crate::element::Status;
        use crate::model::Assembly;
        use nalgebra::Vector3;
        let case = case("rpepo-mass-accel.toml");
        let (opts, _) = FeOptions::parse(&case);
        let (mut cond, _, _) = build_model(&case, variant::DOUBLE, &opts).expect("builds");
        let mut nodes = cond.clone();
        nodes.condensed = false;
        let (q0, mut un) = crate::stepper::preload(&mut nodes).expect("preload");
        let (mut a, mut b) = (Assembly::new(&cond), Assembly::new(&nodes));
        let (mut force, mut tangent, mut seen) = (0.0_f64, 0.0_f64, [0; 3]);
        for (dx, dtheta, slip) in [
            (0.0, 0.0, 0.0),
            (2e-4, 0.0, 0.0),
            (-3e-3, 0.0, 1e-3),
            (1e-3, 2e-4, -1e-3),
            (-2e-3, -1e-3, 5e-4),
            (5e-3, 3e-3, 0.0),
            (1e-3, 2e-2, 1e-3),
            (-1e-3, -5e-2, 0.0),
        ] {
            for (sup, eq) in nodes.supports.iter_mut().zip(cond.equivalents.iter_mut()) {
                let e1 = &mut sup.lower;
                let mut st = *e1.state();
                st.slip = slip;
                e1.set_committed(st);
                eq.set_committed(st);
            }
            let q = q0 + Vector3::new(dx, 0.0, dtheta);
            let ground = (1e-4, 0.0, 0.0);
            cond.assemble(&q, &q, &mut un.clone(), &ground, &mut a);
            nodes.assemble(&q, &q, &mut un, &ground, &mut b);
            force = force.max((a.pb - b.pb).norm() / b.pb.norm());
            assert!(!a.singular && !b.singular);
            let (ka, kb) = (a.kbb, b.kbb);
            tangent = tangent.max((ka - kb).norm() / kb.norm());
            nodes.commit();
            for sup in &nodes.supports {
                match sup.lower.state().status {
                    Status::Open => seen[0] += 1,
                    Status::Stick => seen[1] += 1,
                    Status::Slip => seen[2] += 1,
                }
            }
        }
        (force, tangent, seen)
    }

    #[test]
    fn condensed_rpepo_double_supports_give_the_node_models_force_and_tangent() {
        // Measured: 6.8e-16 and 1.4e-15 relative (round-off), with 9 supports seen open,
        // 20 sticking and 51 slipping. Whole RPEPO runs cannot be compared this way: the
        // node model itself moves 48 % in peak sliding when the mass changes by 4e-16.
        let (force, tangent, seen) = rpepo_states();
        eprintln!("force {force:e}, tangent {tangent:e}; open, sticking, slipping {seen:?}");
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
        assert!(force <= 1e-15 && tangent <= 2e-15, "{force:e} {tangent:e}");
    }
}

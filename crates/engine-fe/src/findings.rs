//! What an fe run found about itself, reported as findings: the model's eigenfrequencies,
//! the series stiffness of a double arrangement and the node-versus-slip check, the
//! Newton statistics, and for a rocking body the sensitivity to the rotational inertia
//! and to the kinematics (the run repeated with each alternative).

use super::model::Model;
use super::modes::eigenfrequencies;
use super::options::{FeOptions, Kinematics};
use super::recording::{SelfCheck, run_model};
use super::stepper::Counters;
use rockslide_core::case::{Case, DoubleContact, Model as SceneModel};
use rockslide_core::trace::Trace;
use rockslide_engine_api::RunStatus;

const PI: f64 = std::f64::consts::PI;

/// A finished run, as the findings need it.
pub(crate) struct Findings<'a> {
    pub case: &'a Case,
    pub model: &'a Model,
    pub double: Option<&'a DoubleContact>,
    pub opts: &'a FeOptions,
    pub dt: f64,
    pub trace: &'a Trace,
    pub status: &'a RunStatus,
    pub counters: Counters,
    pub check: SelfCheck,
}

/// The findings of a run, in the order the report shows them.
pub(crate) fn findings(run: &Findings) -> Vec<String> {
    let Findings {
        case,
        model,
        double,
        opts,
        dt,
        trace,
        status,
        counters,
        check,
    } = *run;
    let scene = &case.scene;
    let rocking = model.body.rotation;
    let mut findings = Vec::new();
    match eigenfrequencies(model) {
        Ok(m) => {
            findings.push(format!(
                "model eigenfrequencies about the static equilibrium{}: ωX = {:.4} rad/s ({:.4}π), ωZ = {:.4} rad/s ({:.4}π){}",
                if rocking { " with θ condensed (no rotational inertia)" } else { "" },
                m.omega_x,
                m.omega_x / PI,
                m.omega_z,
                m.omega_z / PI,
                if rocking { "; the paper designs ωX = 10π, ωZ = 20π" } else { "" }
            ));
            if let Some(w) = m.with_inertia {
                findings.push(format!(
                    "with the rotational inertia: ω = {:.4}, {:.4}, {:.1} rad/s",
                    w[0], w[1], w[2]
                ));
            }
        }
        Err(e) => findings.push(format!("eigenfrequencies not computed: {e}")),
    }
    if rocking && opts.p_delta {
        let mut lin = model.clone();
        lin.kinematics = Kinematics::SmallRotation;
        lin.p_delta = false;
        if let Ok(m) = eigenfrequencies(&lin) {
            findings.push(format!(
                "without P-Delta (the paper's small-rotation model): ωX = {:.4} rad/s ({:.4}π), ωZ = {:.4} rad/s ({:.4}π)",
                m.omega_x,
                m.omega_x / PI,
                m.omega_z,
                m.omega_z / PI
            ));
        }
    }
    if let Some(d) = double {
        let single = match &scene.model {
            SceneModel::Oscillator(o) => o.contact,
            SceneModel::RockingBody(r) => r.contact,
            SceneModel::RigidBlock(_) => unreachable!("rejected above"),
        };
        let (kx, kz) = d.series();
        let px = 100.0 * (kx / single.kx - 1.0);
        let pz = 100.0 * (kz / single.kz - 1.0);
        let mut f = format!(
            "series stiffness of the double arrangement: Kx = {:.6e} N/m ({px:+.3} % against the single element's {:.6e}), Kz = {:.6e} N/m ({pz:+.3} % against {:.6e})",
            kx, single.kx, kz, single.kz
        );
        if px.abs().max(pz.abs()) > 0.1 {
            f.push_str(
                " — the double model is stiffer than the single one it claims to equal (the paper's RPEPO values differ by about 1 %); this run uses the double values as given",
            );
        }
        findings.push(f);
        findings.push(format!(
            "intermediate-node displacement minus element 1's slip (its elastic deflection T1/Kx1): at most {:.3e} m",
            check.node_minus_slip
        ));
    }
    findings.push(format!(
        "Newton: {} iterations in {} steps (at most {} in one step); static preload {} iterations; {} step cuts; {} steps accepted at round-off",
        counters.iterations,
        counters.steps,
        counters.max_step_iterations,
        counters.static_iterations,
        counters.step_cuts,
        counters.roundoff_accepted
    ));
    if rocking && opts.sensitivity && status.completed() {
        let base = Summary::of(trace);
        findings.push(format!("this run: {}", base.describe()));
        let mut alternatives: Vec<(String, Model)> = Vec::new();
        for factor in [0.1, 10.0, 100.0] {
            let mut m = model.clone();
            m.body.inertia *= factor;
            alternatives.push((format!("rotational inertia ×{factor}"), m));
        }
        if opts.kinematics == Kinematics::Exact {
            let mut m = model.clone();
            m.kinematics = Kinematics::SmallRotation;
            m.p_delta = false;
            alternatives.push((
                "small rotation without P-Delta (the paper's programs)".into(),
                m,
            ));
        }
        for (label, m) in alternatives {
            let (tr, st, _, _) = run_model(case, m, dt, opts);
            if st.completed() {
                findings.push(format!(
                    "sensitivity — {label}: {}",
                    Summary::of(&tr).describe()
                ));
            } else {
                findings.push(format!("sensitivity — {label}: {st}"));
            }
        }
    }
    findings
}

/// Headline numbers of a rocking run, for sensitivity findings.
struct Summary {
    slide: f64,
    rotation: f64,
    uplift: f64,
    cm_z: (f64, f64),
    liftoff: Option<f64>,
}

impl Summary {
    fn of(t: &Trace) -> Self {
        let col = |k: &str| t.column(k).unwrap_or(&[]);
        let peak = |k: &str| col(k).iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let cz = col("cm_z");
        Summary {
            slide: peak("slide"),
            rotation: peak("rotation"),
            uplift: col("uplift").iter().copied().fold(0.0, f64::max),
            cm_z: (
                cz.iter().copied().fold(f64::INFINITY, f64::min),
                cz.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            ),
            liftoff: col("contacts")
                .iter()
                .position(|&c| c <= 0.0)
                .map(|i| t.time[i]),
        }
    }
    fn describe(&self) -> String {
        format!(
            "peak |sliding| {:.3} mm, peak |rotation| {:.3} mrad, peak uplift {:.3} mm, CM vertical {:.3} … {:.3} mm, first full lift-off {}",
            self.slide * 1e3,
            self.rotation * 1e3,
            self.uplift * 1e3,
            self.cm_z.0 * 1e3,
            self.cm_z.1 * 1e3,
            self.liftoff.map_or("none".into(), |t| format!("{t:.3} s"))
        )
    }
}

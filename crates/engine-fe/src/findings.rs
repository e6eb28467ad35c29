//! What an fe run found about itself, reported as findings: the model's eigenfrequencies,
//! the series stiffness of a double arrangement and the node-versus-slip check, the
//! Newton statistics, and for a rocking body the sensitivity to the rotational inertia
//! and to the kinematics (the run repeated with each alternative). A rocking run's headline
//! numbers for those findings are read as it runs ([`Summary`], a [`StepSink`]), so
//! neither the run nor its alternatives keep a trace for them.

use super::model::{Model, Plane, PlaneKinematics};
use super::modes::eigenfrequencies;
use super::options::{FeOptions, Kinematics};
use super::recording::{FIELDS, ROW_VALUES, RowSink, Rows, SelfCheck, run_model};
use super::stepper::Counters;
use rockslide_core::case::{Case, DoubleContact, Model as SceneModel};
use rockslide_core::trace::{ContactState, Trace};
use rockslide_engine_api::{RunStatus, StepSink};

const PI: f64 = std::f64::consts::PI;

/// A finished run, as the findings need it.
pub(crate) struct Findings<'a> {
    pub case: &'a Case,
    pub model: &'a Model<Plane>,
    pub double: Option<&'a DoubleContact>,
    pub opts: &'a FeOptions,
    pub dt: f64,
    /// The run's headline numbers, read as it ran (a rocking run with sensitivity on).
    pub summary: Option<&'a Summary>,
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
        summary,
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
        lin.kinematics = PlaneKinematics::SMALL_ROTATION;
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
    if let (true, Some(base)) = (rocking && opts.sensitivity && status.completed(), summary) {
        findings.extend(sensitivity(case, model, opts, dt, base));
    }
    findings
}

/// The sensitivity findings of a rocking run whose headline numbers are `base`: the same
/// run with the rotational inertia scaled, and with small-rotation kinematics.
fn sensitivity(
    case: &Case,
    model: &Model<Plane>,
    opts: &FeOptions,
    dt: f64,
    base: &Summary,
) -> Vec<String> {
    let mut out = vec![format!("this run: {}", base.describe())];
    let mut alternatives: Vec<(String, Model<Plane>)> = Vec::new();
    for factor in [0.1, 10.0, 100.0] {
        let mut m = model.clone();
        m.body.inertia *= factor;
        alternatives.push((format!("rotational inertia ×{factor}"), m));
    }
    if opts.kinematics == Kinematics::Exact {
        let mut m = model.clone();
        m.kinematics = PlaneKinematics::SMALL_ROTATION;
        alternatives.push((
            "small rotation without P-Delta (the paper's programs)".into(),
            m,
        ));
    }
    for (label, m) in alternatives {
        let mut alternative = Summary::default();
        let (st, _, _) = run_model(case, m, dt, opts, &mut Rows::new(&mut alternative));
        if st.completed() {
            out.push(format!("sensitivity — {label}: {}", alternative.describe()));
        } else {
            out.push(format!("sensitivity — {label}: {st}"));
        }
    }
    out
}

/// Headline numbers of a rocking run, for sensitivity findings, read row by row as the
/// run is recorded (a [`StepSink`] that keeps no rows): the peak |sliding| and |rotation|,
/// the peak uplift, the range of the centre of mass's height and the first row with no
/// contact, each folded in row order as over the whole columns.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Summary {
    /// Columns of slide, rotation, uplift, cm_z and contacts (absent: `None`).
    columns: [Option<usize>; 5],
    slide: f64,
    rotation: f64,
    uplift: f64,
    cm_z: (f64, f64),
    liftoff: Option<f64>,
}

impl Default for Summary {
    fn default() -> Self {
        Summary {
            columns: [None; 5],
            slide: 0.0,
            rotation: 0.0,
            uplift: 0.0,
            cm_z: (f64::INFINITY, f64::NEG_INFINITY),
            liftoff: None,
        }
    }
}

impl StepSink for Summary {
    fn begin(&mut self, layout: &Trace) {
        let column = |key: &str| layout.channels.iter().position(|q| q.key == key);
        self.columns = ["slide", "rotation", "uplift", "cm_z", "contacts"].map(column);
    }

    fn row(&mut self, t: f64, values: &[f64], _contacts: &[ContactState]) {
        let [slide, rotation, uplift, cm_z, contacts] = self.columns.map(|c| c.map(|c| values[c]));
        if let Some(x) = slide {
            self.slide = self.slide.max(x.abs());
        }
        if let Some(x) = rotation {
            self.rotation = self.rotation.max(x.abs());
        }
        if let Some(x) = uplift {
            self.uplift = f64::max(self.uplift, x);
        }
        if let Some(z) = cm_z {
            self.cm_z = (f64::min(self.cm_z.0, z), f64::max(self.cm_z.1, z));
        }
        if let (None, Some(c)) = (self.liftoff, contacts)
            && c <= 0.0
        {
            self.liftoff = Some(t);
        }
    }
}

/// A sink that reads a [`Summary`] of every row it hands on to another sink (the summary
/// reads channels only).
pub(crate) struct Summarised<'a, S: RowSink + ?Sized> {
    /// The run's summary so far.
    pub summary: Summary,
    /// Where the rows go.
    sink: &'a mut S,
}

impl<'a, S: RowSink + ?Sized> Summarised<'a, S> {
    /// Summarise the rows handed on to `sink`.
    pub fn new(sink: &'a mut S) -> Self {
        Self {
            summary: Summary::default(),
            sink,
        }
    }
}

impl<S: RowSink + ?Sized> RowSink for Summarised<'_, S> {
    fn start(&mut self, layout: &Trace) {
        self.summary.begin(layout);
        self.sink.start(layout);
    }

    #[inline]
    fn contacts(&mut self) -> &mut [[f64; FIELDS]] {
        self.sink.contacts()
    }

    #[inline]
    fn values(&mut self) -> &mut [f64; ROW_VALUES] {
        self.sink.values()
    }

    fn end_row(&mut self, t: f64, count: usize) {
        let values = self.sink.values();
        self.summary.row(t, &values[..count], &[]);
        self.sink.end_row(t, count);
    }
}

impl Summary {
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

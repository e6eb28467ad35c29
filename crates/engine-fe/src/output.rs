//! Running a scene variant and writing what it shows: the trace channels (relative
//! quantities: mass or base point O against the ground), the settings, the counters and
//! the findings (eigenfrequencies, series stiffness, node-versus-slip check, and for a
//! rocking body the sensitivity to the rotational inertia and to the kinematics).

use nalgebra::Vector2;

use super::model::{Model, default_rotational_inertia};
use super::modes::eigenfrequencies;
use super::options::{FeOptions, Integrator, Kinematics};
use super::stepper::{Drive, Snapshot, integrate};
use super::variant;
use rockslide_core::case::{Case, DoubleContact, Model as SceneModel};
use rockslide_core::error::InputError;
use rockslide_core::trace::{Quantity, Trace, q};
use rockslide_engine_api::{Run, RunStatus, step_count};

const PI: f64 = std::f64::consts::PI;

/// Run `variant` of the case's scene at time step `dt` with `opts`.
pub fn simulate(case: &Case, variant: &str, dt: f64, opts: &FeOptions) -> Result<Run, InputError> {
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
    let rocking = model.body.rotation;
    let (trace, status, counters, check) = run_model(case, model.clone(), dt, opts);

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
                "preset \"{}\": force {:.1e} (relative), displacement {:.1e} (relative), at most {} iterations per step; consistent tangent",
                opts.newton.preset,
                opts.newton.force_tol,
                opts.newton.displacement_tol,
                opts.newton.max_iterations
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
    if rocking {
        settings.push(("kinematics".into(), opts.kinematics.name().into()));
        settings.push((
            "P-Delta".into(),
            if opts.p_delta { "on" } else { "off" }.into(),
        ));
        settings.push(("rotational inertia".into(), inertia_note));
    }
    if double.is_some() {
        settings.push((
            "element 2".into(),
            "bonded normal (series with the compression-only element 1 transmits the same forces; keeps the massless node determinate when element 1 opens)".into(),
        ));
    }

    let mut findings = Vec::new();
    match eigenfrequencies(&model) {
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
    if let Some(d) = &double {
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
        let base = Summary::of(&trace);
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
    Ok(Run {
        engine: "fe",
        variant: variant.to_string(),
        dt,
        settings,
        counters: vec![
            ("steps".into(), counters.steps),
            ("Newton iterations".into(), counters.iterations),
            (
                "max iterations in a step".into(),
                counters.max_step_iterations,
            ),
            (
                "static preload iterations".into(),
                counters.static_iterations,
            ),
            ("step cuts".into(), counters.step_cuts),
            (
                "steps accepted at round-off".into(),
                counters.roundoff_accepted,
            ),
        ],
        findings,
        trace,
        status,
        wall_seconds: 0.0,
    })
}

/// Self-checks gathered while recording.
#[derive(Debug, Clone, Copy, Default)]
struct SelfCheck {
    /// max |node x − ground − element-1 slip| over supports and time, m.
    node_minus_slip: f64,
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

/// The channels of a scene.
fn channels(rocking: bool, moves_ground: bool, double: bool) -> Vec<&'static Quantity> {
    let mut c = vec![&q::FORCE, &q::RESISTANCE, &q::REL_DISP, &q::SLIDE];
    if rocking {
        c.push(&q::SLIDE_SPREAD);
    }
    c.extend([&q::VEL, &q::ACC]);
    if moves_ground {
        c.push(&q::GROUND_DISP);
    }
    if rocking {
        c.extend([
            &q::CM_X,
            &q::CM_Z,
            &q::ROTATION,
            &q::UPLIFT,
            &q::CONTACTS,
            &q::BASE_SHEAR,
        ]);
    }
    c.push(&q::NORMAL);
    if double {
        c.push(&q::NODE_DISP);
    }
    if rocking {
        // Energy bookkeeping from the element states (see `EnergyBook`); last, so the
        // columns before them are those of every other engine.
        c.extend([
            &q::ENERGY_INPUT,
            &q::ENERGY_KINETIC,
            &q::ENERGY_STRAIN,
            &q::ENERGY_FRICTION,
            &q::ENERGY_POTENTIAL,
            &q::ENERGY_ERROR,
            &q::ENERGY_NONSMOOTH,
        ]);
    }
    c
}

/// The energy terms of a run, accumulated from the engine's own element states and
/// kinematics at every converged step (rocking bodies; `analysis::energy` audits them):
///
/// - input work W: ½(Fₙ + Fₙ₊₁)·ΔX_cm of the applied horizontal force, plus the moving
///   ground's work −½(Tₙ + Tₙ₊₁)·Δxg on each ground element (T the element's force on
///   its upper end; the ground pushes its lower end with −T);
/// - kinetic K = ½M(vx² + vz²) + ½I·ω² (absolute velocities in the model's frame);
/// - strain U = Σ ½T²/Kx + ½N²/Kz over every element, both of a double arrangement;
/// - friction D = Σ ½(Tₙ + Tₙ₊₁)·Δs over elements closed at both ends of the step (the
///   origin shift of an open element follows the point and is no slip), counted when
///   ≥ 0, so D never decreases;
/// - potential V = M·g·(Z − Z_static): gravity's work, −M·g·ΔZ, booked as potential.
///
/// Newmark average acceleration conserves this balance exactly for elements closed over
/// the step (ΔK = ½(aₙ + aₙ₊₁)·M·Δq; ½(Tₙ + Tₙ₊₁)·Δδx = Δ(½T²/Kx) + ½(Tₙ + Tₙ₊₁)·Δs since
/// T = Kx(δx − s)), so its residual E0 + W − (K + U + V + D) is the Newton tolerance,
/// the kink of an element opening or closing inside a step, and the exact kinematics'
/// curvature. HHT-α's numerical dissipation is not computed separately: it is that
/// residual (a loss, positive). Rocking bodies have no viscous damping in this engine.
/// The part of the residual made by the contact law's kinks inside a step is also
/// recorded on its own (`energy_nonsmooth`): for an element opening or closing, its
/// trapezoidal work ½(fₙ + fₙ₊₁)·Δδ minus its strain-energy change; for a slip reversal,
/// the negative trapezoid ½(Tₙ + Tₙ₊₁)·Δs left out of D. It is a numerical error of
/// stepping across a kink (the penalty contact itself is elastic), kept in the balance
/// error; E0 + W − (K + U + D + V) − energy_nonsmooth is what is left for the Newton
/// tolerance, the exact kinematics and HHT-α (measured: round-off, 1e-13 of the energy,
/// for Newmark with small-rotation kinematics).
struct EnergyBook {
    /// Per element at the last recorded step.
    prev: Vec<ElementEnergy>,
    /// Applied horizontal force, X_cm and ground displacement at the last step.
    last: (f64, f64, f64),
    /// E0 = K + U + V at t = 0.
    initial: f64,
    input: f64,
    friction: f64,
    /// Non-smooth part of the residual (`energy_nonsmooth`), J.
    contact: f64,
    started: bool,
}

/// What the energy book keeps of one element between steps.
#[derive(Debug, Clone, Copy, Default)]
struct ElementEnergy {
    /// Force on the upper end (T, −N), N.
    force: Vector2<f64>,
    /// Relative displacement δ, m.
    delta: Vector2<f64>,
    /// Slip, m.
    slip: f64,
    /// Strain energy, J.
    strain: f64,
    /// Gap open.
    open: bool,
}

impl EnergyBook {
    fn new(links: usize) -> Self {
        Self {
            prev: vec![ElementEnergy::default(); links],
            last: (0.0, 0.0, 0.0),
            initial: 0.0,
            input: 0.0,
            friction: 0.0,
            contact: 0.0,
            started: false,
        }
    }

    /// Book the converged state `s` (applied force `f`); returns
    /// (W, K, U, D, V, E0 + W − (K + U + D + V), non-smooth part). Allocation-free.
    fn record(&mut self, m: &Model, s: &Snapshot, f: f64) -> [f64; 7] {
        let xg = s.ground.0;
        let body = &m.body;
        let kinetic =
            0.5 * body.mass * (s.v.x * s.v.x + s.v.y * s.v.y) + 0.5 * body.inertia * s.v.z * s.v.z;
        let potential = m.weight() * (s.q.y - s.q_static.y);
        let mut strain = 0.0;
        let mut ground_force = 0.0; // Σ ½(Tₙ + Tₙ₊₁) over ground elements
        for (link, prev) in m.links.iter().zip(self.prev.iter_mut()) {
            let e = &link.element;
            let st = e.state();
            let (t, n) = (e.tangential(), e.normal());
            let open = st.status == super::element::Status::Open;
            let mut u = 0.0;
            if e.kx.is_finite() && e.kx > 0.0 {
                u += 0.5 * t * t / e.kx;
            }
            if e.kz.is_finite() && e.kz > 0.0 {
                u += 0.5 * n * n / e.kz;
            }
            strain += u;
            if self.started {
                if !open && !prev.open {
                    // Trapezoidal, as Newmark's work: ½(Tₙ + Tₙ₊₁)·Δs. It is ≥ 0 unless
                    // T reverses inside the step (|Tₙ| > |Tₙ₊₁|, opposite signs); such
                    // a step is not dissipation and goes to the non-smooth part.
                    let d = 0.5 * (prev.force.x + t) * (st.slip - prev.slip);
                    if d >= 0.0 {
                        self.friction += d;
                    } else {
                        self.contact += d;
                    }
                } else if open != prev.open {
                    // Opening or closing inside the step: the element's trapezoidal work
                    // minus its strain-energy change is what the step's kink lost.
                    let work = 0.5 * (prev.force + st.force).dot(&(st.delta - prev.delta));
                    self.contact += work - (u - prev.strain);
                }
                if link.lower == super::model::Point::Ground {
                    ground_force += 0.5 * (prev.force.x + t);
                }
            }
            *prev = ElementEnergy {
                force: st.force,
                delta: st.delta,
                slip: st.slip,
                strain: u,
                open,
            };
        }
        if self.started {
            let (f_n, x_n, xg_n) = self.last;
            self.input += 0.5 * (f_n + f) * (s.q.x - x_n) - ground_force * (xg - xg_n);
        } else {
            self.initial = kinetic + strain + potential;
            self.started = true;
        }
        self.last = (f, s.q.x, xg);
        let error = self.initial + self.input - (kinetic + strain + self.friction + potential);
        [
            self.input,
            kinetic,
            strain,
            self.friction,
            potential,
            error,
            self.contact,
        ]
    }
}

/// Run a built model and record its trace.
fn run_model(
    case: &Case,
    mut model: Model,
    dt: f64,
    opts: &FeOptions,
) -> (Trace, RunStatus, super::stepper::Counters, SelfCheck) {
    let excitation = &case.scene.excitation;
    let moves_ground = matches!(
        excitation,
        rockslide_core::case::Excitation::GroundDisplacement(_)
    );
    let rocking = model.body.rotation;
    let double = model.nodes > 0;
    let chans = channels(rocking, moves_ground, double);
    let steps = step_count(case.run.duration, dt);
    let mut trace = Trace::with_channels(&chans, steps + 1);
    let drive = Drive::new(excitation, model.body.mass);
    let o_offset = match &case.scene.model {
        SceneModel::RockingBody(r) => Vector2::new(0.0, -r.cm_height),
        _ => Vector2::zeros(),
    };
    let mut check = SelfCheck::default();
    let mut book = EnergyBook::new(model.links.len());
    let mut row = [0.0_f64; 24];
    let (status, counters) = integrate(&mut model, &drive, opts, dt, steps, |m, s: &Snapshot| {
        let (xg, vg, ag) = s.ground;
        let (mut shear, mut normal) = (0.0, 0.0);
        let (mut slip_sum, mut slip_min, mut slip_max) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
        let (mut uplift, mut contacts) = (0.0_f64, 0.0);
        let mut node_sum = 0.0;
        for sup in &m.supports {
            let e = &m.links[sup.ground_link].element;
            let st = e.state();
            shear += e.tangential();
            normal += e.normal();
            // The sliding is element 1's own accumulated slip (return-mapping state). In
            // the double arrangement the node shows it too, plus element 1's deflection.
            let slip = st.slip;
            if let Some(k) = sup.node {
                let node = s.un[k].x - xg;
                node_sum += node;
                check.node_minus_slip = check.node_minus_slip.max((node - slip).abs());
            }
            slip_sum += slip;
            slip_min = slip_min.min(slip);
            slip_max = slip_max.max(slip);
            uplift = uplift.max(st.delta.y);
            if st.status != super::element::Status::Open && e.normal() > 0.0 {
                contacts += 1.0;
            }
        }
        let slide = slip_sum / m.supports.len() as f64;
        let mut i = 0;
        let mut put = |v: f64| {
            row[i] = v;
            i += 1;
        };
        put(drive.equivalent_force(s.t));
        put(shear);
        if rocking {
            put(m.displacement_of(&s.q, &o_offset).x - xg);
        } else {
            put(s.q.x - xg);
        }
        put(slide);
        if rocking {
            put(slip_max - slip_min);
        }
        put(s.v.x - vg);
        put(s.a.x - ag);
        if moves_ground {
            put(xg);
        }
        if rocking {
            put(s.q.x - xg);
            put(s.q.y - s.q_static.y);
            put(s.q.z);
            put(uplift.max(0.0));
            put(contacts);
            put(shear);
        }
        put(normal);
        if double {
            put(node_sum / m.supports.len() as f64);
        }
        if rocking {
            for v in book.record(m, s, drive.force(s.t)) {
                put(v);
            }
        }
        trace.push(s.t, &row[..i]);
    });
    (trace, status, counters, check)
}

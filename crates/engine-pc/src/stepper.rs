//! The time loop of the paper's method (steps 1–6) and its two routes for support motion.

use super::resistance::resistance;
use crate::vertical::NormalStepper;
use rockslide_core::case::{Excitation, Jump, Oscillator, Vertical};
use rockslide_core::trace::{ContactBlock, ContactState, Trace, q};
use rockslide_engine_api::{
    Arrangement, Run, RunStatus, Setting, SolverStats, StepSink, TraceSink, step_count,
};

/// How support motion enters the equation of motion (paper Eqs 10–12).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GroundRoute {
    /// Paper Eq 12: xg-eff_i = xg_i − xp_{i−1}, differentiated twice (backward differences,
    /// as a spreadsheet column would), force −M·ag-eff.
    Eq12,
    /// Eq 12 with the slip counted once: the integrated variable is the spring
    /// deflection w = x − (xg + xp), the resistance is elastic-plastic on w without an
    /// origin shift, and the slip enters only through xg-eff = xg + xp (the paper's minus
    /// sign with slip measured the other way).
    Eq12SlipOnce,
    /// Relative coordinates driven by the ground acceleration, −M·ag(t), with the jumps
    /// of the ground velocity applied as jumps of the relative velocity.
    GroundAcceleration,
}

/// What the method runs with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PcSettings {
    /// Time step Δt, s (the paper recommends Δt < T/10).
    pub dt: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Support-motion route (ignored for mass acceleration).
    pub route: GroundRoute,
}

/// Run the paper's method on an oscillator.
pub fn simulate(osc: &Oscillator, excitation: &Excitation, s: &PcSettings, variant: &str) -> Run {
    simulate_with_vertical(osc, excitation, None, s, variant)
}

/// Run the paper's method on an oscillator, with a vertical ground motion if given: the
/// friction limit is then Ru(t) = μ·N(t) at every step, N from [`NormalStepper`].
pub fn simulate_with_vertical(
    osc: &Oscillator,
    excitation: &Excitation,
    vertical: Option<&Vertical>,
    s: &PcSettings,
    variant: &str,
) -> Run {
    let mut sink = TraceSink::sized(step_count(s.duration, s.dt) + 1);
    let mut run = integrate(osc, excitation, vertical, s, variant, &mut sink, None);
    run.trace = sink.trace;
    // Eq 9 read off the whole columns (the streamed run keeps a front of them instead)
    let largest = largest_eq9_change(&run.trace);
    run.findings = vec![eq9_finding(largest)];
    run
}

/// The largest Eq 9 change over the rows whose |x| is at least 1 % of the run's peak (Eq 9
/// is a ratio: near x = 0 it is meaningless, the first step's prediction being 0).
fn largest_eq9_change(trace: &Trace) -> f64 {
    let xs = trace.column("rel_disp").unwrap_or(&[]);
    let peak = xs.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let mut max_change: f64 = 0.0;
    if let Some(changes) = trace.column("pc_change") {
        for (x, c) in xs.iter().zip(changes) {
            if x.abs() >= 0.01 * peak {
                max_change = max_change.max(c.abs());
            }
        }
    }
    max_change
}

/// The run's finding on Eq 9.
fn eq9_finding(max_change: f64) -> String {
    format!(
        "largest Eq 9 change |x_correct − x_predict|/|x_correct| = {max_change:.3e} (steps with |x| ≥ 1 % of peak)"
    )
}

/// [`simulate_with_vertical`] handing each row to `sink` as it is computed: no trace is
/// held, whatever the number of steps; the returned run's trace is the layout only.
pub fn simulate_streaming(
    osc: &Oscillator,
    excitation: &Excitation,
    vertical: Option<&Vertical>,
    s: &PcSettings,
    variant: &str,
    sink: &mut dyn StepSink,
) -> Run {
    // Eq 9 over the rows with |x| ≥ 1 % of the run's peak: a first pass (the time loop
    // alone) finds the peak, the second hands the rows on and keeps the largest change
    let mut peak = PeakDisplacement(0.0);
    integrate(osc, excitation, vertical, s, variant, &mut peak, None);
    let mut eq9 = Eq9Change {
        floor: 0.01 * peak.0,
        largest: 0.0,
    };
    let mut run = integrate(osc, excitation, vertical, s, variant, sink, Some(&mut eq9));
    run.findings = vec![eq9_finding(eq9.largest)];
    run
}

/// The peak |x| of a run (the first pass of a streamed run).
struct PeakDisplacement(f64);

impl StepSink for PeakDisplacement {
    fn begin(&mut self, _layout: &Trace) {}

    fn row(&mut self, _t: f64, values: &[f64], _contacts: &[ContactState]) {
        // rel_disp is the third sliding channel (force, resistance, rel_disp, …)
        self.0 = self.0.max(values[REL_DISP_COLUMN].abs());
    }
}

/// Column of `rel_disp` in the predictor-corrector's rows ([`q::sliding`]).
const REL_DISP_COLUMN: usize = 2;

/// The largest Eq 9 change over the rows whose |x| is at least `floor` (1 % of the run's
/// peak |x|, known from a first pass), kept step by step.
struct Eq9Change {
    floor: f64,
    largest: f64,
}

impl Eq9Change {
    fn observe(&mut self, x: f64, change: f64) {
        if x.abs() >= self.floor {
            self.largest = self.largest.max(change.abs());
        }
    }
}

/// The method's constants for one run: mass, stiffness, damping, friction coefficient,
/// time step, and whether the slip-once route integrates the deflection.
struct Method {
    m: f64,
    k: f64,
    c: f64,
    mu: f64,
    dt: f64,
    /// Eq 12 with the slip counted once, under ground motion ([`GroundRoute::Eq12SlipOnce`]).
    slip_once: bool,
}

/// What the method carries from one step to the next.
#[derive(Clone, Copy)]
struct State {
    x: f64,
    v: f64,
    a: f64,
    /// Slip xp.
    xp: f64,
    /// Resistance R.
    r: f64,
}

impl Method {
    /// Steps 3–6 at time `t` under force `f`: the predicting pass, then the correcting
    /// pass; returns the corrected state (velocity jump not yet applied) and the predicted
    /// displacement (for Eq 9). With a vertical ground motion the friction limit `ru` is
    /// μ·N(t) of each pass, N stepped by the same scheme, pass for pass.
    #[inline]
    fn predict_correct(
        &self,
        prev: &State,
        f: f64,
        t: f64,
        ru: &mut f64,
        mut normal_stepper: Option<&mut NormalStepper<'_>>,
    ) -> (State, f64) {
        let (m, k, c, dt) = (self.m, self.k, self.c, self.dt);
        let (x_prev, v_prev, a_prev, xp) = (prev.x, prev.v, prev.a, prev.xp);
        let mut a_t = a_prev; // step 3: predictor a_t = a_{t−1}
        let mut x_predict = 0.0;
        let mut next = *prev;
        for pass in 0..2 {
            // The friction limit of this pass: Ru = μ·N(t) from the vertical motion, the
            // normal force stepped by the same scheme, pass for pass.
            if let Some(ns) = normal_stepper.as_deref_mut() {
                ns.pass(t, dt, pass == 1);
                *ru = self.mu * ns.normal();
            }
            let ru = *ru;
            // step 4: Eqs 3 and 4
            let v_t = v_prev + 0.5 * (a_t + a_prev) * dt;
            let x_t = x_prev + 0.5 * (v_t + v_prev) * dt;
            // step 5: R from Eqs 7–8 with the previous step's slip
            let (r_t, xp_new) = if self.slip_once {
                let trial = k * x_t;
                let r = trial.clamp(-ru, ru);
                (r, xp + (trial - r) / k)
            } else {
                resistance(x_t, xp, k, ru)
            };
            // step 6: Eq 5
            a_t = (f - r_t - c * (v_prev + a_prev * dt / 2.0)) / (m + c * dt / 2.0);
            if pass == 0 {
                x_predict = x_t;
            } else {
                next.x = x_t;
                next.v = v_t;
                next.r = r_t;
                next.xp = xp_new;
            }
        }
        next.a = a_t;
        (next, x_predict)
    }
}

/// The predictor-corrector's trace layout: the sliding channels, the Eq 9 change, N(t)
/// when it varies (horizontal-only traces stay as they were), and the one contact.
fn layout_of(osc: &Oscillator, moves_ground: bool, varying_normal: bool) -> Trace {
    let mut channels = q::sliding(moves_ground);
    debug_assert_eq!(channels[REL_DISP_COLUMN].key, q::REL_DISP.key);
    channels.push(&q::PC_CHANGE);
    if varying_normal {
        channels.push(&q::NORMAL);
    }
    let mut layout = Trace::with_channels(&channels, 0);
    layout.contacts = ContactBlock::with_contacts(&["base"], &[1.0 / osc.contact.kz], 0);
    layout
}

/// Hands each row to the sink (and the Eq 9 observer), counting them; one row buffer for
/// the whole run.
struct Recorder<'a, S: StepSink + ?Sized> {
    sink: &'a mut S,
    eq9: Option<&'a mut Eq9Change>,
    excitation: &'a Excitation,
    moves_ground: bool,
    row: Vec<f64>,
    rows: u64,
}

impl<S: StepSink + ?Sized> Recorder<'_, S> {
    /// The row at time `t`: force `f`, the contact's (normal force, gap), the state (its
    /// x the relative displacement) and the Eq 9 change.
    #[inline]
    fn record(&mut self, t: f64, f: f64, (normal, gap): (f64, f64), s: &State, change: f64) {
        let State { x, v, a, xp, r } = *s;
        let mut vals = [f, r, x, xp, v, a, 0.0, 0.0, 0.0];
        if self.moves_ground {
            vals[6] = forcing_ground_disp(self.excitation, t);
            vals[7] = change;
            vals[8] = normal;
        } else {
            vals[6] = change;
            vals[7] = normal;
        }
        let n = self.row.len();
        self.row.copy_from_slice(&vals[..n]);
        let base = ContactState {
            normal,
            tangential: r,
            slip: xp,
            gap,
        };
        self.sink.row(t, &self.row, &[base]);
        if let Some(e) = self.eq9.as_deref_mut() {
            e.observe(x, change);
        }
        self.rows += 1;
    }
}

/// The time loop: every row to `sink`, and to `eq9` when given; the run's findings are
/// the caller's.
fn integrate<S: StepSink + ?Sized>(
    osc: &Oscillator,
    excitation: &Excitation,
    vertical: Option<&Vertical>,
    s: &PcSettings,
    variant: &str,
    sink: &mut S,
    eq9: Option<&mut Eq9Change>,
) -> Run {
    let dt = s.dt;
    let n = step_count(s.duration, dt);
    let moves_ground = excitation.moves_ground();
    let method = Method {
        m: osc.mass,
        k: osc.contact.kx,
        c: osc.damping(),
        mu: osc.contact.mu,
        dt,
        slip_once: s.route == GroundRoute::Eq12SlipOnce && moves_ground,
    };
    let (m, c) = (method.m, method.c);
    let mut normal_stepper = vertical.map(|v| NormalStepper::new(osc, v));
    let layout = layout_of(osc, moves_ground, normal_stepper.is_some());
    // The one contact: the normal force is the weight (no vertical motion), its static
    // penalty compression N/Kz the gap; T is the resistance R, the slip xp.
    let kz = osc.contact.kz;
    let (mut normal, mut gap) = (osc.normal_force(), -osc.normal_force() / kz);
    let mut ru = osc.friction_limit();
    if let Some(ns) = &normal_stepper {
        (normal, gap) = (ns.normal(), ns.gap());
        ru = osc.contact.mu * normal;
    }
    sink.begin(&layout);
    let mut out = Recorder {
        sink,
        eq9,
        excitation,
        moves_ground,
        row: vec![0.0; layout.channels.len()],
        rows: 0,
    };

    let mut forcing = Forcing::new(excitation, s.route, m, dt);
    let (mut state, f0) = initial_state(&mut forcing, m, c, dt);
    out.record(0.0, f0, (normal, gap), &state, 0.0);

    let mut status = RunStatus::Completed;
    for i in 1..=n {
        let t = i as f64 * dt; // step 2
        let f = forcing.force(i, t, state.xp);
        let x_predict;
        (state, x_predict) = method.predict_correct(&state, f, t, &mut ru, normal_stepper.as_mut());
        let State {
            x, mut v, a, xp, ..
        } = state;
        // Eq 9: change between the corrected and the predicted displacement.
        let change = if x != 0.0 { (x - x_predict) / x } else { 0.0 };
        v += forcing.velocity_jump(t, dt);
        state.v = v;
        if !(x.is_finite() && v.is_finite() && a.is_finite()) {
            status = RunStatus::Diverged {
                time: t,
                reason: "displacement, velocity or acceleration is not finite".into(),
            };
            break;
        }
        // The slip-once route integrates the deflection w: the relative displacement is w + xp.
        let x_rel = if method.slip_once { x + xp } else { x };
        if let Some(ns) = &normal_stepper {
            (normal, gap) = (ns.normal(), ns.gap());
        }
        out.record(t, f, (normal, gap), &State { x: x_rel, ..state }, change);
    }
    let rows = out.rows;

    Run {
        engine: crate::options::ID,
        variant: variant.to_string(),
        arrangement: Arrangement::Single,
        dt,
        settings: settings_of(osc, s, moves_ground, c, normal_stepper.as_ref()),
        stats: SolverStats::steps(rows - 1),
        findings: Vec::new(),
        trace: layout,
        status,
        wall_seconds: 0.0,
    }
}

/// Step 1: a at t0 from Eq 2 and zero initial conditions (plus the relative-velocity jump
/// when the ground starts moving abruptly); returns the state and the force at t0.
fn initial_state(forcing: &mut Forcing<'_>, m: f64, c: f64, dt: f64) -> (State, f64) {
    let (x, v, xp) = (0.0, forcing.velocity_jump(0.0, dt), 0.0);
    let f0 = forcing.force(0, 0.0, xp);
    let r = 0.0;
    let a = (f0 - r - c * v) / m;
    (State { x, v, a, xp, r }, f0)
}

/// The run's settings: Δt, Δt/T, the passes, the damping, the support route and, under
/// vertical ground motion, how N(t) is stepped.
fn settings_of(
    osc: &Oscillator,
    s: &PcSettings,
    moves_ground: bool,
    c: f64,
    normal_stepper: Option<&NormalStepper<'_>>,
) -> Vec<Setting> {
    let dt = s.dt;
    let route = match (moves_ground, s.route) {
        (false, _) => "mass force M·a(t)",
        (true, GroundRoute::Eq12SlipOnce) => {
            "Eq 12 with slip counted once (deflection w integrated, xg-eff = xg + xp)"
        }
        (true, GroundRoute::Eq12) => {
            "paper Eq 12: xg − xp differentiated twice (backward differences)"
        }
        (true, GroundRoute::GroundAcceleration) => {
            "ground acceleration, velocity jumps as impulses"
        }
    };
    let mut settings = vec![
        Setting::number("dt", "s", dt),
        Setting::rounded("dt/T", dt / osc.period(), 4),
        Setting::text("passes", "1 predicting + 1 correcting (paper steps 1–6)"),
        Setting::number("damping C", "N·s/m", c),
        Setting::choice("support route", route),
    ];
    if let Some(ns) = normal_stepper {
        settings.push(Setting::text("normal force", ns.describe()));
    }
    settings
}

fn forcing_ground_disp(excitation: &Excitation, t: f64) -> f64 {
    match excitation {
        Excitation::GroundDisplacement(s) => s.value(t),
        _ => 0.0,
    }
}

/// The force on the mass at each step, per excitation and route, with the history the
/// Eq 12 route's finite differences need.
struct Forcing<'a> {
    excitation: &'a Excitation,
    route: GroundRoute,
    m: f64,
    dt: f64,
    /// xg-eff at steps i−1 and i−2 (Eq 12 route).
    eff_prev: [f64; 2],
    /// Jumps of the ground velocity (computed once, outside the time loop).
    jumps: Vec<Jump>,
}

impl<'a> Forcing<'a> {
    fn new(excitation: &'a Excitation, route: GroundRoute, m: f64, dt: f64) -> Self {
        let jumps = match excitation {
            Excitation::GroundDisplacement(s) => s.derivative_jumps(),
            _ => Vec::new(),
        };
        Self {
            excitation,
            route,
            m,
            dt,
            eff_prev: [0.0; 2],
            jumps,
        }
    }

    /// Force at step `i` (time `t`), given the slip of the previous step.
    fn force(&mut self, i: usize, t: f64, xp_prev: f64) -> f64 {
        match self.excitation {
            Excitation::None => 0.0,
            Excitation::MassAcceleration(s) => self.m * s.value(t),
            Excitation::GroundAcceleration(s) => -self.m * s.value(t),
            Excitation::GroundDisplacement(s) => match self.route {
                GroundRoute::GroundAcceleration => -self.m * s.second_derivative(t),
                GroundRoute::Eq12 | GroundRoute::Eq12SlipOnce => {
                    let eff = if self.route == GroundRoute::Eq12 {
                        s.value(t) - xp_prev // paper Eq 12, literally
                    } else {
                        s.value(t) + xp_prev
                    };
                    let ag = if i == 0 {
                        0.0
                    } else {
                        (eff - 2.0 * self.eff_prev[0] + self.eff_prev[1]) / (self.dt * self.dt)
                    };
                    self.eff_prev = [eff, self.eff_prev[0]];
                    -self.m * ag
                }
            },
        }
    }

    /// Jump of the relative velocity to apply at the end of the step ending at `t`
    /// (ground-acceleration route only: the Eq 12 route sees jumps through its differences).
    fn velocity_jump(&self, t: f64, dt: f64) -> f64 {
        if self.route != GroundRoute::GroundAcceleration {
            return 0.0;
        }
        // The jump is applied at the step end nearest to it (exact when it falls on one).
        self.jumps
            .iter()
            .filter(|j| j.time - t > -dt / 2.0 && j.time - t <= dt / 2.0)
            .map(|j| -j.size)
            .sum()
    }
}

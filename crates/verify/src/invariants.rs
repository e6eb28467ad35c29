//! Physical invariants, checked on every completed run of every engine with no reference:
//! what any correct solution of a Coulomb contact must satisfy, whatever the excitation.
//!
//! Read off the run's trace (the contact's tangential force — `base_shear` where the scene
//! has several supports, else `resistance` — its normal force, the accumulated slip and,
//! where the engine records them, the energy channels):
//!
//! - `friction_bound`: |T| ≤ μ·N at every step; measured as max (|T| − μN) / (μ·M·g).
//!   With several supports the sums are compared (|ΣT| ≤ Σ|Tᵢ| ≤ μΣNᵢ still holds).
//! - `compression`: N ≥ 0 (compression-only contacts); measured as max(−N) / (M·g).
//! - `stick_slip` (one-contact scenes): no slip while the contact is stuck: the slip accumulated over steps whose
//!   both ends have |T| < (1 − 10⁻³)·μN, over the whole slip path (floored at 1 mm).
//! - `dissipation` (one-contact scenes): friction does no positive work on the structure: the negative part of
//!   Σ T·Δslip over the absolute friction work (floored at μ·M·g × 1 mm).
//! - `energy_balance`: max |energy_error| over the peak input work (where the engine records
//!   energy channels).
//!
//! Each is gated with a tolerance per engine ([`limit`]), measured on the shipped cases
//! (docs in `cases/README.md`); an engine's known violation on a case is declared there as
//! `[[expected_violation]]` and is then reported with its size but does not fail the gate.

use rockslide_core::case::{Case, Model};
use rockslide_core::trace::Trace;
use rockslide_engine_api::Run;

/// Below this fraction of μN the contact counts as stuck for `stick_slip`.
const STUCK_MARGIN: f64 = 1e-3;
/// Floor of the slip path in `stick_slip` and `dissipation`, m.
const SLIP_FLOOR: f64 = 1e-3;

/// One invariant measured on one run.
#[derive(Debug, Clone, PartialEq)]
pub struct InvariantCheck {
    /// Invariant key (`friction_bound`, ...).
    pub invariant: &'static str,
    /// The run, `engine/variant`.
    pub run: String,
    /// The worst measured value (the invariant's own dimensionless measure).
    pub worst: f64,
    /// Time of the worst value, s (`None` for measures over the whole run).
    pub at: Option<f64>,
    /// The engine's tolerance on it.
    pub limit: f64,
    /// Declared known on this case (`[[expected_violation]]` field and reason).
    pub expected: Option<(String, String)>,
}

impl InvariantCheck {
    /// Whether the measured value is within the engine's tolerance.
    pub fn holds(&self) -> bool {
        self.worst <= self.limit
    }
    /// Whether it fails the gate: violated and not declared.
    pub fn fails(&self) -> bool {
        !self.holds() && self.expected.is_none()
    }
    /// The measure in words, with where it was found.
    pub fn describe(&self) -> String {
        let at = self
            .at
            .map(|t| format!(" at t = {t:.4} s"))
            .unwrap_or_default();
        format!(
            "{} {:.3e}{at} (limit {:.1e})",
            self.invariant, self.worst, self.limit
        )
    }
}

/// The invariant keys, in report order.
pub const INVARIANTS: &[&str] = &[
    "friction_bound",
    "compression",
    "stick_slip",
    "dissipation",
    "energy_balance",
];

/// What each invariant means, in one line (for reports).
pub fn meaning(invariant: &str) -> &'static str {
    match invariant {
        "friction_bound" => {
            "max (|T| − μN) / (μ·M·g): the tangential force within the friction cone"
        }
        "compression" => "max (−N) / (M·g): compression-only contact",
        "stick_slip" => "slip while |T| < μN (stuck) / slip path: no creep while stuck",
        "dissipation" => "negative friction work / |friction work|: friction dissipates",
        "energy_balance" => "max |energy error| / peak input work: the energy balance closes",
        _ => "",
    }
}

/// The tolerance of an engine on an invariant, measured on every shipped case with margin:
/// the predictor-corrector and fe hold the contact law to round-off; rapier's
/// velocity-level solver with warm-starting and substeps to a few per cent.
pub fn limit(engine: &str, invariant: &str) -> f64 {
    match (engine, invariant) {
        ("rapier", "friction_bound") => 0.05,
        ("rapier", "compression") => 0.05,
        ("rapier", "stick_slip") => 0.05,
        ("rapier", "dissipation") => 0.02,
        ("rapier", "energy_balance") => 0.05,
        (_, "energy_balance") => 1e-2,
        _ => 1e-9,
    }
}

/// The contact data a trace offers: tangential force, normal force, slip.
struct ContactSeries<'a> {
    tangential: &'a [f64],
    normal: Normal<'a>,
    slip: &'a [f64],
}

/// The normal force: recorded, or the constant weight of a sliding-only oscillator.
enum Normal<'a> {
    Recorded(&'a [f64]),
    Constant(f64),
}

impl Normal<'_> {
    fn at(&self, i: usize) -> f64 {
        match self {
            Normal::Recorded(n) => n[i],
            Normal::Constant(n) => *n,
        }
    }
}

/// μ and the weight M·g of the scene.
fn friction_and_weight(case: &Case) -> (f64, f64) {
    match &case.scene.model {
        Model::Oscillator(o) => (o.contact.mu, o.normal_force()),
        Model::RockingBody(r) => (r.contact.mu, r.weight()),
        Model::RigidBlock(b) => (b.mu, b.mass * b.gravity),
    }
}

fn contact_series<'a>(case: &Case, trace: &'a Trace) -> Option<ContactSeries<'a>> {
    let tangential = trace
        .column("base_shear")
        .or_else(|| trace.column("resistance"))?;
    let slip = trace.column("slide")?;
    let normal = match (trace.column("normal"), &case.scene.model) {
        (Some(n), _) => Normal::Recorded(n),
        (None, Model::Oscillator(o)) => Normal::Constant(o.normal_force()),
        (None, _) => return None,
    };
    Some(ContactSeries {
        tangential,
        normal,
        slip,
    })
}

/// Every invariant measurable on a completed run, with the engine's tolerance and the
/// case's declarations. A run that did not complete is judged by its status instead.
pub fn check_run(case: &Case, run: &Run) -> Vec<InvariantCheck> {
    if !run.status.completed() || run.trace.is_empty() {
        return Vec::new();
    }
    let mut found: Vec<(&'static str, f64, Option<f64>)> = Vec::new();
    let (mu, weight) = friction_and_weight(case);
    if let Some(c) = contact_series(case, &run.trace) {
        let time = &run.trace.time;
        if mu.is_finite() && mu > 0.0 {
            let (w, at) = friction_bound(&c, mu, weight, time);
            found.push(("friction_bound", w, Some(at)));
            if single_contact(case) {
                found.push(("stick_slip", stick_slip(&c, mu), None));
                found.push(("dissipation", dissipation(&c, mu, weight), None));
            }
        }
        if let Normal::Recorded(n) = c.normal {
            let (w, at) = worst(n.iter().map(|n| -n / weight), time);
            found.push(("compression", w, Some(at)));
        }
    }
    if let Some(b) = energy_balance(&run.trace) {
        found.push(("energy_balance", b.0, Some(b.1)));
    }
    found
        .into_iter()
        .map(|(invariant, worst, at)| InvariantCheck {
            invariant,
            run: run.label(),
            worst,
            at,
            limit: limit(run.engine, invariant),
            expected: case
                .expected_violations
                .iter()
                .find(|v| v.engine == run.engine && v.invariant == invariant)
                .map(|v| (v.field.clone(), v.reason.clone())),
        })
        .collect()
}

/// Whether the scene has one contact, so that the trace's slip and force are that
/// contact's own: the oscillator. With several supports the trace holds sums and the mean
/// slip (a lifted support moves without force), which do not decide stick or slip.
fn single_contact(case: &Case) -> bool {
    matches!(case.scene.model, Model::Oscillator(_))
}

/// The largest value of a series and its time (−∞ and NaN-free: NaN counts as +∞).
fn worst(values: impl Iterator<Item = f64>, time: &[f64]) -> (f64, f64) {
    values
        .zip(time)
        .map(|(v, t)| (if v.is_nan() { f64::INFINITY } else { v }, *t))
        .fold(
            (f64::NEG_INFINITY, 0.0),
            |a, b| if b.0 > a.0 { b } else { a },
        )
}

fn friction_bound(c: &ContactSeries, mu: f64, weight: f64, time: &[f64]) -> (f64, f64) {
    let excess =
        (0..time.len()).map(|i| (c.tangential[i].abs() - mu * c.normal.at(i)) / (mu * weight));
    worst(excess, time)
}

/// Whether the contact is stuck at row `i`: |T| clearly below μN.
fn stuck(c: &ContactSeries, mu: f64, i: usize) -> bool {
    c.tangential[i].abs() < (1.0 - STUCK_MARGIN) * mu * c.normal.at(i)
}

fn stick_slip(c: &ContactSeries, mu: f64) -> f64 {
    let (mut creep, mut path) = (0.0, 0.0);
    for i in 1..c.slip.len() {
        let ds = (c.slip[i] - c.slip[i - 1]).abs();
        path += ds;
        if stuck(c, mu, i - 1) && stuck(c, mu, i) {
            creep += ds;
        }
    }
    creep / path.max(SLIP_FLOOR)
}

fn dissipation(c: &ContactSeries, mu: f64, weight: f64) -> f64 {
    let (mut negative, mut total) = (0.0, 0.0);
    for i in 1..c.slip.len() {
        let work = 0.5 * (c.tangential[i] + c.tangential[i - 1]) * (c.slip[i] - c.slip[i - 1]);
        total += work.abs();
        if work < 0.0 {
            negative -= work;
        }
    }
    negative / total.max(mu * weight * SLIP_FLOOR)
}

fn energy_balance(trace: &Trace) -> Option<(f64, f64)> {
    let error = trace.column("energy_error")?;
    let input = trace.column("energy_input")?;
    let scale = input.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if scale <= 0.0 {
        return None;
    }
    Some(worst(error.iter().map(|e| e.abs() / scale), &trace.time))
}

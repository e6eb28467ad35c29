//! Physical invariants, checked on every completed run of every engine with no reference:
//! what any correct solution of a Coulomb contact must satisfy, whatever the excitation.
//!
//! Read off the run's per-contact block (each contact's own normal force N, tangential
//! force T, slip and gap, see `rockslide_core::trace::ContactBlock`) and its trace (the
//! summed tangential force — `base_shear` where the scene has several supports, else
//! `resistance` — the summed normal force, the slip and, where recorded, the energy
//! channels):
//!
//! - `friction_bound`: |T| ≤ μ·N at every contact and step; measured as
//!   max (|Tᵢ| − μNᵢ) / (μ·M·g) over contacts, and the same on the trace's sums (which an
//!   engine computes from the structure's side: rapier's springs and momentum), the worse.
//! - `compression`: N ≥ 0 (compression-only contacts); max(−Nᵢ) / (M·g), contacts and sum.
//! - `stick_slip`: no slip while a contact is stuck: the slip accumulated over steps whose
//!   both ends have |Tᵢ| < (1 − 10⁻³)·μNᵢ, summed over contacts, over the whole slip path
//!   (floored at 1 mm); only steps where the contact is closed (Nᵢ > 0) at both ends count.
//! - `dissipation`: friction does no positive work: the negative part of Σ Tᵢ·Δslipᵢ (Tᵢ
//!   at the step's end, the return mapping's dissipation) over the absolute friction work
//!   (floored at μ·M·g × 1 mm), over contacts and steps closed at both ends.
//! - `penetration`: no contact goes into the ground beyond its model's stated compliance:
//!   max (−gapᵢ − cᵢ·Nᵢ) in metres, cᵢ the contact's normal compliance (1/Kz for a penalty
//!   contact, 0 for rapier's rigid contacts).
//! - `energy_balance`: max |energy_error| over the peak input work (where the engine records
//!   energy channels).
//!
//! A trace without a contact block (a run recorded before it existed) falls back to the
//! trace's sums; stick/slip and dissipation are then measured on one-contact scenes only.
//!
//! Each is gated with a tolerance per engine (`Engine::invariant_limit`), measured on the shipped cases
//! (docs in `cases/README.md`); an engine's known violation on a case is declared there as
//! `[[expected_violation]]` and is then reported with its size but does not fail the gate.

use rockslide_core::case::{Case, Invariant, Model};
use rockslide_core::trace::{ContactBlock, ContactState, Trace};
use rockslide_engine_api::Run;

/// Below this fraction of μN the contact counts as stuck for `stick_slip`.
const STUCK_MARGIN: f64 = 1e-3;
/// Floor of the slip path in `stick_slip` and `dissipation`, m.
const SLIP_FLOOR: f64 = 1e-3;

/// One invariant measured on one run.
#[derive(Debug, Clone, PartialEq)]
pub struct InvariantCheck {
    /// The invariant.
    pub invariant: Invariant,
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

/// What each invariant means, in one line (for reports).
pub fn meaning(invariant: Invariant) -> &'static str {
    match invariant {
        Invariant::FrictionBound => {
            "max (|T| − μN) / (μ·M·g): the tangential force within the friction cone"
        }
        Invariant::Compression => "max (−N) / (M·g): compression-only contact",
        Invariant::StickSlip => "slip while |T| < μN (stuck) / slip path: no creep while stuck",
        Invariant::Dissipation => "negative friction work / |friction work|: friction dissipates",
        Invariant::EnergyBalance => {
            "max |energy error| / peak input work: the energy balance closes"
        }
        Invariant::Penetration => {
            "max (−gap − compliance·N) per contact, m: no penetration beyond the contact model"
        }
    }
}

/// The summed contact data a trace offers: tangential force, normal force, slip (empty
/// for another program's file without one).
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

/// Where the normal force of the summed series comes from.
#[derive(Clone, Copy, PartialEq)]
enum NormalSource {
    /// An engine's run: the scene's M·g for a horizontally shaken oscillator.
    Engine,
    /// Another program's results: its own normal force wherever it gives one.
    Own,
}

fn contact_series<'a>(
    case: &Case,
    trace: &'a Trace,
    source: NormalSource,
) -> Option<ContactSeries<'a>> {
    let tangential = trace
        .column("base_shear")
        .or_else(|| trace.column("resistance"))?;
    // An engine's sums need its slip; another program's force and normal are checked
    // without one (its stick/slip and dissipation then are not measured).
    let slip = match (trace.column("slide"), source) {
        (Some(s), _) => s,
        (None, NormalSource::Own) => &[],
        (None, NormalSource::Engine) => return None,
    };
    // A horizontally shaken oscillator has no vertical dynamics in the scene: its normal
    // force is M·g, whatever an engine's own model of it (rapier's foot) records, so the
    // structure's resistance is held to μ·M·g. Under vertical motion N(t) is recorded.
    // Another program's normal force is its own: a sign error in its model must show.
    let normal = match (trace.column("normal"), &case.scene.model) {
        (Some(n), _) if source == NormalSource::Own => Normal::Recorded(n),
        (_, Model::Oscillator(o)) if case.scene.vertical().is_none() => {
            Normal::Constant(o.normal_force())
        }
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

/// A measure with where it was worst: (value, time of the worst value if it has one).
type Measure = (f64, Option<f64>);

/// The worse of two measures (NaN counts as worst).
fn worse(a: Option<Measure>, b: Option<Measure>) -> Option<Measure> {
    match (a, b) {
        (Some(x), Some(y)) => Some(if y.0 > x.0 || y.0.is_nan() { y } else { x }),
        (x, None) => x,
        (None, y) => y,
    }
}

/// Every invariant measurable on a completed run, with the engine's tolerance and the
/// case's declarations. A run that did not complete is judged by its status instead.
pub fn check_run(case: &Case, run: &Run) -> Vec<InvariantCheck> {
    check_trace(case, run, NormalSource::Engine)
}

/// [`check_run`] for another program's results: its trace sums are its own, so its
/// normal force (where given) is checked for compression and bounds its friction.
pub fn check_external_run(case: &Case, run: &Run) -> Vec<InvariantCheck> {
    check_trace(case, run, NormalSource::Own)
}

fn check_trace(case: &Case, run: &Run, source: NormalSource) -> Vec<InvariantCheck> {
    if !run.status.completed() || run.trace.is_empty() {
        return Vec::new();
    }
    let (mu, weight) = friction_and_weight(case);
    let frictional = mu.is_finite() && mu > 0.0;
    let block = &run.trace.contacts;
    let per_contact = !block.is_empty();
    let summed = contact_series(case, &run.trace, source);
    let time = &run.trace.time;
    let mut found: Vec<(Invariant, Measure)> = Vec::new();
    let mut put = |key: Invariant, m: Option<Measure>| {
        if let Some(m) = m {
            found.push((key, m));
        }
    };
    if frictional {
        let from_contacts = per_contact.then(|| block_friction_bound(block, mu, weight));
        let from_sums = summed.as_ref().map(|c| {
            let (w, at) = friction_bound(c, mu, weight, time);
            (w, Some(at))
        });
        put(Invariant::FrictionBound, worse(from_contacts, from_sums));
    }
    let from_contacts = per_contact.then(|| {
        let n = (0..block.len()).map(|i| {
            (0..block.count()).fold(f64::NEG_INFINITY, |m, c| {
                m.max(-block.at(i, c).normal / weight)
            })
        });
        let (w, at) = worst(n, &block.time);
        (w, Some(at))
    });
    let from_sums = match summed.as_ref().map(|c| &c.normal) {
        Some(Normal::Recorded(n)) => {
            let (w, at) = worst(n.iter().map(|n| -n / weight), time);
            Some((w, Some(at)))
        }
        _ => None,
    };
    put(Invariant::Compression, worse(from_contacts, from_sums));
    if frictional {
        if per_contact {
            put(
                Invariant::StickSlip,
                Some((block_stick_slip(block, mu), None)),
            );
            put(
                Invariant::Dissipation,
                Some((block_dissipation(block, mu, weight), None)),
            );
        } else if let (Some(c), true) = (&summed, single_contact(case))
            && !c.slip.is_empty()
        {
            put(Invariant::StickSlip, Some((stick_slip(c, mu), None)));
            put(
                Invariant::Dissipation,
                Some((dissipation(c, mu, weight), None)),
            );
        }
    }
    if per_contact {
        let (w, at) = penetration(block);
        put(Invariant::Penetration, Some((w, Some(at))));
    }
    if let Some(b) = energy_balance(&run.trace) {
        put(Invariant::EnergyBalance, Some((b.0, Some(b.1))));
    }
    checks_of(case, run, found)
}

/// The checks of the measures `found` on `run`: each with the engine's tolerance and the
/// case's declared violation.
fn checks_of(case: &Case, run: &Run, found: Vec<(Invariant, Measure)>) -> Vec<InvariantCheck> {
    found
        .into_iter()
        .map(|(invariant, (worst, at))| InvariantCheck {
            invariant,
            run: run.label(),
            worst,
            at,
            limit: crate::registry::invariant_limit(run.engine, invariant),
            expected: case
                .expected_violations
                .iter()
                .find(|v| v.engine == run.engine && invariant == v.invariant.as_str())
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

/// `friction_bound` per contact: max (|Tᵢ| − μNᵢ) / (μ·M·g) and its time.
fn block_friction_bound(b: &ContactBlock, mu: f64, weight: f64) -> Measure {
    let excess = (0..b.len()).map(|i| {
        (0..b.count()).fold(f64::NEG_INFINITY, |m, c| {
            let s = b.at(i, c);
            let e = (s.tangential.abs() - mu * s.normal) / (mu * weight);
            if e.is_nan() { f64::INFINITY } else { m.max(e) }
        })
    });
    let (w, at) = worst(excess, &b.time);
    (w, Some(at))
}

/// Whether a contact state is stuck: |T| clearly below μN (an open contact is not).
fn stuck_state(s: &ContactState, mu: f64) -> bool {
    s.tangential.abs() < (1.0 - STUCK_MARGIN) * mu * s.normal
}

/// Whether a contact is closed (carries a normal force) at both ends of a step: only
/// then is its slip friction slip (an open contact's tangential origin follows it).
fn closed_over(s0: &ContactState, s1: &ContactState) -> bool {
    s0.normal > 0.0 && s1.normal > 0.0
}

/// `stick_slip` per contact: creep while stuck over the slip path (steps closed at both
/// ends), each contact's sums added in contact order (as [`StreamedInvariants`] adds
/// them, so a streamed run's measure is the whole run's bit for bit).
fn block_stick_slip(b: &ContactBlock, mu: f64) -> f64 {
    let (mut creep, mut path) = (0.0, 0.0);
    for c in 0..b.count() {
        let (mut creep_c, mut path_c) = (0.0, 0.0);
        for i in 1..b.len() {
            let (s0, s1) = (b.at(i - 1, c), b.at(i, c));
            if !closed_over(&s0, &s1) {
                continue;
            }
            let ds = (s1.slip - s0.slip).abs();
            path_c += ds;
            if stuck_state(&s0, mu) && stuck_state(&s1, mu) {
                creep_c += ds;
            }
        }
        creep += creep_c;
        path += path_c;
    }
    creep / path.max(SLIP_FLOOR)
}

/// `dissipation` per contact: negative friction work over the absolute friction work, the
/// work of a step being T at its end times its slip (the return mapping's dissipation,
/// ≥ 0 for any backward-Euler Coulomb law), over steps closed at both ends; each
/// contact's sums added in contact order (as [`StreamedInvariants`] adds them).
fn block_dissipation(b: &ContactBlock, mu: f64, weight: f64) -> f64 {
    let (mut negative, mut total) = (0.0, 0.0);
    for c in 0..b.count() {
        let (mut negative_c, mut total_c) = (0.0, 0.0);
        for i in 1..b.len() {
            let (s0, s1) = (b.at(i - 1, c), b.at(i, c));
            if !closed_over(&s0, &s1) {
                continue;
            }
            let work = s1.tangential * (s1.slip - s0.slip);
            total_c += work.abs();
            if work < 0.0 {
                negative_c -= work;
            }
        }
        negative += negative_c;
        total += total_c;
    }
    negative / total.max(mu * weight * SLIP_FLOOR)
}

/// `penetration`: max over contacts and rows of −gap − compliance·N, m, and its time.
fn penetration(b: &ContactBlock) -> (f64, f64) {
    let depth = (0..b.len()).map(|i| {
        (0..b.count()).fold(f64::NEG_INFINITY, |m, c| {
            let s = b.at(i, c);
            let d = -s.gap - b.compliance[c] * s.normal.max(0.0);
            if d.is_nan() { f64::INFINITY } else { m.max(d) }
        })
    });
    worst(depth, &b.time)
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

/// The invariants of a run measured step by step as it streams ([`check_run`] on rows it
/// never holds): the same measures, the same arithmetic in the same order, so a streamed
/// run of a one-contact scene gives [`check_run`]'s numbers bit for bit (with several
/// contacts, stick/slip and dissipation sum per contact and then over contacts: the same
/// terms, another order). `energy_scale` is the run's peak |energy_input|, read by a first
/// pass.
pub struct StreamedInvariants {
    mu: f64,
    weight: f64,
    frictional: bool,
    single_contact: bool,
    /// Columns of the summed tangential force, slip, recorded normal force, energy error.
    tangential: Option<usize>,
    slip: Option<usize>,
    normal: Option<usize>,
    constant_normal: Option<f64>,
    energy_error: Option<usize>,
    energy_scale: f64,
    contacts: usize,
    rows: u64,
    block_rows: u64,
    block_friction: (f64, f64),
    sum_friction: (f64, f64),
    block_compression: (f64, f64),
    sum_compression: (f64, f64),
    penetration: (f64, f64),
    energy: (f64, f64),
    /// Per contact: (creep, path, negative work, total work) and the previous state.
    block_sums: Vec<[f64; 4]>,
    previous: Vec<ContactState>,
    /// On the sums: (creep, path, negative work, total work) and the previous (T, N, slip).
    sums: [f64; 4],
    previous_sum: Option<(f64, f64, f64)>,
    compliance: Vec<f64>,
}

/// The running form of [`worst`]: keep the first strictly greater value (NaN as +∞).
fn keep_worst(w: &mut (f64, f64), v: f64, t: f64) {
    let v = if v.is_nan() { f64::INFINITY } else { v };
    if v > w.0 {
        *w = (v, t);
    }
}

impl StreamedInvariants {
    /// Ready for the rows of a run of `case` with this layout (channels and contacts).
    pub fn new(case: &Case, layout: &Trace, energy_scale: f64) -> Self {
        let (mu, weight) = friction_and_weight(case);
        let col = |k: &str| layout.channels.iter().position(|c| c.key == k);
        let tangential = col("base_shear").or_else(|| col("resistance"));
        let recorded = col("normal");
        let (normal, constant_normal) = match (recorded, &case.scene.model) {
            (_, Model::Oscillator(o)) if case.scene.vertical().is_none() => {
                (None, Some(o.normal_force()))
            }
            (Some(n), _) => (Some(n), None),
            (None, Model::Oscillator(o)) => (None, Some(o.normal_force())),
            (None, _) => (None, None),
        };
        let energy_error = col("energy_input").and(col("energy_error"));
        let contacts = layout.contacts.names.len();
        let none = (f64::NEG_INFINITY, 0.0);
        Self {
            mu,
            weight,
            frictional: mu.is_finite() && mu > 0.0,
            single_contact: single_contact(case),
            tangential,
            slip: col("slide"),
            normal,
            constant_normal,
            energy_error,
            energy_scale,
            contacts,
            rows: 0,
            block_rows: 0,
            block_friction: none,
            sum_friction: none,
            block_compression: none,
            sum_compression: none,
            penetration: none,
            energy: none,
            block_sums: vec![[0.0; 4]; contacts],
            previous: vec![ContactState::default(); contacts],
            sums: [0.0; 4],
            previous_sum: None,
            compliance: layout.contacts.compliance.clone(),
        }
    }

    /// Whether the summed series exists (tangential force, slip and a normal force).
    fn has_sums(&self) -> bool {
        self.tangential.is_some()
            && self.slip.is_some()
            && (self.normal.is_some() || self.constant_normal.is_some())
    }

    /// One row of the run.
    pub fn row(&mut self, t: f64, values: &[f64], states: &[ContactState]) {
        let (mu, weight) = (self.mu, self.weight);
        if states.len() == self.contacts && self.contacts > 0 {
            self.block_row(t, states);
        }
        if self.has_sums() {
            let tangential = values[self.tangential.unwrap_or(0)];
            let slip = values[self.slip.unwrap_or(0)];
            let normal = match self.normal {
                Some(n) => values[n],
                None => self.constant_normal.unwrap_or(0.0),
            };
            let excess = (tangential.abs() - mu * normal) / (mu * weight);
            keep_worst(&mut self.sum_friction, excess, t);
            if self.normal.is_some() {
                keep_worst(&mut self.sum_compression, -normal / weight, t);
            }
            if let Some((t0, n0, s0)) = self.previous_sum {
                let stuck = |tt: f64, n: f64| tt.abs() < (1.0 - STUCK_MARGIN) * mu * n;
                let ds = (slip - s0).abs();
                self.sums[1] += ds;
                if stuck(t0, n0) && stuck(tangential, normal) {
                    self.sums[0] += ds;
                }
                let work = 0.5 * (tangential + t0) * (slip - s0);
                self.sums[3] += work.abs();
                if work < 0.0 {
                    self.sums[2] -= work;
                }
            }
            self.previous_sum = Some((tangential, normal, slip));
        }
        if let Some(e) = self.energy_error {
            keep_worst(&mut self.energy, values[e].abs() / self.energy_scale, t);
        }
        self.rows += 1;
    }

    fn block_row(&mut self, t: f64, states: &[ContactState]) {
        let (mu, weight) = (self.mu, self.weight);
        let (mut excess, mut compression, mut depth) =
            (f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for (c, s) in states.iter().enumerate() {
            let e = (s.tangential.abs() - mu * s.normal) / (mu * weight);
            excess = if e.is_nan() {
                f64::INFINITY
            } else {
                excess.max(e)
            };
            compression = compression.max(-s.normal / weight);
            let d = -s.gap - self.compliance[c] * s.normal.max(0.0);
            depth = if d.is_nan() {
                f64::INFINITY
            } else {
                depth.max(d)
            };
            if self.block_rows > 0 {
                let s0 = self.previous[c];
                if closed_over(&s0, s) {
                    let sums = &mut self.block_sums[c];
                    let ds = (s.slip - s0.slip).abs();
                    sums[1] += ds;
                    if stuck_state(&s0, mu) && stuck_state(s, mu) {
                        sums[0] += ds;
                    }
                    let work = s.tangential * (s.slip - s0.slip);
                    sums[3] += work.abs();
                    if work < 0.0 {
                        sums[2] -= work;
                    }
                }
            }
            self.previous[c] = *s;
        }
        keep_worst(&mut self.block_friction, excess, t);
        keep_worst(&mut self.block_compression, compression, t);
        keep_worst(&mut self.penetration, depth, t);
        self.block_rows += 1;
    }

    /// The checks of the run, as [`check_run`] gives them for a whole trace (none for a
    /// run that did not complete or recorded no row).
    pub fn checks(&self, case: &Case, run: &Run) -> Vec<InvariantCheck> {
        if !run.status.completed() || self.rows == 0 {
            return Vec::new();
        }
        let (mu, weight) = (self.mu, self.weight);
        let per_contact = self.block_rows > 0;
        let sums = self.has_sums();
        let mut found: Vec<(Invariant, Measure)> = Vec::new();
        let at = |m: (f64, f64)| Some((m.0, Some(m.1)));
        if self.frictional {
            let from_contacts = if per_contact {
                at(self.block_friction)
            } else {
                None
            };
            let from_sums = if sums { at(self.sum_friction) } else { None };
            if let Some(m) = worse(from_contacts, from_sums) {
                found.push((Invariant::FrictionBound, m));
            }
        }
        let from_contacts = if per_contact {
            at(self.block_compression)
        } else {
            None
        };
        let from_sums = if sums && self.normal.is_some() {
            at(self.sum_compression)
        } else {
            None
        };
        if let Some(m) = worse(from_contacts, from_sums) {
            found.push((Invariant::Compression, m));
        }
        if self.frictional {
            let total = |k: usize| self.block_sums.iter().map(|s| s[k]).fold(0.0, |a, b| a + b);
            if per_contact {
                let stick = total(0) / total(1).max(SLIP_FLOOR);
                let dissipation = total(2) / total(3).max(mu * weight * SLIP_FLOOR);
                found.push((Invariant::StickSlip, (stick, None)));
                found.push((Invariant::Dissipation, (dissipation, None)));
            } else if sums && self.single_contact {
                let s = &self.sums;
                found.push((Invariant::StickSlip, (s[0] / s[1].max(SLIP_FLOOR), None)));
                let d = s[2] / s[3].max(mu * weight * SLIP_FLOOR);
                found.push((Invariant::Dissipation, (d, None)));
            }
        }
        if per_contact {
            found.push((
                Invariant::Penetration,
                (self.penetration.0, Some(self.penetration.1)),
            ));
        }
        let no_energy_scale = self.energy_scale <= 0.0; // NaN: measured, as check_run does
        if self.energy_error.is_some() && !no_energy_scale {
            found.push((
                Invariant::EnergyBalance,
                (self.energy.0, Some(self.energy.1)),
            ));
        }
        checks_of(case, run, found)
    }
}

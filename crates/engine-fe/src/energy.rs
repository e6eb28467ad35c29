//! Energy bookkeeping of a rocking run from the engine's own element states.

use super::element::{Contact178, ContactState, Status};
use super::model::{Model, Plane, Snapshot};

/// The energy terms of a run, accumulated from the engine's own element states and
/// kinematics at every converged step (rocking bodies; `analysis::energy` audits them):
///
/// - input work W: ½(Fₙ + Fₙ₊₁)·ΔX_cm of the applied horizontal force and
///   ½(Fzₙ + Fzₙ₊₁)·ΔZ_cm of the vertical ground motion's load −M·a_v, plus the moving
///   ground's work −½(Tₙ + Tₙ₊₁)·Δxg on each ground element (T the element's force on
///   its upper end; the ground pushes its lower end with −T);
/// - kinetic K = ½M(vx² + vz²) + ½I·ω² (absolute velocities in the model's frame);
/// - strain U = Σ ½T²/Kx + ½N²/Kz over every element (a condensed double support's
///   series equivalent standing for its two elements);
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
pub(crate) struct EnergyBook {
    /// Per element at the last recorded step.
    prev: Vec<ElementEnergy>,
    /// Applied horizontal force, X_cm, ground displacement, vertical load −M·a_v and Z_cm
    /// at the last step.
    last: (f64, f64, f64, f64, f64),
    /// E0 = K + U + V at t = 0.
    initial: f64,
    input: f64,
    friction: f64,
    /// Non-smooth part of the residual (`energy_nonsmooth`), J.
    contact: f64,
    started: bool,
}

/// What the energy book keeps of one element between steps.
#[derive(Debug, Clone, Copy)]
struct ElementEnergy {
    /// The element's committed state (force on the upper end (T, −N), relative
    /// displacement δ, slip, and its status: gap open or not), kept whole: one copy of
    /// the state a step.
    state: ContactState,
    /// Strain energy, J.
    strain: f64,
    /// Whether the element's tangential and normal stiffnesses are finite and positive
    /// (a strain term is booked for them): found at the first step, kept after.
    springs: (bool, bool),
}

impl EnergyBook {
    pub(crate) fn new(elements: usize) -> Self {
        Self {
            prev: vec![
                ElementEnergy {
                    state: ContactState::at_rest(),
                    strain: 0.0,
                    springs: (false, false),
                };
                elements
            ],
            last: (0.0, 0.0, 0.0, 0.0, 0.0),
            initial: 0.0,
            input: 0.0,
            friction: 0.0,
            contact: 0.0,
            started: false,
        }
    }

    /// Book the converged state `s` (applied horizontal force and vertical load `f`); returns
    /// (W, K, U, D, V, E0 + W − (K + U + D + V), non-smooth part). Allocation-free.
    pub(crate) fn record(
        &mut self,
        m: &Model<Plane>,
        s: &Snapshot<Plane>,
        f: (f64, f64),
    ) -> [f64; 7] {
        let (f, fz) = f;
        let xg = s.ground.0;
        let body = &m.body;
        let kinetic =
            0.5 * body.mass * (s.v.x * s.v.x + s.v.y * s.v.y) + 0.5 * body.inertia * s.v.z * s.v.z;
        let potential = m.weight() * (s.pose.y - s.statics.y);
        // Condensed double supports are booked on their series equivalents: the pair's
        // strain ½T²/kx1 + ½T²/kx2 is ½T²/ks (and so for N), element 2 (bonded, linear)
        // neither slips nor opens, and element 1's force, slip and status are the
        // equivalent's — the same terms up to round-off, over half the elements.
        let (strain, ground_force) = match (m.condensed && !m.equivalents.is_empty(), self.started)
        {
            (true, true) => self.book_elements::<true>(m.equivalents.iter().map(|e| (e, true))),
            (true, false) => self.book_elements::<false>(m.equivalents.iter().map(|e| (e, true))),
            (false, started) => {
                // Each support's element 1 (from the ground), then its element 2.
                if m.nodes == 0 {
                    let elements = m.supports.iter().map(|s| (&s.lower, true));
                    if started {
                        self.book_elements::<true>(elements)
                    } else {
                        self.book_elements::<false>(elements)
                    }
                } else {
                    let elements = m.supports.iter().flat_map(|s| {
                        std::iter::once((&s.lower, true)).chain(s.upper.iter().map(|u| (u, false)))
                    });
                    if started {
                        self.book_elements::<true>(elements)
                    } else {
                        self.book_elements::<false>(elements)
                    }
                }
            }
        };
        if self.started {
            let (f_n, x_n, xg_n, fz_n, z_n) = self.last;
            self.input += 0.5 * (f_n + f) * (s.pose.x - x_n) - ground_force * (xg - xg_n)
                + 0.5 * (fz_n + fz) * (s.pose.y - z_n);
        } else {
            self.initial = kinetic + strain + potential;
            self.started = true;
        }
        self.last = (f, s.pose.x, xg, fz, s.pose.y);
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

    /// Book the elements' committed states (each with whether its lower end is the
    /// ground): friction and non-smooth terms into the book; returns (strain U,
    /// Σ ½(Tₙ + Tₙ₊₁) over ground elements). `STARTED` is `self.started`, a constant so
    /// that the loop of every step after the first carries no first-step branch.
    #[inline(always)]
    fn book_elements<'e, const STARTED: bool>(
        &mut self,
        elements: impl Iterator<Item = (&'e Contact178, bool)>,
    ) -> (f64, f64) {
        let mut strain = 0.0;
        let mut ground_force = 0.0;
        // The book's running sums in locals over the loop (the same additions in the same
        // order), stored once after it.
        let (mut friction, mut contact) = (self.friction, self.contact);
        for ((e, on_ground), prev) in elements.zip(self.prev.iter_mut()) {
            let prev_open = prev.state.status == Status::Open;
            let st = e.state();
            let (t, n) = (e.tangential(), e.normal());
            let open = st.status == Status::Open;
            let springs = if STARTED {
                prev.springs
            } else {
                let spring = |k: f64| k.is_finite() && k > 0.0;
                (spring(e.kt), spring(e.kz))
            };
            // A zero force stores nothing: the term would be +0 (skipped, the same bits;
            // no division for an open element).
            let mut u = 0.0;
            if t != 0.0 && springs.0 {
                u += 0.5 * t * t / e.kt;
            }
            if n != 0.0 && springs.1 {
                u += 0.5 * n * n / e.kz;
            }
            strain += u;
            if STARTED {
                if !open && !prev_open {
                    // Trapezoidal, as Newmark's work: ½(Tₙ + Tₙ₊₁)·Δs. It is ≥ 0 unless
                    // T reverses inside the step (|Tₙ| > |Tₙ₊₁|, opposite signs); such
                    // a step is not dissipation and goes to the non-smooth part.
                    let d = 0.5 * (prev.state.force.x + t) * (st.slip - prev.state.slip);
                    if d >= 0.0 {
                        friction += d;
                    } else {
                        contact += d;
                    }
                } else if open != prev_open {
                    // Opening or closing inside the step: the element's trapezoidal work
                    // minus its strain-energy change is what the step's kink lost.
                    let work =
                        0.5 * (prev.state.force + st.force).dot(&(st.delta - prev.state.delta));
                    contact += work - (u - prev.strain);
                }
                if on_ground {
                    ground_force += 0.5 * (prev.state.force.x + t);
                }
            }
            prev.state = *st;
            (prev.strain, prev.springs) = (u, springs);
        }
        (self.friction, self.contact) = (friction, contact);
        (strain, ground_force)
    }
}

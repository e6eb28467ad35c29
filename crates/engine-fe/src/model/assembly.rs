//! The assembly, in either dimension: every element evaluated at a trial state, the
//! internal force on the body and the nodes and the consistent tangent, and the commit or
//! restore of the elements' states once a step is decided.
//!
//! Condensed supports (the single arrangement, or double supports as their series
//! equivalents, `series`): the time loop iterates on the ground-to-body elements alone
//! ([`sum_ground_elements`]): no node unknowns. The node and the two elements' states are
//! rebuilt from the equivalent once per converged step (`commit_step`) for the outputs
//! and the energy book. Uncondensed (`Model::condensed` false): each massless node is put
//! at its exact local equilibrium (`series::node_equilibrium`) and condensed out exactly:
//! its support enters the body's tangent through the series tangent
//! D2 − D2·(D1 + D2)⁻¹·D2, and its residual through the solve (`solve`).

use super::dimension::{Dimension, ForceSums, GroundSums, Model, Tangent, Touch, Vector};
use crate::element::{Contact, Element, Status, Tangential};
use crate::series::{node_equilibrium, split_equivalent};

/// Preallocated results of one assembly.
#[derive(Debug, Clone)]
pub struct Assembly<D: Dimension> {
    /// Internal force on the body's unknowns.
    pub pb: D::Unknowns,
    /// Its tangent with respect to the unknowns, the nodes condensed out.
    pub kbb: D::Matrix,
    /// Internal force on each node.
    pub pn: Vec<Vector<D>>,
    /// Inverses of the node blocks (D1 + D2)⁻¹.
    pub(crate) knn_inv: Vec<Tangent<D>>,
    /// Element 2's tangent D2 of each node (its coupling to the body).
    pub(crate) d2: Vec<Tangent<D>>,
    /// The body point of each node.
    pub(crate) points: Vec<D::Point>,
    /// A node block was singular.
    pub(crate) singular: bool,
    /// The iterate of the last assembly.
    pub(crate) at: D::Iterate,
    /// The last Newton matrix factored (none before the first solve) and its LU factors,
    /// reused while the matrix is bit for bit the same (a contact state that does not
    /// change, a rotation that does not enter); factored in place.
    pub(crate) factored: Option<D::Matrix>,
    pub(crate) lu: D::Lu,
    /// The dimension's own room (the plane oscillator's scalar factors).
    pub(crate) extra: D::Extra,
    /// The condensed supports' tangent sums of the last assembly.
    pub(crate) sums: D::Sums,
    /// What each touching support leaves for the tangent, while it is deferred: room for
    /// one a body offset (none where the dimension sums its tangent at once), the first
    /// `touching` in use.
    pub(crate) touches: Vec<Touch<D>>,
    pub(crate) touching: usize,
    /// The last assembly's tangent `kbb` is not yet summed (`Model::finish_tangent`).
    pub(crate) tangent_pending: bool,
}

impl<D: Dimension> Assembly<D> {
    /// Room for a model's nodes.
    pub fn new(model: &Model<D>) -> Self {
        let n = model.nodes;
        let deferred = <D::Sums as GroundSums<D>>::DEFERRED_TANGENT;
        let deferred_room = if deferred {
            model.body.offsets.len()
        } else {
            0
        };
        Self {
            pb: D::zero(),
            kbb: D::zero_matrix(),
            pn: vec![D::Tangential::zero().join(0.0); n],
            knn_inv: vec![D::Tangential::no_tangent(); n],
            d2: vec![D::Tangential::no_tangent(); n],
            points: vec![D::Point::default(); n],
            singular: false,
            at: D::iterate(&model.kinematics, false, &D::zero(), &D::rest_pose()),
            factored: None,
            lu: D::Lu::default(),
            extra: D::Extra::default(),
            sums: D::Sums::default(),
            // The condensed loop visits one element per body offset at most.
            touches: vec![Touch::<D>::default(); deferred_room],
            touching: 0,
            tangent_pending: false,
        }
    }

    /// The iterate of the last assembly.
    pub fn iterate(&self) -> &D::Iterate {
        &self.at
    }
}

/// The sums of `elements` (each a ground-to-body element at its body offset) at the
/// iterate whose support points `point` gives, ground at `ground`: each element's return
/// mapping read as force and status, an open element left out (it adds nothing: zero
/// force, zero tangent). Returns the force's sums and the number of touching elements;
/// the tangent's sums go to `sums`, or, when the dimension defers them, each touching
/// element's part to `touches` (room for one an element) and `sums` is left for
/// `Model::finish_tangent`.
#[inline(always)]
pub(crate) fn sum_ground_elements<'e, D: Dimension>(
    elements: impl Iterator<Item = (&'e Vector<D>, &'e mut Contact<D::Tangential>)>,
    ground: &Vector<D>,
    point: impl Fn(&Vector<D>) -> D::Point,
    sums: &mut D::Sums,
    touches: &mut [Touch<D>],
) -> (ForceSums<D>, usize) {
    // Summed in locals: the sums stay in registers, out of the assembly's memory.
    let mut force = ForceSums::<D>::default();
    let mut tangent = D::Sums::default();
    let mut touching = 0;
    let deferred = <D::Sums as GroundSums<D>>::DEFERRED_TANGENT;
    for (d, e) in elements {
        let p = point(d);
        let (f, status, slip) = e.trial_ground(D::displacement(&p) - *ground);
        if status != Status::Open {
            let touch = D::Sums::add_force(&mut force, &p, &f, e, status, slip);
            if deferred {
                touches[touching] = touch;
                touching += 1;
            } else {
                tangent.add_tangent(&touch);
            }
        }
    }
    if !deferred {
        *sums = tangent;
    }
    (force, touching)
}

impl<D: Dimension> Model<D> {
    /// Evaluate every element at the unknowns `q` of a step from `from` (nodes `un`,
    /// ground `g`) and assemble internal forces and the consistent tangent into `a`;
    /// returns the iterate. Uncondensed, the massless nodes are first put at their exact
    /// local equilibrium, so `un` is updated.
    #[inline]
    pub fn assemble(
        &mut self,
        q: &D::Unknowns,
        from: &D::Pose,
        un: &mut [Vector<D>],
        g: &D::Ground,
        a: &mut Assembly<D>,
    ) -> D::Iterate {
        let at = self.assemble_force(q, from, un, g, a);
        self.finish_tangent(a);
        at
    }

    /// [`Self::assemble`] with the condensed supports' tangent left for
    /// [`Self::finish_tangent`] when the dimension defers it: a Newton iteration whose
    /// residual ends the step, or is backtracked from, never needs it.
    #[inline]
    pub(crate) fn assemble_force(
        &mut self,
        q: &D::Unknowns,
        from: &D::Pose,
        un: &mut [Vector<D>],
        g: &D::Ground,
        a: &mut Assembly<D>,
    ) -> D::Iterate {
        let at = D::iterate(&self.kinematics, self.body.rotation, q, from);
        a.at = at;
        a.singular = false;
        let ground = D::ground_point(g);
        if self.condensed {
            let (sums, touches) = (&mut a.sums, &mut a.touches);
            let offsets = self.body.offsets.iter();
            let kin = &self.kinematics;
            let (force, touching) = if self.nodes == 0 {
                let elements = offsets.zip(self.supports.iter_mut().map(|s| &mut s.lower));
                D::sum_ground_elements(kin, q, &at, elements, &ground, sums, touches)
            } else {
                let elements = offsets.zip(self.equivalents.iter_mut());
                D::sum_ground_elements(kin, q, &at, elements, &ground, sums, touches)
            };
            a.touching = touching;
            D::Sums::write_force(&force, &at, &mut a.pb);
            a.tangent_pending = true;
        } else {
            self.assemble_with_nodes(q, &at, un, &ground, a);
            D::to_unknowns(&at, self.body.rotation, &mut a.kbb);
            a.tangent_pending = false;
        }
        at
    }

    /// Sum the last assembly's deferred tangent, if it is pending, into `a.kbb`.
    #[inline]
    pub(crate) fn finish_tangent(&self, a: &mut Assembly<D>) {
        if !a.tangent_pending {
            return;
        }
        if <D::Sums as GroundSums<D>>::DEFERRED_TANGENT {
            a.sums = D::Sums::from_touches(&a.touches[..a.touching]);
        }
        a.sums.write_tangent(&a.at, &mut a.kbb);
        D::to_unknowns(&a.at, self.body.rotation, &mut a.kbb);
        a.tangent_pending = false;
    }

    /// The uncondensed assembly: the nodes relaxed and condensed into series tangents.
    fn assemble_with_nodes(
        &mut self,
        q: &D::Unknowns,
        at: &D::Iterate,
        un: &mut [Vector<D>],
        ground: &Vector<D>,
        a: &mut Assembly<D>,
    ) {
        a.pb = D::zero();
        a.kbb = D::zero_matrix();
        let offsets = self.body.offsets.iter();
        for (k, (sup, d)) in self.supports.iter_mut().zip(offsets).enumerate() {
            let p = D::point(&self.kinematics, q, at, d);
            let u = D::displacement(&p);
            let (f, k_support) = match &mut sup.upper {
                None => sup.lower.trial(u - *ground),
                Some(upper) => {
                    // Element 2 bonded with μ2 = ∞ (the double arrangement's): the node's
                    // equilibrium in closed form (Newton on its saturating friction law
                    // cycles); else the node moves with Newton's corrections.
                    if upper.bonded && upper.mu.is_infinite() && !sup.lower.bonded {
                        un[k] = node_equilibrium(&sup.lower, upper, u - *ground) + *ground;
                    }
                    let (f1, d1) = sup.lower.trial(un[k] - *ground);
                    let (f2, d2) = upper.trial(u - un[k]);
                    a.pn[k] = f1 - f2;
                    let inv = D::Tangential::inverse(&(d1 + d2)).unwrap_or_else(|| {
                        a.singular = true;
                        D::Tangential::no_tangent()
                    });
                    a.knn_inv[k] = inv;
                    a.d2[k] = d2;
                    a.points[k] = p;
                    // Static condensation of the node (exact): the series tangent.
                    (f2, d2 - d2 * inv * d2)
                }
            };
            D::add_support(&p, at, &f, &k_support, &mut a.pb, &mut a.kbb);
        }
    }

    /// Commit every element's trial state.
    pub fn commit(&mut self) {
        for s in &mut self.supports {
            s.lower.commit();
            if let Some(u) = &mut s.upper {
                u.commit();
            }
        }
        for e in &mut self.equivalents {
            e.commit();
        }
    }

    /// Commit the state of the last assembly (ground `g`). With condensed double
    /// supports each support's node (`un`) and two elements are first set from its
    /// series equivalent (`split_equivalent`), so outputs and the energy book see every
    /// element.
    pub fn commit_step(&mut self, un: &mut [Vector<D>], g: &D::Ground) {
        if !(self.condensed && self.nodes > 0) {
            self.commit();
            return;
        }
        let ground = D::ground_point(g);
        let supports = self.supports.iter_mut().zip(&mut self.equivalents);
        for ((sup, eq), node) in supports.zip(un) {
            if let Some(upper) = &mut sup.upper {
                *node = split_equivalent(eq, &mut sup.lower, upper) + ground;
            }
            eq.commit();
        }
    }

    /// Restore every element's committed state.
    pub fn restore(&mut self) {
        for s in &mut self.supports {
            s.lower.restore();
            if let Some(u) = &mut s.upper {
                u.restore();
            }
        }
        for e in &mut self.equivalents {
            e.restore();
        }
    }
}

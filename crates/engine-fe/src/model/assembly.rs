//! The plane model's assembly: every element evaluated at a trial state, the internal
//! force on the body and the nodes and the consistent tangent, and the commit or restore
//! of the elements' states once a step is decided.
//!
//! A node links only to the ground and to the body, so the Newton matrix is an
//! arrowhead; each node's 2×2 block is condensed out exactly in the solve (`solve`),
//! leaving a 3×3 body system. Condensed supports (`series`): the time loop iterates on the
//! series equivalents alone, ground to body, exactly like the single arrangement
//! (`assemble_direct`): no node unknowns, no node blocks, no Schur complement. The node
//! and the two elements' states are rebuilt from it once per converged step
//! (`commit_step`) for the outputs and the energy book.

use nalgebra::{Matrix2, Matrix2x3, Matrix3, Matrix3x2, Vector2, Vector3};

use super::body::{Model, Point};
use super::kinematics::{PointKin, point_kin};
use crate::element::{Contact178, Element};
use crate::lu::{Lu2, Lu3};
use crate::options::Kinematics;
use crate::series::{node_equilibrium, split_equivalent};

/// Preallocated results of one assembly.
#[derive(Debug, Clone)]
pub struct Assembly {
    /// Internal force on the body's (X, Z, θ), N and N·m.
    pub pb: Vector3<f64>,
    /// Tangent of `pb` with respect to q.
    pub kbb: Matrix3<f64>,
    /// Internal force on each node.
    pub pn: Vec<Vector2<f64>>,
    /// Node blocks ∂pn/∂un.
    pub knn: Vec<Matrix2<f64>>,
    /// ∂pb/∂un.
    pub kbn: Vec<Matrix3x2<f64>>,
    /// ∂pn/∂q.
    pub knb: Vec<Matrix2x3<f64>>,
    /// Inverses of the node blocks (filled by `solve`).
    pub(crate) knn_inv: Vec<Matrix2<f64>>,
    /// Kinematics of every body attachment at the current q (computed once per assembly).
    points: Vec<PointKin>,
    /// The last condensed Newton matrix and its LU factors, reused while the matrix is
    /// bit for bit the same (a contact state that does not change, small rotations).
    pub(crate) factors: Option<Factors>,
    /// The sliding oscillator's cached 2×2 factors (`slider`).
    pub(crate) slider_factors: Option<Lu2>,
    /// The ground point (displacement) of the last assembly.
    ground: Vector2<f64>,
    /// (cos θ, sin θ) of the last assembly ((1, 0) with small-rotation kinematics, which
    /// do not use them).
    cs: (f64, f64),
}

/// A condensed Newton matrix and its LU factors (fixed size, on the stack).
pub(crate) type Factors = (Matrix3<f64>, Lu3);

impl Assembly {
    /// Record the ground point of a step assembled outside `Model::assemble` (the sliding
    /// oscillator's scalar step), for `Model::commit_step`.
    pub(crate) fn set_ground(&mut self, xg: f64) {
        self.ground = Vector2::new(xg, 0.0);
    }

    /// (cos θ, sin θ) of the last assembly's body position, as its kinematics use them
    /// ((1, 0) with small rotations, whose kinematics ignore them).
    pub fn rotation(&self) -> (f64, f64) {
        self.cs
    }

    /// Room for a model's nodes and attachment points.
    pub fn new(model: &Model) -> Self {
        let nodes = model.nodes;
        Self {
            points: vec![PointKin::default(); model.body.attachments.len()],
            pb: Vector3::zeros(),
            kbb: Matrix3::zeros(),
            pn: vec![Vector2::zeros(); nodes],
            knn: vec![Matrix2::zeros(); nodes],
            kbn: vec![Matrix3x2::zeros(); nodes],
            knb: vec![Matrix2x3::zeros(); nodes],
            knn_inv: vec![Matrix2::zeros(); nodes],
            factors: None,
            slider_factors: None,
            ground: Vector2::zeros(),
            cs: (1.0, 0.0),
        }
    }
}

impl Model {
    /// Evaluate every element at the trial state (body q, nodes `un`, ground at `xg`)
    /// and assemble internal forces and the consistent tangent into `a`.
    /// The massless nodes are first put at their exact local equilibrium
    /// (`relax_nodes`), so `un` is updated.
    pub fn assemble(
        &mut self,
        q: &Vector3<f64>,
        un: &mut [Vector2<f64>],
        xg: f64,
        a: &mut Assembly,
    ) {
        let ground = Vector2::new(xg, 0.0);
        a.ground = ground;
        let cs = if self.kinematics == Kinematics::Exact {
            (q.z.cos(), q.z.sin())
        } else {
            (1.0, 0.0)
        };
        a.cs = cs;
        if self.condensed {
            (a.pb, a.kbb) = self.assemble_condensed(q, cs, ground);
            return;
        }
        for (p, d) in a.points.iter_mut().zip(&self.body.attachments) {
            *p = point_kin(self.kinematics, self.p_delta, q, cs, d);
        }
        self.assemble_with_nodes(un, a);
    }

    /// The condensed assembly (`assemble_direct`) with the attachment kinematics fixed per
    /// call, so the loop over elements carries no kinematics dispatch and no array of
    /// point kinematics.
    fn assemble_condensed(
        &mut self,
        q: &Vector3<f64>,
        cs: (f64, f64),
        ground: Vector2<f64>,
    ) -> (Vector3<f64>, Matrix3<f64>) {
        let attachments = &self.body.attachments;
        macro_rules! with_kinematics {
            ($kin:expr, $pd:expr) => {
                if self.nodes == 0 {
                    let elements = self.links.iter_mut().map(|l| &mut l.element);
                    assemble_direct(elements, attachments, ground, |d| {
                        point_kin($kin, $pd, q, cs, d)
                    })
                } else {
                    assemble_direct(self.equivalents.iter_mut(), attachments, ground, |d| {
                        point_kin($kin, $pd, q, cs, d)
                    })
                }
            };
        }
        match (self.kinematics, self.p_delta) {
            (Kinematics::Exact, _) => with_kinematics!(Kinematics::Exact, false),
            (Kinematics::SmallRotation, false) => {
                with_kinematics!(Kinematics::SmallRotation, false)
            }
            (Kinematics::SmallRotation, true) => with_kinematics!(Kinematics::SmallRotation, true),
        }
    }

    /// The uncondensed assembly: every element, the massless nodes as unknowns.
    fn assemble_with_nodes(&mut self, un: &mut [Vector2<f64>], a: &mut Assembly) {
        let ground = a.ground;
        let xg = ground.x;
        a.pb = Vector3::zeros();
        a.kbb = Matrix3::zeros();
        for k in 0..self.nodes {
            a.pn[k] = Vector2::zeros();
            a.knn[k] = Matrix2::zeros();
            a.kbn[k] = Matrix3x2::zeros();
            a.knb[k] = Matrix2x3::zeros();
        }
        self.relax_nodes(&a.points, un, xg);
        let un: &[Vector2<f64>] = un;
        for link in &mut self.links {
            let at = |p: Point| match p {
                Point::Ground => (ground, None),
                Point::Node(k) => (un[k], None),
                Point::Body(i) => {
                    let pk = a.points[i];
                    (pk.u, Some(pk))
                }
            };
            let (ul, kl) = at(link.lower);
            let (uu, ku) = at(link.upper);
            let (f, d) = link.element.trial(uu - ul);
            // Upper end gets +f, lower end −f; ∂f/∂u_upper = D, ∂f/∂u_lower = −D.
            // With G = [I₂ | g]: Gᵀf = (f, g·f), GᵀDG = [[D, Dg], [gᵀD, gᵀDg]].
            let body_end = match (&ku, &kl) {
                (Some(pk), _) => Some((pk, 1.0)),
                (_, Some(pk)) => Some((pk, -1.0)),
                _ => None,
            };
            let mut coupling = None;
            if let Some((pk, sign)) = body_end {
                let dg = d * pk.g;
                let gtd = d.tr_mul(&pk.g); // (gᵀD)ᵀ
                a.pb += Vector3::new(f.x, f.y, pk.g.dot(&f)) * sign;
                let k = &mut a.kbb;
                k[(0, 0)] += d[(0, 0)];
                k[(0, 1)] += d[(0, 1)];
                k[(1, 0)] += d[(1, 0)];
                k[(1, 1)] += d[(1, 1)];
                k[(0, 2)] += dg.x;
                k[(1, 2)] += dg.y;
                k[(2, 0)] += gtd.x;
                k[(2, 1)] += gtd.y;
                // geometric stiffness ±f·∂²u/∂θ²
                k[(2, 2)] += pk.g.dot(&dg) + sign * f.dot(&pk.h);
                coupling = Some((dg, gtd));
            }
            let node = match (link.upper, link.lower) {
                (Point::Node(k), _) => Some((k, 1.0)),
                (_, Point::Node(k)) => Some((k, -1.0)),
                _ => None,
            };
            if let Some((k, sign)) = node {
                a.pn[k] += f * sign;
                a.knn[k] += d;
                if let Some((dg, gtd)) = coupling {
                    // ∂pb/∂un = −GᵀD, ∂pn/∂q = −DG
                    a.kbn[k] -=
                        Matrix3x2::new(d[(0, 0)], d[(0, 1)], d[(1, 0)], d[(1, 1)], gtd.x, gtd.y);
                    a.knb[k] -=
                        Matrix2x3::new(d[(0, 0)], d[(0, 1)], dg.x, d[(1, 0)], d[(1, 1)], dg.y);
                }
            }
        }
    }

    /// Commit every element's trial state.
    pub fn commit(&mut self) {
        for l in &mut self.links {
            l.element.commit();
        }
        for e in &mut self.equivalents {
            e.commit();
        }
    }

    /// Commit the state of the last assembly `a`. With condensed double supports each
    /// support's node and two elements are first rebuilt from its series equivalent
    /// (`split_equivalent`), so outputs and the energy book see every element.
    pub fn commit_step(&mut self, a: &Assembly, un: &mut [Vector2<f64>]) {
        if self.condensed && self.nodes > 0 {
            // Support i's elements 1 and 2 are links 2i and 2i + 1 and its node is node i
            // (`supports_for`, checked by `with_equivalents`): one pass over the three
            // arrays, no index to check. Every link is a condensed support's element 1
            // or 2, its committed state set by `split_equivalent`; the equivalent is
            // committed beside them.
            let supports = self.links.chunks_exact_mut(2).zip(un.iter_mut());
            for ((pair, node), eq) in supports.zip(self.equivalents.iter_mut()) {
                if let [l1, l2] = pair {
                    *node = split_equivalent(eq, &mut l1.element, &mut l2.element) + a.ground;
                }
                eq.commit();
            }
            return;
        }
        self.commit();
    }

    /// Restore every element's committed state.
    pub fn restore(&mut self) {
        for l in &mut self.links {
            l.element.restore();
        }
        for e in &mut self.equivalents {
            e.restore();
        }
    }

    /// Put every intermediate node at its exact equilibrium for the current body
    /// position and ground (`series::node_equilibrium`: exact for the double
    /// arrangement, element 1 compression-only with friction from the ground, element 2
    /// bonded with μ2 = ∞). The global Newton then iterates on the body alone with the
    /// condensed (Schur) tangent, which is the derivative of this local solution.
    fn relax_nodes(&self, points: &[PointKin], un: &mut [Vector2<f64>], xg: f64) {
        for sup in &self.supports {
            let Some(k) = sup.node else { continue };
            let (l1, l2) = (
                &self.links[sup.ground_link],
                &self.links[sup.ground_link + 1],
            );
            let Point::Body(i) = l2.upper else { continue };
            let (e1, e2) = (&l1.element, &l2.element);
            if !(e2.bonded && e2.mu.is_infinite()) || e1.bonded {
                continue;
            }
            let ground = Vector2::new(xg, 0.0);
            un[k] = node_equilibrium(e1, e2, points[i].u - ground) + ground;
        }
    }
}

/// Internal force on the body and its tangent from elements joining the ground to body
/// attachment `i` (the `i`-th element): Gᵀf and GᵀDG + f·∂²u/∂θ² with G = [I₂ | g].
/// Plain scalars in the loop (no matrix temporaries); the same sums in the same order as
/// the general assembly, so a single arrangement gives the same bits.
#[inline(always)]
fn assemble_direct<'e>(
    elements: impl Iterator<Item = &'e mut Contact178>,
    attachments: &[Vector2<f64>],
    ground: Vector2<f64>,
    kinematics: impl Fn(&Vector2<f64>) -> PointKin,
) -> (Vector3<f64>, Matrix3<f64>) {
    let (mut p0, mut p1, mut p2) = (0.0, 0.0, 0.0);
    let mut k = [[0.0_f64; 3]; 3];
    for (e, d) in elements.zip(attachments) {
        let pk = kinematics(d);
        let (f, d) = e.trial_contact(pk.u - ground);
        let (gx, gz) = (pk.g.x, pk.g.y);
        // d10 = ∂N/∂δx is +0 in every state of the element (its normal is fixed): its
        // products are ±0, and every sum they entered starts from +0 (`k` below, or
        // `k22`'s term, itself added to a sum from +0), where a ±0 term changes no bit.
        let (d00, d01, d11) = (d[(0, 0)], d[(0, 1)], d[(1, 1)]);
        let (dgx, dgy) = (d00 * gx + d01 * gz, d11 * gz);
        let (gtdx, gtdy) = (d00 * gx, d01 * gx + d11 * gz);
        p0 += f.x;
        p1 += f.y;
        p2 += gx * f.x + gz * f.y;
        k[0][0] += d00;
        k[0][1] += d01;
        k[1][1] += d11;
        k[0][2] += dgx;
        k[1][2] += dgy;
        k[2][0] += gtdx;
        k[2][1] += gtdy;
        k[2][2] += (gx * dgx + gz * dgy) + (f.x * pk.h.x + f.y * pk.h.y);
    }
    (
        Vector3::new(p0, p1, p2),
        Matrix3::new(
            k[0][0], k[0][1], k[0][2], k[1][0], k[1][1], k[1][2], k[2][0], k[2][1], k[2][2],
        ),
    )
}

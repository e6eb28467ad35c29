//! The FE model: a rigid body (point mass at the centre of mass, rigid massless base),
//! massless intermediate nodes, and contact elements linking ground, nodes and support
//! points; its assembly (internal force and consistent tangent) and the block solve of
//! the Newton system.
//!
//! Degrees of freedom: the body's q = (X, Z, θ) of the centre of mass (θ locked for a
//! sliding oscillator) and (x, z) of each massless node. A node links only to the ground
//! and to the body, so the Newton matrix is an arrowhead; each node's 2×2 block is
//! condensed out exactly (static condensation), leaving a 3×3 body system. This is an
//! exact elimination, not an approximation, and it keeps a step allocation-free and
//! cheap (fixed-size nalgebra matrices on the stack).
//!
//! Condensed supports: when element 2 of the double arrangement is bonded with μ2 = ∞
//! (every shipped case), the pair in series *is* one CONTA178-like element with the
//! series stiffnesses and element 1's friction and slip (`series_equivalent`, derived
//! there). The time loop then iterates on that element alone, ground to body, exactly like
//! the single arrangement (`assemble_direct`): no node unknowns, no node blocks, no Schur
//! complement. The node and the two elements' states are rebuilt from it once per
//! converged step (`commit_step`) for the outputs and the energy book.
//!
//! Gravity is a constant load −M·g on Z; the run starts from the static equilibrium
//! under it (`static_preload`).

use nalgebra::{Matrix2, Matrix2x3, Matrix3, Matrix3x2, Vector2, Vector3};

use super::element::{Contact178, ContactState, Element, Status};
use super::lu::Lu3;
use super::options::Kinematics;
use rockslide_core::case::{Contact, DoubleContact, Oscillator, RockingBody};

/// Where an element end sits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Point {
    /// The ground (prescribed horizontal displacement xg(t)).
    Ground,
    /// Massless node `k`.
    Node(usize),
    /// Attachment point `i` of the body.
    Body(usize),
}

/// One element between two points.
#[derive(Debug, Clone)]
pub struct Link {
    /// Lower end.
    pub lower: Point,
    /// Upper end.
    pub upper: Point,
    /// The element.
    pub element: Contact178,
}

/// One support: the element touching the ground and, in the double arrangement, the
/// intermediate node above it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Support {
    /// Index of the link whose lower end is the ground.
    pub ground_link: usize,
    /// The intermediate node, if any.
    pub node: Option<usize>,
}

/// The rigid body.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Translational mass (X and Z), kg.
    pub mass: f64,
    /// Rotational inertia about the centre of mass, kg·m² (unused when θ is locked).
    pub inertia: f64,
    /// Whether θ is a degree of freedom.
    pub rotation: bool,
    /// Attachment points in the body frame, relative to the centre of mass, m.
    pub attachments: Vec<Vector2<f64>>,
    /// Horizontal viscous damping on the body relative to the ground, N·s/m.
    pub damping: f64,
}

/// Model assembled from a scene variant.
#[derive(Debug, Clone)]
pub struct Model {
    /// The body.
    pub body: Body,
    /// Number of massless nodes.
    pub nodes: usize,
    /// Elements.
    pub links: Vec<Link>,
    /// Supports, for outputs.
    pub supports: Vec<Support>,
    /// Gravity, m/s².
    pub gravity: f64,
    /// Kinematics of the attachment points.
    pub kinematics: Kinematics,
    /// Second-order rotation terms with small-rotation kinematics.
    pub p_delta: bool,
    /// The double arrangement's supports as single series-equivalent elements, ground to
    /// body attachment `i` (`series_equivalent`); empty for the single arrangement.
    pub equivalents: Vec<Contact178>,
    /// Whether the time loop iterates on the body alone (the single arrangement, or the
    /// double one with every support condensed into its `equivalents`). `false` runs the
    /// node unknowns through Newton (element 2 with finite friction, or set by a test to
    /// compare with the uncondensed model).
    pub condensed: bool,
}

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
    knn_inv: Vec<Matrix2<f64>>,
    /// Kinematics of every body attachment at the current q (computed once per assembly).
    points: Vec<PointKin>,
    /// The last condensed Newton matrix and its LU factors, reused while the matrix is
    /// bit for bit the same (a contact state that does not change, small rotations).
    factors: Option<Factors>,
    /// The ground point (displacement) of the last assembly.
    ground: Vector2<f64>,
    /// (cos θ, sin θ) of the last assembly ((1, 0) with small-rotation kinematics, which
    /// do not use them).
    cs: (f64, f64),
}

/// A condensed Newton matrix and its LU factors (fixed size, on the stack).
type Factors = (Matrix3<f64>, Lu3);

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
            ground: Vector2::zeros(),
            cs: (1.0, 0.0),
        }
    }
}

/// Displacement of a body point, the θ column g of its Jacobian G = ∂u/∂q = [I₂ | g],
/// and h = ∂²u/∂θ².
#[derive(Debug, Clone, Copy, Default)]
struct PointKin {
    u: Vector2<f64>,
    g: Vector2<f64>,
    h: Vector2<f64>,
}

/// Kinematics of a body point at body-frame offset `d` from the centre of mass.
#[inline]
fn point_kin(
    kin: Kinematics,
    p_delta: bool,
    q: &Vector3<f64>,
    cs: (f64, f64),
    d: &Vector2<f64>,
) -> PointKin {
    let (dx, dz) = (d.x, d.y);
    let th = q.z;
    let (ux, uz, gx, gz, hx, hz) = match (kin, p_delta) {
        (Kinematics::Exact, _) => {
            // r = R(θ)·d, R = [[c, −s], [s, c]]: u = (R − I)·d
            let (c, s) = cs;
            (
                (c - 1.0) * dx - s * dz,
                s * dx + (c - 1.0) * dz,
                -s * dx - c * dz,
                c * dx - s * dz,
                -c * dx + s * dz,
                -s * dx - c * dz,
            )
        }
        (Kinematics::SmallRotation, false) => (-th * dz, th * dx, -dz, dx, 0.0, 0.0),
        // Second order in θ: cos θ ≈ 1 − θ²/2, sin θ ≈ θ.
        (Kinematics::SmallRotation, true) => (
            -th * dz - 0.5 * th * th * dx,
            th * dx - 0.5 * th * th * dz,
            -dz - th * dx,
            dx - th * dz,
            -dx,
            -dz,
        ),
    };
    PointKin {
        u: Vector2::new(q.x + ux, q.y + uz),
        g: Vector2::new(gx, gz),
        h: Vector2::new(hx, hz),
    }
}

/// The engine's stated rotational inertia when a case gives none: 0.01 % of that of a
/// uniform solid block 2b wide and 2h tall about its centre, I = 1e-4·M(b² + h²)/3
/// (21.35 kg·m² for the RPEPO). Measured on the RPEPO (docs/fe-engine.md): results with
/// I and I/10 agree to about 1–3 % while 100·I (1 % of the block's) changes the peak
/// sliding by 50 %, so this value stands for the paper's "no rotational inertia". The
/// rapier engine applies the same rule in its own code; the shipped RPEPO cases state it.
pub fn default_rotational_inertia(r: &RockingBody) -> f64 {
    1e-4 * r.mass * (r.half_width.powi(2) + r.cm_height.powi(2)) / 3.0
}

fn element(c: &Contact, bonded: bool) -> Contact178 {
    Contact178::new(c.kx, c.kz, c.mu, bonded)
}

impl Model {
    /// The sliding oscillator, single element (`double` = None) or two in series.
    pub fn oscillator(o: &Oscillator, double: Option<&DoubleContact>) -> Self {
        let body = Body {
            mass: o.mass,
            inertia: 0.0,
            rotation: false,
            attachments: vec![Vector2::zeros()],
            damping: o.damping(),
        };
        let (links, supports, nodes) = supports_for(1, &o.contact, double);
        Model {
            body,
            nodes,
            links,
            supports,
            gravity: o.gravity,
            kinematics: Kinematics::SmallRotation,
            p_delta: false,
            equivalents: Vec::new(),
            condensed: false,
        }
        .with_equivalents()
    }

    /// The rocking body with its supports.
    pub fn rocking(
        r: &RockingBody,
        double: Option<&DoubleContact>,
        inertia: f64,
        kinematics: Kinematics,
        p_delta: bool,
    ) -> Self {
        let body = Body {
            mass: r.mass,
            inertia,
            rotation: true,
            attachments: r
                .support_positions()
                .into_iter()
                .map(|x| Vector2::new(x, -r.cm_height))
                .collect(),
            damping: 0.0,
        };
        let (links, supports, nodes) = supports_for(r.supports, &r.contact, double);
        Model {
            body,
            nodes,
            links,
            supports,
            gravity: r.gravity,
            kinematics,
            p_delta,
            equivalents: Vec::new(),
            condensed: false,
        }
        .with_equivalents()
    }

    /// Body mass matrix diagonal (M, M, I).
    pub fn mass_diag(&self) -> Vector3<f64> {
        Vector3::new(self.body.mass, self.body.mass, self.body.inertia)
    }

    /// Weight M·g, N.
    pub fn weight(&self) -> f64 {
        self.body.mass * self.gravity
    }

    /// Displacement of body attachment `i` (for outputs).
    pub fn point_displacement(&self, q: &Vector3<f64>, i: usize) -> Vector2<f64> {
        let cs = (q.z.cos(), q.z.sin());
        point_kin(
            self.kinematics,
            self.p_delta,
            q,
            cs,
            &self.body.attachments[i],
        )
        .u
    }

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

    /// Whether the model is a sliding oscillator whose step can run in scalars (the
    /// body's X and Z, θ locked, one support at the centre of mass, condensed), on
    /// `slider_element` (`stepper::slider`).
    pub(crate) fn is_slider(&self) -> bool {
        self.condensed
            && !self.body.rotation
            && self.kinematics == Kinematics::SmallRotation
            && !self.p_delta
            && self.body.inertia.is_finite()
            && self.body.attachments == [Vector2::zeros()]
            && matches!(
                (self.nodes, self.links.len(), self.equivalents.len()),
                (0, 1, 0) | (1, 2, 1)
            )
    }

    /// The one element a slider's step iterates on (`is_slider`): the single
    /// arrangement's element or the double one's series equivalent.
    #[inline]
    pub(crate) fn slider_element(&mut self) -> &mut Contact178 {
        if self.nodes == 0 {
            &mut self.links[0].element
        } else {
            &mut self.equivalents[0]
        }
    }

    /// Unknowns of the massless nodes the Newton iteration carries (none when condensed).
    pub fn loop_nodes(&self) -> usize {
        if self.condensed { 0 } else { self.nodes }
    }

    /// Condense every double support into its series equivalent where it is exact.
    fn with_equivalents(mut self) -> Self {
        if self.nodes == 0 {
            self.condensed = true;
            return self;
        }
        let pairs = self.supports.iter().map(|sup| {
            let (l1, l2) = (
                &self.links[sup.ground_link],
                self.links.get(sup.ground_link + 1),
            );
            l2.and_then(|l2| series_equivalent(&l1.element, &l2.element))
        });
        let laid_out = self.supports.iter().enumerate().all(|(i, sup)| {
            sup.ground_link == 2 * i && sup.node == Some(i) && self.links.len() == 2 * self.nodes
        });
        if let Some(eq) = pairs.collect::<Option<Vec<_>>>()
            && laid_out
        {
            self.equivalents = eq;
            self.condensed = true;
        }
        self
    }
}

/// The exact single element of two CONTA178-like elements in series through a massless
/// node, element 1 (ground side: compression-only, friction μ1) and element 2 (bonded,
/// μ2 = ∞); `None` for any other pair.
///
/// Derivation. The node carries no load, so both elements transmit the same force f.
/// Normal: element 1 closed (δtz ≤ 0) gives N = kz1·(−δ1z) = kz2·(δ1z − δtz), so
/// N = kzs·(−δtz) with kzs = kz1·kz2/(kz1 + kz2); δtz > 0 opens element 1 and nothing is
/// transmitted (element 2 is bonded, so it only follows). Tangential, with element 1's
/// slip s1: sticking, T = kx1·(δ1x − s1) = kx2·(δtx − δ1x) gives T = ks·(δtx − s1),
/// ks = kx1·kx2/(kx1 + kx2), and the pair sticks while |T| ≤ μ1·N — the same test on the
/// same numbers; slipping, T = ±μ1·N and s1 = δ1x − T/kx1 = δtx − T/kx2 − T/kx1 = δtx − T/ks,
/// the return mapping of an element (ks, kzs, μ1) whose slip is s1. Open: δ1 = δt, and
/// CONTA178 moves the tangential origin with the point, s1 = δtx, again the same. The
/// consistent tangents agree too: the Schur complement D2·(D1 + D2)⁻¹·D1 of the node is
/// diag(ks, kzs) sticking and [[0, −sg·μ1·kzs], [0, kzs]] slipping. So the equivalent is
/// exact in every state; only round-off differs (kzs·δtz against kz1·(kz2·δtz/(kz1 + kz2))).
pub fn series_equivalent(lower: &Contact178, upper: &Contact178) -> Option<Contact178> {
    if lower.bonded || !upper.bonded || upper.mu.is_finite() {
        return None;
    }
    let series = |a: f64, b: f64| a * b / (a + b);
    let mut eq = Contact178::new(
        series(lower.kx, upper.kx),
        series(lower.kz, upper.kz),
        lower.mu,
        false,
    );
    eq.set_committed(*lower.state());
    Some(eq)
}

/// Set the committed states of a condensed support's element 1 (`lower`) and element 2
/// (`upper`) from the last trial of their series equivalent `eq`; returns the node's
/// position relative to the ground, δ1. Both elements carry the equivalent's force f;
/// element 2 sticks, so its deflection is δ2 = (fx/kx2, fz/kz2) and δ1 = δt − δ2
/// (δ1 = δt, δ2 = 0 when element 1 is open); element 1 has the equivalent's slip and
/// status (`series_equivalent`).
fn split_equivalent(
    eq: &Contact178,
    lower: &mut Contact178,
    upper: &mut Contact178,
) -> Vector2<f64> {
    let st = *eq.trial_state();
    let d2 = if st.status == Status::Open {
        Vector2::zeros()
    } else {
        Vector2::new(st.force.x / upper.kx, st.force.y / upper.kz)
    };
    let d1 = st.delta - d2;
    // Only the committed states: a condensed support's elements are never trialled.
    lower.set_state(ContactState { delta: d1, ..st });
    upper.set_state(ContactState {
        slip: upper.state().slip,
        delta: d2,
        force: st.force,
        status: Status::Stick,
    });
    d1
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

/// Links and supports for `n` supports (body attachment `i` each).
fn supports_for(
    n: usize,
    single: &Contact,
    double: Option<&DoubleContact>,
) -> (Vec<Link>, Vec<Support>, usize) {
    let mut links = Vec::new();
    let mut supports = Vec::new();
    for i in 0..n {
        match double {
            None => {
                supports.push(Support {
                    ground_link: links.len(),
                    node: None,
                });
                links.push(Link {
                    lower: Point::Ground,
                    upper: Point::Body(i),
                    element: element(single, false),
                });
            }
            Some(dc) => {
                supports.push(Support {
                    ground_link: links.len(),
                    node: Some(i),
                });
                links.push(Link {
                    lower: Point::Ground,
                    upper: Point::Node(i),
                    element: element(&dc.lower, false),
                });
                // Element 2 is bonded: with element 1 compression-only in series the pair
                // transmits exactly what two compression-only elements would (the
                // massless node balances N2 = N1 ≥ 0), but the node stays determinate
                // when element 1 opens.
                links.push(Link {
                    lower: Point::Node(i),
                    upper: Point::Body(i),
                    element: element(&dc.upper, true),
                });
            }
        }
    }
    let nodes = if double.is_some() { n } else { 0 };
    (links, supports, nodes)
}

/// Scaling of the Newton system: S·Δq = rhs with S = diag(M)·c0 + s·(Kbb − Σ Kbn Knn⁻¹ Knb)
/// (+ c_damp on XX), rhs = rb − Σ Kbn Knn⁻¹ rn; nodes Δun = Knn⁻¹(rn/s − Knb Δq).
pub struct System {
    /// Coefficient of the mass matrix, 1/(β·Δt²) (0 for statics).
    pub c0: f64,
    /// Scale of the stiffness, 1 + α.
    pub s: f64,
    /// Extra XX stiffness (damping γ/(βΔt)·C·(1+α)).
    pub damp_xx: f64,
}

/// Solve the Newton system; writes Δq and Δun. Returns false if a block is singular.
pub fn solve(
    model: &Model,
    sys: &System,
    a: &mut Assembly,
    rb: &Vector3<f64>,
    rn: &[Vector2<f64>],
    dq: &mut Vector3<f64>,
    dun: &mut [Vector2<f64>],
) -> bool {
    let m = model.mass_diag();
    let mut s_mat = Matrix3::from_diagonal(&(m * sys.c0)) + a.kbb * sys.s;
    s_mat[(0, 0)] += sys.damp_xx;
    let mut rhs = *rb;
    for (k, r) in rn.iter().enumerate().take(model.loop_nodes()) {
        let Some(inv) = a.knn[k].try_inverse() else {
            return false;
        };
        a.knn_inv[k] = inv;
        let kbn_inv = a.kbn[k] * inv;
        s_mat -= kbn_inv * a.knb[k] * sys.s;
        rhs -= kbn_inv * r;
    }
    if !model.body.rotation {
        for j in 0..3 {
            s_mat[(2, j)] = 0.0;
            s_mat[(j, 2)] = 0.0;
        }
        s_mat[(2, 2)] = 1.0;
        rhs.z = 0.0;
    }
    // LU with partial pivoting (`Lu3`): the closed-form 3×3 inverse is a little cheaper but
    // loses digits, and the tight preset then needs more iterations. The factors are
    // reused while the matrix is unchanged (the same bits, so the same solution).
    let Some(x) = factors_of(&mut a.factors, &s_mat).and_then(|lu| lu.solve(&rhs)) else {
        return false;
    };
    *dq = x;
    for k in 0..model.loop_nodes() {
        dun[k] = a.knn_inv[k] * (rn[k] / sys.s - a.knb[k] * x);
    }
    true
}

/// The LU factors of `s_mat`: the cached ones when `s_mat` is bit for bit the matrix they
/// factor, else new ones (cached). On the stack: no allocation.
fn factors_of<'a>(cache: &'a mut Option<Factors>, s_mat: &Matrix3<f64>) -> Option<&'a Lu3> {
    let same = |m: &Matrix3<f64>| {
        m.iter()
            .zip(s_mat.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    };
    if !matches!(cache, Some((m, _)) if same(m)) {
        *cache = Some((*s_mat, Lu3::new(s_mat)));
    }
    cache.as_ref().map(|(_, lu)| lu)
}

/// The tangent stiffness condensed onto the body's (X, Z, θ) at the current element
/// states (Schur complement of the node blocks); `None` if a node block is singular.
pub fn condensed_tangent(model: &Model, a: &Assembly) -> Option<Matrix3<f64>> {
    let mut k = a.kbb;
    for n in 0..model.loop_nodes() {
        let inv = a.knn[n].try_inverse()?;
        k -= a.kbn[n] * inv * a.knb[n];
    }
    Some(k)
}

impl Model {
    /// Displacement of any body-frame point `d` (e.g. the base centre O).
    pub fn displacement_of(&self, q: &Vector3<f64>, d: &Vector2<f64>) -> Vector2<f64> {
        let cs = (q.z.cos(), q.z.sin());
        point_kin(self.kinematics, self.p_delta, q, cs, d).u
    }

    /// `displacement_of` with (cos θ, sin θ) of `q` given (`Assembly::rotation`): the
    /// same bits without a second sine and cosine.
    pub fn displacement_at(
        &self,
        q: &Vector3<f64>,
        cs: (f64, f64),
        d: &Vector2<f64>,
    ) -> Vector2<f64> {
        point_kin(self.kinematics, self.p_delta, q, cs, d).u
    }
}

impl Model {
    /// Put every intermediate node at its exact equilibrium for the current body
    /// position and ground (a local solve, exact for the double arrangement: element 1
    /// compression-only with friction from the ground, element 2 bonded with μ2 = ∞).
    ///
    /// The node's two equations f1(δ1) = f2(δt − δ1) are piecewise linear; Newton on them
    /// cycles between stick and slip (a saturating force plus a soft spring behaves like
    /// arctan), so they are solved in closed form:
    ///   closed (δtz ≤ 0): δ1z = kz2·δtz/(kz1 + kz2);  open: δ1 = δt (no force).
    ///   stick: T = ks(δtx − s1), δ1x = (kx1·s1 + kx2·δtx)/(kx1 + kx2), ks = series kx;
    ///   slip (|T| > μ1·N): T = ±μ1·N, δ1x = δtx − T/kx2.
    /// The global Newton then iterates on the body alone with the condensed (Schur)
    /// tangent, which is the derivative of this local solution.
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
            let ub = points[i].u;
            let dt = ub - Vector2::new(xg, 0.0);
            let d1 = if dt.y > 0.0 {
                dt
            } else {
                let z1 = e2.kz * dt.y / (e1.kz + e2.kz);
                let n = -e1.kz * z1;
                let s1 = e1.state().slip;
                let ks = e1.kx * e2.kx / (e1.kx + e2.kx);
                let t = ks * (dt.x - s1);
                let cap = e1.mu * n;
                let x1 = if e1.mu.is_infinite() || t.abs() <= cap {
                    (e1.kx * s1 + e2.kx * dt.x) / (e1.kx + e2.kx)
                } else {
                    dt.x - t.signum() * cap / e2.kx
                };
                Vector2::new(x1, z1)
            };
            un[k] = d1 + Vector2::new(xg, 0.0);
        }
    }
}

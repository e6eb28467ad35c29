//! The 3D model: a rigid body with six degrees of freedom (centre-of-mass displacement X
//! and a finite rotation R) on supports, each one cone contact from the ground to the
//! body (single) or two in series through a massless node (double); its assembly
//! (internal force and consistent tangent) and the condensed Newton solve.
//!
//! Unknowns of a step: X and the incremental rotation vector Θ since the last converged
//! step, R = Rₙ·exp(Θ̂) (`rotation`). A support point at body offset d moves by
//! u = X + (R − I)·d; a body-frame virtual rotation W gives δu = δX + G·W with
//! G = −R·d̂, and W = J_r(Θ)·δΘ. The body's internal force is (Σf, Σ d × Rᵀf) — the
//! moment in the body frame — and its tangent with respect to (X, W)
//!   [[ΣD, ΣD·G], [ΣGᵀD, Σ GᵀDG + d̂·(Rᵀf)^]]
//! (the last term the geometric stiffness of the finite rotation), its W columns then
//! multiplied by J_r(Θ): the exact derivative with respect to the unknowns.
//!
//! A node links only to the ground and the body, so each node's 3×3 block is condensed
//! out exactly, leaving a 6×6 body system (fixed-size arrays, nothing allocated).
//!
//! Condensed supports (`crate::series`): when element 2 of the
//! double arrangement is bonded with μ2 = ∞ (every shipped case), the pair in series *is*
//! one cone contact with the series stiffnesses and element 1's friction and slip
//! (`series_equivalent`, derived there for the circular cone). The time loop then iterates
//! on that element alone, ground to body, exactly like the single arrangement
//! (`assemble_direct`): no node relaxation, no node blocks, no series tangent. The node and
//! both elements are set from it once per converged step (`commit_step`).

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

use super::body::SpaceBody;
use super::ground_sums::assemble_direct;
use super::rotation::{right_jacobian, skew};
use crate::element::{ConeContact, Element};
use crate::lu::Lu6;
use crate::series::{node_equilibrium, series_equivalent, split_equivalent};
use rockslide_core::case::Contact;

/// One support: element 1 from the ground (to the node, or to the body), and element 2
/// from the node to the body in the double arrangement.
#[derive(Debug, Clone)]
pub struct SpaceSupport {
    /// Body-frame offset from the centre of mass, m.
    pub offset: Vector3<f64>,
    /// The element touching the ground.
    pub lower: ConeContact,
    /// Element 2 (bonded, μ = ∞), double arrangement only.
    pub upper: Option<ConeContact>,
}

/// The 3D model.
#[derive(Debug, Clone)]
pub struct SpaceModel {
    /// The body it was built from.
    pub body: SpaceBody,
    /// Supports (node k belongs to support k in the double arrangement).
    pub supports: Vec<SpaceSupport>,
    /// Number of massless nodes (0 or the number of supports).
    pub nodes: usize,
    /// The double arrangement's supports as single series-equivalent cone contacts, ground
    /// to body (`series_equivalent`); empty for the single arrangement.
    pub equivalents: Vec<ConeContact>,
    /// Whether the time loop iterates on the body alone (the single arrangement, or the
    /// double one with every support condensed into its `equivalents`); `false` carries the
    /// nodes (element 2 with finite friction).
    pub condensed: bool,
}

/// Preallocated results of one assembly.
#[derive(Debug, Clone)]
pub struct SpaceAssembly {
    /// Internal force on the body: force (ground frame) and moment (body frame).
    pub pb: Vector6<f64>,
    /// Tangent of `pb` with respect to (X, Θ), the nodes condensed out: a double support
    /// enters through its series tangent D2 − D2·(D1 + D2)⁻¹·D2.
    pub kbb: Matrix6<f64>,
    /// Internal force on each node.
    pub pn: Vec<Vector3<f64>>,
    /// Inverses of the node blocks (D1 + D2)⁻¹.
    knn_inv: Vec<Matrix3<f64>>,
    /// Element 2's tangent D2 of each node (its coupling to the body).
    d2: Vec<Matrix3<f64>>,
    /// G = −R·d̂ of each node's body point.
    g: Vec<Matrix3<f64>>,
    /// J_r(Θ) of the assembly's pose (the identity when Θ = 0).
    jr: Matrix3<f64>,
    /// A node block was singular.
    singular: bool,
    /// The last Newton matrix and its LU factors, reused while the matrix is bit for bit
    /// the same (the rotation locked and the contact states unchanged).
    factors: Option<(Matrix6<f64>, Lu6)>,
}

impl SpaceAssembly {
    /// Room for a model's nodes.
    pub fn new(model: &SpaceModel) -> Self {
        let n = model.nodes;
        Self {
            pb: Vector6::zeros(),
            kbb: Matrix6::zeros(),
            pn: vec![Vector3::zeros(); n],
            knn_inv: vec![Matrix3::zeros(); n],
            d2: vec![Matrix3::zeros(); n],
            g: vec![Matrix3::zeros(); n],
            jr: Matrix3::identity(),
            singular: false,
            factors: None,
        }
    }
}

/// The body's configuration at a Newton iterate.
#[derive(Debug, Clone, Copy)]
pub struct Pose {
    /// Centre-of-mass displacement, m.
    pub x: Vector3<f64>,
    /// Rotation R = Rₙ·exp(Θ̂).
    pub r: Matrix3<f64>,
    /// Incremental rotation vector Θ (for J_r).
    pub theta: Vector3<f64>,
}

fn cone(c: &Contact, bonded: bool) -> ConeContact {
    ConeContact::new(c.kx, c.kz, c.mu, bonded)
}

impl SpaceModel {
    /// The model of a body: one element per support, or two through a node.
    pub fn new(body: &SpaceBody) -> Self {
        let supports = body
            .supports
            .iter()
            .map(|&offset| match &body.double {
                None => SpaceSupport {
                    offset,
                    lower: cone(&body.contact, false),
                    upper: None,
                },
                Some(d) => SpaceSupport {
                    offset,
                    lower: cone(&d.lower, false),
                    upper: Some(cone(&d.upper, true)),
                },
            })
            .collect::<Vec<_>>();
        let nodes = if body.double.is_some() {
            supports.len()
        } else {
            0
        };
        Self {
            body: body.clone(),
            supports,
            nodes,
            equivalents: Vec::new(),
            condensed: false,
        }
        .with_equivalents()
    }

    /// Condense every double support into its series equivalent where that is exact.
    fn with_equivalents(mut self) -> Self {
        if self.nodes == 0 {
            self.condensed = true;
            return self;
        }
        let pairs = self.supports.iter().map(|sup| {
            sup.upper
                .as_ref()
                .and_then(|upper| series_equivalent(&sup.lower, upper))
        });
        if let Some(eq) = pairs.collect::<Option<Vec<_>>>() {
            self.equivalents = eq;
            self.condensed = true;
        }
        self
    }

    /// Node unknowns the Newton iteration carries (none when condensed).
    pub fn loop_nodes(&self) -> usize {
        if self.condensed { 0 } else { self.nodes }
    }

    /// Weight M·g, N.
    pub fn weight(&self) -> f64 {
        self.body.mass * self.body.gravity
    }

    /// Displacement of the body-frame point `d`: X + (R − I)·d.
    #[inline]
    pub fn displacement_of(x: &Vector3<f64>, r: &Matrix3<f64>, d: &Vector3<f64>) -> Vector3<f64> {
        x + (r * d - d)
    }

    /// Evaluate every element at `pose` (nodes `un`, ground at `ground`) and assemble the
    /// internal forces and the consistent tangent into `a`. Condensed: the ground-to-body
    /// elements alone (`assemble_direct`); else the massless nodes are first put at their
    /// exact local equilibrium (`series::node_equilibrium`) and condensed out.
    pub fn assemble(
        &mut self,
        pose: &Pose,
        un: &mut [Vector3<f64>],
        ground: &Vector3<f64>,
        a: &mut SpaceAssembly,
    ) {
        a.singular = false;
        if self.condensed {
            let out = (&mut a.pb, &mut a.kbb);
            if self.nodes == 0 {
                let elements = self.supports.iter_mut().map(|s| (s.offset, &mut s.lower));
                assemble_direct(elements, &pose.x, &pose.r, ground, out);
            } else {
                let offsets = self.supports.iter().map(|s| s.offset);
                let elements = offsets.zip(self.equivalents.iter_mut());
                assemble_direct(elements, &pose.x, &pose.r, ground, out);
            }
        } else {
            self.assemble_with_nodes(pose, un, ground, a);
        }
        // From the body-frame virtual rotation W to the unknown Θ: W = J_r(Θ)·δΘ.
        a.jr = Matrix3::identity();
        if self.body.rotation && pose.theta != Vector3::zeros() {
            a.jr = right_jacobian(&pose.theta);
            let cols = a.kbb.fixed_columns::<3>(3) * a.jr;
            a.kbb.fixed_columns_mut::<3>(3).copy_from(&cols);
        }
    }

    /// The uncondensed assembly: the nodes relaxed and condensed into series tangents.
    fn assemble_with_nodes(
        &mut self,
        pose: &Pose,
        un: &mut [Vector3<f64>],
        ground: &Vector3<f64>,
        a: &mut SpaceAssembly,
    ) {
        a.pb = Vector6::zeros();
        a.kbb = Matrix6::zeros();
        let rt = pose.r.transpose();
        for (k, sup) in self.supports.iter_mut().enumerate() {
            let d = sup.offset;
            let u = Self::displacement_of(&pose.x, &pose.r, &d);
            let dh = skew(&d);
            let g = -(pose.r * dh); // δu = δX + G·W
            let (f, dm) = match &mut sup.upper {
                None => sup.lower.trial(u - ground),
                Some(upper) => {
                    un[k] = node_equilibrium(&sup.lower, upper, u - ground) + ground;
                    let (f1, d1) = sup.lower.trial(un[k] - ground);
                    let (f2, d2) = upper.trial(u - un[k]);
                    a.pn[k] = f1 - f2;
                    let inv = node_inverse(&(d1 + d2)).unwrap_or_else(|| {
                        a.singular = true;
                        Matrix3::zeros()
                    });
                    a.knn_inv[k] = inv;
                    a.d2[k] = d2;
                    a.g[k] = g;
                    // Static condensation of the node (exact): the series tangent.
                    (f2, d2 - d2 * inv * d2)
                }
            };
            let rtf = rt * f;
            let (dg, gtd) = tangent_times_g(&dm, &g);
            let mut pb = a.pb.fixed_rows_mut::<3>(0);
            pb += f;
            let mut pr = a.pb.fixed_rows_mut::<3>(3);
            pr += d.cross(&rtf);
            let mut k00 = a.kbb.fixed_view_mut::<3, 3>(0, 0);
            k00 += dm;
            let mut k01 = a.kbb.fixed_view_mut::<3, 3>(0, 3);
            k01 += dg;
            let mut k10 = a.kbb.fixed_view_mut::<3, 3>(3, 0);
            k10 += gtd;
            let mut k11 = a.kbb.fixed_view_mut::<3, 3>(3, 3);
            // d̂·(Rᵀf)^ = (Rᵀf)·dᵀ − (d·Rᵀf)·I
            k11 += gtd * g + rtf * d.transpose() - Matrix3::identity() * d.dot(&rtf);
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

    /// Commit the state of the last assembly. With condensed double supports each
    /// support's node (`un`, ground at `ground`) and two elements are first set from its
    /// series equivalent (`split_equivalent`), so the outputs see every element.
    pub fn commit_step(&mut self, un: &mut [Vector3<f64>], ground: &Vector3<f64>) {
        if !(self.condensed && self.nodes > 0) {
            self.commit();
            return;
        }
        // Split sets both elements' committed (and trial) states.
        for ((sup, eq), node) in self.supports.iter_mut().zip(&mut self.equivalents).zip(un) {
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

/// The inverse of a node block D1 + D2: reciprocals when it is diagonal (both elements
/// sticking or open), else the general inverse.
#[inline]
fn node_inverse(k: &Matrix3<f64>) -> Option<Matrix3<f64>> {
    if is_diagonal(k) {
        let d = k.diagonal();
        if d.iter().all(|x| *x != 0.0) {
            return Some(Matrix3::from_diagonal(&d.map(|x| 1.0 / x)));
        }
        return None;
    }
    k.try_inverse()
}

/// Whether every off-diagonal entry is exactly zero.
#[inline]
fn is_diagonal(m: &Matrix3<f64>) -> bool {
    m[(0, 1)] == 0.0
        && m[(0, 2)] == 0.0
        && m[(1, 0)] == 0.0
        && m[(1, 2)] == 0.0
        && m[(2, 0)] == 0.0
        && m[(2, 1)] == 0.0
}

/// (D·G, Gᵀ·D) of an element tangent D: a diagonal D (a sticking or bonded element)
/// scales G's rows, the same bits as the full products (the other terms are exact zeros).
#[inline]
fn tangent_times_g(dm: &Matrix3<f64>, g: &Matrix3<f64>) -> (Matrix3<f64>, Matrix3<f64>) {
    if is_diagonal(dm) {
        let dg = Matrix3::from_fn(|i, j| dm[(i, i)] * g[(i, j)]);
        (dg, dg.transpose())
    } else {
        (dm * g, g.tr_mul(dm))
    }
}

/// Coefficients of the Newton system of one step:
/// S = blockdiag(M·c0·I, inertial tangent) + s·K (+ damping on x and y).
#[derive(Debug, Clone, Copy)]
pub struct SpaceSystem {
    /// Mass coefficient 1/(β·Δt²) (0 for statics).
    pub c0: f64,
    /// Stiffness scale 1 + α.
    pub s: f64,
    /// Damping on x and y: γ/(βΔt)·C·(1 + α).
    pub damp: f64,
    /// ∂(J·A + Ω × J·Ω)/∂Θ = c0·J + c1·(Ω̂·J − (J·Ω)^).
    pub inertial: Matrix3<f64>,
}

/// Solve the Newton system: writes the body correction and the nodes'; false if singular.
/// The nodes are condensed in the assembly; here their residuals enter the right-hand
/// side, rhs += [v; Gᵀv] with v = D2·(D1 + D2)⁻¹·rn, and are recovered after the body's
/// solve, Δun = (D1 + D2)⁻¹·(rn/s + D2·(Δx + G·J_r·ΔΘ)).
pub fn solve(
    model: &SpaceModel,
    sys: &SpaceSystem,
    a: &mut SpaceAssembly,
    rb: &Vector6<f64>,
    rn: &[Vector3<f64>],
    dq: &mut Vector6<f64>,
    dun: &mut [Vector3<f64>],
) -> bool {
    if a.singular {
        return false;
    }
    let mut s_mat = a.kbb * sys.s;
    let m = model.body.mass * sys.c0;
    s_mat[(0, 0)] += m + sys.damp;
    s_mat[(1, 1)] += m + sys.damp;
    s_mat[(2, 2)] += m;
    let mut rot = s_mat.fixed_view_mut::<3, 3>(3, 3);
    rot += sys.inertial;
    let mut rhs = *rb;
    for (k, r) in rn.iter().enumerate().take(model.loop_nodes()) {
        let v = a.d2[k] * (a.knn_inv[k] * r);
        let mut rx = rhs.fixed_rows_mut::<3>(0);
        rx += v;
        let gv = a.g[k].tr_mul(&v);
        let mut rw = rhs.fixed_rows_mut::<3>(3);
        rw += gv;
    }
    if !model.body.rotation {
        for i in 3..6 {
            for j in 0..6 {
                s_mat[(i, j)] = 0.0;
                s_mat[(j, i)] = 0.0;
            }
            s_mat[(i, i)] = 1.0;
            rhs[i] = 0.0;
        }
    }
    // LU with partial pivoting (`Lu6`, nalgebra's algorithm written out), its factors
    // reused while the matrix is bit for bit the same.
    let same = |m: &Matrix6<f64>| {
        m.iter()
            .zip(s_mat.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    };
    if !matches!(&a.factors, Some((m, _)) if same(m)) {
        a.factors = Some((s_mat, Lu6::new(&s_mat)));
    }
    let Some(x) = a.factors.as_ref().and_then(|(_, lu)| lu.solve(&rhs)) else {
        return false;
    };
    *dq = x;
    let dx = x.fixed_rows::<3>(0).into_owned();
    let dw = a.jr * x.fixed_rows::<3>(3);
    for k in 0..model.loop_nodes() {
        dun[k] = a.knn_inv[k] * (rn[k] / sys.s + a.d2[k] * (dx + a.g[k] * dw));
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::space::body::BlockGrid;
    use crate::space::rotation::exp;
    use rockslide_core::case::DoubleContact;

    /// A 4 × 3 block with the RPEPO's double elements (kx1 ≫ kx2, μ1 = 0.5).
    fn block() -> SpaceBody {
        let c = |kx: f64, kz: f64, mu: f64| Contact { kx, kz, mu };
        SpaceBody::block(
            &BlockGrid {
                mass: 1e5,
                gravity: 9.81,
                cm_height: 1.25,
                half_length: 0.5,
                half_width: 0.3,
                nx: 4,
                ny: 3,
                inertia: Matrix3::from_diagonal(&Vector3::new(3e4, 4e4, 2e4)),
                contact: c(1e9, 4e9, 0.5),
                double: Some(DoubleContact {
                    lower: c(2.45e11, 9.8e10, 0.5),
                    upper: c(1e9, 4e9, f64::INFINITY),
                }),
            },
            true,
        )
    }

    #[test]
    fn condensed_supports_give_the_node_models_force_and_tangent() {
        // A pose that opens some supports, sticks some and slips others (tipped about a
        // skew axis, pushed down and sideways).
        let pose = Pose {
            x: Vector3::new(1.0e-6, -0.5e-6, -2.0e-6),
            r: exp(&Vector3::new(4e-6, -6e-6, 4e-6)),
            theta: Vector3::new(1e-6, -2e-6, 5e-7),
        };
        let ground = Vector3::new(1e-6, 0.0, 0.0);
        let body = block();
        let mut condensed = SpaceModel::new(&body);
        assert!(condensed.condensed && condensed.loop_nodes() == 0);
        let mut nodes = condensed.clone();
        nodes.condensed = false;
        let (mut a1, mut a2) = (SpaceAssembly::new(&condensed), SpaceAssembly::new(&nodes));
        let mut un = vec![Vector3::zeros(); nodes.nodes];
        condensed.assemble(&pose, &mut un, &ground, &mut a1);
        nodes.assemble(&pose, &mut un, &ground, &mut a2);
        let states = |m: &SpaceModel| {
            let mut n = [0; 3];
            for s in &m.equivalents {
                n[s.trial_state().status as usize] += 1;
            }
            n
        };
        let [open, stick, slip] = states(&condensed);
        assert!(stick > 0 && slip > 0 && open > 0, "{stick} {slip} {open}");
        let df = (a1.pb - a2.pb).norm() / a2.pb.norm();
        let dk = (a1.kbb - a2.kbb).norm() / a2.kbb.norm();
        eprintln!("{stick} stick, {slip} slip, {open} open: force {df:e}, tangent {dk:e}");
        // Measured 3 sticking, 6 slipping, 3 open; force 1.0e-16 and tangent 1.3e-16 of
        // their norms: the same to round-off.
        assert!(df < 5e-16 && dk < 5e-16, "{df:e} {dk:e}");
    }
}

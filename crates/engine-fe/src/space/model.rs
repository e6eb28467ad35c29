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

use nalgebra::{Matrix3, Matrix6, Vector2, Vector3, Vector6};

use super::contact::ConeContact;
use super::rotation::{right_jacobian, skew};
use rockslide_core::case::{Contact, DoubleContact, Oscillator, RockingBody};

/// A rigid body on supports, as the 3D model is built from it.
#[derive(Debug, Clone, PartialEq)]
pub struct SpaceBody {
    /// Mass, kg.
    pub mass: f64,
    /// Gravity, m/s² (along −z).
    pub gravity: f64,
    /// Inertia tensor about the centre of mass in the body frame (ground axes at rest),
    /// kg·m² (unused when the rotation is locked).
    pub inertia: Matrix3<f64>,
    /// Whether the body rotates (false: the PEPO, a translating mass).
    pub rotation: bool,
    /// Support points in the body frame, relative to the centre of mass, m.
    pub supports: Vec<Vector3<f64>>,
    /// Each support as one element (kx is the tangential stiffness in both directions).
    pub contact: Contact,
    /// Each support as two elements in series, if so.
    pub double: Option<DoubleContact>,
    /// Horizontal viscous damping relative to the ground (both directions), N·s/m.
    pub damping: f64,
}

/// A rigid block on an nx × ny grid of supports under its base (the RPEPO extended).
#[derive(Debug, Clone, PartialEq)]
pub struct BlockGrid {
    /// Mass, kg.
    pub mass: f64,
    /// Gravity, m/s².
    pub gravity: f64,
    /// Height of the centre of mass above the base centre O, m.
    pub cm_height: f64,
    /// Half-length of the base along x, m.
    pub half_length: f64,
    /// Half-width of the base along y, m.
    pub half_width: f64,
    /// Supports along x (≥ 1).
    pub nx: usize,
    /// Supports along y (≥ 1).
    pub ny: usize,
    /// Inertia tensor about the centre of mass, kg·m².
    pub inertia: Matrix3<f64>,
    /// Single element per support.
    pub contact: Contact,
    /// Double arrangement, if any.
    pub double: Option<DoubleContact>,
}

/// Equally spaced abscissae from −half to +half (0 for one), the 2D model's formula.
fn positions(n: usize, half: f64) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| {
        if n == 1 {
            0.0
        } else {
            -half + 2.0 * half * i as f64 / (n - 1) as f64
        }
    })
}

impl SpaceBody {
    /// The PEPO as a 3D oscillator: a translating mass on one contact.
    pub fn oscillator(o: &Oscillator, double: bool) -> Self {
        Self {
            mass: o.mass,
            gravity: o.gravity,
            inertia: Matrix3::zeros(),
            rotation: false,
            supports: vec![Vector3::zeros()],
            contact: o.contact,
            double: if double { o.double } else { None },
            damping: o.damping(),
        }
    }

    /// A block on a grid of supports (x fastest, then y).
    pub fn block(g: &BlockGrid, double: bool) -> Self {
        let mut supports = Vec::with_capacity(g.nx * g.ny);
        for y in positions(g.ny, g.half_width) {
            for x in positions(g.nx, g.half_length) {
                supports.push(Vector3::new(x, y, -g.cm_height));
            }
        }
        Self {
            mass: g.mass,
            gravity: g.gravity,
            inertia: g.inertia,
            rotation: true,
            supports,
            contact: g.contact,
            double: if double { g.double } else { None },
            damping: 0.0,
        }
    }

    /// The 2D rocking body in 3D: a symmetric two-row grid, each 2D support split into two
    /// at y = ±`half_width` carrying half its stiffnesses, and an isotropic inertia
    /// `inertia`. In its plane it is the 2D structure (the same sums of forces, each half
    /// element at half the force); out of plane it stands (a single row of supports
    /// would be a knife edge, free to tip sideways).
    pub fn from_rocking(r: &RockingBody, inertia: f64, half_width: f64, double: bool) -> Self {
        let half = |c: Contact| Contact {
            kx: 0.5 * c.kx,
            kz: 0.5 * c.kz,
            mu: c.mu,
        };
        Self::block(
            &BlockGrid {
                mass: r.mass,
                gravity: r.gravity,
                cm_height: r.cm_height,
                half_length: r.half_width,
                half_width,
                nx: r.supports,
                ny: 2,
                inertia: Matrix3::identity() * inertia,
                contact: half(r.contact),
                double: r.double.map(|d| DoubleContact {
                    lower: half(d.lower),
                    upper: half(d.upper),
                }),
            },
            double,
        )
    }
}

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
        }
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
    /// internal forces and the consistent tangent into `a`. The massless nodes are first
    /// put at their exact local equilibrium (`relax_node`) and condensed out.
    pub fn assemble(
        &mut self,
        pose: &Pose,
        un: &mut [Vector3<f64>],
        ground: &Vector3<f64>,
        a: &mut SpaceAssembly,
    ) {
        a.pb = Vector6::zeros();
        a.kbb = Matrix6::zeros();
        a.singular = false;
        let rt = pose.r.transpose();
        for (k, sup) in self.supports.iter_mut().enumerate() {
            let d = sup.offset;
            let u = Self::displacement_of(&pose.x, &pose.r, &d);
            let dh = skew(&d);
            let g = -(pose.r * dh); // δu = δX + G·W
            let (f, dm) = match &mut sup.upper {
                None => sup.lower.trial(u - ground),
                Some(upper) => {
                    un[k] = relax_node(&sup.lower, upper, &u, ground);
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
        // From the body-frame virtual rotation W to the unknown Θ: W = J_r(Θ)·δΘ.
        a.jr = Matrix3::identity();
        if self.body.rotation && pose.theta != Vector3::zeros() {
            a.jr = right_jacobian(&pose.theta);
            let cols = a.kbb.fixed_columns::<3>(3) * a.jr;
            a.kbb.fixed_columns_mut::<3>(3).copy_from(&cols);
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
    }

    /// Restore every element's committed state.
    pub fn restore(&mut self) {
        for s in &mut self.supports {
            s.lower.restore();
            if let Some(u) = &mut s.upper {
                u.restore();
            }
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

/// The exact equilibrium position of a massless node between element 1 (friction on the
/// circular cone, compression-only) and the bonded element 2 (μ = ∞), for the body point
/// at `u` and the ground at `ground` — the 2D closed form with the tangential pair as a
/// vector (radial return of the series spring):
///   closed (δz ≤ 0): z1 = kz2·δz/(kz1 + kz2);  open: the node sits at the body point;
///   stick: p1 + (δt − p1)·kt2/(kt1 + kt2);  slip (|T| > μ1·N): δt − μ1·N·T/|T|/kt2.
#[inline]
fn relax_node(
    e1: &ConeContact,
    e2: &ConeContact,
    u: &Vector3<f64>,
    ground: &Vector3<f64>,
) -> Vector3<f64> {
    let dt = u - ground;
    let d1 = if dt.z > 0.0 {
        dt
    } else {
        let z1 = e2.kz * dt.z / (e1.kz + e2.kz);
        let n = -e1.kz * z1;
        let s1 = e1.state().slip;
        let ks = e1.kt * e2.kt / (e1.kt + e2.kt);
        let t: Vector2<f64> = (dt.xy() - s1) * ks;
        let cap = e1.mu * n;
        let size = t.norm();
        let x1 = if e1.mu.is_infinite() || size <= cap {
            (s1 * e1.kt + dt.xy() * e2.kt) / (e1.kt + e2.kt)
        } else {
            dt.xy() - (t / size) * cap / e2.kt
        };
        Vector3::new(x1.x, x1.y, z1)
    };
    d1 + ground
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
    for (k, r) in rn.iter().enumerate().take(model.nodes) {
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
    let Some(x) = s_mat.lu().solve(&rhs) else {
        return false;
    };
    *dq = x;
    let dx = x.fixed_rows::<3>(0).into_owned();
    let dw = a.jr * x.fixed_rows::<3>(3);
    for k in 0..model.nodes {
        dun[k] = a.knn_inv[k] * (rn[k] / sys.s + a.d2[k] * (dx + a.g[k] * dw));
    }
    true
}

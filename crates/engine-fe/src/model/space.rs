//! Space: six degrees of freedom, the centre-of-mass displacement X and a finite rotation
//! R, inertia tensor J about the centre of mass (body frame); the contact's tangential
//! part the horizontal pair (the circular friction cone).
//!
//! Finite rotations (Simo & Vu-Quoc 1988, material form): a step's unknowns are X and the
//! body-frame incremental rotation vector Θ since the last converged step,
//! R₊ = Rₙ·exp(Θ̂) (`rotation`); the angular velocity Ω and acceleration A are body-frame
//! vectors, Newmark acts on Θ as on a displacement increment, and Euler's equations
//! J·A + Ω × J·Ω = moment give the inertia. Why this and not a quaternion or the total
//! rotation vector: the increment Θ is a vector-space unknown, so the Newmark and HHT
//! algebra, the line search and the convergence tests apply unchanged, and for a motion in
//! one plane Θ = (0, −Δθ, 0) and every formula reduces to the plane's. HHT-α weights the
//! moments of steps n and n+1 each in its own body frame: exact in plane; for a 3D
//! rotation the two frames differ by the step's rotation Θ = O(Δt), a simplification of
//! the Lie-group HHT/generalised-α (Brüls & Cardona 2010) not analysed further here.
//!
//! A support point at body offset d moves by u = X + (R − I)·d; a body-frame virtual
//! rotation W gives δu = δX + G·W with G = −R·d̂, and W = J_r(Θ)·δΘ. The body's internal
//! force is (Σf, Σ d × Rᵀf) — the moment in the body frame — and its tangent with respect
//! to (X, W) [[ΣD, ΣD·G], [ΣGᵀD, Σ GᵀDG + d̂·(Rᵀf)^]] (the last term the geometric
//! stiffness of the finite rotation), its W columns then multiplied by J_r(Θ).

use std::any::Any;

use nalgebra::{Matrix3, Matrix6, Vector2, Vector3, Vector6};

use super::assembly::sum_ground_elements;
use super::dimension::{Body, Dimension, GroundSums, Model, System};
use super::ground_sums::{M3, SpaceForceSums, SpaceSums};
use super::rotation::{exp_and_right_jacobian, log, skew};
use crate::element::{ConeContact, Status};
use crate::lu::Lu6;

/// Space.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Space;

/// Where the body is at the end of a step: its centre of mass, its rotation, and the
/// rotation's vector (a displacement scale for the convergence test only).
#[derive(Debug, Clone, Copy)]
pub struct Placement {
    /// Centre-of-mass displacement from the unloaded position, m.
    pub x: Vector3<f64>,
    /// Rotation of the body.
    pub r: Matrix3<f64>,
    /// Rotation vector of `r`.
    pub psi: Vector3<f64>,
}

/// The body's configuration at a Newton iterate.
#[derive(Debug, Clone, Copy)]
pub struct Pose {
    /// Centre-of-mass displacement, m.
    pub x: Vector3<f64>,
    /// Rotation R = Rₙ·exp(Θ̂).
    pub r: Matrix3<f64>,
    /// Incremental rotation vector Θ.
    pub theta: Vector3<f64>,
    /// J_r(Θ) of a rotating body whose Θ is not zero (`None`: the identity), taken with
    /// exp(Θ̂) from the same coefficients.
    jacobian: Option<Matrix3<f64>>,
}

impl Pose {
    /// J_r(Θ) of a rotating body whose Θ is not zero (`None`: the identity).
    #[inline]
    fn jr(&self, rotates: bool) -> Option<Matrix3<f64>> {
        self.jacobian.filter(|_| rotates)
    }
}

/// A support point at an iterate: its displacement u = X + (c − d), its body offset d and
/// c = R·d, the offset turned into the ground frame.
#[derive(Debug, Clone, Copy, Default)]
pub struct SpacePoint {
    u: Vector3<f64>,
    c: [f64; 3],
    d: [f64; 3],
}

/// R as rows of plain scalars.
#[inline]
fn rows(r: &Matrix3<f64>) -> M3 {
    std::array::from_fn(|i| [r[(i, 0)], r[(i, 1)], r[(i, 2)]])
}

/// The support point at offset `d` of a body at `x` turned by `rm`.
#[inline(always)]
fn point_at(x: &Vector3<f64>, rm: &M3, d: &Vector3<f64>) -> SpacePoint {
    let d = [d.x, d.y, d.z];
    let c: [f64; 3] = std::array::from_fn(|i| rm[i][0] * d[0] + rm[i][1] * d[1] + rm[i][2] * d[2]);
    SpacePoint {
        u: Vector3::from_fn(|i, _| x[i] + (c[i] - d[i])),
        c,
        d,
    }
}

/// G = −R·d̂ of the support point `p` (δu = δX + G·W).
#[inline]
fn g_of(p: &SpacePoint, at: &Pose) -> Matrix3<f64> {
    -(at.r * skew(&Vector3::from(p.d)))
}

/// What a touching support leaves for the tangent: its force f, its offset d and
/// c = R·d, and its tangent's terms, D = diag(a, a, b) sticking, and slipping minus the
/// rank-one v·wᵀ of v = (n, 0), w = (a·n, μ·kz) (`SpaceSums::add_slipping`).
#[derive(Debug, Clone, Copy, Default)]
pub struct SpaceTouch {
    f: [f64; 3],
    d: [f64; 3],
    c: [f64; 3],
    a: f64,
    b: f64,
    /// Slipping: the direction n and μ·kz.
    slip: Option<(Vector2<f64>, f64)>,
}

/// A touching support's D terms: a sticking one's moments of c, a slipping one's with its
/// rank-one correction.
#[inline(always)]
fn add_d_terms(sums: &mut SpaceSums, t: &SpaceTouch) {
    match t.slip {
        None => sums.add_sticking(t.a, t.b, &t.c),
        Some((n, mu_kz)) => sums.add_slipping(t.a, t.b, &n, mu_kz, &t.c),
    }
}

impl GroundSums<Space> for SpaceSums {
    type Force = SpaceForceSums;
    type Touch = SpaceTouch;
    /// A step's last iteration (its residual at round-off) and a backtracked one need
    /// the force only: the tangent waits for the solve.
    const DEFERRED_TANGENT: bool = true;

    #[inline(always)]
    fn add_force(
        force: &mut SpaceForceSums,
        p: &SpacePoint,
        f: &Vector3<f64>,
        e: &ConeContact,
        status: Status,
        (rho, n): (f64, Vector2<f64>),
    ) -> SpaceTouch {
        let f = [f.x, f.y, f.z];
        force.add(&f, &p.c);
        let (a, slip) = if status == Status::Stick {
            // Sticking: D = diag(kt, kt, kz).
            (e.kt, None)
        } else {
            (rho, Some((n, e.mu * e.kz)))
        };
        SpaceTouch {
            f,
            d: p.d,
            c: p.c,
            a,
            b: e.kz,
            slip,
        }
    }

    #[inline(always)]
    fn add_tangent(&mut self, t: &SpaceTouch) {
        self.add_geometric(&t.f, &t.d, &t.c);
        add_d_terms(self, t);
    }

    /// The geometric sums in a pass of their own (ten sums, held in registers), then the
    /// D sums: each sum still takes its terms in the supports' order.
    #[inline]
    fn from_touches(touches: &[SpaceTouch]) -> Self {
        let mut sums = Self::default();
        for t in touches {
            sums.add_geometric(&t.f, &t.d, &t.c);
        }
        for t in touches {
            add_d_terms(&mut sums, t);
        }
        sums
    }

    #[inline]
    fn write_force(force: &SpaceForceSums, at: &Pose, pb: &mut Vector6<f64>) {
        force.write(&rows(&at.r), pb);
    }

    #[inline]
    fn write_tangent(&mut self, at: &Pose, kbb: &mut Matrix6<f64>) {
        self.write_tangent(&rows(&at.r), kbb);
    }
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

impl Dimension for Space {
    type Tangential = Vector2<f64>;
    type Unknowns = Vector6<f64>;
    type Matrix = Matrix6<f64>;
    type Lu = Lu6;
    type Inertia = Matrix3<f64>;
    type Kinematics = ();
    type Pose = Placement;
    type Iterate = Pose;
    type Point = SpacePoint;
    type Horizontal = Vector3<f64>;
    type Ground = [Vector3<f64>; 3];
    type Sums = SpaceSums;
    type Extra = ();
    const ROTATING_MATRIX_REPEATS: bool = false;
    // A correction mixes metres and radians: no unit.
    const CORRECTION_UNIT: &'static str = "";

    #[inline]
    fn zero() -> Vector6<f64> {
        Vector6::zeros()
    }
    #[inline]
    fn zero_matrix() -> Matrix6<f64> {
        Matrix6::zeros()
    }
    #[inline]
    fn lock_rotation(x: &mut Vector6<f64>) {
        x.fixed_rows_mut::<3>(3).fill(0.0);
    }
    fn rest_pose() -> Placement {
        Placement {
            x: Vector3::zeros(),
            r: Matrix3::identity(),
            psi: Vector3::zeros(),
        }
    }
    fn rest_ground() -> [Vector3<f64>; 3] {
        [Vector3::zeros(); 3]
    }
    /// (X, 0): the step's unknowns are X and the rotation Θ since the step's start.
    #[inline]
    fn reference(p: &Placement) -> Vector6<f64> {
        let mut v = Vector6::zeros();
        v.fixed_rows_mut::<3>(0).copy_from(&p.x);
        v
    }
    #[inline]
    fn predict(
        p: &Placement,
        v: &Vector6<f64>,
        a: &Vector6<f64>,
        h: f64,
        rotates: bool,
    ) -> Vector6<f64> {
        let mut q = Vector6::zeros();
        q.fixed_rows_mut::<3>(0)
            .copy_from(&(p.x + v.fixed_rows::<3>(0) * h + a.fixed_rows::<3>(0) * (0.5 * h * h)));
        if rotates {
            q.fixed_rows_mut::<3>(3)
                .copy_from(&(v.fixed_rows::<3>(3) * h + a.fixed_rows::<3>(3) * (0.5 * h * h)));
        }
        q
    }
    /// The pose of unknowns q = (X, Θ) from the rotation of the step's start.
    #[inline]
    fn iterate(_kin: &(), rotates: bool, q: &Vector6<f64>, from: &Placement) -> Pose {
        let theta = q.fixed_rows::<3>(3).into_owned();
        let (r, jr) = if theta == Vector3::zeros() {
            (from.r, None)
        } else {
            let (turn, jr) = exp_and_right_jacobian(&theta, rotates);
            (from.r * turn, jr)
        };
        Pose {
            x: q.fixed_rows::<3>(0).into_owned(),
            r,
            theta,
            jacobian: jr,
        }
    }
    #[inline]
    fn pose(_q: &Vector6<f64>, at: &Pose) -> Placement {
        Placement {
            x: at.x,
            r: at.r,
            psi: log(&at.r),
        }
    }
    #[inline]
    fn displacement_squared(_q: &Vector6<f64>, at: &Pose, from: &Placement) -> f64 {
        at.x.norm_squared() + (from.psi + at.theta).norm_squared()
    }

    #[inline]
    fn point(_kin: &(), _q: &Vector6<f64>, at: &Pose, d: &Vector3<f64>) -> SpacePoint {
        point_at(&at.x, &rows(&at.r), d)
    }
    #[inline(always)]
    fn displacement(p: &SpacePoint) -> Vector3<f64> {
        p.u
    }
    /// Summed in the ground frame with R·d̂ = ĉ·R (c = R·d) and turned into the body
    /// frame once (`SpaceSums`).
    #[inline(always)]
    fn sum_ground_elements<'e>(
        _kin: &(),
        _q: &Vector6<f64>,
        at: &Pose,
        elements: impl Iterator<Item = (&'e Vector3<f64>, &'e mut ConeContact)>,
        ground: &Vector3<f64>,
        sums: &mut SpaceSums,
        touches: &mut [SpaceTouch],
    ) -> (SpaceForceSums, usize) {
        let rm = rows(&at.r);
        sum_ground_elements::<Space>(elements, ground, |d| point_at(&at.x, &rm, d), sums, touches)
    }
    fn add_support(
        p: &SpacePoint,
        at: &Pose,
        f: &Vector3<f64>,
        dm: &Matrix3<f64>,
        pb: &mut Vector6<f64>,
        kbb: &mut Matrix6<f64>,
    ) {
        let d = Vector3::from(p.d);
        let g = g_of(p, at);
        let rtf = at.r.transpose() * f;
        let (dg, gtd) = tangent_times_g(dm, &g);
        let mut pf = pb.fixed_rows_mut::<3>(0);
        pf += f;
        let mut pr = pb.fixed_rows_mut::<3>(3);
        pr += d.cross(&rtf);
        let mut k00 = kbb.fixed_view_mut::<3, 3>(0, 0);
        k00 += dm;
        let mut k01 = kbb.fixed_view_mut::<3, 3>(0, 3);
        k01 += dg;
        let mut k10 = kbb.fixed_view_mut::<3, 3>(3, 0);
        k10 += gtd;
        let mut k11 = kbb.fixed_view_mut::<3, 3>(3, 3);
        // d̂·(Rᵀf)^ = (Rᵀf)·dᵀ − (d·Rᵀf)·I
        k11 += gtd * g + rtf * d.transpose() - Matrix3::identity() * d.dot(&rtf);
    }
    /// From the body-frame virtual rotation W to the unknown Θ: W = J_r(Θ)·δΘ.
    #[inline]
    fn to_unknowns(at: &Pose, rotates: bool, kbb: &mut Matrix6<f64>) {
        if let Some(jr) = at.jr(rotates) {
            let cols = kbb.fixed_columns::<3>(3) * jr;
            kbb.fixed_columns_mut::<3>(3).copy_from(&cols);
        }
    }
    #[inline]
    fn generalized_force(p: &SpacePoint, at: &Pose, v: &Vector3<f64>) -> Vector6<f64> {
        let gv = g_of(p, at).tr_mul(v);
        Vector6::new(v.x, v.y, v.z, gv.x, gv.y, gv.z)
    }
    #[inline]
    fn point_motion(p: &SpacePoint, at: &Pose, rotates: bool, dq: &Vector6<f64>) -> Vector3<f64> {
        let dx = dq.fixed_rows::<3>(0).into_owned();
        let dtheta = dq.fixed_rows::<3>(3).into_owned();
        let dw = at.jr(rotates).map_or(dtheta, |jr| jr * dtheta);
        dx + g_of(p, at) * dw
    }

    /// S = blockdiag(M·c0·I, inertial tangent) + s·K (+ damping on x and y), the inertial
    /// tangent ∂(J·A + Ω × J·Ω)/∂Θ = c0·J + c1·(Ω̂·J − (J·Ω)^).
    #[inline]
    fn newton_matrix(
        body: &Body<Space>,
        sys: &System<Vector6<f64>>,
        kbb: &Matrix6<f64>,
    ) -> Matrix6<f64> {
        let mut s_mat = kbb * sys.s;
        let m = body.mass * sys.c0;
        let (damp, inertial) = match (&sys.v, body.rotation) {
            (Some(v), true) => {
                let j = body.inertia;
                let om = v.fixed_rows::<3>(3).into_owned();
                (
                    sys.s * body.damping * sys.c1,
                    j * sys.c0 + (skew(&om) * j - skew(&(j * om))) * sys.c1,
                )
            }
            (Some(_), false) => (sys.s * body.damping * sys.c1, Matrix3::zeros()),
            (None, _) => (0.0, Matrix3::zeros()),
        };
        s_mat[(0, 0)] += m + damp;
        s_mat[(1, 1)] += m + damp;
        s_mat[(2, 2)] += m;
        let mut rot = s_mat.fixed_view_mut::<3, 3>(3, 3);
        rot += inertial;
        s_mat
    }
    #[inline]
    fn lock_rotation_rows(s: &mut Matrix6<f64>, rhs: &mut Vector6<f64>) {
        for i in 3..6 {
            for j in 0..6 {
                s[(i, j)] = 0.0;
                s[(j, i)] = 0.0;
            }
            s[(i, i)] = 1.0;
            rhs[i] = 0.0;
        }
    }
    #[inline]
    fn same_bits(a: &Matrix6<f64>, b: &Matrix6<f64>) -> bool {
        a.iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    }
    /// LU with partial pivoting (`Lu6`, nalgebra's algorithm written out), in place.
    #[inline]
    fn factor(m: &Matrix6<f64>, lu: &mut Lu6) {
        lu.refactor(m);
    }
    #[inline]
    fn solve(lu: &Lu6, b: &Vector6<f64>) -> Option<Vector6<f64>> {
        lu.solve(b)
    }

    /// Inertial force (M·a, J·A + Ω × J·Ω).
    #[inline]
    fn inertia_force(body: &Body<Space>, a: &Vector6<f64>, v: &Vector6<f64>) -> Vector6<f64> {
        let m = body.mass;
        let mut out = Vector6::new(m * a[0], m * a[1], m * a[2], 0.0, 0.0, 0.0);
        if body.rotation {
            let j = &body.inertia;
            let om = v.fixed_rows::<3>(3).into_owned();
            let rot = j * a.fixed_rows::<3>(3) + om.cross(&(j * om));
            out.fixed_rows_mut::<3>(3).copy_from(&rot);
        }
        out
    }
    fn initial_acceleration(body: &Body<Space>, out: &Vector6<f64>) -> Vector6<f64> {
        let m = body.mass;
        let mut a = Vector6::new(out[0] / m, out[1] / m, out[2] / m, 0.0, 0.0, 0.0);
        if body.rotation
            && let Some(a_rot) = body.inertia.lu().solve(&out.fixed_rows::<3>(3))
        {
            a.fixed_rows_mut::<3>(3).copy_from(&a_rot);
        }
        a
    }
    /// Horizontal viscous damping force C·(v − v_ground) on x and y.
    #[inline]
    fn damping(c: f64, v: &Vector6<f64>, g: &[Vector3<f64>; 3]) -> Vector6<f64> {
        let vg = &g[1];
        Vector6::new(c * (v[0] - vg.x), c * (v[1] - vg.y), 0.0, 0.0, 0.0, 0.0)
    }
    #[inline]
    fn load(h: Vector3<f64>, z: f64) -> Vector6<f64> {
        Vector6::new(h.x, h.y, z, 0.0, 0.0, 0.0)
    }
    #[inline]
    fn horizontal_of(f: &Vector6<f64>) -> Vector3<f64> {
        Vector3::new(f[0], f[1], 0.0)
    }

    #[inline]
    fn horizontal(first: f64, second: Option<f64>, directions: &[Vector3<f64>; 2]) -> Vector3<f64> {
        let v = directions[0] * first;
        match second {
            Some(s) => v + directions[1] * s,
            None => v,
        }
    }
    #[inline]
    fn no_horizontal() -> Vector3<f64> {
        Vector3::zeros()
    }
    #[inline]
    fn ground(d: Vector3<f64>, v: Vector3<f64>, a: Vector3<f64>) -> [Vector3<f64>; 3] {
        [d, v, a]
    }
    #[inline]
    fn ground_point(g: &[Vector3<f64>; 3]) -> Vector3<f64> {
        g[0]
    }

    fn own_step(_model: &Model<Space>) -> Option<&'static (dyn Any + Send + Sync)> {
        None
    }
}

impl Model<Space> {
    /// Displacement of the body-frame point `d` at centre of mass `x`, rotation `r`:
    /// X + (R − I)·d.
    #[inline]
    pub fn displacement_of(x: &Vector3<f64>, r: &Matrix3<f64>, d: &Vector3<f64>) -> Vector3<f64> {
        x + (r * d - d)
    }
}

#[cfg(test)]
mod tests {
    use super::super::rotation::exp;
    use super::*;
    use crate::model::Assembly;
    use crate::space::{BlockGrid, SpaceBody};
    use rockslide_core::case::{Contact, DoubleContact};

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
        let from = Placement {
            x: Vector3::zeros(),
            r: exp(&Vector3::new(4e-6, -6e-6, 4e-6)),
            psi: Vector3::new(4e-6, -6e-6, 4e-6),
        };
        let q = Vector6::new(1.0e-6, -0.5e-6, -2.0e-6, 1e-6, -2e-6, 5e-7);
        let ground = [
            Vector3::new(1e-6, 0.0, 0.0),
            Vector3::zeros(),
            Vector3::zeros(),
        ];
        let body = block();
        let mut condensed = Model::space(&body);
        assert!(condensed.condensed && condensed.loop_nodes() == 0);
        let mut nodes = condensed.clone();
        nodes.condensed = false;
        let (mut a1, mut a2) = (Assembly::new(&condensed), Assembly::new(&nodes));
        let mut un = vec![Vector3::zeros(); nodes.nodes];
        condensed.assemble(&q, &from, &mut un, &ground, &mut a1);
        nodes.assemble(&q, &from, &mut un, &ground, &mut a2);
        let mut states = [0; 3];
        for s in &condensed.equivalents {
            states[s.trial_state().status as usize] += 1;
        }
        let [open, stick, slip] = states;
        assert!(stick > 0 && slip > 0 && open > 0, "{stick} {slip} {open}");
        let df = (a1.pb - a2.pb).norm() / a2.pb.norm();
        let dk = (a1.kbb - a2.kbb).norm() / a2.kbb.norm();
        eprintln!("{stick} stick, {slip} slip, {open} open: force {df:e}, tangent {dk:e}");
        // Measured 2 sticking, 6 slipping, 4 open; force 1.1e-16 and tangent 1.6e-16 of
        // their norms: the same to round-off.
        assert!(df < 5e-16 && dk < 5e-16, "{df:e} {dk:e}");
    }
}

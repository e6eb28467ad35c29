//! The plane: the body's unknowns q = (X, Z, θ) of the centre of mass (θ locked for a
//! sliding oscillator), mass matrix diag(M, M, I), the ground along x, the contact's
//! tangential part along x. A support point at body offset d moves by u with Jacobian
//! G = ∂u/∂q = [I₂ | g] and h = ∂²u/∂θ² — exact rotations u = (R(θ) − I)·d (P-Delta
//! included), small rotations u = (−θ·dz, θ·dx), or small rotations with the second-order
//! (P-Delta) terms. The internal force is Gᵀf and its tangent GᵀDG + f·h on θθ.
//!
//! - `slider`: the sliding oscillator (the PEPO) stepped in scalars.

mod slider;

use std::any::Any;

use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

use super::assembly::sum_ground_elements;
use super::dimension::{Body, Dimension, GroundSums, Model, System};
use crate::element::{Contact178, Status};
use crate::lu::{Lu2, Lu3};
use crate::options::Kinematics;

/// The plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Plane;

/// How the plane body's support points follow its rotation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlaneKinematics {
    /// Exact or small rotations.
    pub kind: Kinematics,
    /// Second-order rotation terms with small rotations (exact ones always have them).
    pub p_delta: bool,
}

impl PlaneKinematics {
    /// Small rotations without P-Delta (the paper's programs; a sliding oscillator,
    /// whose rotation is locked).
    pub const SMALL_ROTATION: Self = Self {
        kind: Kinematics::SmallRotation,
        p_delta: false,
    };
}

/// Displacement of a body point, the θ column g of its Jacobian G = ∂u/∂q = [I₂ | g],
/// and h = ∂²u/∂θ².
#[derive(Debug, Clone, Copy, Default)]
pub struct PointKin {
    pub(crate) u: Vector2<f64>,
    pub(crate) g: Vector2<f64>,
    pub(crate) h: Vector2<f64>,
}

/// Kinematics of a body point at body-frame offset `d` from the centre of mass, (cos θ,
/// sin θ) = `cs` (exact rotations only).
#[inline(always)]
pub(crate) fn point_kin(
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

/// The plane assembly's tangent sums: GᵀDG + f·h in plain scalars, each element's terms
/// in the same order (`k[1][0]` stays +0: ∂N/∂δx is +0 in every state of the element);
/// its force sums Gᵀf, `[f64; 3]`.
#[derive(Debug, Default, Clone)]
pub struct PlaneSums {
    k: [[f64; 3]; 3],
}

/// What a touching element leaves for the plane's tangent: G's (x, z), the element's
/// tangent [[d00, d01], [+0, d11]] and f·h.
#[derive(Debug, Clone, Copy, Default)]
pub struct PlaneTouch {
    g: (f64, f64),
    d: (f64, f64, f64),
    fh: f64,
}

impl GroundSums<Plane> for PlaneSums {
    type Force = [f64; 3];
    type Touch = PlaneTouch;
    /// Summed with the force: the plane's tangent is a few sums.
    const DEFERRED_TANGENT: bool = false;

    #[inline(always)]
    fn add_force(
        p: &mut [f64; 3],
        pk: &PointKin,
        f: &Vector2<f64>,
        e: &Contact178,
        status: Status,
        (_, n): (f64, f64),
    ) -> PlaneTouch {
        // The element's tangent [[d00, d01], [+0, d11]] (`Tangential::stick_tangent`,
        // `slip_tangent`): d10 is +0, its products ±0, and every sum they entered starts
        // from +0, where a ±0 term changes no bit.
        let d = if status == Status::Stick {
            (e.kt, 0.0, e.kz)
        } else {
            (0.0, -n * e.mu * e.kz, e.kz)
        };
        let (gx, gz) = (pk.g.x, pk.g.y);
        p[0] += f.x;
        p[1] += f.y;
        p[2] += gx * f.x + gz * f.y;
        PlaneTouch {
            g: (gx, gz),
            d,
            fh: f.x * pk.h.x + f.y * pk.h.y,
        }
    }

    #[inline(always)]
    fn add_tangent(&mut self, t: &PlaneTouch) {
        let ((gx, gz), (d00, d01, d11)) = (t.g, t.d);
        let (dgx, dgy) = (d00 * gx + d01 * gz, d11 * gz);
        let (gtdx, gtdy) = (d00 * gx, d01 * gx + d11 * gz);
        let k = &mut self.k;
        k[0][0] += d00;
        k[0][1] += d01;
        k[1][1] += d11;
        k[0][2] += dgx;
        k[1][2] += dgy;
        k[2][0] += gtdx;
        k[2][1] += gtdy;
        k[2][2] += (gx * dgx + gz * dgy) + t.fh;
    }

    #[inline(always)]
    fn write_force(p: &[f64; 3], _at: &(f64, f64), pb: &mut Vector3<f64>) {
        *pb = Vector3::new(p[0], p[1], p[2]);
    }

    #[inline(always)]
    fn write_tangent(&mut self, _at: &(f64, f64), kbb: &mut Matrix3<f64>) {
        let k = self.k;
        *kbb = Matrix3::new(
            k[0][0], k[0][1], k[0][2], k[1][0], k[1][1], k[1][2], k[2][0], k[2][1], k[2][2],
        );
    }
}

/// The sliding oscillator's step in scalars (`slider`), as the time loop takes it.
static SLIDER: crate::stepper::StepFn<3, 2, Model<Plane>> = slider::step;

impl Dimension for Plane {
    type Tangential = f64;
    type Unknowns = Vector3<f64>;
    type Matrix = Matrix3<f64>;
    type Lu = Lu3;
    type Inertia = f64;
    type Kinematics = PlaneKinematics;
    type Pose = Vector3<f64>;
    /// (cos θ, sin θ) as the kinematics use them ((1, 0) with small rotations, which do
    /// not use them).
    type Iterate = (f64, f64);
    type Point = PointKin;
    type Horizontal = f64;
    type Ground = (f64, f64, f64);
    type Sums = PlaneSums;
    type Extra = Option<Lu2>;
    const ROTATING_MATRIX_REPEATS: bool = true;
    const CORRECTION_UNIT: &'static str = " m";

    #[inline]
    fn zero() -> Vector3<f64> {
        Vector3::zeros()
    }
    #[inline]
    fn zero_matrix() -> Matrix3<f64> {
        Matrix3::zeros()
    }
    #[inline]
    fn lock_rotation(x: &mut Vector3<f64>) {
        x.z = 0.0;
    }
    fn rest_pose() -> Vector3<f64> {
        Vector3::zeros()
    }
    fn rest_ground() -> (f64, f64, f64) {
        (0.0, 0.0, 0.0)
    }
    #[inline]
    fn reference(p: &Vector3<f64>) -> Vector3<f64> {
        *p
    }
    #[inline]
    fn predict(
        p: &Vector3<f64>,
        v: &Vector3<f64>,
        a: &Vector3<f64>,
        h: f64,
        _rotates: bool,
    ) -> Vector3<f64> {
        p + v * h + a * (0.5 * h * h)
    }
    #[inline]
    fn iterate(
        kin: &PlaneKinematics,
        _rotates: bool,
        q: &Vector3<f64>,
        _from: &Vector3<f64>,
    ) -> (f64, f64) {
        if kin.kind == Kinematics::Exact {
            (q.z.cos(), q.z.sin())
        } else {
            (1.0, 0.0)
        }
    }
    #[inline]
    fn pose(q: &Vector3<f64>, _at: &(f64, f64)) -> Vector3<f64> {
        *q
    }
    #[inline]
    fn displacement_squared(q: &Vector3<f64>, _at: &(f64, f64), _from: &Vector3<f64>) -> f64 {
        q.norm_squared()
    }

    #[inline]
    fn point(
        kin: &PlaneKinematics,
        q: &Vector3<f64>,
        at: &(f64, f64),
        d: &Vector2<f64>,
    ) -> PointKin {
        point_kin(kin.kind, kin.p_delta, q, *at, d)
    }
    #[inline(always)]
    fn displacement(p: &PointKin) -> Vector2<f64> {
        p.u
    }
    /// The loop compiled once per kinematics (no dispatch per element).
    #[inline(always)]
    fn sum_ground_elements<'e>(
        kin: &PlaneKinematics,
        q: &Vector3<f64>,
        at: &(f64, f64),
        elements: impl Iterator<Item = (&'e Vector2<f64>, &'e mut Contact178)>,
        ground: &Vector2<f64>,
        sums: &mut PlaneSums,
        touches: &mut [PlaneTouch],
    ) -> ([f64; 3], usize) {
        let cs = *at;
        macro_rules! with_kinematics {
            ($kin:expr, $pd:expr) => {
                sum_ground_elements::<Plane>(
                    elements,
                    ground,
                    |d| point_kin($kin, $pd, q, cs, d),
                    sums,
                    touches,
                )
            };
        }
        match (kin.kind, kin.p_delta) {
            (Kinematics::Exact, _) => with_kinematics!(Kinematics::Exact, false),
            (Kinematics::SmallRotation, false) => {
                with_kinematics!(Kinematics::SmallRotation, false)
            }
            (Kinematics::SmallRotation, true) => with_kinematics!(Kinematics::SmallRotation, true),
        }
    }
    fn add_support(
        pk: &PointKin,
        _at: &(f64, f64),
        f: &Vector2<f64>,
        d: &Matrix2<f64>,
        pb: &mut Vector3<f64>,
        k: &mut Matrix3<f64>,
    ) {
        // With G = [I₂ | g]: Gᵀf = (f, g·f), GᵀDG = [[D, Dg], [gᵀD, gᵀDg]].
        let dg = d * pk.g;
        let gtd = d.tr_mul(&pk.g); // (gᵀD)ᵀ
        *pb += Vector3::new(f.x, f.y, pk.g.dot(f));
        k[(0, 0)] += d[(0, 0)];
        k[(0, 1)] += d[(0, 1)];
        k[(1, 0)] += d[(1, 0)];
        k[(1, 1)] += d[(1, 1)];
        k[(0, 2)] += dg.x;
        k[(1, 2)] += dg.y;
        k[(2, 0)] += gtd.x;
        k[(2, 1)] += gtd.y;
        // geometric stiffness f·∂²u/∂θ²
        k[(2, 2)] += pk.g.dot(&dg) + f.dot(&pk.h);
    }
    #[inline(always)]
    fn to_unknowns(_at: &(f64, f64), _rotates: bool, _kbb: &mut Matrix3<f64>) {}
    #[inline]
    fn generalized_force(pk: &PointKin, _at: &(f64, f64), v: &Vector2<f64>) -> Vector3<f64> {
        Vector3::new(v.x, v.y, pk.g.dot(v))
    }
    #[inline]
    fn point_motion(
        pk: &PointKin,
        _at: &(f64, f64),
        _rotates: bool,
        dq: &Vector3<f64>,
    ) -> Vector2<f64> {
        dq.xy() + pk.g * dq.z
    }

    #[inline]
    fn newton_matrix(
        body: &Body<Plane>,
        sys: &System<Vector3<f64>>,
        kbb: &Matrix3<f64>,
    ) -> Matrix3<f64> {
        let m = Vector3::new(body.mass, body.mass, body.inertia);
        let mut s_mat = Matrix3::from_diagonal(&(m * sys.c0)) + kbb * sys.s;
        s_mat[(0, 0)] += if sys.v.is_some() {
            sys.s * body.damping * sys.c1
        } else {
            0.0
        };
        s_mat
    }
    #[inline]
    fn lock_rotation_rows(s: &mut Matrix3<f64>, rhs: &mut Vector3<f64>) {
        for j in 0..3 {
            s[(2, j)] = 0.0;
            s[(j, 2)] = 0.0;
        }
        s[(2, 2)] = 1.0;
        rhs.z = 0.0;
    }
    #[inline]
    fn same_bits(a: &Matrix3<f64>, b: &Matrix3<f64>) -> bool {
        a.iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    }
    /// LU with partial pivoting (`Lu3`): the closed-form 3×3 inverse is a little cheaper
    /// but loses digits, and the tight preset then needs more iterations.
    #[inline]
    fn factor(m: &Matrix3<f64>, lu: &mut Lu3) {
        *lu = Lu3::new(m);
    }
    #[inline]
    fn solve(lu: &Lu3, b: &Vector3<f64>) -> Option<Vector3<f64>> {
        lu.solve(b)
    }

    #[inline]
    fn inertia_force(body: &Body<Plane>, a: &Vector3<f64>, _v: &Vector3<f64>) -> Vector3<f64> {
        Vector3::new(body.mass, body.mass, body.inertia).component_mul(a)
    }
    fn initial_acceleration(body: &Body<Plane>, out: &Vector3<f64>) -> Vector3<f64> {
        let m = Vector3::new(body.mass, body.mass, body.inertia);
        let mut a = out.component_div(&m.map(|x| if x > 0.0 { x } else { f64::INFINITY }));
        if !body.rotation {
            a.z = 0.0;
        }
        a
    }
    #[inline]
    fn damping(c: f64, v: &Vector3<f64>, g: &(f64, f64, f64)) -> Vector3<f64> {
        Vector3::new(c * (v.x - g.1), 0.0, 0.0)
    }
    #[inline]
    fn load(h: f64, z: f64) -> Vector3<f64> {
        Vector3::new(h, z, 0.0)
    }
    #[inline]
    fn horizontal_of(f: &Vector3<f64>) -> f64 {
        f.x
    }

    #[inline]
    fn horizontal(first: f64, _second: Option<f64>, _directions: &[Vector3<f64>; 2]) -> f64 {
        first
    }
    #[inline]
    fn no_horizontal() -> f64 {
        0.0
    }
    #[inline]
    fn ground(d: f64, v: f64, a: f64) -> (f64, f64, f64) {
        (d, v, a)
    }
    #[inline]
    fn ground_point(g: &(f64, f64, f64)) -> Vector2<f64> {
        Vector2::new(g.0, 0.0)
    }

    fn own_step(model: &Model<Plane>) -> Option<&'static (dyn Any + Send + Sync)> {
        // A sliding oscillator steps in scalars (`slider`): the same operations, fewer.
        model
            .is_slider()
            .then_some(&SLIDER as &(dyn Any + Send + Sync))
    }
}

impl Model<Plane> {
    /// Displacement of the body-frame point `d` (e.g. the base centre O) at `q`.
    pub fn displacement_of(&self, q: &Vector3<f64>, d: &Vector2<f64>) -> Vector2<f64> {
        let cs = Plane::iterate(&self.kinematics, true, q, q);
        self.displacement_at(q, cs, d)
    }

    /// `displacement_of` with (cos θ, sin θ) of `q` given (`Assembly::iterate`): the same
    /// bits without a second sine and cosine.
    pub fn displacement_at(
        &self,
        q: &Vector3<f64>,
        cs: (f64, f64),
        d: &Vector2<f64>,
    ) -> Vector2<f64> {
        point_kin(self.kinematics.kind, self.kinematics.p_delta, q, cs, d).u
    }

    /// Whether the model is a sliding oscillator whose step can run in scalars (the
    /// body's X and Z, θ locked, one support at the centre of mass, condensed), on
    /// `slider_element` (`slider`).
    pub(crate) fn is_slider(&self) -> bool {
        self.condensed
            && !self.body.rotation
            && self.kinematics == PlaneKinematics::SMALL_ROTATION
            && self.body.inertia.is_finite()
            && self.body.offsets == [Vector2::zeros()]
            && self.supports.len() == 1
            && self.equivalents.len() == self.nodes
    }

    /// The one element a slider's step iterates on (`is_slider`): the single
    /// arrangement's element or the double one's series equivalent.
    #[inline]
    pub(crate) fn slider_element(&mut self) -> &mut Contact178 {
        if self.nodes == 0 {
            &mut self.supports[0].lower
        } else {
            &mut self.equivalents[0]
        }
    }
}

//! The element interface the time loop drives, in either dimension, and the contact
//! element of both: CONTA178-like with a fixed normal (the ground's vertical), a
//! compression-only normal penalty and a tangential penalty capped at μ·N, written once
//! over its tangential part ([`Tangential`]): one direction in the plane (`f64`,
//! [`Contact178`]), the horizontal pair in space (`Vector2`, [`ConeContact`]: the circular
//! friction cone |T| ≤ μ·N).
//!
//! An element computes its force and tangent for a *trial* relative displacement,
//! always starting from its *committed* state (so Newton iterations inside a step never
//! accumulate history); the time loop commits the trial once the step has converged, or
//! restores the committed state when it abandons a step. Pattern after cpmech/pmsim's
//! element trait and the return-mapping algorithms of Simo & Hughes, *Computational
//! Inelasticity* (1998), §1.2 (1-D elastoplastic return mapping; here the yield limit is
//! μ times the element's own normal force) and §2.3 applied to the friction cone
//! (radial return; Wriggers, *Computational Contact Mechanics* (2006), §5.2):
//!
//!   N = kz·max(−δz, 0);  trial T* = kt·(δt − p)  (p: accumulated slip, the spring origin)
//!   stick (|T*| ≤ μN): T = T*, tangent diag(kt, kz);
//!   slip: n = T*/|T*|, T = μN·n, p ← δt − T/kt, consistent tangent
//!     ∂T/∂δt = μN/|T*|·kt·(I − n⊗n),  ∂T/∂δz = −μ·kz·n  (unsymmetric).
//!
//! Open (δz > 0): no force, the origin follows the point (CONTA178 re-establishes
//! sticking on contact). In the plane n = sign(T*) and I − n⊗n = 0: each operation is the
//! 1-D return mapping's, and an in-plane motion in space (δy = 0, no y slip) takes the
//! same values bit for bit (|T*| = √(T*x²) = |T*x| exactly and 1 − n_x² = 0 exactly).
//!
//! Sign conventions: the relative displacement is δ = u_upper − u_lower (x, y horizontal,
//! z vertical up; in the plane (x, z)); the element's force is the internal (resisting)
//! force on the upper point, −force on the lower point: (T, −N). A gap δz > 0 is open.

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, Mul, Sub};

use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

/// What the time loop asks of an element, in the dimension of its relative displacement
/// (`Vector2` in the plane, `Vector3` in space).
pub trait Element {
    /// The relative displacement δ and the force on the upper point.
    type Vector;
    /// The tangent ∂force/∂δ.
    type Tangent;
    /// Force on the upper point and tangent ∂force/∂δ at the trial relative displacement
    /// `delta`, computed from the committed state (the trial state is kept).
    fn trial(&mut self, delta: Self::Vector) -> (Self::Vector, Self::Tangent);
    /// Accept the last trial state.
    fn commit(&mut self);
    /// Forget the trial state (back to the committed one).
    fn restore(&mut self);
}

/// The tangential part of a contact's relative displacement and force: `f64` in the plane
/// (along x), `Vector2` in space (x, y). Each operation is the one its dimension's
/// element always did, so the plane's values are those of the 1-D return mapping.
pub trait Tangential:
    Copy + Debug + PartialEq + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self>
{
    /// The relative displacement or force: the tangential part and the vertical.
    type Vector: Copy
        + Debug
        + PartialEq
        + Add<Output = Self::Vector>
        + Sub<Output = Self::Vector>
        + AddAssign
        + Mul<f64, Output = Self::Vector>
        + Div<f64, Output = Self::Vector>;
    /// The tangent ∂force/∂δ.
    type Tangent: Copy
        + Debug
        + PartialEq
        + Add<Output = Self::Tangent>
        + Sub<Output = Self::Tangent>
        + Mul<Output = Self::Tangent>
        + Mul<Self::Vector, Output = Self::Vector>;
    /// Whether the slipping tangent has a tangential term (its ratio μN/|T*|·kt is
    /// computed by the return mapping only then): not in the plane.
    const SLIP_RATIO: bool;
    /// No displacement.
    fn zero() -> Self;
    /// The tangential part and the vertical of `v`.
    fn split(v: &Self::Vector) -> (Self, f64);
    /// The vector of tangential part `self` and vertical `z`.
    fn join(self, z: f64) -> Self::Vector;
    /// |self|.
    fn size(self) -> f64;
    /// The direction of `self`, whose size is `size` > 0: its sign in the plane.
    fn direction(self, size: f64) -> Self;
    /// `self` divided by `k`.
    fn over(self, k: f64) -> Self;
    /// The sticking tangent diag(kt, kz).
    fn stick_tangent(kt: f64, kz: f64) -> Self::Tangent;
    /// The slipping tangent: ∂T/∂δt = ratio·(I − n⊗n) (zero in the plane),
    /// ∂T/∂δz = −μ·kz·n, ∂N-row (0, kz).
    fn slip_tangent(ratio: f64, n: Self, mu: f64, kz: f64) -> Self::Tangent;
    /// No stiffness (an open contact).
    fn no_tangent() -> Self::Tangent;
    /// The inverse of a massless node's block D1 + D2, `None` if singular.
    fn inverse(k: &Self::Tangent) -> Option<Self::Tangent>;
}

impl Tangential for f64 {
    type Vector = Vector2<f64>;
    type Tangent = Matrix2<f64>;
    const SLIP_RATIO: bool = false;

    #[inline(always)]
    fn zero() -> Self {
        0.0
    }
    #[inline(always)]
    fn split(v: &Vector2<f64>) -> (f64, f64) {
        (v.x, v.y)
    }
    #[inline(always)]
    fn join(self, z: f64) -> Vector2<f64> {
        Vector2::new(self, z)
    }
    #[inline(always)]
    fn size(self) -> f64 {
        self.abs()
    }
    #[inline(always)]
    fn direction(self, _size: f64) -> f64 {
        self.signum()
    }
    #[inline(always)]
    fn over(self, k: f64) -> f64 {
        self / k
    }
    #[inline(always)]
    fn stick_tangent(kt: f64, kz: f64) -> Matrix2<f64> {
        Matrix2::new(kt, 0.0, 0.0, kz)
    }
    #[inline(always)]
    fn slip_tangent(_ratio: f64, n: f64, mu: f64, kz: f64) -> Matrix2<f64> {
        // ∂T/∂δx = 0, ∂T/∂δz = −sign·μ·kz.
        Matrix2::new(0.0, -n * mu * kz, 0.0, kz)
    }
    #[inline(always)]
    fn no_tangent() -> Matrix2<f64> {
        Matrix2::zeros()
    }
    #[inline]
    fn inverse(k: &Matrix2<f64>) -> Option<Matrix2<f64>> {
        k.try_inverse()
    }
}

impl Tangential for Vector2<f64> {
    type Vector = Vector3<f64>;
    type Tangent = Matrix3<f64>;
    const SLIP_RATIO: bool = true;

    #[inline(always)]
    fn zero() -> Self {
        Vector2::zeros()
    }
    #[inline(always)]
    fn split(v: &Vector3<f64>) -> (Vector2<f64>, f64) {
        (v.xy(), v.z)
    }
    #[inline(always)]
    fn join(self, z: f64) -> Vector3<f64> {
        Vector3::new(self.x, self.y, z)
    }
    #[inline(always)]
    fn size(self) -> f64 {
        self.norm()
    }
    #[inline(always)]
    fn direction(self, size: f64) -> Vector2<f64> {
        self / size
    }
    #[inline(always)]
    fn over(self, k: f64) -> Vector2<f64> {
        self / k
    }
    #[inline(always)]
    fn stick_tangent(kt: f64, kz: f64) -> Matrix3<f64> {
        Matrix3::new(kt, 0.0, 0.0, 0.0, kt, 0.0, 0.0, 0.0, kz)
    }
    #[inline(always)]
    fn slip_tangent(ratio: f64, n: Vector2<f64>, mu: f64, kz: f64) -> Matrix3<f64> {
        let (nx, ny) = (n.x, n.y);
        let (zx, zy) = (-mu * kz * nx, -mu * kz * ny);
        Matrix3::new(
            ratio * (1.0 - nx * nx),
            -ratio * nx * ny,
            zx,
            -ratio * ny * nx,
            ratio * (1.0 - ny * ny),
            zy,
            0.0,
            0.0,
            kz,
        )
    }
    #[inline(always)]
    fn no_tangent() -> Matrix3<f64> {
        Matrix3::zeros()
    }
    /// Reciprocals when the block is diagonal (both elements sticking or open), else the
    /// general inverse.
    #[inline]
    fn inverse(k: &Matrix3<f64>) -> Option<Matrix3<f64>> {
        let diagonal = k[(0, 1)] == 0.0
            && k[(0, 2)] == 0.0
            && k[(1, 0)] == 0.0
            && k[(1, 2)] == 0.0
            && k[(2, 0)] == 0.0
            && k[(2, 1)] == 0.0;
        if !diagonal {
            return k.try_inverse();
        }
        let d = k.diagonal();
        d.iter()
            .all(|x| *x != 0.0)
            .then(|| Matrix3::from_diagonal(&d.map(|x| 1.0 / x)))
    }
}

/// Contact status of an element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// Gap open: no force.
    Open,
    /// Closed, tangential force elastic.
    Stick,
    /// Closed, tangential force at μ·N, slipping.
    Slip,
}

/// The state that history depends on, plus what the last evaluation found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState<T: Tangential = f64> {
    /// Accumulated slip (the shift of the tangential spring's origin), m.
    pub slip: T,
    /// Relative displacement δ of the evaluation, m.
    pub delta: T::Vector,
    /// Force on the upper point, N: (T, −N).
    pub force: T::Vector,
    /// Status.
    pub status: Status,
}

/// The 3D contact's state.
pub type ConeState = ContactState<Vector2<f64>>;

/// CONTA178-like contact (see the module docs): compression-only normal penalty `kz`
/// (unless `bonded`), elastic tangential penalty `kt` capped at μ·N by return mapping, no
/// force when open; `T` its tangential part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact<T: Tangential> {
    /// Tangential (sticking) stiffness, in each horizontal direction, N/m.
    pub kt: f64,
    /// Normal stiffness, N/m.
    pub kz: f64,
    /// Friction coefficient (`f64::INFINITY`: never slips).
    pub mu: f64,
    /// Carries tension too and sticks when not compressed (element 2 of the double
    /// arrangement, see `series`), so a massless node never floats free.
    pub bonded: bool,
    committed: ContactState<T>,
    trial: ContactState<T>,
}

/// The plane contact element.
pub type Contact178 = Contact<f64>;

/// The 3D contact element: the circular friction cone.
pub type ConeContact = Contact<Vector2<f64>>;

impl<T: Tangential> ContactState<T> {
    /// A closed, unstressed element's state: no slip, no displacement, no force.
    pub fn at_rest() -> Self {
        ContactState {
            slip: T::zero(),
            delta: T::zero().join(0.0),
            force: T::zero().join(0.0),
            status: Status::Stick,
        }
    }
}

impl<T: Tangential> Contact<T> {
    /// A closed, unstressed element.
    pub fn new(kt: f64, kz: f64, mu: f64, bonded: bool) -> Self {
        let s = ContactState::at_rest();
        Self {
            kt,
            kz,
            mu,
            bonded,
            committed: s,
            trial: s,
        }
    }

    /// The committed state.
    pub fn state(&self) -> &ContactState<T> {
        &self.committed
    }

    /// The state of the last trial (what `commit` would accept).
    pub fn trial_state(&self) -> &ContactState<T> {
        &self.trial
    }

    /// Start from `state` (committed and trial), e.g. a series equivalent taking over the
    /// state of the element whose slip it carries.
    pub fn set_committed(&mut self, state: ContactState<T>) {
        self.committed = state;
        self.trial = state;
    }

    /// Set the committed state only, for an element that is never trialled: a condensed
    /// support's elements 1 and 2, whose states are rebuilt from their series equivalent
    /// at every converged step (`series::split_equivalent`) and only read after. Its
    /// trial state is left as it was (`restore` would copy the committed one over it).
    pub(crate) fn set_state(&mut self, state: ContactState<T>) {
        self.committed = state;
    }

    /// Normal compression N ≥ 0 of the committed state (tension for bonded elements is
    /// returned negative), N.
    pub fn normal(&self) -> f64 {
        -T::split(&self.committed.force).1
    }

    /// Tangential force T on the upper point of the committed state, N.
    pub fn tangential(&self) -> T {
        T::split(&self.committed.force).0
    }

    /// [`Element::trial`] of an element known not to be bonded (a contact with the ground:
    /// the single arrangement's elements and the series equivalents). The same
    /// operations on the same path with the bonded element's tests left out, so the same
    /// bits.
    #[inline(always)]
    pub(crate) fn trial_contact(&mut self, d: T::Vector) -> (T::Vector, T::Tangent) {
        debug_assert!(!self.bonded);
        self.trial_as(d, false)
    }

    /// The return mapping of an element known not to be bonded (a contact with the
    /// ground: the single arrangement's elements and the series equivalents): the force,
    /// the status and, slipping, the tangent's ratio μN/|T*|·kt (where `T` has it) and
    /// the direction n; the trial state is set, the tangent left to the caller, who reads
    /// it from these (`model::GroundSums`).
    #[inline(always)]
    pub(crate) fn trial_ground(&mut self, d: T::Vector) -> (T::Vector, Status, (f64, T)) {
        debug_assert!(!self.bonded);
        self.return_map(d, false)
    }

    /// The return mapping at trial displacement `d`, bonded or not as `bonded` says, and
    /// its consistent tangent.
    #[inline(always)]
    fn trial_as(&mut self, d: T::Vector, bonded: bool) -> (T::Vector, T::Tangent) {
        let (force, status, (ratio, dir)) = self.return_map(d, bonded);
        let tangent = match status {
            Status::Open => T::no_tangent(),
            Status::Stick => T::stick_tangent(self.kt, self.kz),
            Status::Slip => T::slip_tangent(ratio, dir, self.mu, self.kz),
        };
        (force, tangent)
    }

    /// The return mapping at trial displacement `d`, bonded or not as `bonded` says: sets
    /// the trial state and returns the force, the status and, slipping, the tangent's
    /// ratio μN/|T*|·kt (0 in the plane, where no term uses it) and direction.
    #[inline(always)]
    fn return_map(&mut self, d: T::Vector, bonded: bool) -> (T::Vector, Status, (f64, T)) {
        let (kt, kz) = (self.kt, self.kz);
        let p = self.committed.slip;
        let (dt, dz) = T::split(&d);
        if !bonded && dz > 0.0 {
            // Open: no force; the tangential origin follows the point, so a contact that
            // closes again starts unstressed.
            let zero = T::zero().join(0.0);
            self.trial = ContactState {
                slip: dt,
                delta: d,
                force: zero,
                status: Status::Open,
            };
            return (zero, Status::Open, (0.0, T::zero()));
        }
        let n = -kz * dz; // normal compression, N = −kz·δz
        let t_trial = (dt - p) * kt; // elastic predictor
        let cap = self.mu * n.max(0.0); // Coulomb limit μ·N of this element
        let size = t_trial.size();
        let stick = self.mu.is_infinite() || size <= cap || (bonded && n <= 0.0);
        if stick {
            let force = t_trial.join(-n);
            self.trial = ContactState {
                slip: p,
                delta: d,
                force,
                status: Status::Stick,
            };
            return (force, Status::Stick, (0.0, T::zero()));
        }
        // Return mapping onto the limit: T = μN·n, slip = δt − T/kt.
        let dir = t_trial.direction(size);
        let t = dir * cap;
        let force = t.join(-n);
        self.trial = ContactState {
            slip: dt - t.over(kt),
            delta: d,
            force,
            status: Status::Slip,
        };
        let ratio = if T::SLIP_RATIO { cap / size * kt } else { 0.0 };
        (force, Status::Slip, (ratio, dir))
    }
}

impl<T: Tangential> Element for Contact<T> {
    type Vector = T::Vector;
    type Tangent = T::Tangent;

    #[inline]
    fn trial(&mut self, d: T::Vector) -> (T::Vector, T::Tangent) {
        self.trial_as(d, self.bonded)
    }

    #[inline]
    fn commit(&mut self) {
        self.committed = self.trial;
    }

    fn restore(&mut self) {
        self.trial = self.committed;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sticks_then_slips_at_mu_times_its_own_normal_force() {
        let mut c = Contact178::new(1000.0, 4000.0, 0.5, false);
        // Compressed by 1 mm: N = 4 N, limit 2 N.
        let (f, k) = c.trial(Vector2::new(0.001, -0.001));
        assert_eq!(f, Vector2::new(1.0, -4.0));
        assert_eq!(k, Matrix2::new(1000.0, 0.0, 0.0, 4000.0));
        let (f, k) = c.trial(Vector2::new(0.005, -0.001));
        assert_eq!(f.x, 2.0);
        assert!((c.trial.slip - 0.003).abs() < 1e-15);
        assert_eq!(k[(0, 1)], -0.5 * 4000.0);
        c.commit();
        // Unloading from the shifted origin: δx = 0.004 gives T = kx(0.004 − 0.003) = 1.
        let (f, _) = c.trial(Vector2::new(0.004, -0.001));
        assert!((f.x - 1.0).abs() < 1e-12);
        c.restore();
        assert!((c.state().slip - 0.003).abs() < 1e-15);
    }

    #[test]
    fn open_contact_carries_nothing_and_resets_its_origin() {
        let mut c = Contact178::new(1000.0, 4000.0, 0.5, false);
        let (f, k) = c.trial(Vector2::new(0.01, 0.002));
        assert_eq!(f, Vector2::zeros());
        assert_eq!(k, Matrix2::zeros());
        c.commit();
        assert_eq!(c.state().slip, 0.01);
        assert_eq!(c.state().status, Status::Open);
    }

    #[test]
    fn bonded_infinite_friction_is_linear_both_ways() {
        let mut c = Contact178::new(10.0, 20.0, f64::INFINITY, true);
        let (f, _) = c.trial(Vector2::new(1.0, 0.5));
        assert_eq!(f, Vector2::new(10.0, 10.0));
    }

    #[test]
    fn radial_return_lands_on_the_cone_along_the_trial_force() {
        let mut c = ConeContact::new(1000.0, 4000.0, 0.5, false);
        // N = 4 N, cap 2 N; trial T* = 1000·(0.003, 0.004) = (3, 4), |T*| = 5.
        let (f, _) = c.trial(Vector3::new(0.003, 0.004, -0.001));
        assert!((f.x - 1.2).abs() < 1e-15 && (f.y - 1.6).abs() < 1e-15);
        assert_eq!(f.z, -4.0);
        // p = δt − T/kt = (0.003 − 0.0012, 0.004 − 0.0016)
        assert!((c.trial.slip - Vector2::new(0.0018, 0.0024)).norm() < 1e-18);
        c.commit();
        assert_eq!(c.state().status, Status::Slip);
    }

    #[test]
    fn the_tangent_is_the_derivative_of_the_return_mapping() {
        // Central differences of the force against the consistent tangent, in slip.
        let c0 = ConeContact::new(1000.0, 4000.0, 0.5, false);
        let d = Vector3::new(0.003, -0.004, -0.001);
        let (_, k) = c0.clone().trial(d);
        let h = 1e-9;
        let mut worst: f64 = 0.0;
        for j in 0..3 {
            let mut dp = d;
            dp[j] += h;
            let mut dm = d;
            dm[j] -= h;
            let fd = (c0.clone().trial(dp).0 - c0.clone().trial(dm).0) / (2.0 * h);
            worst = worst.max((fd - k.column(j)).norm());
        }
        // Measured 2.6e-7 against entries of order 1e3 (difference quotient round-off).
        assert!(worst < 1e-5, "{worst}");
    }

    #[test]
    fn reduces_to_the_two_dimensional_element_in_plane() {
        let mut c2 = Contact178::new(1000.0, 4000.0, 0.5, false);
        let mut c3 = ConeContact::new(1000.0, 4000.0, 0.5, false);
        for (x, z) in [
            (0.001, -0.001),
            (0.007, -0.001),
            (-0.002, -0.0015),
            (0.01, 0.002),
        ] {
            let (f2, k2) = c2.trial(nalgebra::Vector2::new(x, z));
            let (f3, k3) = c3.trial(Vector3::new(x, 0.0, z));
            assert_eq!((f3.x, f3.y, f3.z), (f2.x, 0.0, f2.y));
            assert_eq!(
                (k3[(0, 0)], k3[(0, 2)], k3[(2, 0)], k3[(2, 2)]),
                (k2[(0, 0)], k2[(0, 1)], k2[(1, 0)], k2[(1, 1)])
            );
            c2.commit();
            c3.commit();
            assert_eq!(c3.state().slip, Vector2::new(c2.state().slip, 0.0));
        }
    }
}

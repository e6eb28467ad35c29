//! What the one model leaves to its dimension ([`Dimension`]): the body's generalized
//! coordinates and their update, a support point's displacement and how its force and
//! tangent enter the body's unknowns (G at the point's offset), the inertia, the contact's
//! tangential part and the vector types; and the model's parts over it ([`Model`]: the
//! [`Body`] and its [`Support`]s). Everything else — building a scene's model, the
//! assembly's loops, the nodes' condensation, the Newton solve, commit and restore, the
//! time loop — is written once over it (`build`, `assembly`, `solve`, `mechanics`). Two implementations: [`Plane`](super::Plane) and
//! [`Space`](super::Space). Statically dispatched: each model is compiled for its
//! dimension.

use std::any::Any;
use std::fmt::Debug;
use std::ops::AddAssign;

use nalgebra::Vector3;

use crate::element::{Contact, Status, Tangential};

/// A point's displacement (and an element's force) in dimension `D`: (x, z) in the plane,
/// (x, y, z) in space.
pub type Vector<D> = <<D as Dimension>::Tangential as Tangential>::Vector;

/// What a touching element leaves for the tangent's sums in dimension `D`.
pub type Touch<D> = <<D as Dimension>::Sums as GroundSums<D>>::Touch;

/// The force's sums of an assembly in dimension `D`.
pub type ForceSums<D> = <<D as Dimension>::Sums as GroundSums<D>>::Force;

/// An element's tangent in dimension `D`.
pub type Tangent<D> = <<D as Dimension>::Tangential as Tangential>::Tangent;

/// The Newton system's coefficients of a step: S = c0·M + s·K (+ the damping's
/// s·C·c1 and, for a rotating body in space, the inertia's tangent at velocity `v`).
#[derive(Debug, Clone, Copy)]
pub struct System<U> {
    /// Mass coefficient 1/(β·Δt²) (0 for statics).
    pub c0: f64,
    /// Stiffness scale 1 + α.
    pub s: f64,
    /// Velocity coefficient γ/(β·Δt) (0 for statics).
    pub c1: f64,
    /// The body's velocity (none for statics).
    pub v: Option<U>,
}

impl<U> System<U> {
    /// The static system: the stiffness alone.
    pub(crate) fn statics() -> Self {
        Self {
            c0: 0.0,
            s: 1.0,
            c1: 0.0,
            v: None,
        }
    }
}

/// The rigid body.
#[derive(Debug, Clone, PartialEq)]
pub struct Body<D: Dimension> {
    /// Mass, kg.
    pub mass: f64,
    /// Gravity, m/s² (along −z).
    pub gravity: f64,
    /// Rotational inertia about the centre of mass (unused when the rotation is locked).
    pub inertia: D::Inertia,
    /// Whether the body rotates (else its rotation is locked: a sliding oscillator).
    pub rotation: bool,
    /// Support points in the body frame, relative to the centre of mass, m.
    pub offsets: Vec<Vector<D>>,
    /// Horizontal viscous damping on the body relative to the ground, N·s/m.
    pub damping: f64,
}

/// One support: element 1 from the ground (to the body, or to the support's massless
/// node) and, in the double arrangement, element 2 from the node to the body.
#[derive(Debug, Clone)]
pub struct Support<D: Dimension> {
    /// The element touching the ground.
    pub lower: Contact<D::Tangential>,
    /// Element 2 (bonded), double arrangement only.
    pub upper: Option<Contact<D::Tangential>>,
}

/// The penalty FE model of a rigid body on contact supports, in the plane
/// ([`Plane`](super::Plane)) or in space ([`Space`](super::Space)).
#[derive(Debug, Clone)]
pub struct Model<D: Dimension> {
    /// The body.
    pub body: Body<D>,
    /// Supports, one per body offset (node k belongs to support k).
    pub supports: Vec<Support<D>>,
    /// Massless nodes (0, or one per support in the double arrangement).
    pub nodes: usize,
    /// How the support points follow the body.
    pub kinematics: D::Kinematics,
    /// The double arrangement's supports as single series-equivalent elements, ground to
    /// body (`series_equivalent`); empty for the single arrangement.
    pub equivalents: Vec<Contact<D::Tangential>>,
    /// Whether the time loop iterates on the body alone (the single arrangement, or the
    /// double one with every support condensed into its `equivalents`). `false` carries
    /// the node unknowns (element 2 with finite friction, or set by a test to compare
    /// with the uncondensed model).
    pub condensed: bool,
}

/// The sums one assembly accumulates over the elements joining the ground to the body
/// (`Model::assemble`), each dimension in its own order, in two parts: the force's sums
/// ([`Self::Force`]), which every Newton iteration needs, and the tangent's (`Self`),
/// which only an iteration that solves needs. Each sum is its own accumulator, taken over
/// the elements in their order, so the bits do not depend on when the tangent is summed.
pub trait GroundSums<D: Dimension>: Default + Clone + Debug {
    /// The sums of the body's internal force.
    type Force: Copy + Default + Debug;
    /// What one touching element leaves for the tangent's sums.
    type Touch: Copy + Debug + Default;
    /// Whether the tangent waits until a solve needs it (`Model::finish_tangent`), each
    /// element's [`Self::Touch`] kept until then; otherwise it is summed with the force.
    const DEFERRED_TANGENT: bool;
    /// Add a closed element's force `f` at the support point `p` to `force`, the element
    /// sticking or (`slip`: μN/|T*|·kt and the direction n) slipping; returns what its
    /// tangent needs.
    fn add_force(
        force: &mut Self::Force,
        p: &D::Point,
        f: &Vector<D>,
        e: &Contact<D::Tangential>,
        status: Status,
        slip: (f64, D::Tangential),
    ) -> Self::Touch;
    /// Add a touching element's tangent.
    fn add_tangent(&mut self, touch: &Self::Touch);
    /// The tangent's sums of the touching elements `touches`, each sum taking its terms
    /// in their order.
    #[inline]
    fn from_touches(touches: &[Self::Touch]) -> Self {
        let mut sums = Self::default();
        for touch in touches {
            sums.add_tangent(touch);
        }
        sums
    }
    /// The body's internal force.
    fn write_force(force: &Self::Force, at: &D::Iterate, pb: &mut D::Unknowns);
    /// The tangent with respect to the body's virtual displacement (before
    /// `Dimension::to_unknowns`), once every touching element's tangent is added.
    fn write_tangent(&mut self, at: &D::Iterate, kbb: &mut D::Matrix);
}

/// What is specific to the dimension of the one model (see the module docs).
pub trait Dimension: Copy + Debug + PartialEq + 'static {
    /// The contact's tangential part: `f64` (x) in the plane, `Vector2` (x, y) in space.
    type Tangential: Tangential;
    /// The body's unknowns: (X, Z, θ) in the plane, (X, Θ) in space.
    type Unknowns: Copy + Debug + PartialEq + AddAssign;
    /// A matrix on the body's unknowns.
    type Matrix: Copy + Debug;
    /// The LU factors of a [`Self::Matrix`].
    type Lu: Copy + Debug + Default;
    /// The body's rotational inertia about its centre of mass.
    type Inertia: Copy + Debug + PartialEq;
    /// How a support point follows the body (the plane's exact or small rotations).
    type Kinematics: Copy + Debug + PartialEq;
    /// Where the body is at the end of a step.
    type Pose: Copy + Debug;
    /// The body's configuration at a Newton iterate, as the assembly reads it.
    type Iterate: Copy + Debug;
    /// A support point at an iterate: its displacement and what its G needs.
    type Point: Copy + Debug + Default;
    /// A horizontal force or ground motion: x in the plane, (x, y, 0) in space.
    type Horizontal: Copy + Debug;
    /// The ground's displacement, velocity and acceleration.
    type Ground: Copy + Debug;
    /// The sums of an assembly over the ground-to-body elements.
    type Sums: GroundSums<Self>;
    /// The model's own room in an assembly (the plane oscillator's scalar factors).
    type Extra: Copy + Debug + Default;
    /// Whether a rotating body's Newton matrix can repeat bit for bit from one solve to
    /// the next (the plane's small-rotation kinematics), so that its factors are worth
    /// keeping; in space the matrix turns with R at every iteration.
    const ROTATING_MATRIX_REPEATS: bool;
    /// The unit of a failed step's correction and increment (" m", or nothing for the
    /// space model's mixed metres and radians).
    const CORRECTION_UNIT: &'static str;

    /// The body's unknowns at zero.
    fn zero() -> Self::Unknowns;
    /// A zero matrix on them.
    fn zero_matrix() -> Self::Matrix;
    /// Zero the rotational entries of the body's unknowns.
    fn lock_rotation(x: &mut Self::Unknowns);
    /// The unloaded body.
    fn rest_pose() -> Self::Pose;
    /// The ground at rest.
    fn rest_ground() -> Self::Ground;
    /// The unknowns of pose `p` as a step's reference (a step's increment is q − it).
    fn reference(p: &Self::Pose) -> Self::Unknowns;
    /// The predictor of a step of length `h` from pose `p`, velocity `v`, acceleration
    /// `a`: constant acceleration.
    fn predict(
        p: &Self::Pose,
        v: &Self::Unknowns,
        a: &Self::Unknowns,
        h: f64,
        rotates: bool,
    ) -> Self::Unknowns;
    /// The iterate of unknowns `q` in a step from pose `from`.
    fn iterate(
        kin: &Self::Kinematics,
        rotates: bool,
        q: &Self::Unknowns,
        from: &Self::Pose,
    ) -> Self::Iterate;
    /// The pose of an accepted iterate.
    fn pose(q: &Self::Unknowns, at: &Self::Iterate) -> Self::Pose;
    /// The squared size of the displacement at an iterate (the round-off floor of the
    /// displacement test).
    fn displacement_squared(q: &Self::Unknowns, at: &Self::Iterate, from: &Self::Pose) -> f64;

    /// The support point at body offset `d`.
    fn point(
        kin: &Self::Kinematics,
        q: &Self::Unknowns,
        at: &Self::Iterate,
        d: &Vector<Self>,
    ) -> Self::Point;
    /// Its displacement.
    fn displacement(p: &Self::Point) -> Vector<Self>;
    /// The ground-to-body elements' sums of one assembly: `elements` (each at its body
    /// offset) evaluated at the iterate and the ground point `ground`
    /// (`assembly::sum_ground_elements` with this dimension's point kinematics); returns
    /// the force's sums and the number of touching elements, the tangent's sums in `sums`
    /// (from zero) or, deferred, the touching elements' parts in `touches`.
    fn sum_ground_elements<'e>(
        kin: &Self::Kinematics,
        q: &Self::Unknowns,
        at: &Self::Iterate,
        elements: impl Iterator<Item = (&'e Vector<Self>, &'e mut Contact<Self::Tangential>)>,
        ground: &Vector<Self>,
        sums: &mut Self::Sums,
        touches: &mut [Touch<Self>],
    ) -> (ForceSums<Self>, usize);
    /// Add an element's force `f` and tangent `k` at the support point `p` to the body's
    /// internal force and tangent (the uncondensed assembly).
    fn add_support(
        p: &Self::Point,
        at: &Self::Iterate,
        f: &Vector<Self>,
        k: &Tangent<Self>,
        pb: &mut Self::Unknowns,
        kbb: &mut Self::Matrix,
    );
    /// Turn the tangent's rotational columns from the body's virtual rotation to the
    /// unknowns of a body that `rotates` (space: W = J_r(Θ)·δΘ).
    fn to_unknowns(at: &Self::Iterate, rotates: bool, kbb: &mut Self::Matrix);
    /// The generalized force Gᵀ·v of a force `v` at the support point `p`.
    fn generalized_force(p: &Self::Point, at: &Self::Iterate, v: &Vector<Self>) -> Self::Unknowns;
    /// The support point's motion G·dq for a change `dq` of the unknowns of a body that
    /// `rotates`.
    fn point_motion(
        p: &Self::Point,
        at: &Self::Iterate,
        rotates: bool,
        dq: &Self::Unknowns,
    ) -> Vector<Self>;

    /// The Newton matrix c0·M + s·K (+ damping, inertial tangent) of `body` with
    /// tangent `kbb`.
    fn newton_matrix(
        body: &Body<Self>,
        sys: &System<Self::Unknowns>,
        kbb: &Self::Matrix,
    ) -> Self::Matrix;
    /// Lock the rotational rows and columns of a Newton system.
    fn lock_rotation_rows(s: &mut Self::Matrix, rhs: &mut Self::Unknowns);
    /// Whether two matrices are the same bit for bit.
    fn same_bits(a: &Self::Matrix, b: &Self::Matrix) -> bool;
    /// Factor a Newton matrix into `lu`.
    fn factor(m: &Self::Matrix, lu: &mut Self::Lu);
    /// Solve with the factors; `None` if singular.
    fn solve(lu: &Self::Lu, b: &Self::Unknowns) -> Option<Self::Unknowns>;

    /// The inertial force at acceleration `a` and velocity `v`.
    fn inertia_force(body: &Body<Self>, a: &Self::Unknowns, v: &Self::Unknowns) -> Self::Unknowns;
    /// The acceleration at t = 0 under the net force `out`.
    fn initial_acceleration(body: &Body<Self>, out: &Self::Unknowns) -> Self::Unknowns;
    /// The damping force C·(v − v_ground) at velocity `v`.
    fn damping(c: f64, v: &Self::Unknowns, g: &Self::Ground) -> Self::Unknowns;
    /// The load on the body's unknowns of a horizontal force `h` and a vertical `z`.
    fn load(h: Self::Horizontal, z: f64) -> Self::Unknowns;
    /// The horizontal part of a load on the body's unknowns.
    fn horizontal_of(f: &Self::Unknowns) -> Self::Horizontal;

    /// A horizontal quantity from its value along the excitation's first direction and
    /// along the second (at right angles), `directions` the two.
    fn horizontal(
        first: f64,
        second: Option<f64>,
        directions: &[Vector3<f64>; 2],
    ) -> Self::Horizontal;
    /// No horizontal quantity.
    fn no_horizontal() -> Self::Horizontal;
    /// The ground of displacement, velocity and acceleration.
    fn ground(d: Self::Horizontal, v: Self::Horizontal, a: Self::Horizontal) -> Self::Ground;
    /// The ground's displacement as a point.
    fn ground_point(g: &Self::Ground) -> Vector<Self>;

    /// A step written for this dimension's `model` alone, if it has one: a
    /// `stepper::StepFn` of the model, which the time loop takes in place of its Newton
    /// step (the plane's sliding oscillator in scalars).
    fn own_step(_model: &Model<Self>) -> Option<&'static (dyn Any + Send + Sync)> {
        None
    }
}

//! What the time loop asks of a model ([`Mechanics`]): the one model implements it for
//! either dimension (`model`: body unknowns q = (X, Z, θ) and nodes (x, z) in the plane,
//! q = (X, Θ) and nodes (x, y, z) in space), and the static preload, the Newmark/HHT step
//! with its Newton iteration and the step cutting are written once over it (`newton`,
//! `time_loop`). Every vector the loop needs lives in a [`Workspace`], allocated once.

use nalgebra::SVector;

use super::failure::{Counters, StepFailure};
use super::newmark::Newmark;
use crate::options::FeOptions;

/// The body's state at the end of a (sub)step, what the next step starts from.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StepState<const Q: usize, P, G> {
    /// Time, s.
    pub t: f64,
    /// Where the body is (`Mechanics::Pose`).
    pub pose: P,
    /// Velocity and acceleration of the body's unknowns.
    pub v: SVector<f64, Q>,
    pub a: SVector<f64, Q>,
    /// External force.
    pub f: SVector<f64, Q>,
    /// Vertical load beyond the preload (`vertical`), N.
    pub fz: f64,
    /// Internal (support) force on the body.
    pub pb: SVector<f64, Q>,
    /// Damping force.
    pub damp: SVector<f64, Q>,
    /// Ground (displacement, velocity, acceleration).
    pub g: G,
}

/// The step state of model `M`.
pub(crate) type State<const Q: usize, const N: usize, M> =
    StepState<Q, <M as Mechanics<Q, N>>::Pose, <M as Mechanics<Q, N>>::Ground>;

/// A step written for one model alone (the same operations as `newton::step` on fewer
/// values): the plane's sliding oscillator.
pub(crate) type StepFn<const Q: usize, const N: usize, M> =
    for<'d, 'w> fn(
        &mut M,
        &<M as Mechanics<Q, N>>::Drive<'d>,
        &FeOptions,
        &Newmark,
        &'w mut Workspace<Q, N, M>,
        (&State<Q, N, M>, &mut State<Q, N, M>),
        f64,
        &mut Counters,
    ) -> Result<(), StepFailure>;

/// A model the time loop drives: `Q` unknowns of the body, `N` of each massless node.
pub(crate) trait Mechanics<const Q: usize, const N: usize>: Sized {
    /// Where the body is at the end of a step.
    type Pose: Copy;
    /// The ground's displacement, velocity and acceleration at an instant.
    type Ground: Copy;
    /// How the excitation loads the model.
    type Drive<'d>;
    /// One assembly's internal forces and tangents.
    type Assembly;
    /// The body's configuration at a Newton iterate, as the assembly computed it.
    type Iterate: Copy;
    /// What an observer is shown at an output instant.
    type Snapshot<'s>;
    /// The quantity a failed step's correction and increment are measured in (" m", or
    /// nothing for the space model's mixed metres and radians).
    const CORRECTION_UNIT: &'static str;

    /// Room for one assembly.
    fn new_assembly(&self) -> Self::Assembly;
    /// Massless nodes (the length of the node vectors).
    fn nodes(&self) -> usize;
    /// Node unknowns the Newton iteration carries (none when the supports are condensed).
    fn loop_nodes(&self) -> usize;
    /// Whether the body rotates (else its rotational unknowns are locked at zero).
    fn rotates(&self) -> bool;
    /// Zero the rotational entries of a vector of the body's unknowns.
    fn lock_rotation(x: &mut SVector<f64, Q>);

    /// The unloaded body, the preload's start.
    fn rest_pose() -> Self::Pose;
    /// The ground at rest.
    fn rest_ground() -> Self::Ground;
    /// The gravity load M·g on the body's unknowns.
    fn static_load(&self) -> SVector<f64, Q>;
    /// Solve the static Newton system (no inertia, no damping).
    fn solve_static(
        &self,
        asm: &mut Self::Assembly,
        rb: &SVector<f64, Q>,
        rn: &[SVector<f64, N>],
        dq: &mut SVector<f64, Q>,
        dun: &mut [SVector<f64, N>],
    ) -> bool;

    /// The load at `t`: external force, vertical load beyond the preload, ground.
    fn load(&self, drive: &Self::Drive<'_>, t: f64) -> (SVector<f64, Q>, f64, Self::Ground);
    /// The load of the state at t = 0.
    fn initial_load(&self, drive: &Self::Drive<'_>) -> (SVector<f64, Q>, f64, Self::Ground);
    /// The acceleration at t = 0 under the net force `out`.
    fn initial_acceleration(&self, out: SVector<f64, Q>) -> SVector<f64, Q>;
    /// The unknowns of the pose `p` as a step's reference: a step's displacement
    /// increment is q − reference.
    fn reference(p: &Self::Pose) -> SVector<f64, Q>;
    /// The predictor of a step of length `h` from `n`: constant acceleration.
    fn predict(&self, n: &State<Q, N, Self>, h: f64) -> SVector<f64, Q>;
    /// The nodes' predictor: they move with the ground (from `from` to `to`): element 1
    /// is the stiff one, and a node left behind would put it far into slip and let
    /// Newton cycle.
    fn predict_nodes(&self, un: &mut [SVector<f64, N>], to: &Self::Ground, from: &Self::Ground);
    /// Evaluate every element at the unknowns `q` of a step from pose `from` (nodes `un`,
    /// ground `g`) and assemble internal forces and the consistent tangent into `asm`
    /// (the tangent may be summed only when a solve needs it).
    fn assemble(
        &mut self,
        q: &SVector<f64, Q>,
        from: &Self::Pose,
        un: &mut [SVector<f64, N>],
        g: &Self::Ground,
        asm: &mut Self::Assembly,
    ) -> Self::Iterate;
    /// The internal force on the body of the last assembly.
    fn body_force(asm: &Self::Assembly) -> &SVector<f64, Q>;
    /// The internal force on each node of the last assembly.
    fn node_forces(asm: &Self::Assembly) -> &[SVector<f64, N>];
    /// The damping force at velocity `v` over the ground `g`.
    fn damping(&self, v: &SVector<f64, Q>, g: &Self::Ground) -> SVector<f64, Q>;
    /// The inertial force at acceleration `a` and velocity `v`.
    fn inertia(&self, a: &SVector<f64, Q>, v: &SVector<f64, Q>) -> SVector<f64, Q>;
    /// Solve a step's Newton system with Newmark's coefficients `nm` at velocity `v`.
    #[allow(clippy::too_many_arguments)]
    fn solve_step(
        &self,
        nm: &Newmark,
        v: &SVector<f64, Q>,
        asm: &mut Self::Assembly,
        rb: &SVector<f64, Q>,
        rn: &[SVector<f64, N>],
        dq: &mut SVector<f64, Q>,
        dun: &mut [SVector<f64, N>],
    ) -> bool;
    /// The squared size of the displacement at an iterate (the round-off floor of the
    /// displacement test).
    fn displacement_squared(q: &SVector<f64, Q>, at: &Self::Iterate, from: &Self::Pose) -> f64;
    /// The pose of an accepted iterate.
    fn pose(q: &SVector<f64, Q>, at: &Self::Iterate) -> Self::Pose;
    /// Commit the state of the last assembly (ground `g`), writing every node into `un`.
    fn commit_step(&mut self, asm: &Self::Assembly, un: &mut [SVector<f64, N>], g: &Self::Ground);
    /// Forget every element's trial state.
    fn restore(&mut self);
    /// What an observer is shown of state `n` (nodes `un`, static equilibrium `statics`).
    fn snapshot<'s>(
        n: &State<Q, N, Self>,
        un: &'s [SVector<f64, N>],
        statics: &'s Self::Pose,
        asm: &'s Self::Assembly,
    ) -> Self::Snapshot<'s>;
    /// A step written for this model alone, if it has one.
    fn own_step(&self) -> Option<StepFn<Q, N, Self>> {
        None
    }
}

/// Every vector the loop needs, allocated once.
pub(crate) struct Workspace<const Q: usize, const N: usize, M: Mechanics<Q, N>> {
    /// The last assembly.
    pub asm: M::Assembly,
    /// Node displacements of the iterate, and at the start of the step.
    pub un: Vec<SVector<f64, N>>,
    pub un_n: Vec<SVector<f64, N>>,
    /// Node forces at the start of the step.
    pub pn_n: Vec<SVector<f64, N>>,
    /// Node residuals and corrections.
    pub rn: Vec<SVector<f64, N>>,
    pub dun: Vec<SVector<f64, N>>,
    /// Line search: the last accepted iterate and its Newton direction.
    pub un_prev: Vec<SVector<f64, N>>,
    pub dun_prev: Vec<SVector<f64, N>>,
}

impl<const Q: usize, const N: usize, M: Mechanics<Q, N>> Workspace<Q, N, M> {
    /// Room for `model`'s nodes.
    pub(crate) fn new(model: &M) -> Self {
        let z = vec![SVector::<f64, N>::zeros(); model.nodes()];
        Self {
            asm: model.new_assembly(),
            un: z.clone(),
            un_n: z.clone(),
            pn_n: z.clone(),
            rn: z.clone(),
            dun: z.clone(),
            un_prev: z.clone(),
            dun_prev: z,
        }
    }

    /// Keep the nodes' converged displacements and forces as the next step's start
    /// (nothing to copy without nodes: no call for an empty copy every step). With
    /// condensed supports (`loop_nodes` = 0) the step reads neither `un` nor the node
    /// forces, and `commit_step` writes every node of `un`: the two vectors are swapped,
    /// and the node forces (never assembled) are not copied.
    pub(crate) fn keep_nodes(&mut self, loop_nodes: usize) {
        if self.un.is_empty() {
            return;
        }
        if loop_nodes == 0 {
            std::mem::swap(&mut self.un, &mut self.un_n);
        } else {
            self.un_n.copy_from_slice(&self.un);
            self.pn_n.copy_from_slice(M::node_forces(&self.asm));
        }
    }
}

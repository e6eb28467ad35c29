//! The model in the time loop (`stepper::Mechanics`), once for both dimensions: the body's
//! unknowns and each node's, the drive's loads, the inertia and damping, the assembly and
//! the Newton solve, each piece the dimension's where it must be (`Dimension`).

use nalgebra::SVector;

use super::assembly::Assembly;
use super::dimension::{Dimension, Model, System};
use super::drive::{Drive, Snapshot};
use super::solve::solve;
use crate::element::Tangential;
use crate::stepper::{Mechanics, Newmark, State, StepFn};

impl<const Q: usize, const N: usize, D> Mechanics<Q, N> for Model<D>
where
    D: Dimension<Unknowns = SVector<f64, Q>>,
    D::Tangential: Tangential<Vector = SVector<f64, N>>,
{
    type Pose = D::Pose;
    type Ground = D::Ground;
    type Drive<'d> = Drive<'d>;
    type Assembly = Assembly<D>;
    type Iterate = D::Iterate;
    type Snapshot<'s> = Snapshot<'s, D>;
    const CORRECTION_UNIT: &'static str = D::CORRECTION_UNIT;

    fn new_assembly(&self) -> Assembly<D> {
        Assembly::new(self)
    }

    fn nodes(&self) -> usize {
        self.nodes
    }

    fn loop_nodes(&self) -> usize {
        Model::loop_nodes(self)
    }

    fn rotates(&self) -> bool {
        self.body.rotation
    }

    #[inline]
    fn lock_rotation(x: &mut SVector<f64, Q>) {
        D::lock_rotation(x);
    }

    fn rest_pose() -> D::Pose {
        D::rest_pose()
    }

    fn rest_ground() -> D::Ground {
        D::rest_ground()
    }

    fn static_load(&self) -> SVector<f64, Q> {
        D::load(D::no_horizontal(), -self.weight())
    }

    fn solve_static(
        &self,
        asm: &mut Assembly<D>,
        rb: &SVector<f64, Q>,
        rn: &[SVector<f64, N>],
        dq: &mut SVector<f64, Q>,
        dun: &mut [SVector<f64, N>],
    ) -> bool {
        solve(self, &System::statics(), asm, rb, rn, dq, dun)
    }

    #[inline]
    fn load(&self, drive: &Drive<'_>, t: f64) -> (SVector<f64, Q>, f64, D::Ground) {
        let g = drive.ground::<D>(t);
        let fz = drive.vertical_force(t);
        let f = D::load(drive.force::<D>(t), -self.weight() + fz);
        (f, fz, g)
    }

    fn initial_load(&self, drive: &Drive<'_>) -> (SVector<f64, Q>, f64, D::Ground) {
        self.load(drive, 0.0)
    }

    fn initial_acceleration(&self, out: SVector<f64, Q>) -> SVector<f64, Q> {
        D::initial_acceleration(&self.body, &out)
    }

    #[inline]
    fn reference(p: &D::Pose) -> SVector<f64, Q> {
        D::reference(p)
    }

    #[inline]
    fn predict(&self, n: &State<Q, N, Self>, h: f64) -> SVector<f64, Q> {
        D::predict(&n.pose, &n.v, &n.a, h, self.body.rotation)
    }

    fn predict_nodes(&self, un: &mut [SVector<f64, N>], to: &D::Ground, from: &D::Ground) {
        let shift = D::ground_point(to) - D::ground_point(from);
        for u in un.iter_mut().take(self.nodes) {
            *u += shift;
        }
    }

    #[inline]
    fn assemble(
        &mut self,
        q: &SVector<f64, Q>,
        from: &D::Pose,
        un: &mut [SVector<f64, N>],
        g: &D::Ground,
        asm: &mut Assembly<D>,
    ) -> D::Iterate {
        Model::assemble_force(self, q, from, un, g, asm)
    }

    #[inline]
    fn body_force(asm: &Assembly<D>) -> &SVector<f64, Q> {
        &asm.pb
    }

    #[inline]
    fn node_forces(asm: &Assembly<D>) -> &[SVector<f64, N>] {
        &asm.pn
    }

    #[inline]
    fn damping(&self, v: &SVector<f64, Q>, g: &D::Ground) -> SVector<f64, Q> {
        D::damping(self.body.damping, v, g)
    }

    #[inline]
    fn inertia(&self, a: &SVector<f64, Q>, v: &SVector<f64, Q>) -> SVector<f64, Q> {
        D::inertia_force(&self.body, a, v)
    }

    #[inline]
    fn solve_step(
        &self,
        nm: &Newmark,
        v: &SVector<f64, Q>,
        asm: &mut Assembly<D>,
        rb: &SVector<f64, Q>,
        rn: &[SVector<f64, N>],
        dq: &mut SVector<f64, Q>,
        dun: &mut [SVector<f64, N>],
    ) -> bool {
        let sys = System {
            c0: nm.c0,
            s: nm.s,
            c1: nm.c1,
            v: Some(*v),
        };
        solve(self, &sys, asm, rb, rn, dq, dun)
    }

    #[inline]
    fn displacement_squared(q: &SVector<f64, Q>, at: &D::Iterate, from: &D::Pose) -> f64 {
        D::displacement_squared(q, at, from)
    }

    #[inline]
    fn pose(q: &SVector<f64, Q>, at: &D::Iterate) -> D::Pose {
        D::pose(q, at)
    }

    #[inline]
    fn commit_step(&mut self, _asm: &Assembly<D>, un: &mut [SVector<f64, N>], g: &D::Ground) {
        Model::commit_step(self, un, g);
    }

    fn restore(&mut self) {
        Model::restore(self);
    }

    #[inline]
    fn snapshot<'s>(
        n: &State<Q, N, Self>,
        un: &'s [SVector<f64, N>],
        statics: &'s D::Pose,
        asm: &'s Assembly<D>,
    ) -> Snapshot<'s, D> {
        Snapshot {
            t: n.t,
            pose: n.pose,
            v: n.v,
            a: n.a,
            un,
            ground: n.g,
            statics,
            force: D::horizontal_of(&n.f),
            vertical_force: n.fz,
            at: &asm.at,
        }
    }

    /// The dimension's own step, typed as this model's: the plane's is written for its
    /// unknowns (`StepFn<3, 2, _>`), which are this impl's Q and N for the plane, so the
    /// check is always met (once per run).
    fn own_step(&self) -> Option<StepFn<Q, N, Self>> {
        D::own_step(self)?
            .downcast_ref::<StepFn<Q, N, Self>>()
            .copied()
    }
}

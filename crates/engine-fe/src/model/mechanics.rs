//! The plane model in the time loop (`stepper::Mechanics`): the body's unknowns
//! q = (X, Z, θ) (θ locked for a sliding oscillator), each node's (x, z); the drive's
//! horizontal force, ground motion and vertical load; the body's mass matrix diag(M, M, I)
//! and horizontal viscous damping relative to the ground.

use nalgebra::{SVector, Vector2, Vector3};

use super::assembly::Assembly;
use super::body::Model;
use super::drive::{Drive, Snapshot};
use super::slider;
use super::solve::{System, solve};
use crate::stepper::{Mechanics, Newmark, State, StepFn};

impl Mechanics<3, 2> for Model {
    type Pose = Vector3<f64>;
    type Ground = (f64, f64, f64);
    type Drive<'d> = Drive<'d>;
    type Assembly = Assembly;
    type Iterate = ();
    type Snapshot<'s> = Snapshot<'s>;
    const CORRECTION_UNIT: &'static str = " m";

    fn new_assembly(&self) -> Assembly {
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
    fn lock_rotation(x: &mut Vector3<f64>) {
        x.z = 0.0;
    }

    fn rest_pose() -> Vector3<f64> {
        Vector3::zeros()
    }

    fn rest_ground() -> (f64, f64, f64) {
        (0.0, 0.0, 0.0)
    }

    fn static_load(&self) -> Vector3<f64> {
        Vector3::new(0.0, -self.weight(), 0.0)
    }

    fn solve_static(
        &self,
        asm: &mut Assembly,
        rb: &Vector3<f64>,
        rn: &[Vector2<f64>],
        dq: &mut Vector3<f64>,
        dun: &mut [Vector2<f64>],
    ) -> bool {
        let sys = System {
            c0: 0.0,
            s: 1.0,
            damp_xx: 0.0,
        };
        solve(self, &sys, asm, rb, rn, dq, dun)
    }

    #[inline]
    fn load(&self, drive: &Drive<'_>, t: f64) -> (Vector3<f64>, f64, (f64, f64, f64)) {
        let g = drive.ground(t);
        let fz = drive.vertical_force(t);
        let f = Vector3::new(drive.force(t), -self.weight() + fz, 0.0);
        (f, fz, g)
    }

    fn initial_load(&self, drive: &Drive<'_>) -> (Vector3<f64>, f64, (f64, f64, f64)) {
        self.load(drive, 0.0)
    }

    fn initial_acceleration(&self, out: Vector3<f64>) -> Vector3<f64> {
        let m = self.mass_diag();
        let mut a = out.component_div(&m.map(|x| if x > 0.0 { x } else { f64::INFINITY }));
        if !self.body.rotation {
            a.z = 0.0;
        }
        a
    }

    #[inline]
    fn reference(p: &Vector3<f64>) -> Vector3<f64> {
        *p
    }

    #[inline]
    fn predict(&self, n: &State<3, 2, Self>, h: f64) -> Vector3<f64> {
        n.pose + n.v * h + n.a * (0.5 * h * h)
    }

    fn predict_nodes(&self, un: &mut [Vector2<f64>], to: &(f64, f64, f64), from: &(f64, f64, f64)) {
        for sup in &self.supports {
            if let Some(k) = sup.node {
                un[k].x += to.0 - from.0;
            }
        }
    }

    #[inline]
    fn assemble(
        &mut self,
        q: &Vector3<f64>,
        _from: &Vector3<f64>,
        un: &mut [Vector2<f64>],
        g: &(f64, f64, f64),
        asm: &mut Assembly,
    ) {
        Model::assemble(self, q, un, g.0, asm);
    }

    #[inline]
    fn body_force(asm: &Assembly) -> &Vector3<f64> {
        &asm.pb
    }

    #[inline]
    fn node_forces(asm: &Assembly) -> &[Vector2<f64>] {
        &asm.pn
    }

    #[inline]
    fn damping(&self, v: &Vector3<f64>, g: &(f64, f64, f64)) -> Vector3<f64> {
        Vector3::new(self.body.damping * (v.x - g.1), 0.0, 0.0)
    }

    #[inline]
    fn inertia(&self, a: &Vector3<f64>, _v: &Vector3<f64>) -> Vector3<f64> {
        self.mass_diag().component_mul(a)
    }

    #[inline]
    fn solve_step(
        &self,
        nm: &Newmark,
        _v: &Vector3<f64>,
        asm: &mut Assembly,
        rb: &Vector3<f64>,
        rn: &[Vector2<f64>],
        dq: &mut Vector3<f64>,
        dun: &mut [Vector2<f64>],
    ) -> bool {
        let sys = System {
            c0: nm.c0,
            s: nm.s,
            damp_xx: nm.s * self.body.damping * nm.c1,
        };
        solve(self, &sys, asm, rb, rn, dq, dun)
    }

    #[inline]
    fn displacement_squared(q: &Vector3<f64>, _at: &(), _from: &Vector3<f64>) -> f64 {
        q.norm_squared()
    }

    #[inline]
    fn pose(q: &Vector3<f64>, _at: &()) -> Vector3<f64> {
        *q
    }

    #[inline]
    fn commit_step(&mut self, asm: &Assembly, un: &mut [Vector2<f64>], _g: &(f64, f64, f64)) {
        Model::commit_step(self, asm, un);
    }

    fn restore(&mut self) {
        Model::restore(self);
    }

    #[inline]
    fn snapshot<'s>(
        n: &State<3, 2, Self>,
        un: &'s [SVector<f64, 2>],
        statics: &Vector3<f64>,
        asm: &Assembly,
    ) -> Snapshot<'s> {
        Snapshot {
            t: n.t,
            q: n.pose,
            v: n.v,
            a: n.a,
            un,
            ground: n.g,
            q_static: *statics,
            force: n.f.x,
            vertical_force: n.fz,
            rotation: asm.rotation(),
        }
    }

    fn own_step(&self) -> Option<StepFn<3, 2, Self>> {
        // A sliding oscillator steps in scalars (`slider`): the same operations, fewer.
        if self.is_slider() {
            Some(slider::step)
        } else {
            None
        }
    }
}

//! The 3D model in the time loop (`stepper::Mechanics`, the loop the plane model runs
//! in): Newmark or HHT-α with Newton on SO(3), the rotation advanced exactly.
//!
//! Formulation (Simo & Vu-Quoc 1988, material form): the angular velocity Ω and
//! acceleration A are body-frame vectors; a step's unknowns are the centre of mass X and
//! the body-frame incremental rotation vector Θ, R₊ = Rₙ·exp(Θ̂), and Newmark acts on Θ
//! as on a displacement increment:
//!   A₊ = (Θ − Δt·Ωₙ)/(βΔt²) − (1/(2β) − 1)·Aₙ,   Ω₊ = Ωₙ + Δt·((1 − γ)Aₙ + γA₊),
//! with Euler's equations J·A + Ω × J·Ω = moment (body frame). The rotation stays exactly
//! orthogonal (a product of exponentials); the Newton tangent is exact (the right Jacobian
//! J_r(Θ) in `model.rs`, the gyroscopic tangent c0·J + c1·(Ω̂J − (JΩ)^)). Why this and
//! not a quaternion or the total rotation vector: the increment Θ is a vector-space
//! unknown, so the 2D Newmark and HHT algebra, its line search and convergence tests
//! apply unchanged, and for a motion in one plane Θ = (0, −Δθ, 0), J_r acts as the
//! identity on it and every formula reduces to the 2D one. HHT-α weights the moments of
//! steps n and n+1 each in its own body frame: exact in plane; for a 3D rotation the two
//! frames differ by the step's rotation Θ = O(Δt), a simplification of the Lie-group
//! HHT/generalised-α (Brüls & Cardona 2010) not analysed further here (the measured
//! self-convergence in `tests/all/fe_space.rs` runs HHT with α = −0.1).

use nalgebra::{Matrix3, SVector, Vector3, Vector6};

use super::model::{Pose, SpaceAssembly, SpaceModel, SpaceSystem, solve};
use super::rotation::{exp, log, skew};
use crate::stepper::{Mechanics, Newmark, State};
use rockslide_core::case::{Excitation, Signal};

/// How an excitation drives the 3D model: the scene's signal along the horizontal
/// direction e₁ at `azimuth` (radians from x towards y) and an optional second signal of
/// the same kind along e₂ = (−sin, cos) of the azimuth.
#[derive(Debug, Clone, Copy)]
pub struct SpaceDrive<'a> {
    excitation: &'a Excitation,
    second: Option<&'a Signal>,
    /// The vertical ground acceleration a_v(t), if any (positive upward).
    vertical: Option<&'a Signal>,
    mass: f64,
    first_direction: Vector3<f64>,
    second_direction: Vector3<f64>,
}

impl<'a> SpaceDrive<'a> {
    /// The drive of `excitation` (and `second`) at `azimuth` on a body of mass `mass`.
    pub fn new(
        excitation: &'a Excitation,
        second: Option<&'a Signal>,
        azimuth: f64,
        mass: f64,
    ) -> Self {
        let (s, c) = azimuth.sin_cos();
        Self {
            excitation,
            second,
            vertical: None,
            mass,
            first_direction: Vector3::new(c, s, 0.0),
            second_direction: Vector3::new(-s, c, 0.0),
        }
    }
    /// The same drive with a vertical ground acceleration a_v(t) (positive upward).
    pub fn with_vertical(self, vertical: Option<&'a Signal>) -> Self {
        Self { vertical, ..self }
    }
    /// Vertical force on the body at `t` beyond the preload, N: −M·a_v(t), in relative
    /// coordinates as in 2D (`crate::vertical`).
    pub fn vertical_force(&self, t: f64) -> f64 {
        crate::vertical::load(self.vertical, self.mass, t)
    }
    /// The horizontal vector Σ value(signal)·direction, `value` one of the signal's
    /// derivatives.
    #[inline]
    fn vector(&self, first: &Signal, value: impl Fn(&Signal) -> f64) -> Vector3<f64> {
        let v = self.first_direction * value(first);
        match self.second {
            Some(s) => v + self.second_direction * value(s),
            None => v,
        }
    }
    /// Force on the body at `t` (ground acceleration in relative coordinates), N.
    pub fn force(&self, t: f64) -> Vector3<f64> {
        match self.excitation {
            Excitation::MassAcceleration(s) => self.vector(s, |s| self.mass * s.value(t)),
            Excitation::GroundAcceleration(s) => self.vector(s, |s| -self.mass * s.value(t)),
            _ => Vector3::zeros(),
        }
    }
    /// Prescribed ground (displacement, velocity, acceleration) at `t`.
    pub fn ground(&self, t: f64) -> [Vector3<f64>; 3] {
        match self.excitation {
            Excitation::GroundDisplacement(s) => [
                self.vector(s, |s| s.value(t)),
                self.vector(s, |s| s.derivative(t)),
                self.vector(s, |s| s.second_derivative(t)),
            ],
            _ => [Vector3::zeros(); 3],
        }
    }
    /// The horizontal force on the mass in relative coordinates.
    pub fn equivalent_force(&self, t: f64) -> Vector3<f64> {
        match self.excitation {
            Excitation::GroundDisplacement(s) => {
                self.vector(s, |s| -self.mass * s.second_derivative(t))
            }
            _ => self.force(t),
        }
    }
}

/// The model's state at one output instant.
#[derive(Debug, Clone, Copy)]
pub struct SpaceSnapshot<'a> {
    /// Time, s.
    pub t: f64,
    /// Centre-of-mass displacement from the unloaded position, m.
    pub x: Vector3<f64>,
    /// Rotation of the body.
    pub r: Matrix3<f64>,
    /// Velocity: centre of mass (ground frame) and Ω (body frame).
    pub v: Vector6<f64>,
    /// Acceleration: centre of mass and A (body frame).
    pub a: Vector6<f64>,
    /// Node displacements.
    pub un: &'a [Vector3<f64>],
    /// Ground displacement, velocity, acceleration.
    pub ground: [Vector3<f64>; 3],
    /// Centre of mass at static equilibrium.
    pub x_static: Vector3<f64>,
}

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

/// The pose of unknowns q = (X, Θ) from the rotation `rn` of the last step.
#[inline]
fn pose(q: &Vector6<f64>, rn: &Matrix3<f64>) -> Pose {
    let theta = q.fixed_rows::<3>(3).into_owned();
    Pose {
        x: q.fixed_rows::<3>(0).into_owned(),
        r: if theta == Vector3::zeros() {
            *rn
        } else {
            rn * exp(&theta)
        },
        theta,
    }
}

/// Horizontal viscous damping force C·(v − v_ground) on x and y.
#[inline]
fn damping(c: f64, v: &Vector6<f64>, vg: &Vector3<f64>) -> Vector6<f64> {
    Vector6::new(c * (v[0] - vg.x), c * (v[1] - vg.y), 0.0, 0.0, 0.0, 0.0)
}

/// Inertial force (M·a, J·A + Ω × J·Ω).
#[inline]
fn inertia_force(model: &SpaceModel, a: &Vector6<f64>, v: &Vector6<f64>) -> Vector6<f64> {
    let m = model.body.mass;
    let mut out = Vector6::new(m * a[0], m * a[1], m * a[2], 0.0, 0.0, 0.0);
    if model.body.rotation {
        let j = &model.body.inertia;
        let om = v.fixed_rows::<3>(3).into_owned();
        let rot = j * a.fixed_rows::<3>(3) + om.cross(&(j * om));
        out.fixed_rows_mut::<3>(3).copy_from(&rot);
    }
    out
}

impl Mechanics<6, 3> for SpaceModel {
    type Pose = Placement;
    type Ground = [Vector3<f64>; 3];
    type Drive<'d> = SpaceDrive<'d>;
    type Assembly = SpaceAssembly;
    type Iterate = Pose;
    type Snapshot<'s> = SpaceSnapshot<'s>;
    // A correction mixes metres and radians: no unit.
    const CORRECTION_UNIT: &'static str = "";

    fn new_assembly(&self) -> SpaceAssembly {
        SpaceAssembly::new(self)
    }

    fn nodes(&self) -> usize {
        self.nodes
    }

    fn loop_nodes(&self) -> usize {
        SpaceModel::loop_nodes(self)
    }

    fn rotates(&self) -> bool {
        self.body.rotation
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

    fn static_load(&self) -> Vector6<f64> {
        Vector6::new(0.0, 0.0, -self.weight(), 0.0, 0.0, 0.0)
    }

    fn solve_static(
        &self,
        asm: &mut SpaceAssembly,
        rb: &Vector6<f64>,
        rn: &[Vector3<f64>],
        dq: &mut Vector6<f64>,
        dun: &mut [Vector3<f64>],
    ) -> bool {
        let sys = SpaceSystem {
            c0: 0.0,
            s: 1.0,
            damp: 0.0,
            inertial: Matrix3::zeros(),
        };
        solve(self, &sys, asm, rb, rn, dq, dun)
    }

    #[inline]
    fn load(&self, drive: &SpaceDrive<'_>, t: f64) -> (Vector6<f64>, f64, [Vector3<f64>; 3]) {
        let g = drive.ground(t);
        let fd = drive.force(t);
        let vertical = drive.vertical_force(t);
        let fz = vertical - self.weight();
        (Vector6::new(fd.x, fd.y, fz, 0.0, 0.0, 0.0), vertical, g)
    }

    /// The load at t = 0: the excitation and the weight (the vertical load enters from
    /// the first step).
    fn initial_load(&self, drive: &SpaceDrive<'_>) -> (Vector6<f64>, f64, [Vector3<f64>; 3]) {
        let g0 = drive.ground(0.0);
        let f0 = drive.force(0.0);
        let f = Vector6::new(f0.x, f0.y, -self.weight(), 0.0, 0.0, 0.0);
        (f, 0.0, g0)
    }

    fn initial_acceleration(&self, out: Vector6<f64>) -> Vector6<f64> {
        let m = self.body.mass;
        let mut a = Vector6::new(out[0] / m, out[1] / m, out[2] / m, 0.0, 0.0, 0.0);
        if self.body.rotation {
            if let Some(a_rot) = self.body.inertia.lu().solve(&out.fixed_rows::<3>(3)) {
                a.fixed_rows_mut::<3>(3).copy_from(&a_rot);
            }
        }
        a
    }

    /// (X, 0): the step's unknowns are X and the rotation Θ since the step's start.
    #[inline]
    fn reference(p: &Placement) -> Vector6<f64> {
        let mut v = Vector6::zeros();
        v.fixed_rows_mut::<3>(0).copy_from(&p.x);
        v
    }

    #[inline]
    fn predict(&self, n: &State<6, 3, Self>, h: f64) -> Vector6<f64> {
        let mut q = Vector6::zeros();
        q.fixed_rows_mut::<3>(0).copy_from(
            &(n.pose.x + n.v.fixed_rows::<3>(0) * h + n.a.fixed_rows::<3>(0) * (0.5 * h * h)),
        );
        if self.body.rotation {
            q.fixed_rows_mut::<3>(3)
                .copy_from(&(n.v.fixed_rows::<3>(3) * h + n.a.fixed_rows::<3>(3) * (0.5 * h * h)));
        }
        q
    }

    fn predict_nodes(
        &self,
        un: &mut [Vector3<f64>],
        to: &[Vector3<f64>; 3],
        from: &[Vector3<f64>; 3],
    ) {
        for u in un {
            *u += to[0] - from[0];
        }
    }

    #[inline]
    fn assemble(
        &mut self,
        q: &Vector6<f64>,
        from: &Placement,
        un: &mut [Vector3<f64>],
        g: &[Vector3<f64>; 3],
        asm: &mut SpaceAssembly,
    ) -> Pose {
        let p = pose(q, &from.r);
        SpaceModel::assemble(self, &p, un, &g[0], asm);
        p
    }

    #[inline]
    fn body_force(asm: &SpaceAssembly) -> &Vector6<f64> {
        &asm.pb
    }

    #[inline]
    fn node_forces(asm: &SpaceAssembly) -> &[Vector3<f64>] {
        &asm.pn
    }

    #[inline]
    fn damping(&self, v: &Vector6<f64>, g: &[Vector3<f64>; 3]) -> Vector6<f64> {
        damping(self.body.damping, v, &g[1])
    }

    #[inline]
    fn inertia(&self, a: &Vector6<f64>, v: &Vector6<f64>) -> Vector6<f64> {
        inertia_force(self, a, v)
    }

    fn solve_step(
        &self,
        nm: &Newmark,
        v: &Vector6<f64>,
        asm: &mut SpaceAssembly,
        rb: &Vector6<f64>,
        rn: &[Vector3<f64>],
        dq: &mut Vector6<f64>,
        dun: &mut [Vector3<f64>],
    ) -> bool {
        let Newmark { c0, c1, s, .. } = *nm;
        let j = self.body.inertia;
        let om = v.fixed_rows::<3>(3).into_owned();
        let sys = SpaceSystem {
            c0,
            s,
            damp: s * self.body.damping * c1,
            inertial: if self.body.rotation {
                j * c0 + (skew(&om) * j - skew(&(j * om))) * c1
            } else {
                Matrix3::zeros()
            },
        };
        solve(self, &sys, asm, rb, rn, dq, dun)
    }

    #[inline]
    fn displacement_squared(_q: &Vector6<f64>, at: &Pose, from: &Placement) -> f64 {
        at.x.norm_squared() + (from.psi + at.theta).norm_squared()
    }

    #[inline]
    fn pose(_q: &Vector6<f64>, at: &Pose) -> Placement {
        Placement {
            x: at.x,
            r: at.r,
            psi: log(&at.r),
        }
    }

    fn commit_step(
        &mut self,
        _asm: &SpaceAssembly,
        un: &mut [Vector3<f64>],
        g: &[Vector3<f64>; 3],
    ) {
        SpaceModel::commit_step(self, un, &g[0]);
    }

    fn restore(&mut self) {
        SpaceModel::restore(self);
    }

    fn snapshot<'s>(
        n: &State<6, 3, Self>,
        un: &'s [SVector<f64, 3>],
        statics: &Placement,
        _asm: &SpaceAssembly,
    ) -> SpaceSnapshot<'s> {
        SpaceSnapshot {
            t: n.t,
            x: n.pose.x,
            r: n.pose.r,
            v: n.v,
            a: n.a,
            un,
            ground: n.g,
            x_static: statics.x,
        }
    }
}

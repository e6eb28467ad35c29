//! How the ground moves, as the time loop drives it ([`StepDrive`]): the route
//! ([`Drive`]: a force on the mass, a kinematic ground or an inertial force, or nothing)
//! over the ground's tables, in one horizontal line with its vertical component
//! ([`LineDrive`], the planar scenes) or in plan ([`PlanDrive`], the 3D scenes). The
//! rigs read the step's loads from the drive ([`crate::time_loop::Rig::load`]); the
//! recorders read the frame the outputs are measured in.

use rapier3d_f64::prelude::*;

use super::ground::{GroundTable, VerticalTable};
use super::space_axes::{norm, sub, to_world};
use super::time_loop::StepDrive;
use super::world::GroundKind;
use rockslide_core::case::{Excitation, Signal, Spatial, Vertical};

/// How the excitation enters the rapier world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Drive {
    /// Force M·a(t) on the structure (mass acceleration), or nothing (free response).
    AppliedForce,
    /// Kinematic ground moved to xg(t).
    KinematicGround,
    /// Fixed ground, −m·ag on every dynamic body.
    InertialForce,
}

impl Drive {
    /// The ground body this drive needs.
    pub fn ground_kind(self) -> GroundKind {
        match self {
            Drive::KinematicGround => GroundKind::Kinematic,
            _ => GroundKind::Fixed,
        }
    }
}

/// Mean of a mass-acceleration signal over [t, t + dt] (Simpson's rule), m/s².
pub(crate) fn mean_over_step(s: &Signal, t: f64, dt: f64) -> f64 {
    (s.value(t) + 4.0 * s.value(t + 0.5 * dt) + s.value(t + dt)) / 6.0
}

/// The force channel: M·a(t) for mass acceleration, −M·ag(t) for ground motion.
pub(crate) fn force_at(excitation: &Excitation, m: f64, t: f64) -> f64 {
    match excitation {
        Excitation::None => 0.0,
        Excitation::MassAcceleration(s) => m * s.value(t),
        Excitation::GroundDisplacement(s) => -m * s.second_derivative(t),
        Excitation::GroundAcceleration(s) => -m * s.value(t),
    }
}

/// The drive of a planar scene: the route over the ground's horizontal and vertical
/// tables at the rapier step times.
pub(crate) struct LineDrive<'a> {
    /// The route.
    pub(crate) route: Drive,
    /// The scene's (horizontal) excitation.
    pub(crate) excitation: &'a Excitation,
    /// The ground at the rapier step times, with the vertical component if any.
    pub(crate) ground: GroundTable,
    /// rapier's step, s.
    pub(crate) dt: f64,
}

impl<'a> LineDrive<'a> {
    /// `route` over `excitation` (and `vertical`) at rapier steps of `dt`.
    pub(crate) fn new(
        route: Drive,
        excitation: &'a Excitation,
        vertical: Option<&rockslide_core::case::Vertical>,
        dt: f64,
    ) -> Self {
        Self {
            route,
            excitation,
            ground: GroundTable::new(excitation, dt).with_vertical(vertical, dt),
            dt,
        }
    }

    /// Where the recorder measures from at step `k`: the moving ground's (displacement,
    /// velocity) for a kinematic ground, zero for a fixed one.
    pub(crate) fn frame(&self, k: usize) -> (f64, f64) {
        if self.route == Drive::KinematicGround {
            (self.ground.disp(k), self.ground.vel(k))
        } else {
            (0.0, 0.0)
        }
    }

    /// Height of the ground at step `k` in the frame the recorder measures from: the
    /// moving ground's yg for a kinematic ground, 0 for a fixed one.
    pub(crate) fn height(&self, k: usize) -> f64 {
        match (&self.ground.vertical, self.route) {
            (Some(v), Drive::KinematicGround) => v.disp(k),
            _ => 0.0,
        }
    }

    /// The vertical ground acceleration a body feels as a force over the output step
    /// ending at `k` (`stride` rapier steps of `dt_out`/stride), m/s²: its mean on the
    /// fixed-ground routes, 0 on the kinematic one (there the body's own acceleration is
    /// absolute).
    pub(crate) fn vertical_acceleration(&self, k: usize, stride: usize, dt_out: f64) -> f64 {
        match (&self.ground.vertical, self.route) {
            (Some(_), Drive::KinematicGround) | (None, _) => 0.0,
            (Some(v), _) if k >= stride => (v.vel(k) - v.vel(k - stride)) / dt_out,
            _ => 0.0,
        }
    }

    /// The horizontal force per unit mass on the structure over step k → k+1 on the
    /// fixed-ground routes: the mass acceleration's Simpson mean (applied force), or
    /// −(vg(k+1) − vg(k))/Δt (inertial force, the `ag` it returns second, which every
    /// other dynamic body feels too); zero on the kinematic ground.
    pub(crate) fn horizontal(&self, k: usize) -> (Option<f64>, f64) {
        let t = k as f64 * self.dt;
        let ag = match self.route {
            Drive::InertialForce => self.ground.mean_acceleration(k, self.dt),
            _ => 0.0,
        };
        let mass_acc = match (self.route, self.excitation) {
            (Drive::AppliedForce, Excitation::MassAcceleration(s)) => {
                Some(mean_over_step(s, t, self.dt))
            }
            _ => None,
        };
        (mass_acc, ag)
    }

    /// The vertical ground acceleration over step k → k+1 that the fixed-ground routes
    /// apply as −m·a_v on every dynamic body (a_v positive upward), if any.
    pub(crate) fn vertical(&self, k: usize) -> Option<f64> {
        let v = self.ground.vertical.as_ref()?;
        (self.route != Drive::KinematicGround).then(|| (v.vel(k + 1) - v.vel(k)) / self.dt)
    }

    /// With the inertial-force route a ground velocity that jumps at t = 0 gives every
    /// body the relative velocity −vg(0⁺) in the ground's frame.
    pub(crate) fn start(&self, world: &mut PhysicsWorld, bodies: &[(RigidBodyHandle, f64)]) {
        if self.route == Drive::InertialForce && self.ground.vel(0) != 0.0 {
            for &(h, _) in bodies {
                world.bodies[h].set_linvel(Vector::new(-self.ground.vel(0), 0.0, 0.0), false);
            }
        }
    }
}

impl StepDrive for LineDrive<'_> {
    /// The kinematic ground to xg(t_{n+1}), and with a vertical component from where it
    /// started (the rigs place it differently) to yg(t_{n+1}).
    fn move_ground(&self, world: &mut PhysicsWorld, ground: RigidBodyHandle, k: usize) {
        if self.route != Drive::KinematicGround {
            return;
        }
        let body = &mut world.bodies[ground];
        let y = body.translation().y;
        body.set_next_kinematic_translation(Vector::new(self.ground.disp(k + 1), y, 0.0));
        if let Some(v) = &self.ground.vertical {
            let body = &mut world.bodies[ground];
            let y = body.translation().y - v.disp(k) + v.disp(k + 1);
            body.set_next_kinematic_translation(Vector::new(self.ground.disp(k + 1), y, 0.0));
        }
    }
}

/// The excitation of the same kind as `ex` with signal `s` (the `[excitation.y]`
/// component's own excitation).
fn same_kind(ex: &Excitation, s: Signal) -> Excitation {
    match ex {
        Excitation::None => Excitation::None,
        Excitation::MassAcceleration(_) => Excitation::MassAcceleration(s),
        Excitation::GroundDisplacement(_) => Excitation::GroundDisplacement(s),
        Excitation::GroundAcceleration(_) => Excitation::GroundAcceleration(s),
    }
}

/// The excitation pair as the time loop reads it, every table built before the loop:
/// the ground's plan displacement and velocity at the rapier step times, and the
/// mass-acceleration signals.
pub(crate) struct PlanDrive<'a> {
    pub(crate) drive: Drive,
    pub(crate) first: &'a Excitation,
    second: Excitation,
    e1: [f64; 2],
    e2: [f64; 2],
    /// The first component's ground motion at the step times (evaluated when asked for).
    g1: GroundTable,
    /// The second component's.
    g2: GroundTable,
    /// The vertical ground motion the drive moves the ground by (or pushes the body
    /// with), if it carries one ([`PlanDrive::with_vertical`]).
    vertical: Option<VerticalTable>,
    /// rapier's steps in the run.
    n: usize,
    /// rapier's step, s.
    dt: f64,
}

impl<'a> PlanDrive<'a> {
    /// The drive of `n` rapier steps of `dt` (the ground evaluated at each step's time
    /// when asked for: no table grows with the run).
    pub(crate) fn new(
        drive: Drive,
        ex: &'a Excitation,
        spatial: &Spatial,
        dt: f64,
        n: usize,
    ) -> Self {
        let second = spatial
            .second
            .as_ref()
            .map_or(Excitation::None, |s| same_kind(ex, s.clone()));
        let (e1, e2) = (spatial.first_direction(), spatial.second_direction());
        let g1 = GroundTable::new(ex, dt);
        let g2 = GroundTable::new(&second, dt);
        Self {
            drive,
            first: ex,
            second,
            e1,
            e2,
            g1,
            g2,
            vertical: None,
            n,
            dt,
        }
    }

    /// The same drive carrying the vertical ground motion `vertical` (if any) by the
    /// planar routes: the kinematic ground moved to y_g(t_{n+1}) as well, or −m·a_v on
    /// the body over each step on a fixed ground ([`PlanDrive::vertical_force`]).
    pub(crate) fn with_vertical(self, vertical: Option<&Vertical>) -> Self {
        Self {
            vertical: vertical.map(|v| VerticalTable::new(v, self.dt)),
            ..self
        }
    }

    /// Whether the drive carries a vertical component.
    pub(crate) fn has_vertical(&self) -> bool {
        self.vertical.is_some()
    }

    /// The vertical force per unit mass on a body over step k → k+1 on a fixed ground,
    /// −(vg_y(k+1) − vg_y(k))/Δt (a_v positive upward); zero on the kinematic ground
    /// (the ground itself moves) and without a vertical component.
    pub(crate) fn vertical_force(&self, k: usize) -> f64 {
        match (&self.vertical, self.drive) {
            (Some(v), Drive::AppliedForce | Drive::InertialForce) => {
                -(v.vel(k + 1) - v.vel(k)) / self.dt
            }
            _ => 0.0,
        }
    }

    /// The ground's height at step `k` in the frame the recorder measures from: y_g on
    /// the kinematic route, 0 on a fixed ground.
    pub(crate) fn height(&self, k: usize) -> f64 {
        match (&self.vertical, self.drive) {
            (Some(v), Drive::KinematicGround) => v.disp(k),
            _ => 0.0,
        }
    }

    /// x_g(t_k) in plan, m.
    pub(crate) fn disp(&self, k: usize) -> [f64; 2] {
        self.comb(self.g1.disp(k), self.g2.disp(k))
    }

    /// v_g(t_k⁺) in plan, m/s.
    fn vel(&self, k: usize) -> [f64; 2] {
        self.comb(self.g1.vel(k), self.g2.vel(k))
    }

    fn comb(&self, a: f64, b: f64) -> [f64; 2] {
        [
            a * self.e1[0] + b * self.e2[0],
            a * self.e1[1] + b * self.e2[1],
        ]
    }

    /// Force per unit mass on a body over step k → k+1 (fixed-ground routes): the mass
    /// acceleration's Simpson mean, or −(v_g(k+1) − v_g(k))/Δt; zero on a kinematic
    /// ground (the ground itself moves).
    pub(crate) fn specific_force(&self, k: usize) -> [f64; 2] {
        let t = k as f64 * self.dt;
        match self.drive {
            Drive::AppliedForce => {
                let mean = |ex: &Excitation| match ex {
                    Excitation::MassAcceleration(s) => mean_over_step(s, t, self.dt),
                    _ => 0.0,
                };
                self.comb(mean(self.first), mean(&self.second))
            }
            Drive::InertialForce => {
                let dv = sub(self.vel(k + 1), self.vel(k));
                [-dv[0] / self.dt, -dv[1] / self.dt]
            }
            Drive::KinematicGround => [0.0, 0.0],
        }
    }

    /// The frame the outputs are measured in at step k: the moving ground's (x_g, v_g)
    /// on the kinematic route, zero on a fixed ground.
    pub(crate) fn frame(&self, k: usize) -> ([f64; 2], [f64; 2]) {
        if self.drive == Drive::KinematicGround {
            (self.disp(k), self.vel(k))
        } else {
            ([0.0, 0.0], [0.0, 0.0])
        }
    }

    /// The force channel at `t` in plan: M·a(t) for a mass acceleration, −M·a_g(t) for
    /// ground motion.
    pub(crate) fn force(&self, m: f64, t: f64) -> [f64; 2] {
        self.comb(force_at(self.first, m, t), force_at(&self.second, m, t))
    }

    /// At t = 0 on the inertial route, a ground velocity that jumps gives the body the
    /// relative velocity −v_g(0⁺).
    pub(crate) fn start(&self, world: &mut PhysicsWorld, body: RigidBodyHandle) {
        let v0 = self.vel(0);
        if self.drive == Drive::InertialForce && v0 != [0.0, 0.0] {
            world.bodies[body].set_linvel(to_world([-v0[0], -v0[1]], 0.0), false);
        }
    }

    /// Σ |Δv_g| over the run's steps: ∫|a_g|dt of the plan ground acceleration (vector norm),
    /// m/s.
    pub(crate) fn abs_acceleration_integral(&self) -> f64 {
        (0..self.n)
            .map(|k| norm(sub(self.vel(k + 1), self.vel(k))))
            .sum()
    }
}

impl StepDrive for PlanDrive<'_> {
    /// Before step k → k+1 on the kinematic route: the ground's next plan position, and
    /// with a vertical component its next height (from where it stands: the rigs place
    /// it differently) y_g(t_{n+1}).
    fn move_ground(&self, world: &mut PhysicsWorld, ground: RigidBodyHandle, k: usize) {
        if self.drive == Drive::KinematicGround {
            let g = &mut world.bodies[ground];
            let mut up = g.translation().y;
            if let Some(v) = &self.vertical {
                up += v.disp(k + 1) - v.disp(k);
            }
            g.set_next_kinematic_translation(to_world(self.disp(k + 1), up));
        }
    }
}

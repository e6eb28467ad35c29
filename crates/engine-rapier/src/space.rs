//! rapier on a bidirectional (3D) scene (`Scene::spatial`), its native setting: the
//! excitation pair drives the bodies in both horizontal directions at once.
//!
//! - the rigid block: a cuboid 2b × 2h × 2d on a ground slab with contact friction μ,
//!   free to slide, lift and yaw, its tipping rotations locked; rapier's 3D friction is a
//!   circular cone per friction constraint (the tangential impulse is solved as a coupled
//!   2 × 2 system, Δλ = −K⁻¹·Δv, and capped in magnitude, `simd_cap_magnitude`, in
//!   `contact_constraint_element.rs` of rapier 0.36); with the tipping locked K = I/m, so
//!   the capped impulse opposes the slip in every direction (free to tip, K holds h²/I
//!   about each horizontal axis and a slab slid 6.6° off its drive);
//! - the oscillator (PEPO): one body free in the horizontal plane (rotations and the
//!   vertical locked, no collider) with its contact as an applied force the engine
//!   computes after every rapier step: the spring Kx·(u − p) in series with a massless
//!   slider p, returned radially onto the circle |F| ≤ μ·M·g (the circular cone), plus
//!   the viscous C·u̇; rapier integrates the body (symplectic Euler), at the planar
//!   oscillator's step rule ([`OscillatorSteps`]).
//!
//! Axes: scene (x, y, z up) is rapier's (X, −Z, Y), so the frame stays right-handed.
//! The ground moves by either route of the planar engine (`Drive`): a kinematic ground
//! moved to x_g(t_{n+1}) in plan each step, or a fixed ground with the inertial force
//! −m·(v_g(n+1) − v_g(n))/Δt on the body. Traces keep the planar keys for x and add the
//! catalogue's y channels, the resultant sliding and its azimuth; the contact block gives
//! |T|, N and the slip accumulated along the friction force (Σ T̂·Δs, so that |T|·Δslip
//! is the friction work T·Δs the dissipation invariant judges). The rocking body on its
//! nx × ny grid of supports is [`super::space_rocking`]; vertical motion in a 3D scene is
//! not modelled here ("not applicable", with why).

use rapier3d_f64::prelude::*;

use super::contact_forces::ground_force;
use super::ground::GroundTable;
use super::rows::{PathLength, layout};
use super::settings::{OscillatorSteps, RapierSettings, StepRule};
use super::simulate::{Drive, force_at, mean_over_step};
use super::vertical::VerticalTable;
use super::world::{GroundKind, add_ground, new_world, rapier_friction};
use super::{MAX_BLOCK_STEPS, block_stride};
use rockslide_core::case::{
    Case, Excitation, Model, NormalForce, Oscillator, RigidBlock, Scene, Signal, Spatial, Vertical,
};
use rockslide_core::error::InputError;
use rockslide_core::trace::{ContactState, Quantity, Trace, plan_slip_increment, q};
use rockslide_engine_api::{NotApplicable, Run, RunStatus, SolverStats, StepSink, step_count};

/// A plan vector (x, y) as a rapier vector at height `up`.
pub(crate) fn to_world(p: [f64; 2], up: f64) -> Vector {
    Vector::new(p[0], up, -p[1])
}

/// The plan part (x, y) of a rapier vector.
pub(crate) fn plan(v: Vector) -> [f64; 2] {
    [v.x, -v.z]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

/// Azimuth of a plan vector, degrees from +x toward +y (0 for the zero vector).
fn azimuth_deg(a: [f64; 2]) -> f64 {
    if a == [0.0, 0.0] {
        0.0
    } else {
        a[1].atan2(a[0]).to_degrees()
    }
}

/// Why rapier does not run a 3D scene, if it does not. A vertical component is the
/// oscillator's only ([`PlanVertical`]: its support's Kz, as in 2D).
pub fn check(scene: &Scene) -> Result<(), NotApplicable> {
    if let Some(v) = scene.vertical() {
        return match &scene.model {
            Model::Oscillator(_) if v.normal_force == NormalForce::QuasiStatic => Err(NotApplicable(
                "rapier's oscillator in plan under vertical motion stands on its vertical stiffness Kz: a rigid vertical contact (normal_force = \"quasi-static\") is not its model".into(),
            )),
            Model::RockingBody(_) if v.normal_force == NormalForce::QuasiStatic => Err(NotApplicable(
                "rapier's rocking body in plan stands on its supports' Kz: a rigid vertical contact (normal_force = \"quasi-static\") is not its model".into(),
            )),
            Model::Oscillator(o) if o.double.is_some() => Err(NotApplicable(
                "rapier models vertical motion in plan on the single contact, not the double arrangement".into(),
            )),
            Model::Oscillator(_) | Model::RockingBody(_) => Ok(()),
            Model::RigidBlock(_) => Err(NotApplicable(
                "vertical excitation in a bidirectional (3D) scene is not yet modelled for rapier's rigid block (the slab block in plan is not built for it)".into(),
            )),
        };
    }
    match &scene.model {
        Model::RigidBlock(b) if b.initial_tilt != 0.0 => Err(NotApplicable(
            "an initially tilted rigid block in a bidirectional (3D) scene is not yet modelled in rapier (3D rocking is not built)".into(),
        )),
        _ => Ok(()),
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
            n,
            dt,
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

    /// Before step k → k+1 on the kinematic route: the ground's next plan position.
    pub(crate) fn move_ground(&self, world: &mut PhysicsWorld, ground: RigidBodyHandle, k: usize) {
        if self.drive == Drive::KinematicGround {
            let g = &mut world.bodies[ground];
            let up = g.translation().y;
            g.set_next_kinematic_translation(to_world(self.disp(k + 1), up));
        }
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
    fn abs_acceleration_integral(&self) -> f64 {
        (0..self.n)
            .map(|k| norm(sub(self.vel(k + 1), self.vel(k))))
            .sum()
    }
}

/// What a 3D run produced.
pub struct Outcome {
    /// The recorded channels.
    pub trace: Trace,
    /// How it ended.
    pub status: RunStatus,
    /// rapier steps taken.
    pub steps: u64,
}

/// The channels every 3D run records (the x channels keep the planar keys).
pub(crate) fn plan_channels(moves: bool) -> Vec<&'static Quantity> {
    let mut c = vec![
        &q::FORCE,
        &q::RESISTANCE,
        &q::REL_DISP,
        &q::REL_DISP_Y,
        &q::SLIDE,
        &q::SLIDE_Y,
        &q::VEL,
        &q::VEL_Y,
        &q::ACC,
        &q::SLIDE_RESULTANT,
        &q::SLIDE_AZIMUTH,
        &q::NORMAL,
    ];
    if moves {
        c.push(&q::GROUND_DISP);
    }
    c
}

/// One output row of a 3D run, in [`plan_channels`] order.
struct PlanRow {
    force: [f64; 2],
    resistance: f64,
    rel_disp: [f64; 2],
    slide: [f64; 2],
    vel: [f64; 2],
    acc: f64,
    normal: f64,
    ground: f64,
}

impl PlanRow {
    fn write(&self, out: &mut [f64]) {
        let vals = [
            self.force[0],
            self.resistance,
            self.rel_disp[0],
            self.rel_disp[1],
            self.slide[0],
            self.slide[1],
            self.vel[0],
            self.vel[1],
            self.acc,
            norm(self.slide),
            azimuth_deg(self.slide),
            self.normal,
            self.ground,
        ];
        let len = out.len();
        out.copy_from_slice(&vals[..len]);
    }
}

/// After step k → k+1 (`k1` = k + 1): `Diverged` when a body's pose is not finite.
pub(crate) fn diverged(world: &PhysicsWorld, k1: usize, dt: f64) -> Option<RunStatus> {
    let finite = world
        .bodies
        .iter()
        .all(|(_, b)| b.translation().is_finite() && b.rotation().is_finite());
    (!finite).then(|| RunStatus::Diverged {
        time: k1 as f64 * dt,
        reason: "a body's position is not finite".into(),
    })
}

/// The oscillator's contact in plan: a spring Kx in series with a massless slider p
/// (relative to the ground), the spring force returned radially onto |F| ≤ R = μ·M·g.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlanSlider {
    kx: f64,
    limit: f64,
    /// Slider position, m.
    pub(crate) p: [f64; 2],
}

impl PlanSlider {
    /// Radial return after a step that took the mass to `u` (relative to the ground):
    /// where Kx·|u − p| > R the slider follows along u − p so that |F| = R. Returns the
    /// spring force on the ground side, F = Kx·(u − p), |F| ≤ R.
    pub(crate) fn update(&mut self, u: [f64; 2]) -> [f64; 2] {
        radial_return(self.kx, self.limit, &mut self.p, u)
    }
}

/// The plan oscillator's vertical contact under a vertical component: the mass is free
/// vertically too, on a compression-only spring Kz (no collider: an applied force, as the
/// plan contact), from static rest compressed by M·g/Kz. World gravity is 0; the engine
/// applies N − M·g − M·a_v over each step, a_v the step's mean (−m·(vg_y(n+1) −
/// vg_y(n))/Δt, every route: the vertical is in the ground's frame), N = Kz·δ after the
/// step (0 once the spring opens), and caps the plan slider at μ·N.
pub(crate) struct PlanVertical {
    kz: f64,
    mass: f64,
    weight: f64,
    /// vg_y(t_k⁺) at the rapier steps, m/s, evaluated when asked for.
    vel: VerticalTable,
    dt: f64,
}

impl PlanVertical {
    /// For rapier steps of `dt`.
    pub(crate) fn new(osc: &Oscillator, vertical: &Vertical, dt: f64) -> Self {
        PlanVertical {
            kz: osc.contact.kz,
            mass: osc.mass,
            weight: osc.normal_force(),
            vel: VerticalTable::new(vertical, dt),
            dt,
        }
    }

    /// The body's height at static rest (the spring compressed by M·g/Kz), m.
    fn rest_height(&self) -> f64 {
        -self.weight / self.kz
    }

    /// N = Kz·δ for a body at `height` (δ = −height), compression only, N.
    fn normal(&self, height: f64) -> f64 {
        (-self.kz * height).max(0.0)
    }

    /// The vertical force on the body over step k → k+1 given the normal force `n`.
    fn force(&self, n: f64, k: usize) -> f64 {
        n - self.weight - self.mass * (self.vel.vel(k + 1) - self.vel.vel(k)) / self.dt
    }
}

/// The radial return of a spring `k` in series with a slider `p` on the circle of radius
/// `limit` (the circular friction cone), after a step that left the spring's end at `u`:
/// where k·|u − p| > limit the slider follows along u − p so that |F| = limit. Returns the
/// spring force on the ground side, F = k·(u − p), |F| ≤ limit.
pub(crate) fn radial_return(k: f64, limit: f64, p: &mut [f64; 2], u: [f64; 2]) -> [f64; 2] {
    let e = sub(u, *p);
    let f = [k * e[0], k * e[1]];
    let size = norm(f);
    if size > limit {
        let scale = limit / size;
        *p = [u[0] - e[0] * scale, u[1] - e[1] * scale];
        [f[0] * scale, f[1] * scale]
    } else {
        f
    }
}

/// Run the oscillator (PEPO) in plan: `n` output steps of `dt`, each `stride` rapier
/// steps, the drive's tables at the rapier step.
pub fn run_oscillator(
    osc: &Oscillator,
    settings: &RapierSettings,
    (pd, vertical): (&PlanDrive, Option<&PlanVertical>),
    (dt, stride): (f64, usize),
    n: usize,
    sink: &mut dyn StepSink,
) -> Outcome {
    let dt_in = dt / stride as f64;
    let mut world = new_world(settings, dt_in, 0.0);
    let ground_body = match pd.drive.ground_kind() {
        GroundKind::Fixed => RigidBodyBuilder::fixed(),
        GroundKind::Kinematic => RigidBodyBuilder::kinematic_position_based(),
    };
    let ground = world.insert_body(ground_body);
    let m = osc.mass;
    let body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(
            0.0,
            vertical.map_or(0.0, |v| v.rest_height()),
            0.0,
        ))
        .additional_mass_properties(MassProperties::new(Vector::ZERO, m, Vector::ONE))
        .enabled_translations(true, vertical.is_some(), true)
        .lock_rotations()
        .can_sleep(false);
    let mass = world.insert_body(body);
    pd.start(&mut world, mass);
    let moves = pd.first.moves_ground();
    let channels = plan_channels(moves);
    // The one contact, |T| = |F| ≤ μ·N: compliance 0 without vertical motion, 1/Kz with.
    let trace = layout(&channels, 1, vertical.map_or(0.0, |v| 1.0 / v.kz));
    sink.begin(&trace);
    let mut row = vec![0.0; channels.len()];
    let mut slider = PlanSlider {
        kx: osc.contact.kx,
        limit: osc.friction_limit(),
        p: [0.0, 0.0],
    };
    let c = osc.damping();
    let mu = osc.contact.mu;
    let mut normal = osc.normal_force();
    let relative = |world: &PhysicsWorld, k: usize| {
        let (xg, vg) = pd.frame(k);
        let b = &world.bodies[mass];
        (sub(plan(b.translation()), xg), sub(plan(b.linvel()), vg))
    };
    let mut spring = [0.0, 0.0];
    let mut v_prev = 0.0;
    let (mut p_prev, mut path) = ([0.0, 0.0], 0.0);
    let height = |world: &PhysicsWorld| world.bodies[mass].translation().y;
    let mut record = |out: &mut dyn StepSink,
                      world: &PhysicsWorld,
                      k: usize,
                      (spring, p): ([f64; 2], [f64; 2]),
                      normal: f64| {
        {
            let t = (k / stride) as f64 * dt;
            let (u, v) = relative(world, k);
            let acc = if k == 0 { 0.0 } else { (v[0] - v_prev) / dt };
            v_prev = v[0];
            PlanRow {
                force: pd.force(m, t),
                resistance: spring[0],
                rel_disp: u,
                slide: p,
                vel: v,
                acc,
                normal,
                ground: pd.disp(k)[0],
            }
            .write(&mut row);
            path += plan_slip_increment(spring, sub(p, p_prev));
            p_prev = p;
            let state = ContactState {
                normal,
                tangential: norm(spring),
                slip: path,
                gap: if vertical.is_some() {
                    height(world)
                } else {
                    0.0
                },
            };
            out.row(t, &row, &[state]);
        }
    };
    record(sink, &world, 0, (spring, slider.p), normal);
    let mut status = RunStatus::Completed;
    let mut steps = 0;
    for k in 0..n * stride {
        let (_, v) = relative(&world, k);
        let a = pd.specific_force(k);
        let f = [
            m * a[0] - spring[0] - c * v[0],
            m * a[1] - spring[1] - c * v[1],
        ];
        let up = vertical.map_or(0.0, |v| v.force(normal, k));
        let b = &mut world.bodies[mass];
        b.reset_forces(false);
        b.add_force(to_world(f, up), false);
        pd.move_ground(&mut world, ground, k);
        world.step();
        steps += 1;
        if let Some(d) = diverged(&world, k + 1, dt_in) {
            status = d;
            break;
        }
        if let Some(v) = vertical {
            normal = v.normal(height(&world));
            slider.limit = mu * normal;
        }
        let (u, _) = relative(&world, k + 1);
        spring = slider.update(u);
        if (k + 1) % stride == 0 {
            record(sink, &world, k + 1, (spring, slider.p), normal);
        }
    }
    Outcome {
        trace,
        status,
        steps,
    }
}

/// Run the rigid block in plan: a cuboid 2b × 2h × 2d on the ground slab, friction μ
/// on both colliders (rule Average → μ), restitution 0, free in x, y, z and yaw; its
/// tipping rotations (about the horizontal axes) are locked: the rigid-plastic block of
/// the reference, and the friction's tangent effective mass isotropic (module docs).
pub fn run_block(
    b: &RigidBlock,
    half_depth: f64,
    settings: &RapierSettings,
    pd: &PlanDrive,
    (dt, stride): (f64, usize),
    n: usize,
    sink: &mut dyn StepSink,
) -> Outcome {
    let dt_in = dt / stride as f64;
    let mu = rapier_friction(b.mu);
    let mut world = new_world(settings, dt_in, b.gravity);
    let ground = add_ground(&mut world, pd.drive.ground_kind(), mu);
    let body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, b.half_height, 0.0))
        // rapier's axes (x, up, −y): yaw only.
        .enabled_rotations(false, true, false)
        .can_sleep(false);
    let collider = ColliderBuilder::cuboid(b.half_width, b.half_height, half_depth)
        .mass(b.mass)
        .friction(mu)
        .friction_combine_rule(CoefficientCombineRule::Average)
        .restitution(0.0)
        .restitution_combine_rule(CoefficientCombineRule::Min);
    let block = world.insert(body, collider).0;
    pd.start(&mut world, block);
    let moves = pd.first.moves_ground();
    let channels = plan_channels(moves);
    let trace = layout(&channels, 1, 0.0);
    sink.begin(&trace);
    let mut row = vec![0.0; channels.len()];
    let m = b.mass;
    let start = plan(world.bodies[block].translation());
    let mut v_prev = [0.0, 0.0];
    let (mut u_prev, mut path) = ([0.0, 0.0], 0.0);
    let mut record = |out: &mut dyn StepSink, world: &PhysicsWorld, k: usize| {
        let t = (k / stride) as f64 * dt;
        let (xg, vg) = pd.frame(k);
        let body = &world.bodies[block];
        let u = sub(sub(plan(body.translation()), start), xg);
        let v = sub(plan(body.linvel()), vg);
        let acc = if k == 0 { 0.0 } else { (v[0] - v_prev[0]) / dt };
        v_prev = v;
        // The ground's force on the block over the last substep, from rapier's contact
        // impulses (R resists +x: R = −T_x).
        let gf = ground_force(world, block, ground, dt_in);
        let resistance = if k == 0 { 0.0 } else { -gf.x };
        PlanRow {
            force: pd.force(m, t),
            resistance,
            rel_disp: u,
            slide: u,
            vel: v,
            acc,
            normal: gf.y,
            ground: pd.disp(k)[0],
        }
        .write(&mut row);
        // T resists the block's motion relative to the ground: minus the ground's force.
        let t_plan = [-gf.x, gf.z];
        path += plan_slip_increment(t_plan, sub(u, u_prev));
        u_prev = u;
        let state = ContactState {
            normal: gf.y,
            tangential: norm(t_plan),
            slip: path,
            gap: gf.dist.unwrap_or(0.0),
        };
        out.row(t, &row, &[state]);
    };
    record(sink, &world, 0);
    let mut status = RunStatus::Completed;
    let mut steps = 0;
    for k in 0..n * stride {
        let a = pd.specific_force(k);
        let body = &mut world.bodies[block];
        body.reset_forces(false);
        body.add_force(to_world([m * a[0], m * a[1]], 0.0), false);
        pd.move_ground(&mut world, ground, k);
        world.step();
        steps += 1;
        if let Some(d) = diverged(&world, k + 1, dt_in) {
            status = d;
            break;
        }
        if (k + 1) % stride == 0 {
            record(sink, &world, k + 1);
        }
    }
    Outcome {
        trace,
        status,
        steps,
    }
}

/// rapier steps per output step for the block on a moving kinematic ground under a
/// recorded pair: the planar rule ([`super::block_kinematic_stride`]) with the plan
/// ground's ∫|a_g|dt (vector norm) and the total distance slid along the path S of a
/// pilot run (inertial force at the output step): Δt ≤ 2·ε·S/∫|a_g|dt, at most
/// [`MAX_BLOCK_STEPS`] steps. Returns (stride, S, ∫|a_g|dt, Δt bound).
pub fn block_kinematic_stride(
    case: &Case,
    spatial: &Spatial,
    b: &RigidBlock,
    half_depth: f64,
    settings: &RapierSettings,
    dt: f64,
) -> (usize, f64, f64, f64) {
    let ex = &case.scene.excitation;
    let n = step_count(case.run.duration, dt);
    let pilot_drive = PlanDrive::new(Drive::InertialForce, ex, spatial, dt, n);
    let abs_ag = pilot_drive.abs_acceleration_integral();
    let mut path = PathLength::of(q::SLIDE.key, Some(q::SLIDE_Y.key));
    run_block(b, half_depth, settings, &pilot_drive, (dt, 1), n, &mut path);
    let slid = path.sum;
    let dt_max = 2.0 * settings.accuracy * slid / abs_ag;
    (block_stride(dt, dt_max, n), slid, abs_ag, dt_max)
}

/// The oscillator's steps in plan: the planar rule, or one rapier step per output step
/// with `step_rule = "none"`.
pub fn oscillator_steps(
    osc: &Oscillator,
    ex: &Excitation,
    settings: &RapierSettings,
    dt: f64,
) -> OscillatorSteps {
    let steps = OscillatorSteps::for_scene(osc, ex, dt, settings.accuracy);
    if settings.step_rule == StepRule::None {
        steps.at_output_step(dt)
    } else {
        steps
    }
}

/// The oscillator's steps in plan under a vertical component: the planar rule with its
/// period scaled to the vertical mode √(Kz/M) when that is faster, and no longer than a
/// vertical record's sample step (the 2D rule, [`super::vertical::oscillator_steps`]).
fn vertical_steps(
    osc: &Oscillator,
    ex: &Excitation,
    vertical: &Vertical,
    settings: &RapierSettings,
    dt: f64,
) -> OscillatorSteps {
    let (stride, dt_inner, steps) =
        super::vertical::oscillator_steps(osc, ex, vertical, dt, settings.accuracy);
    let scale = (osc.omega() / (osc.contact.kz / osc.mass).sqrt()).min(1.0);
    OscillatorSteps {
        stride,
        dt_inner,
        dt_max: steps.dt_max * scale,
        ..steps
    }
}

/// What a run states besides its trace: settings and findings, as (name, value) and text.
pub(crate) struct Statement {
    pub(crate) described: Vec<(String, String)>,
    pub(crate) findings: Vec<String>,
}

/// Run `drive` on the 3D scene of `case` at output step `dt`: the block or the
/// oscillator in plan, with the settings and findings the run states.
pub fn run(
    case: &Case,
    spatial: &Spatial,
    drive: Drive,
    (variant, dt): (&str, f64),
    mut settings: RapierSettings,
    grid: Option<&super::space_rocking::RockingGrid>,
    sink: &mut dyn StepSink,
) -> Result<Run, InputError> {
    check(&case.scene).map_err(|e| case.field_error("model.kind", e.0))?;
    let mut said = Statement {
        described: settings.describe(dt),
        findings: Vec::new(),
    };
    let outcome = match &case.scene.model {
        Model::Oscillator(osc) => {
            oscillator_case(case, spatial, osc, drive, dt, &settings, (&mut said, sink))
        }
        Model::RigidBlock(b) => block_case(
            case,
            spatial,
            b,
            drive,
            dt,
            &mut settings,
            (&mut said, sink),
        )?,
        Model::RockingBody(r) => {
            let depth = spatial.depth.ok_or_else(|| {
                case.field_error(
                    "model.half_depth",
                    "is required for a rocking body in a 3D scene",
                )
            })?;
            let ex = &case.scene.excitation;
            let n = step_count(case.run.duration, dt);
            let pd_for =
                |dt_in: f64, steps: usize| PlanDrive::new(drive, ex, spatial, dt_in, steps);
            let grid = grid.cloned().unwrap_or_else(|| {
                super::space_rocking::RockingGrid::from_scene(r, depth, spatial.inertia)
            });
            super::space_rocking::case(
                &grid,
                spatial,
                depth,
                (pd_for, case.scene.vertical()),
                (dt, n),
                &settings,
                (&mut said, sink),
            )
        }
    };
    said.described.push((
        "ground motion".into(),
        match drive {
            Drive::AppliedForce => "fixed ground; mass acceleration pair as force M·a (Simpson mean over the step), in plan",
            Drive::KinematicGround => "kinematic position-based ground moved in plan to x_g(t_{n+1}) each step",
            Drive::InertialForce => "fixed ground; −m·(v_g(n+1) − v_g(n))/Δt in plan on the body, −v_g(0⁺) initial velocity",
        }
        .into(),
    ));
    said.described.push((
        "excitation".into(),
        format!(
            "azimuth {}°{}; scene (x, y, z up) is rapier's (X, −Z, Y)",
            spatial.azimuth_deg,
            if spatial.second.is_some() {
                ", second component at right angles"
            } else {
                ""
            }
        ),
    ));
    Ok(Run {
        engine: "rapier",
        variant: variant.to_string(),
        arrangement: rockslide_engine_api::Arrangement::Single,
        dt,
        settings: said.described.into_iter().map(Into::into).collect(),
        stats: SolverStats {
            substeps_per_step: Some(settings.substeps as u64),
            ..SolverStats::steps(outcome.steps)
        },
        findings: said.findings,
        trace: outcome.trace,
        status: outcome.status,
        wall_seconds: 0.0,
    })
}

/// The oscillator in plan at the planar step rule, with what it states.
fn oscillator_case(
    case: &Case,
    spatial: &Spatial,
    osc: &Oscillator,
    drive: Drive,
    dt: f64,
    settings: &RapierSettings,
    (said, sink): (&mut Statement, &mut dyn StepSink),
) -> Outcome {
    let ex = &case.scene.excitation;
    let n = step_count(case.run.duration, dt);
    let vertical = case.scene.vertical();
    let steps = match vertical {
        Some(v) => vertical_steps(osc, ex, v, settings, dt),
        None => oscillator_steps(osc, ex, settings, dt),
    };
    let pd = PlanDrive::new(drive, ex, spatial, steps.dt_inner, n * steps.stride);
    let pv = vertical.map(|v| PlanVertical::new(osc, v, steps.dt_inner));
    said.described
        .retain(|(k, _)| !k.starts_with("contact softness") && !k.starts_with("friction"));
    said.described.push((
        "contact model".into(),
        if pv.is_some() {
            "applied force in plan: one body free in x, y and z (no collider, rotations locked); the engine computes Kx·(u − p) − C·u̇ after every rapier step, the slider p returned radially onto |F| ≤ μ·N (circular cone, N from the vertical spring), and applies it over the next step (the only model in plan: contact_model is not read)"
        } else {
            "applied force in plan: one body free in x and y (no collider, rotations and the vertical locked); the engine computes Kx·(u − p) − C·u̇ after every rapier step, the slider p returned radially onto |F| ≤ μ·M·g (circular cone), and applies it over the next step (the only model in plan: contact_model is not read)"
        }
        .into(),
    ));
    if pv.is_some() {
        said.described.push((
            "vertical ground motion".into(),
            "the body free vertically too, on a compression-only spring Kz from static rest (an applied force, world gravity 0): N − M·g − M·a_v over each step, a_v the step's mean −(vg_y(n+1) − vg_y(n))/Δt on every route (the vertical in the ground's frame), N = Kz·δ after the step, the slider's circle μ·N".into(),
        ));
    }
    said.described.push((
        "rapier step [s] (output step / stride)".into(),
        format!("{} (stride {})", steps.dt_inner, steps.stride),
    ));
    said.findings.push(format!(
        "{} the engine's validity: rapier step {:.3e} s, the planar oscillator's step rule asks ≤ {:.3e} s for accuracy {}{}; |F| ≤ μ·N by construction; measured against the plan-motion reference (docs/rapier-engine.md, \"Plan motion\"): {OSCILLATOR_MEASURED}{}",
        if steps.within_target() { "within" } else { "outside" },
        steps.dt_inner,
        steps.dt_max,
        settings.accuracy,
        if pv.is_some() { " (its period scaled to the vertical mode √(Kz/M) when faster)" } else { "" },
        if pv.is_some() { VERTICAL_MEASURED } else { "" },
    ));
    run_oscillator(
        osc,
        settings,
        (&pd, pv.as_ref()),
        (dt, steps.stride),
        n,
        sink,
    )
}

/// The block on the ground slab (the kinematic ground at its step rule under a record),
/// with what it states.
fn block_case(
    case: &Case,
    spatial: &Spatial,
    b: &RigidBlock,
    drive: Drive,
    dt: f64,
    settings: &mut RapierSettings,
    (said, sink): (&mut Statement, &mut dyn StepSink),
) -> Result<Outcome, InputError> {
    let ex = &case.scene.excitation;
    let n = step_count(case.run.duration, dt);
    let depth = spatial.depth.map(|d| d.half_depth).ok_or_else(|| {
        case.field_error(
            "model.half_depth",
            "is required for a rigid block in a 3D scene",
        )
    })?;
    let ruled = drive == Drive::KinematicGround
        && settings.step_rule == StepRule::Scene
        && matches!(ex, Excitation::GroundAcceleration(Signal::Record { .. }));
    let stride = if ruled {
        kinematic_rule(case, spatial, b, depth, dt, settings, said)
    } else {
        1
    };
    let dt_in = dt / stride as f64;
    let pd = PlanDrive::new(drive, ex, spatial, dt_in, n * stride);
    said.described.push((
        "block".into(),
        format!(
            "uniform cuboid 2b × 2h × 2d = {} × {} × {} m (x, z, y), mass {} kg, on the ground slab, free in x, y, z and yaw, its tipping rotations locked (the friction's tangent effective mass isotropic: free to tip, a 2 × 1 m slab slid 6.6° off its drive)",
            2.0 * b.half_width,
            2.0 * b.half_height,
            2.0 * depth,
            b.mass
        ),
    ));
    said.described.push((
        "rapier step [s] (output step / stride)".into(),
        format!("{dt_in} (stride {stride}, {} substeps)", settings.substeps),
    ));
    said.described.push((
        "friction cone".into(),
        "circular: rapier 0.36 solves each friction constraint's two tangential impulses together and caps their magnitude at μ·N".into(),
    ));
    said.findings.push(format!(
        "measured against the plan-motion block reference with the Simplified friction model (docs/rapier-engine.md, \"Plan motion\"): {BLOCK_MEASURED}{}",
        if settings.friction == FrictionModel::Coulomb {
            "; outside the engine's validity with friction_model = \"coulomb\": one record along x slid 59 % too far (+16 % at 30°, within 0.01 % at 45° and 135°)"
        } else {
            ""
        }
    ));
    said.findings.push(tipping_finding(b, depth));
    Ok(run_block(b, depth, settings, &pd, (dt, stride), n, sink))
}

/// Whether the block's locked tipping is its physics: friction, at most μ·M·g at the
/// base, cannot tip a block with μ < min(b, d)/h about an edge of its footprint.
fn tipping_finding(b: &RigidBlock, depth: f64) -> String {
    let limit = b.half_width.min(depth) / b.half_height;
    if b.mu < limit {
        format!(
            "within the engine's validity for its locked tipping: μ = {} < min(b, d)/h = {limit:.4}, so friction cannot tip the block",
            b.mu
        )
    } else {
        format!(
            "outside the engine's validity: the block's tipping rotations are locked (a sliding block), but μ = {} ≥ min(b, d)/h = {limit:.4}: a drive above g·min(b, d)/h would tip it",
            b.mu
        )
    }
}

/// The block's kinematic-ground step rule ([`block_kinematic_stride`]) with what it
/// states; the output step's substeps shared among its rapier steps. Returns the stride.
fn kinematic_rule(
    case: &Case,
    spatial: &Spatial,
    b: &RigidBlock,
    depth: f64,
    dt: f64,
    settings: &mut RapierSettings,
    said: &mut Statement,
) -> usize {
    let (stride, slid, abs_ag, dt_max) =
        block_kinematic_stride(case, spatial, b, depth, settings, dt);
    let dt_in = dt / stride as f64;
    let estimate = 0.5 * dt_in * abs_ag;
    said.described.push((
        "step rule".into(),
        format!(
            "Δt ≤ 2·accuracy·S/∫|a_g|dt = {dt_max:.4e} s (S = {slid:.4e} m slid along the path in a pilot run on the inertial-force route at the output step, ∫|a_g|dt = {abs_ag:.4} m/s of the plan ground acceleration); at most {MAX_BLOCK_STEPS} rapier steps"
        ),
    ));
    said.findings.push(format!(
        "{} the engine's validity for the distance slid: the kinematic ground's slip estimate ½·Δt·∫|a_g|dt = {estimate:.3e} m is {:.2} % of S (target {} %)",
        if dt_in <= dt_max * (1.0 + 1e-12) {
            "within"
        } else {
            "outside"
        },
        100.0 * estimate / slid,
        100.0 * settings.accuracy
    ));
    if stride > 1 {
        settings.substeps = super::block_substeps(settings.substeps, stride);
    }
    stride
}

/// The oscillator's measured agreement, stated in its runs' findings
/// (tests/all/rapier_space.rs).
const OSCILLATOR_MEASURED: &str = "peaks and residual +0.003 %, slip start −0.8 ms; under the shipped record pair (T = 0.5 s, μ = 0.05) peak relative displacement +0.82 %, residual resultant sliding +0.66 %, first order in the step (the radial return moves the slider along the step's last direction)";

/// The vertical component's measured agreement, stated in its runs' findings
/// (tests/all/vertical_plan.rs).
const VERTICAL_MEASURED: &str = "; with a vertical pulse at 2/3 on its spring Kz (pepo-pulse-azimuth30-vertical) peaks and residual within 0.00003 %, slip start −0.8 ms";

/// The block's measured agreement, stated in its runs' findings
/// (tests/all/rapier_space.rs).
const BLOCK_MEASURED: &str = "record pair (block-record-pair), peak / residual resultant sliding −0.11 / −0.09 % on both routes; one record at five azimuths, residual +0.028 % at each, to 5e-14 of each other (inertial force; +0.001 % at 0° and 135° on the kinematic ground); a 2 × 1 m slab under a pulse at 30° (block-pulse-azimuth30) slides along its drive to 2e-13°: isotropic, |T| ≤ μ·N on every step to round-off";

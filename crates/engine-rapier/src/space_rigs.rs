//! The 3D scenes of a block and an oscillator in plan, each a rig the one time loop
//! ([`run_loop`]) drives with a [`PlanDrive`], and its recorder:
//!
//! - the oscillator (PEPO): one body free in the horizontal plane (and vertically on its
//!   spring Kz under a vertical component, its uplift recorded; no collider) with its
//!   contact as an applied
//!   force the engine computes after every rapier step: the spring Kx·(u − p) in series
//!   with a massless slider p returned radially onto the circle |F| ≤ μ·N, plus the
//!   viscous C·u̇ ([`PlanOscillator`]);
//! - the rigid block on the ground slab, free in x, y, z and yaw, its tipping rotations
//!   locked ([`SlabBlock`]); under a vertical component the drive moves its ground
//!   vertically too or pushes it with −m·a_v, and the recorder adds its uplift and the
//!   contact points that carried a force.
//!
//! The contact block gives |T|, N and the slip accumulated along the friction force
//! (Σ T̂·Δs, so that |T|·Δslip is the friction work T·Δs the dissipation invariant
//! judges).

use rapier3d_f64::prelude::*;

use super::contact_forces::ground_force;
use super::drive::PlanDrive;
use super::ground::VerticalTable;
use super::rows::layout;
use super::settings::RapierSettings;
use super::space_axes::{PlanRow, norm, plan, plan_channels, radial_return, sub, to_world};
use super::time_loop::{Outcome, Rig, StepCount, Steps, run_loop};
use super::world::{GroundKind, add_ground, new_world, rapier_friction};
use rockslide_core::case::{Oscillator, RigidBlock, Vertical};
use rockslide_core::trace::{ContactState, plan_slip_increment};
use rockslide_engine_api::StepSink;

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
    pub(crate) kz: f64,
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

/// The oscillator in plan as the time loop drives it: the body, its plan contact (the
/// slider and the spring force of the last step) and its vertical spring, if any.
pub(crate) struct PlanOscillator<'v> {
    world: PhysicsWorld,
    ground: RigidBodyHandle,
    mass: RigidBodyHandle,
    m: f64,
    c: f64,
    mu: f64,
    slider: PlanSlider,
    /// The spring force after the last step (ground side), N.
    spring: [f64; 2],
    /// The normal force after the last step, N.
    normal: f64,
    vertical: Option<&'v PlanVertical>,
}

impl<'v> PlanOscillator<'v> {
    /// The world of rapier steps `dt_in` (no gravity: the weight is the engine's), the
    /// ground for `drive`, the body at rest.
    pub(crate) fn new(
        osc: &Oscillator,
        settings: &RapierSettings,
        (pd, vertical): (&PlanDrive, Option<&'v PlanVertical>),
        dt_in: f64,
    ) -> Self {
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
        Self {
            world,
            ground,
            mass,
            m,
            c: osc.damping(),
            mu: osc.contact.mu,
            slider: PlanSlider {
                kx: osc.contact.kx,
                limit: osc.friction_limit(),
                p: [0.0, 0.0],
            },
            spring: [0.0, 0.0],
            normal: osc.normal_force(),
            vertical,
        }
    }

    /// The body's plan displacement and velocity relative to the ground at step `k`.
    fn relative(&self, pd: &PlanDrive, k: usize) -> ([f64; 2], [f64; 2]) {
        let (xg, vg) = pd.frame(k);
        let b = &self.world.bodies[self.mass];
        (sub(plan(b.translation()), xg), sub(plan(b.linvel()), vg))
    }

    /// The body's height, m.
    fn height(&self) -> f64 {
        self.world.bodies[self.mass].translation().y
    }
}

impl Rig<PlanDrive<'_>> for PlanOscillator<'_> {
    fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    fn world_mut(&mut self) -> &mut PhysicsWorld {
        &mut self.world
    }

    fn ground(&self) -> RigidBodyHandle {
        self.ground
    }

    /// M·a (or −M·a_g) − F − C·u̇ in plan, and N − M·g − M·a_v up, over the step.
    fn load(&mut self, pd: &PlanDrive, k: usize) {
        let (_, v) = self.relative(pd, k);
        let a = pd.specific_force(k);
        let (m, c) = (self.m, self.c);
        let f = [
            m * a[0] - self.spring[0] - c * v[0],
            m * a[1] - self.spring[1] - c * v[1],
        ];
        let up = self.vertical.map_or(0.0, |v| v.force(self.normal, k));
        let b = &mut self.world.bodies[self.mass];
        b.reset_forces(false);
        b.add_force(to_world(f, up), false);
    }

    /// N from the vertical spring (capping the slider's circle at μ·N), then the radial
    /// return of the plan contact.
    fn respond(&mut self, pd: &PlanDrive, k1: usize) {
        if let Some(v) = self.vertical {
            self.normal = v.normal(self.height());
            self.slider.limit = self.mu * self.normal;
        }
        let (u, _) = self.relative(pd, k1);
        self.spring = self.slider.update(u);
    }

    /// The mass: no collider, no joint, only its force set between steps.
    fn forces_only_body(&self) -> Option<RigidBodyHandle> {
        Some(self.mass)
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
    let mut rig = PlanOscillator::new(osc, settings, (pd, vertical), dt_in);
    let moves = pd.first.moves_ground();
    let channels = plan_channels(moves, vertical.is_some());
    // The one contact, |T| = |F| ≤ μ·N: compliance 0 without vertical motion, 1/Kz with.
    let trace = layout(&channels, 1, vertical.map_or(0.0, |v| 1.0 / v.kz));
    let mut row = vec![0.0; channels.len()];
    let m = osc.mass;
    let mut v_prev = 0.0;
    let (mut p_prev, mut path) = ([0.0, 0.0], 0.0);
    let record = |out: &mut dyn StepSink, rig: &PlanOscillator, k: usize| {
        let (spring, p, normal) = (rig.spring, rig.slider.p, rig.normal);
        let t = (k / stride) as f64 * dt;
        let (u, v) = rig.relative(pd, k);
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
            // the spring's opening above the ground (0 while closed) and the contact
            lift: vertical.map(|_| (rig.height().max(0.0), f64::from(normal > 0.0))),
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
                rig.height()
            } else {
                0.0
            },
        };
        out.row(t, &row, &[state]);
    };
    let steps = Steps::new(n * stride, dt_in, stride, StepCount::Taken);
    run_loop(&mut rig, pd, (trace, record), steps, sink)
}

/// The rigid block on the ground slab as the time loop drives it.
pub(crate) struct SlabBlock {
    world: PhysicsWorld,
    ground: RigidBodyHandle,
    block: RigidBodyHandle,
    m: f64,
}

impl SlabBlock {
    /// A cuboid 2b × 2h × 2d on the ground slab, friction μ on both colliders (rule
    /// Average → μ), restitution 0, free in x, y, z and yaw; its tipping rotations
    /// (about the horizontal axes) are locked: the rigid-plastic block of the reference,
    /// and the friction's tangent effective mass isotropic (`space`'s docs).
    pub(crate) fn new(
        b: &RigidBlock,
        half_depth: f64,
        settings: &RapierSettings,
        pd: &PlanDrive,
        dt_in: f64,
    ) -> Self {
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
        Self {
            world,
            ground,
            block,
            m: b.mass,
        }
    }
}

impl Rig<PlanDrive<'_>> for SlabBlock {
    fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    fn world_mut(&mut self) -> &mut PhysicsWorld {
        &mut self.world
    }

    fn ground(&self) -> RigidBodyHandle {
        self.ground
    }

    /// The drive's force on the block over the step, in plan and, under a vertical
    /// component, −m·a_v up (zero on the kinematic ground: the ground itself moves).
    fn load(&mut self, pd: &PlanDrive, k: usize) {
        let a = pd.specific_force(k);
        let m = self.m;
        let up = m * pd.vertical_force(k);
        let body = &mut self.world.bodies[self.block];
        body.reset_forces(false);
        body.add_force(to_world([m * a[0], m * a[1]], up), false);
    }

    /// Nothing: the contact is rapier's.
    fn respond(&mut self, _: &PlanDrive, _: usize) {}
}

/// Run the rigid block in plan ([`SlabBlock`]): `n` output steps of `dt`, each `stride`
/// rapier steps.
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
    let mut rig = SlabBlock::new(b, half_depth, settings, pd, dt_in);
    let moves = pd.first.moves_ground();
    let channels = plan_channels(moves, pd.has_vertical());
    let trace = layout(&channels, 1, 0.0);
    let mut row = vec![0.0; channels.len()];
    let (m, hh) = (b.mass, b.half_height);
    let (block, ground) = (rig.block, rig.ground);
    let start = plan(rig.world.bodies[block].translation());
    let mut v_prev = [0.0, 0.0];
    let (mut u_prev, mut path) = ([0.0, 0.0], 0.0);
    let record = |out: &mut dyn StepSink, rig: &SlabBlock, k: usize| {
        let world = &rig.world;
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
            // the base's height above the ground (its soft contact's sink at rest read as
            // 0) and the contact points that carried a force (at the start, before any
            // contact is solved, the four corners of the base standing on the ground)
            lift: pd.has_vertical().then(|| {
                let base = body.translation().y - hh - pd.height(k);
                let pressed = if k == 0 { 4 } else { gf.pressed };
                (base.max(0.0), pressed as f64)
            }),
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
    let steps = Steps::new(n * stride, dt_in, stride, StepCount::Taken);
    run_loop(&mut rig, pd, (trace, record), steps, sink)
}

//! Building the rapier world of a planar scene, the planar [`Rig`]: the ground body and
//! the structure with its contact — the rigid block's collider on the ground; the
//! oscillator's joint-limit joint ([`Slider`]) or, under a vertical component, its one
//! joint-limit [`Support`]; the rocking body's computed supports (the engine's
//! forces, no joints) or joint-limit ones; and the feet models (`contact_model =
//! "foot"`), light foot bodies that carry the elasticity as spring joints.
//!
//! Axes: rapier's x is the scene's horizontal X, rapier's y the scene's vertical Z (up),
//! rapier's z the out-of-plane depth. Rotations of the scene are about rapier's z axis,
//! counter-clockwise (seen with X to the right and Z up) positive. The ground's top face
//! is the plane y = 0.

use rapier3d_f64::prelude::*;

use super::settings::RapierSettings;
use rockslide_core::case::{Oscillator, RigidBlock, RockingBody};

/// Half-extents of the ground slab, m: wide enough for a block sliding or a ground
/// coasting for many metres; its top face is y = 0.
pub(crate) const GROUND_HALF: (f64, f64) = (1.0e4, 1.0);

/// Friction coefficient standing in for μ = ∞ (a friction limit 1e6 times the weight).
pub const MU_INFINITE: f64 = 1.0e6;

/// Half-extents of a foot, m (it only needs a flat face on the ground).
pub(crate) const FOOT_HALF: (f64, f64) = (0.1, 0.05);

/// How the ground is modelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GroundKind {
    /// A fixed body (inertial-force route, or no ground motion).
    Fixed,
    /// A kinematic, position-driven body moved to xg(t) each step.
    Kinematic,
}

/// A built world and the handles the time loop needs.
pub struct Rig {
    /// The rapier world.
    pub world: PhysicsWorld,
    /// The ground body.
    pub ground: RigidBodyHandle,
    /// The structure (mass of the oscillator, the rigid block).
    pub structure: RigidBodyHandle,
    /// Foot bodies (one for an oscillator, none for a rigid block).
    pub feet: Vec<RigidBodyHandle>,
    /// Dynamic bodies with their *inertial* mass, kg (the inertial-force route pushes
    /// each with −m·ag; a foot's gravity scale does not change its inertia).
    pub inertial_masses: Vec<(RigidBodyHandle, f64)>,
    /// Structure's mass, kg.
    pub mass: f64,
    /// Foot mass, kg (0 without feet).
    pub foot_mass: f64,
    /// The elastic-plastic joint of an oscillator built without a foot
    /// ([`oscillator_joint_limit`]); `None` for every other rig.
    pub slider: Option<Slider>,
    /// The supports of a rocking body built without feet ([`rocking_body_joint_limit`],
    /// [`rocking_body_applied_force`]); empty for every other rig.
    pub supports: Vec<Support>,
    /// Whether the supports act as forces the engine applies to the structure before
    /// each step ([`rocking_body_applied_force`]) rather than through joints.
    pub applied_supports: bool,
}

impl Rig {
    /// A rig of one structure of mass `mass` without feet, slider or supports (the
    /// constructors add what their rig has).
    pub(crate) fn single(
        world: PhysicsWorld,
        ground: RigidBodyHandle,
        structure: RigidBodyHandle,
        mass: f64,
    ) -> Rig {
        Rig {
            world,
            ground,
            structure,
            feet: Vec::new(),
            inertial_masses: vec![(structure, mass)],
            mass,
            foot_mass: 0.0,
            slider: None,
            supports: Vec::new(),
            applied_supports: false,
        }
    }
}

/// An elastic-perfectly-plastic contact as one joint: a spring Kx (a ForceBased motor on
/// X) whose force rapier caps at the friction limit μ·N (the motor's maximum force), in
/// series with a massless slider at `s`, the motor's target. rapier caps the force within
/// a step; after the step the slider is moved to where the capped spring has taken it
/// (`x − sign·Ru/Kx` when `Kx·|x − s| > Ru`), so the spring never stores more than Ru.
#[derive(Debug, Clone, Copy)]
pub struct Slider {
    /// The joint (ground → mass).
    pub joint: ImpulseJointHandle,
    /// Spring stiffness Kx, N/m.
    pub kx: f64,
    /// Motor damping passed to rapier, N·s/m: the scene's C minus h·Kx/2 (see
    /// [`oscillator_joint_limit`]).
    pub motor_damping: f64,
    /// Friction limit Ru = μ·N, N (infinite for μ = ∞).
    pub limit: f64,
    /// Slider position relative to the ground, m.
    pub s: f64,
}

impl Slider {
    /// Return mapping after a step: `stretch` is the mass's position relative to the
    /// ground anchor. Returns the slider's new position when it moved.
    pub fn slip(&mut self, stretch: f64) -> Option<f64> {
        let elastic = stretch - self.s;
        if self.kx * elastic.abs() > self.limit {
            self.s = stretch - elastic.signum() * self.limit / self.kx;
            Some(self.s)
        } else {
            None
        }
    }
}

pub(crate) fn new_world(s: &RapierSettings, dt: f64, gravity: f64) -> PhysicsWorld {
    PhysicsWorld {
        gravity: Vector::new(0.0, -gravity, 0.0),
        integration_parameters: s.integration_parameters(dt),
        ..PhysicsWorld::default()
    }
}

pub(crate) fn add_ground(world: &mut PhysicsWorld, kind: GroundKind, mu: f64) -> RigidBodyHandle {
    let body = match kind {
        GroundKind::Fixed => RigidBodyBuilder::fixed(),
        GroundKind::Kinematic => RigidBodyBuilder::kinematic_position_based(),
    }
    .translation(Vector::new(0.0, -GROUND_HALF.1, 0.0));
    let collider = ColliderBuilder::cuboid(GROUND_HALF.0, GROUND_HALF.1, GROUND_HALF.0)
        .friction(mu)
        .friction_combine_rule(CoefficientCombineRule::Average)
        .restitution(0.0)
        .restitution_combine_rule(CoefficientCombineRule::Min);
    world.insert(body, collider).0
}

/// The oscillator (PEPO, linear SDOF): a point mass joined to one foot on the ground by
/// a horizontal spring joint (stiffness Kx, viscous C = 2ζMω), locked in every other
/// direction. The foot carries the mass's weight directly
/// (gravity scale M/m_f, so its normal force is M·g exactly) and the mass has no gravity,
/// so the joint carries only the horizontal spring: the vertical load path never goes
/// through a 1000:1 mass ratio. Both bodies have their rotations locked (sliding only).
pub fn oscillator(osc: &Oscillator, s: &RapierSettings, dt: f64, kind: GroundKind) -> Rig {
    let mu = rapier_friction(osc.contact.mu);
    let mut world = new_world(s, dt, osc.gravity);
    let ground = add_ground(&mut world, kind, mu);
    let m = osc.mass;
    let mf = s.foot_mass_ratio * m;
    let foot_y = FOOT_HALF.1;
    let foot_body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, foot_y, 0.0))
        .gravity_scale(m / mf) // foot weight = M·g: the normal force of the scene
        .lock_rotations()
        .can_sleep(false);
    let foot_collider = ColliderBuilder::cuboid(FOOT_HALF.0, FOOT_HALF.1, FOOT_HALF.0)
        .mass(mf)
        .friction(mu)
        .friction_combine_rule(CoefficientCombineRule::Average)
        .restitution(0.0)
        .restitution_combine_rule(CoefficientCombineRule::Min);
    let foot = world.insert(foot_body, foot_collider).0;
    let mass_body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, foot_y, 0.0))
        .additional_mass_properties(MassProperties::new(Vector::ZERO, m, Vector::splat(m)))
        .gravity_scale(0.0)
        .lock_rotations()
        .can_sleep(false);
    let structure = world.insert_body(mass_body);
    let joint = GenericJointBuilder::new(
        JointAxesMask::LIN_Y | JointAxesMask::LIN_Z | JointAxesMask::ANG_AXES,
    )
    .motor_model(JointAxis::LinX, MotorModel::ForceBased)
    .motor_position(JointAxis::LinX, 0.0, osc.contact.kx, osc.damping())
    .contacts_enabled(false)
    .build();
    world.insert_impulse_joint(foot, structure, joint);
    Rig {
        world,
        ground,
        structure,
        feet: vec![foot],
        inertial_masses: vec![(structure, m), (foot, mf)],
        mass: m,
        foot_mass: mf,
        slider: None,
        supports: Vec::new(),
        applied_supports: false,
    }
}

/// The share of h·Kx left in the joint-limit spring's motor damping (see
/// [`oscillator_joint_limit`]): c = C − (1 − 1e-3)·h·Kx.
pub const MOTOR_DAMPING_MARGIN: f64 = 1e-3;

/// The oscillator with no foot: the mass joined directly to the ground body by one joint
/// that locks every axis but X, where a ForceBased motor is the spring Kx with its force
/// capped at the friction limit Ru = μ·M·g (rapier's motor `max_force`): the joint is the
/// elastic-plastic contact, and its target is the massless slider ([`Slider`]).
///
/// rapier solves the motor as an implicit spring over each substep h: with stiffness K
/// and damping c it converges to λ·(1 + h(hK + c)/M) = −h(hK + c)·v − hK·err, which damps
/// an undamped oscillator (measured: linear SDOF peak −2.1 % at h = 1 ms with c = C,
/// the error falling linearly with the share of hK removed from c). Passing
/// c = C − (1 − 10⁻³)·h·K leaves λ ≈ −hK·err − h·C·v: the spring force at the step's
/// start (symplectic Euler, energy-bounded, stable for ωh < 2; here ωh ≈ 0.03) with a
/// numerical damping ratio ≈ 10⁻³·ωh. (c = C − hK exactly is singular in rapier's
/// coefficients.) Measured: linear SDOF peak −0.002 % at h = 1 ms.
/// The mass has no gravity (the joint holds it); its normal force is the scene's M·g.
pub fn oscillator_joint_limit(
    osc: &Oscillator,
    s: &RapierSettings,
    dt: f64,
    kind: GroundKind,
) -> Rig {
    let mut world = new_world(s, dt, osc.gravity);
    let ground = add_ground(&mut world, kind, 0.0);
    let m = osc.mass;
    let mass_body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, FOOT_HALF.1, 0.0))
        .additional_mass_properties(MassProperties::new(Vector::ZERO, m, Vector::splat(m)))
        .gravity_scale(0.0)
        .lock_rotations()
        .can_sleep(false);
    let structure = world.insert_body(mass_body);
    let h = dt / s.substeps as f64;
    let kx = osc.contact.kx;
    let motor_damping = osc.damping() - (1.0 - MOTOR_DAMPING_MARGIN) * h * kx;
    let limit = friction_cap(osc.contact.mu, osc.normal_force());
    let joint = GenericJointBuilder::new(
        JointAxesMask::LIN_Y | JointAxesMask::LIN_Z | JointAxesMask::ANG_AXES,
    )
    .local_anchor1(Vector::new(0.0, GROUND_HALF.1 + FOOT_HALF.1, 0.0))
    .local_anchor2(Vector::ZERO)
    .motor_model(JointAxis::LinX, MotorModel::ForceBased)
    .motor_position(JointAxis::LinX, 0.0, kx, motor_damping)
    .motor_max_force(JointAxis::LinX, limit)
    .contacts_enabled(false)
    .build();
    let joint = world.insert_impulse_joint(ground, structure, joint);
    Rig {
        slider: Some(Slider {
            joint,
            kx,
            motor_damping,
            limit,
            s: 0.0,
        }),
        ..Rig::single(world, ground, structure, m)
    }
}

/// The rigid block (Newmark, Housner): a uniform cuboid 2b × 2h (depth 2b) of mass M,
/// friction μ and restitution 0 on the ground, standing on its base or tilted about its
/// right corner by the scene's initial tilt (the left corner lifted: clockwise, so the
/// rotation channel starts at −tilt).
pub fn rigid_block(b: &RigidBlock, s: &RapierSettings, dt: f64, kind: GroundKind) -> Rig {
    let mut world = new_world(s, dt, b.gravity);
    let ground = add_ground(&mut world, kind, b.mu);
    let phi0 = -b.initial_tilt;
    // Centre of mass = right corner (b, 0) + R(φ0)·(−b, h).
    let (sn, cs) = phi0.sin_cos();
    let cm = Vector::new(
        b.half_width + cs * (-b.half_width) - sn * b.half_height,
        sn * (-b.half_width) + cs * b.half_height,
        0.0,
    );
    let body = RigidBodyBuilder::dynamic()
        .translation(cm)
        .rotation(Vector::new(0.0, 0.0, phi0))
        .can_sleep(false);
    let collider = ColliderBuilder::cuboid(b.half_width, b.half_height, b.half_width)
        .mass(b.mass)
        .friction(b.mu)
        .friction_combine_rule(CoefficientCombineRule::Average)
        .restitution(0.0)
        .restitution_combine_rule(CoefficientCombineRule::Min);
    let structure = world.insert(body, collider).0;
    Rig::single(world, ground, structure, b.mass)
}

/// Rotation of a body about rapier's z axis, rad (counter-clockwise positive).
pub fn angle_z(body: &RigidBody) -> f64 {
    let q = body.rotation();
    2.0 * q.z.atan2(q.w)
}

/// Half-extents of a rocking body's foot, m (narrower than half the support spacing).
pub(crate) const ROCK_FOOT_HALF: (f64, f64) = (0.02, 0.02);

/// Rotational inertia of a rocking body: the scene's when it states one; when it gives
/// 0 (the paper's model has none), 0.01 % of a uniform block 2b × 2h,
/// I = 1e-4·M·(b² + h²)/3 (21.35 kg·m² for the RPEPO) — the rule the FE engine documents
/// too (docs/findings.md), so that the two engines differ only by their physics. The
/// shipped RPEPO cases state this value. A lifted foot hangs from the body and adds
/// m_f·(x_i² + h²) to the rotating inertia (all ten feet: ≈ 4.9e3 kg·m², 230 × this
/// value): the main cause of rapier's departures from the FE engine (docs/findings.md).
pub fn rocking_inertia(r: &RockingBody) -> f64 {
    if r.rotational_inertia > 0.0 {
        r.rotational_inertia
    } else {
        1e-4 * r.mass * (r.half_width.powi(2) + r.cm_height.powi(2)) / 3.0
    }
}

/// The rocking body (RPEPO): a point mass M with a small rotational inertia at height h
/// above the base centre O, joined to n feet at x_i by spring joints carrying each
/// support's Kx (horizontal) and Kz (vertical), both ForceBased motors. The joint axes
/// are the foot's, and feet never rotate, so the springs act along the ground's X and Z
/// as the paper's contact elements do; the body's rotation about Z is free at each foot.
/// A foot whose spring goes into tension lifts off (compression-only support); each foot
/// slides on its own with μ times its own normal force. The vertical load path runs
/// through the joints: that is the hard part for rapier's solver (a large mass ratio
/// across a joint chain converges slowly).
/// The springs start compressed by the static preload W/(n·Kz).
pub fn rocking_body(r: &RockingBody, s: &RapierSettings, dt: f64, kind: GroundKind) -> Rig {
    let mu = rapier_friction(r.contact.mu);
    let mut world = new_world(s, dt, r.gravity);
    let ground = add_ground(&mut world, kind, mu);
    let n = r.supports;
    let m = r.mass;
    let mf = s.foot_mass_ratio * m / n as f64;
    let preload = r.weight() / (n as f64 * r.contact.kz);
    let foot_y = ROCK_FOOT_HALF.1;
    let cm = Vector::new(0.0, foot_y + r.cm_height - preload, 0.0);
    let inertia = rocking_inertia(r);
    let body = RigidBodyBuilder::dynamic()
        .translation(cm)
        .additional_mass_properties(MassProperties::new(
            Vector::ZERO,
            m,
            Vector::new(inertia, inertia, inertia),
        ))
        .enabled_rotations(false, false, true)
        .can_sleep(false);
    let structure = world.insert_body(body);
    let mut feet = Vec::with_capacity(n);
    let mut inertial_masses = vec![(structure, m)];
    for x in r.support_positions() {
        let fb = RigidBodyBuilder::dynamic()
            .translation(Vector::new(x, foot_y, 0.0))
            .lock_rotations()
            .can_sleep(false);
        let fc = ColliderBuilder::cuboid(ROCK_FOOT_HALF.0, ROCK_FOOT_HALF.1, ROCK_FOOT_HALF.0)
            .mass(mf)
            .friction(mu)
            .friction_combine_rule(CoefficientCombineRule::Average)
            .restitution(0.0)
            .restitution_combine_rule(CoefficientCombineRule::Min);
        let foot = world.insert(fb, fc).0;
        let joint = GenericJointBuilder::new(
            JointAxesMask::LIN_Z | JointAxesMask::ANG_X | JointAxesMask::ANG_Y,
        )
        .local_anchor1(Vector::ZERO)
        .local_anchor2(Vector::new(x, -r.cm_height, 0.0))
        .motor_model(JointAxis::LinX, MotorModel::ForceBased)
        .motor_position(JointAxis::LinX, 0.0, r.contact.kx, 0.0)
        .motor_model(JointAxis::LinY, MotorModel::ForceBased)
        .motor_position(JointAxis::LinY, 0.0, r.contact.kz, 0.0)
        .contacts_enabled(false)
        .build();
        world.insert_impulse_joint(foot, structure, joint);
        feet.push(foot);
        inertial_masses.push((foot, mf));
    }
    Rig {
        world,
        ground,
        structure,
        feet,
        inertial_masses,
        mass: m,
        foot_mass: mf,
        slider: None,
        supports: Vec::new(),
        applied_supports: false,
    }
}

/// The share of h·K left in a joint-limit support's motor damping (as for the oscillator,
/// [`MOTOR_DAMPING_MARGIN`]): c = −(1 − share)·h·K for the RPEPO, which has no damping.
pub const SUPPORT_DAMPING_SHARE: f64 = 1e-3;

/// One support of a rocking body as two joints between the ground and the body (no
/// foot): a compression-only spring Kz (ForceBased motor on Y) and an elastic-plastic
/// spring Kx (motor on X) capped at μ·N_i, in series with a massless slider at `s`.
///
/// Both are decided from the state after each rapier step, for the next one: a support
/// whose anchor is above the ground (δz > 0) is open, its Z motor's force capped at 0;
/// the X motor's target is the slider and its force cap μ·N_i, N_i = Kz·max(0, −δz); the
/// slider follows where the capped spring has gone (return mapping), and an open
/// support's slider follows the anchor (no force), as the FE engine's CONTA178 does.
/// (Tried and dropped: a compression-only spring from a Z motor with target −a and cap
/// Kz·a plus a constant force Kz·a at the anchor, switching inside the solve: the body's
/// rotation is unstable with it, the faster the larger a — docs/rapier-engine.md.)
#[derive(Debug, Clone, Copy)]
pub struct Support {
    /// The horizontal spring's joint (ground → body); the vertical one is a second joint.
    pub joint: ImpulseJointHandle,
    /// The vertical spring's joint.
    pub vertical: ImpulseJointHandle,
    /// Anchor's x on the base, from O, m.
    pub x: f64,
    /// Height of the CM above the base, m (the anchor is at (x, −h) from the CM).
    pub cm_height: f64,
    /// Horizontal and vertical stiffness, N/m.
    pub kx: f64,
    /// Vertical stiffness, N/m.
    pub kz: f64,
    /// Friction coefficient (f64::INFINITY: never slips).
    pub mu: f64,
    /// Motor dampings passed to rapier (X, Z), N·s/m.
    pub damping: (f64, f64),
    /// Slider position relative to the ground anchor, m.
    pub s: f64,
    /// Normal force N_i of the last step, N.
    pub normal: f64,
    /// Anchor minus ground point (δx, δz) after the last step, m.
    pub delta: (f64, f64),
    /// The anchor's world position after the last step (x, y), m (at the start, at the
    /// body's initial pose for the computed supports, which act there).
    pub anchor: (f64, f64),
}

impl Support {
    /// The elastic-plastic update after a step with anchor offset `delta`: normal force,
    /// friction cap and return mapping. Returns the slider and the cap for the next step.
    pub fn update(&mut self, delta: (f64, f64)) -> (f64, f64) {
        self.delta = delta;
        self.normal = self.kz * (-delta.1).max(0.0);
        let cap = friction_cap(self.mu, self.normal);
        let elastic = delta.0 - self.s;
        if self.kx * elastic.abs() > cap {
            self.s = delta.0 - elastic.signum() * cap / self.kx;
        }
        (self.s, cap)
    }

    /// The anchor's world position for a body at `cm` rotated by `phi`, m.
    pub fn anchor(&self, cm: Vector, phi: f64) -> (f64, f64) {
        self.anchor_at(cm, phi.sin_cos())
    }

    /// [`Support::anchor`] with the rotation's (sin φ, cos φ) computed once for every
    /// support of the body.
    pub fn anchor_at(&self, cm: Vector, (sn, cs): (f64, f64)) -> (f64, f64) {
        (
            cm.x + cs * self.x + sn * self.cm_height,
            cm.y + sn * self.x - cs * self.cm_height,
        )
    }

    /// The support's force on the body at its state after the last step, (Fx, Fz), N:
    /// the capped horizontal spring pulling the anchor back, the normal force pushing up.
    pub fn force_on_body(&self) -> (f64, f64) {
        (-self.shear(), self.normal)
    }

    /// Horizontal spring force on the ground point (the base shear's share), N.
    pub fn shear(&self) -> f64 {
        self.kx * (self.delta.0 - self.s)
    }
}

/// The rocking body (RPEPO) with its supports as joints straight to the ground, no feet
/// ([`Support`]): the body (mass M, the stated rotational inertia, translations in the
/// X–Z plane and rotation about Z only) starts in its static equilibrium, every support
/// compressed by W/(n·Kz); there is nothing to settle.
pub fn rocking_body_joint_limit(
    r: &RockingBody,
    s: &RapierSettings,
    dt: f64,
    kind: GroundKind,
) -> Rig {
    let mut world = new_world(s, dt, r.gravity);
    let ground = add_ground(&mut world, kind, 0.0);
    let n = r.supports;
    let m = r.mass;
    let preload = r.weight() / (n as f64 * r.contact.kz);
    let structure = insert_rocking_structure(&mut world, r, preload);
    let h = dt / s.substeps as f64;
    let (kx, kz) = (r.contact.kx, r.contact.kz);
    let share = 1.0 - SUPPORT_DAMPING_SHARE;
    let damping = (-share * h * kx, -share * h * kz);
    let normal = r.weight() / n as f64;
    let mu = r.contact.mu;
    let cap = friction_cap(mu, normal);
    let mut supports = Vec::with_capacity(n);
    for x in r.support_positions() {
        // Two joints per support, one motor each: rapier orthogonalizes (Gram–Schmidt, in
        // the bodies' mass metric) the rows of one joint, which with the small rotational
        // inertia would leak the large Z motor impulse into X and make the body unstable.
        let spring = |axis: JointAxis, target: f64, k: f64, c: f64, max: f64| {
            GenericJointBuilder::new(JointAxesMask::empty())
                .local_anchor1(Vector::new(x, GROUND_HALF.1, 0.0))
                .local_anchor2(Vector::new(x, -r.cm_height, 0.0))
                .motor_model(axis, MotorModel::ForceBased)
                .motor_position(axis, target, k, c)
                .motor_max_force(axis, max)
                .contacts_enabled(false)
                .build()
        };
        let joint = world.insert_impulse_joint(
            ground,
            structure,
            spring(JointAxis::LinX, 0.0, kx, damping.0, cap),
        );
        let vertical = world.insert_impulse_joint(
            ground,
            structure,
            spring(JointAxis::LinY, 0.0, kz, damping.1, f64::INFINITY),
        );
        supports.push(Support {
            joint,
            vertical,
            x,
            cm_height: r.cm_height,
            kx,
            kz,
            mu,
            damping,
            s: 0.0,
            normal,
            delta: (0.0, -preload),
            anchor: (0.0, 0.0),
        });
    }
    Rig {
        supports,
        ..Rig::single(world, ground, structure, m)
    }
}

/// The rocking body's structure without feet (mass M, the stated rotational inertia, X–Z
/// translations and rotation about Z), its centre of mass at the CM height less the
/// supports' static `preload`.
fn insert_rocking_structure(
    world: &mut PhysicsWorld,
    r: &RockingBody,
    preload: f64,
) -> RigidBodyHandle {
    let inertia = rocking_inertia(r);
    let body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, r.cm_height - preload, 0.0))
        .additional_mass_properties(MassProperties::new(
            Vector::ZERO,
            r.mass,
            Vector::new(inertia, inertia, inertia),
        ))
        .enabled_translations(true, true, false)
        .enabled_rotations(false, false, true)
        .can_sleep(false);
    world.insert_body(body)
}

/// The rocking body (RPEPO) with its supports as forces the engine computes
/// ([`Support::force_on_body`]) and applies to the rapier body before each step: the
/// same body as [`rocking_body_joint_limit`] (mass M, the stated rotational inertia, X–Z
/// translations and rotation about Z, starting in static equilibrium), no joints and no
/// colliders, so that rapier's step is its rigid-body integration alone. The ground is a
/// body without a collider (moved for the kinematic route; the supports read its x).
pub fn rocking_body_applied_force(
    r: &RockingBody,
    s: &RapierSettings,
    dt: f64,
    kind: GroundKind,
) -> Rig {
    let mut world = new_world(s, dt, r.gravity);
    // No joints and no contacts: rapier's stabilization (unbiased) pass has no constraint
    // to solve, so it is skipped; the integrated motion is the same bits (docs/rapier-engine.md).
    world
        .integration_parameters
        .num_internal_stabilization_iterations = 0;
    let ground_body = match kind {
        GroundKind::Fixed => RigidBodyBuilder::fixed(),
        GroundKind::Kinematic => RigidBodyBuilder::kinematic_position_based(),
    };
    let ground = world.insert_body(ground_body);
    let n = r.supports;
    let preload = r.weight() / (n as f64 * r.contact.kz);
    let structure = insert_rocking_structure(&mut world, r, preload);
    let body = &world.bodies[structure];
    let (cm, rotation) = (body.translation(), angle_z(body).sin_cos());
    let supports = r
        .support_positions()
        .into_iter()
        .map(|x| Support {
            joint: ImpulseJointHandle::invalid(),
            vertical: ImpulseJointHandle::invalid(),
            x,
            cm_height: r.cm_height,
            kx: r.contact.kx,
            kz: r.contact.kz,
            mu: r.contact.mu,
            damping: (0.0, 0.0),
            s: 0.0,
            normal: r.weight() / n as f64,
            delta: (0.0, -preload),
            anchor: (0.0, 0.0),
        })
        .map(|sup| Support {
            anchor: sup.anchor_at(cm, rotation),
            ..sup
        })
        .collect();
    Rig {
        supports,
        applied_supports: true,
        ..Rig::single(world, ground, structure, r.mass)
    }
}

/// The Coulomb cap μ·N of a support, infinite when μ is (never 0·∞ = NaN when N = 0).
pub(crate) fn friction_cap(mu: f64, normal: f64) -> f64 {
    if mu.is_finite() {
        mu * normal
    } else {
        f64::INFINITY
    }
}

/// The friction coefficient handed to rapier's contact: μ, or [`MU_INFINITE`] when the
/// case's μ is infinite (rapier wants a finite coefficient).
pub(crate) fn rapier_friction(mu: f64) -> f64 {
    if mu.is_finite() { mu } else { MU_INFINITE }
}

/// The oscillator as a mass free in X and Z (no rotation) on one joint-limit support
/// ([`Support`], as the rocking body's): a compression-only spring Kz on Y and the spring
/// Kx on X capped at μ·N after every step, in series with its slider. The mass carries its
/// weight through the support and starts in static equilibrium, compressed by M·g/Kz.
pub(crate) fn oscillator_with_supports(
    osc: &Oscillator,
    s: &RapierSettings,
    dt: f64,
    kind: GroundKind,
) -> Rig {
    let mut w = new_world(s, dt, osc.gravity);
    let ground = add_ground(&mut w, kind, 0.0);
    let m = osc.mass;
    let (kx, kz, mu) = (osc.contact.kx, osc.contact.kz, osc.contact.mu);
    let preload = m * osc.gravity / kz;
    let body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, -preload, 0.0))
        .additional_mass_properties(MassProperties::new(Vector::ZERO, m, Vector::splat(m)))
        .enabled_translations(true, true, false)
        .lock_rotations()
        .can_sleep(false);
    let structure = w.insert_body(body);
    let h = dt / s.substeps as f64;
    let share = 1.0 - SUPPORT_DAMPING_SHARE;
    let damping = (osc.damping() - share * h * kx, -share * h * kz);
    let normal = m * osc.gravity;
    let cap = friction_cap(mu, normal);
    let spring = |axis: JointAxis, k: f64, c: f64, max: f64| {
        GenericJointBuilder::new(JointAxesMask::empty())
            .local_anchor1(Vector::new(0.0, GROUND_HALF.1, 0.0))
            .local_anchor2(Vector::ZERO)
            .motor_model(axis, MotorModel::ForceBased)
            .motor_position(axis, 0.0, k, c)
            .motor_max_force(axis, max)
            .contacts_enabled(false)
            .build()
    };
    let joint = w.insert_impulse_joint(
        ground,
        structure,
        spring(JointAxis::LinX, kx, damping.0, cap),
    );
    let vertical = w.insert_impulse_joint(
        ground,
        structure,
        spring(JointAxis::LinY, kz, damping.1, f64::INFINITY),
    );
    Rig {
        supports: vec![Support {
            joint,
            vertical,
            x: 0.0,
            cm_height: 0.0,
            kx,
            kz,
            mu,
            damping,
            s: 0.0,
            normal,
            delta: (0.0, -preload),
            anchor: (0.0, 0.0),
        }],
        ..Rig::single(w, ground, structure, m)
    }
}

//! The planar rig ([`Rig`], built by `world`) as the time loop drives it: before each
//! step the structure's forces (the computed supports' resultant, then the drive's
//! M·a or −m·ag on every dynamic body, then −m·a_v), after each step the return mapping
//! of the joint-limit slider and of every support from the body's new pose; and the
//! settling of the feet models before t = 0.

use rapier3d_f64::prelude::*;

use super::drive::{Drive, LineDrive};
use super::time_loop;
use super::world::{Rig, Support, angle_z};

impl time_loop::Rig<LineDrive<'_>> for Rig {
    fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    fn world_mut(&mut self) -> &mut PhysicsWorld {
        &mut self.world
    }

    fn ground(&self) -> RigidBodyHandle {
        self.ground
    }

    /// The step's forces. The structure is looked up once for its own forces (rapier
    /// marks a body modified on every mutable lookup); forces are added in the same
    /// order as they always were.
    fn load(&mut self, drive: &LineDrive, k: usize) {
        let (mass_acc, ag) = drive.horizontal(k);
        let body = &mut self.world.bodies[self.structure];
        body.reset_forces(false);
        if self.applied_supports {
            apply_support_forces(body, &self.supports);
        }
        if let Some(a) = mass_acc {
            body.add_force(Vector::new(self.mass * a, 0.0, 0.0), false);
        } else if drive.route == Drive::InertialForce {
            body.add_force(Vector::new(-self.mass * ag, 0.0, 0.0), false);
        }
        for &(h, m) in &self.inertial_masses {
            if h != self.structure {
                let other = &mut self.world.bodies[h];
                other.reset_forces(false);
                if drive.route == Drive::InertialForce {
                    other.add_force(Vector::new(-m * ag, 0.0, 0.0), false);
                }
            }
        }
        if let Some(av) = drive.vertical(k) {
            for &(h, m) in &self.inertial_masses {
                self.world.bodies[h].add_force(Vector::new(0.0, -m * av, 0.0), false);
            }
        }
    }

    fn respond(&mut self, drive: &LineDrive, k1: usize) {
        slip_after_step(self, drive.height(k1));
    }

    /// The computed supports' structure (no collider, no joint, no feet); every other
    /// rig keeps rapier's tracking.
    fn forces_only_body(&self) -> Option<RigidBodyHandle> {
        (self.applied_supports && self.feet.is_empty()).then_some(self.structure)
    }
}

/// The computed supports' resultant on the structure for the next step: each
/// support's force at its anchor (state after the last step), summed into one force at
/// the CM and a torque about Z. The anchors are the ones [`supports_after_step`] computed
/// at the body's pose after the last step (before the first, the ones the rig was built
/// with at its initial pose): the body has not moved since.
fn apply_support_forces(body: &mut RigidBody, supports: &[Support]) {
    let cm = body.translation();
    let (mut fx, mut fy, mut torque) = (0.0, 0.0, 0.0);
    for sup in supports {
        let (ax, ay) = sup.anchor;
        let (sx, sy) = sup.force_on_body();
        fx += sx;
        fy += sy;
        torque += (ax - cm.x) * sy - (ay - cm.y) * sx;
    }
    body.reset_torques(false);
    body.add_force(Vector::new(fx, fy, 0.0), false);
    body.add_torque(Vector::new(0.0, 0.0, torque), false);
}

/// The joint-limit contact's return mapping after a step: where the capped spring has
/// taken the mass beyond Ru/Kx, the slider follows, and the motor's target with it.
fn slip_after_step(rig: &mut Rig, ground_height: f64) {
    supports_after_step(rig, ground_height);
    let Some(slider) = rig.slider.as_mut() else {
        return;
    };
    let stretch = rig.world.bodies[rig.structure].translation().x
        - rig.world.bodies[rig.ground].translation().x;
    if let Some(s) = slider.slip(stretch)
        && let Some(joint) = rig.world.impulse_joints.get_mut(slider.joint, false)
    {
        joint
            .data
            .set_motor_position(JointAxis::LinX, s, slider.kx, slider.motor_damping);
    }
}

/// The joint-limit supports after a step: each one's normal force, friction cap and
/// slider (return mapping), written back into its joint's X motor.
/// `ground_height`: the moving ground's height above its start (vertical motion on the
/// kinematic route; 0 otherwise), from which the supports' gaps are measured.
fn supports_after_step(rig: &mut Rig, ground_height: f64) {
    if rig.supports.is_empty() {
        return;
    }
    let body = &rig.world.bodies[rig.structure];
    let (cm, phi) = (body.translation(), angle_z(body));
    let rotation = phi.sin_cos();
    let gx = rig.world.bodies[rig.ground].translation().x;
    let gy = ground_height;
    for sup in rig.supports.iter_mut() {
        let (ax, ay) = sup.anchor_at(cm, rotation);
        sup.anchor = (ax, ay);
        let (s, cap) = sup.update((ax - gx - sup.x, ay - gy));
        if rig.applied_supports {
            // no joints: the engine applies the supports' forces before the next step
            continue;
        }
        if let Some(joint) = rig.world.impulse_joints.get_mut(sup.joint, false) {
            joint
                .data
                .set_motor_position(JointAxis::LinX, s, sup.kx, sup.damping.0)
                .set_motor_max_force(JointAxis::LinX, cap);
        }
        if let Some(joint) = rig.world.impulse_joints.get_mut(sup.vertical, false) {
            // Open (the anchor above the ground): no force at all. (A motor with zero
            // stiffness and damping is a rigid velocity lock in rapier: cap it at 0.)
            let open = sup.delta.1 > 0.0;
            joint
                .data
                .set_motor_max_force(JointAxis::LinY, if open { 0.0 } else { f64::INFINITY });
        }
    }
}

/// Settling under gravity before t = 0: `steps` steps in which every velocity is halved
/// after the step (a strongly damped relaxation), then all velocities are zeroed, so the
/// soft contacts and the preloaded springs start in equilibrium.
pub(crate) fn settle(rig: &mut Rig, steps: usize) {
    for _ in 0..steps {
        rig.world.step();
        for &(h, _) in &rig.inertial_masses {
            let b = &mut rig.world.bodies[h];
            let (v, w) = (b.linvel(), b.angvel());
            b.set_linvel(0.5 * v, false);
            b.set_angvel(0.5 * w, false);
        }
    }
    for &(h, _) in &rig.inertial_masses {
        let b = &mut rig.world.bodies[h];
        b.set_linvel(Vector::ZERO, false);
        b.set_angvel(Vector::ZERO, false);
    }
}

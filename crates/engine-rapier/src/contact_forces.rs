//! The ground's force on a body, read from rapier's contact impulses after a step. The
//! solver stores, per contact point, the normal impulse of the step's last substep
//! (`warmstart_impulse`, along the manifold's force direction −normal) and the friction
//! impulse of that substep in world space (`warmstart_tangent_world`; with rapier's
//! simplified friction model one impulse per manifold, copied on each of its points).
//! The force is their sum ÷ the substep: the same substep's normal and friction forces,
//! the pair the Coulomb bound |T| ≤ μN concerns. These are the forces rapier's solver
//! applied, so the friction bound and compression invariants judge the solver itself.

use rapier3d_f64::prelude::*;

/// The ground's force on a body over the last substep, N, and the smallest contact
/// distance (negative: penetration; `None` without contact points).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundForce {
    /// Horizontal force on the body, N (+x).
    pub x: f64,
    /// Vertical force on the body, N (+y, up).
    pub y: f64,
    /// Horizontal force on the body across the plane of a planar scene, N (rapier's +z).
    pub z: f64,
    /// Smallest contact distance, m.
    pub dist: Option<f64>,
    /// Contact points that carried a normal impulse in the last substep.
    pub pressed: usize,
}

/// The ground's force on `body` (through its first collider) from the contact impulses of
/// the last substep of a step of length `dt`.
pub fn ground_force(
    world: &PhysicsWorld,
    body: RigidBodyHandle,
    ground: RigidBodyHandle,
    dt: f64,
) -> GroundForce {
    let none = GroundForce {
        x: 0.0,
        y: 0.0,
        z: 0.0,
        dist: None,
        pressed: 0,
    };
    let (Some(&of), Some(&on)) = (
        world.bodies[body].colliders().first(),
        world.bodies[ground].colliders().first(),
    ) else {
        return none;
    };
    let Some(pair) = world.contact_pair(of, on) else {
        return none;
    };
    let params = &world.integration_parameters;
    let substep = dt / params.num_solver_iterations.max(1) as f64;
    let per_manifold = params.friction_model == FrictionModel::Simplified;
    // Impulses act on collider 1 along −normal (rapier's force direction).
    let sign = if pair.collider1 == of { 1.0 } else { -1.0 };
    let mut impulse = Vector::ZERO;
    let mut pressed = 0;
    for m in pair.solver_manifolds() {
        for (i, p) in m.points.iter().enumerate() {
            impulse -= m.data.normal * p.data.warmstart_impulse;
            pressed += usize::from(p.data.warmstart_impulse > 0.0);
            if !per_manifold || i == 0 {
                impulse += p.data.warmstart_tangent_world;
            }
        }
    }
    let dist = pair
        .manifolds()
        .iter()
        .flat_map(|m| m.points.iter().map(|p| p.dist))
        .reduce(f64::min);
    GroundForce {
        x: sign * impulse.x / substep,
        y: sign * impulse.y / substep,
        z: sign * impulse.z / substep,
        dist,
        pressed,
    }
}

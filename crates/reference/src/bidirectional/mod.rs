//! Bidirectional (plan-motion) references: the rigid-plastic block sliding on an isotropic
//! friction cone ([`PlanBlock`]) and the elastic-perfectly-plastic oscillator with a
//! circular yield surface ([`PlanEpo`]), under the horizontal drive of a 3D scene
//! ([`PlanDrive`]). Neither has a closed form in general: both are integrated on a grid
//! that has a node at every kink of the drive (record samples, pulse ends), with every
//! phase change (slip onset, stop, yield, unloading) located by bisection on the event
//! function of a step of variable length, so that no step straddles an event
//! ([`integrate`], one event loop for both) — the oscillator by the classical fourth-order
//! Runge–Kutta method, the block by the three-stage Radau IIA method (order 5, L-stable)
//! in speed and direction, because its sliding direction is stiff near rest ([`radau`]).
//! Convergence is measured by halving the step (docs/bidirectional.md).
//!
//! A vertical component a_v(t) makes the friction cone's radius follow the normal force:
//! μ·M·(g + a_v) for the block (rigid-plastic), and for the oscillator the scene's
//! `normal_force` — rigid, N = M·(g + a_v), or the contact's Kz, N = Kz·δ with the
//! vertical oscillator integrated beside the plan motion; both stop with an error at
//! lift-off (N ≤ 0).
//!
//! Coordinates: relative to the ground; the drive d(t) is the force per unit mass on the
//! body, a(t) for a mass acceleration, −a_g(t) for a ground acceleration, a 2-vector.

mod block;
mod drive;
mod epo;
mod integrate;
mod radau;

pub use block::{PlanBlock, PlanBlockPhase};
pub use drive::PlanDrive;
pub use epo::{PlanEpo, PlanEpoPhase};
pub use integrate::{Sample, rotate};

use rockslide_core::case::{Case, Model};

/// Default largest integration step of the case references, s.
pub const DEFAULT_STEP: f64 = 1e-4;

/// The plan-motion reference of a 3D case, or why there is none.
pub fn for_case(case: &Case) -> Result<Box<dyn crate::ExactSolution>, String> {
    let scene = &case.scene;
    let drive = PlanDrive::of_scene(scene)?;
    match &scene.model {
        Model::Oscillator(o) => Ok(Box::new(PlanEpo::solve(
            o,
            &drive,
            case.run.duration,
            DEFAULT_STEP,
        )?)),
        Model::RigidBlock(b) => Ok(Box::new(PlanBlock::solve(
            b.mu,
            b.gravity,
            &drive,
            case.run.duration,
            DEFAULT_STEP,
        )?)),
        Model::RockingBody(_) => {
            Err("no exact solution exists for the rocking elastic-plastic oscillator in 3D".into())
        }
    }
}

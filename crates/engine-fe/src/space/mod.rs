//! The fe engine on a bidirectional (3D) scene: the one model (`model`) in space — a
//! rigid body with six degrees of freedom and exact finite rotations on supports with
//! circular friction cones, single or double arrangement — built from the scene, run and
//! recorded with (x, y) pairs. In one vertical plane it reproduces the plane model to
//! round-off.
//!
//! - `body`: the rigid body and its support points (oscillator, block grid, the plane
//!   rocking body extended).
//! - `run`: one run, recorded as rows with (x, y) pairs.
//! - `scene`: the engine on a bidirectional scene (model from `Scene::spatial`, trace).

mod body;
mod run;
mod scene;

pub use crate::element::{ConeContact, ConeState};
pub use crate::model::{Placement, right_jacobian, rotation_exp, rotation_log};
/// Deterministic counters of a run: the plane model's.
pub use crate::stepper::Counters as SpaceCounters;
pub use body::{BlockGrid, SpaceBody};
pub use run::{SpaceRow, SpaceRun, run_space};
pub use scene::variants;
pub(crate) use scene::{recorded_values_space, simulate_space_into};

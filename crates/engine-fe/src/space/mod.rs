//! The fe model in three dimensions (issue 16): a rigid body with six degrees of freedom
//! and exact finite rotations on supports with circular friction cones, single or double
//! arrangement, Newmark/HHT-α with Newton — the 2D model (`model.rs`, `stepper.rs`)
//! extended, reproducing it to round-off when the motion stays in one vertical plane.
//!
//! - `rotation`: exponential map of SO(3), its right Jacobian, the logarithm.
//! - `contact`: the cone contact (radial return, consistent tangent).
//! - `model`: the body and supports, assembly, series equivalents of double supports,
//!   node condensation, the 6×6 Newton solve.
//! - `mechanics`: the model in the time loop on SO(3) (Simo–Vu Quoc material form).
//! - `run`: one run, recorded as rows with (x, y) pairs.
//! - `scene`: the engine on a bidirectional scene (model from `Scene::spatial`, trace).

mod contact;
mod mechanics;
mod model;
mod rotation;
mod run;
mod scene;

/// Deterministic counters of a run: the plane model's.
pub use crate::stepper::Counters as SpaceCounters;
pub use contact::{ConeContact, ConeState};
pub use mechanics::{Placement, SpaceDrive, SpaceSnapshot};
pub use model::{BlockGrid, SpaceBody, SpaceModel};
pub use rotation::{exp as rotation_exp, log as rotation_log, right_jacobian};
pub use run::{SpaceRow, SpaceRun, run_space};
pub use scene::{recorded_values_space, simulate_space, simulate_space_into, variants};

//! The fe model in three dimensions (issue 16): a rigid body with six degrees of freedom
//! and exact finite rotations on supports with circular friction cones, single or double
//! arrangement, Newmark/HHT-α with Newton in the one time loop (`stepper`) — the plane model
//! extended, reproducing it to round-off when the motion stays in one vertical plane.
//!
//! - `rotation`: exponential map of SO(3), its right Jacobian, the logarithm.
//! - `body`: the rigid body and its support points (oscillator, block grid, the plane
//!   rocking body extended).
//! - `model`: the supports, assembly, node condensation, the 6×6 Newton solve.
//! - `ground_sums`: the assembly of ground-to-body elements in the ground frame.
//! - `mechanics`: the model in the time loop on SO(3) (Simo–Vu Quoc material form).
//! - `run`: one run, recorded as rows with (x, y) pairs.
//! - `scene`: the engine on a bidirectional scene (model from `Scene::spatial`, trace).

mod body;
mod ground_sums;
mod mechanics;
mod model;
mod rotation;
mod run;
mod scene;

pub use crate::element::{ConeContact, ConeState};
/// Deterministic counters of a run: the plane model's.
pub use crate::stepper::Counters as SpaceCounters;
pub use body::{BlockGrid, SpaceBody};
pub use mechanics::{Placement, SpaceDrive, SpaceSnapshot};
pub use model::SpaceModel;
pub use rotation::{exp as rotation_exp, log as rotation_log, right_jacobian};
pub use run::{SpaceRow, SpaceRun, run_space};
pub use scene::{recorded_values_space, simulate_space, simulate_space_into, variants};

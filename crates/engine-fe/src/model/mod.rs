//! The FE model, one for the plane and for space: a rigid body (mass and inertia at the
//! centre of mass, rigid massless base), massless intermediate nodes, and CONTA178-like
//! contact elements joining ground, nodes and support points; its assembly (internal
//! force and consistent tangent), the condensed solve of its Newton system, and its place
//! in the time loop — written once, generic over the [`Dimension`] ([`Plane`]:
//! q = (X, Z, θ); [`Space`]: X and a finite rotation), which holds only what differs.
//! Gravity is a constant load −M·g; the run starts from the static equilibrium under it
//! (`stepper`).
//!
//! - `dimension`: what a dimension provides ([`Dimension`]); the model's parts over it
//!   (body, supports, nodes).
//! - `plane`, `space`: the two (`plane::slider`: the plane's sliding oscillator, the PEPO,
//!   stepped in scalars; `rotation`: SO(3); `ground_sums`: the 3D assembly's sums).
//! - `build`: building a scene's model.
//! - `assembly`: internal forces and tangents; commit and restore.
//! - `solve`: the condensed Newton solve.
//! - `drive`: the excitation's loads; what an observer is shown.
//! - `mechanics`: the model in the time loop (`stepper::Mechanics`).

mod assembly;
mod build;
mod dimension;
mod drive;
mod ground_sums;
mod mechanics;
mod plane;
mod rotation;
mod solve;
mod space;

pub use assembly::Assembly;
pub use build::default_rotational_inertia;
pub use dimension::{Body, Dimension, Model};
pub use drive::{Drive, Snapshot};
pub use plane::{Plane, PlaneKinematics};
pub use rotation::{exp as rotation_exp, log as rotation_log, right_jacobian};
pub use space::{Placement, Space};

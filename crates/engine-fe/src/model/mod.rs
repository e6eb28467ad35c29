//! The plane FE model: a rigid body (point mass at the centre of mass, rigid massless
//! base), massless intermediate nodes, and CONTA178-like contact elements linking ground,
//! nodes and support points; its assembly (internal force and consistent tangent), the
//! condensed solve of its Newton system, and its place in the time loop.
//!
//! Degrees of freedom: the body's q = (X, Z, θ) of the centre of mass (θ locked for a
//! sliding oscillator) and (x, z) of each massless node. Gravity is a constant load −M·g
//! on Z; the run starts from the static equilibrium under it (`stepper`).
//!
//! - `body`: the body, nodes, links and supports; building a scene's model.
//! - `kinematics`: a body point's displacement and Jacobian (exact, small rotations,
//!   P-Delta).
//! - `assembly`: internal forces and tangents; commit and restore.
//! - `solve`: the condensed 3×3 Newton solve.
//! - `drive`: the excitation's loads; what an observer is shown.
//! - `mechanics`: the model in the time loop (`stepper::Mechanics`).
//! - `slider`: the sliding oscillator's step in scalars.

mod assembly;
mod body;
mod drive;
mod kinematics;
mod mechanics;
mod slider;
mod solve;

pub use assembly::Assembly;
pub use body::{Model, default_rotational_inertia};
pub(crate) use body::{Point, Support};
pub use drive::{Drive, Snapshot};
pub use solve::condensed_tangent;

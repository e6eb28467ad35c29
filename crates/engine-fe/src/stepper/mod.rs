//! The time loop, written once over what it asks of a model ([`Mechanics`]): the
//! static preload under gravity, then Newmark average acceleration or HHT-α with
//! Newton–Raphson equilibrium iterations on the consistent tangent, failing steps cut in
//! halves. Massless nodes carry no inertia: their rows are (1 + α)·p₊ − α·pₙ = 0.
//!
//! - `mechanics`: what the loop asks of a model ([`Mechanics`]), the step state, the
//!   workspace.
//! - `newmark`: Newmark's relations and the HHT-α weights of a step.
//! - `newton`: one step's Newton iteration, line search and convergence tests.
//! - `time_loop`: the preload, the state at t = 0, the steps and their cutting.
//! - `failure`: the run's counters and why a step failed.

mod failure;
mod mechanics;
mod newmark;
mod newton;
mod time_loop;

pub use failure::Counters;
pub(crate) use failure::{FailureReason, LastIteration, StepFailure};
pub(crate) use mechanics::{Mechanics, State, StepFn, StepState, Workspace};
pub(crate) use newmark::Newmark;
pub(crate) use newton::{LineSearch, failed, judge, not_converged};
pub(crate) use time_loop::{integrate, preload};

//! Many runs of one scene at many time steps, in parallel on all cores, each through the
//! one guarded, timed run ([`crate::run::guarded`]), so that a run that blows up — even
//! one that panics — is a result and never loses the others. Results are typed and
//! serialisable (`sweep.json`, `stability.json`); `rockslide-present` renders them.
//!
//! - [`work_precision`]: error against run time of every applicable engine variant over a
//!   Δt ladder, with the observed order of accuracy ([`SweepResult`]).
//! - [`stability`]: the stiff and extreme scenes of `cases/stability/`, each run
//!   classified, and each engine variant's practical stability limit in Δt/T
//!   ([`StabilityResult`]).
//! - [`plan`]: the characteristic period and the applicable engine variants;
//!   [`options`]: the commands' settings.
//!
//! The arithmetic (errors, orders, classes, energy) lives in [`crate::analysis`]. Both are
//! generic over [`crate::registry::all`]: an engine added there is swept and classified
//! without a change here.

pub mod options;
pub mod plan;
pub mod stability;
pub mod work_precision;

pub use options::{DEFAULT_BUDGET, Options};
pub use plan::{Series, applicable, characteristic_period};
pub use stability::StabilityResult;
pub use work_precision::SweepResult;

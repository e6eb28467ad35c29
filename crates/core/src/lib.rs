//! # rockslide-core — what every rockslide crate shares
//!
//! The input side and the output type, no physics and no file format:
//!
//! - [`case`]: TOML case files → validated scenes (SI units), excitations, recorded ground
//!   motions, with every input error located (`file:line:col: field: reason`).
//! - [`response`]: the response quantities a case's tolerances can name, with display units.
//! - [`trace`]: the output type — channels with units, the quantity catalogue, the
//!   per-contact block — that engines fill. Its files (CSV, MCAP, the Foxglove scene) and
//!   other programs' results are `rockslide-formats`', which engines do not need.
//! - [`study_grid`]: study grid files → validated, expanded grids of points.
//! - [`error`]: input errors and run-time errors; [`io`]: atomic writes into the paths
//!   the user means; [`serde_real`]: non-finite numbers through JSON.
//!
//! ## Glossary (paper symbols)
//!
//! | symbol | meaning | unit |
//! |---|---|---|
//! | M | mass | kg |
//! | Kx, Kz | horizontal (sticking) and vertical contact stiffness | N/m |
//! | μ | friction coefficient | — |
//! | Fz | normal force M·g | N |
//! | Ru | friction limit μ·Fz | N |
//! | R | resistance (base reaction) | N |
//! | x | relative displacement of the mass | m |
//! | xp | accumulated plastic displacement = sliding | m |
//! | θ | circular frequency of the excitation | rad/s |
//! | td | pulse duration | s |
//! | xg | ground displacement | m |

#![warn(missing_docs)]

pub mod case;
pub mod error;
pub mod io;
pub mod response;
pub mod serde_real;
pub mod study_grid;
pub mod trace;

//! # rockslide — cross-code verification of seismic sliding and rocking
//!
//! The data flows one way:
//!
//! ```text
//! case file ─▶ case::Case (validated scene) ─▶ engine::* ─▶ trace::Trace ─▶ analysis ─▶ report / gate
//!                                          └─▶ reference::* (exact, independent) ──┘
//! ```
//!
//! - [`case`]: TOML case files → validated scenes (SI units), with located errors.
//! - [`engine`]: the engines — the paper's predictor-corrector, the penalty FE contact
//!   model, the rapier rigid-body model — behind one [`engine::Engine`] interface. They
//!   share the scene and the trace format, never physics code.
//! - [`reference`]: exact and closed-form solutions, sharing nothing with the engines.
//! - [`trace`]: the output format (channels with units) and its CSV writer.
//! - [`analysis`]: response quantities, discrepancies, tolerance checks.
//! - [`study`]: many-run studies over records, PGAs and μ (sharded, resumable).
//! - [`suite`]: running a case; [`report`]: Markdown/HTML reports, plots, summary CSV;
//!   [`gate`]: gate failures and JUnit XML; [`cli`]: the commands.
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

pub mod analysis;
pub mod case;
pub mod cli;
pub mod engine;
pub mod error;
pub mod gate;
pub mod io;
pub mod reference;
pub mod report;
pub mod study;
pub mod suite;
pub mod sweep_cmd;
pub mod trace;

//! # rockslide-present — what an engineer reads and what CI trusts
//!
//! Every human output is rendered here from a typed result computed by
//! `rockslide-verify`, through one document model (`doc`, rendered to Markdown
//! and HTML) and one palette (`doc::figure`):
//!
//! - `doc`: the document model and its Markdown and HTML renderers, the number formats,
//!   the figure palette and legend strip, pages and CSV files written — what every page
//!   below shares, naming none of them;
//! - [`report`]: the case and suite reports (tables, cross-code matrix, time-history
//!   figures, provenance, the MCAP log of a case);
//! - [`sweep`], [`stability`], [`study`]: the pages, CSV files and figures of a sweep, a
//!   stability study and a records study;
//! - [`gate`]: gate lines, JUnit XML, the GitHub step summary (the verdict itself is
//!   `rockslide_verify::verdict`);
//! - [`stamp`]: the build's version and commit, fixed at build time;
//! - [`foxglove_layout`]: the Foxglove layout beside a case's MCAP file.

#![warn(missing_docs)]

pub(crate) mod doc;
pub mod foxglove_layout;
pub mod gate;
pub mod report;
pub mod stability;
pub mod stamp;
pub mod study;
pub mod sweep;

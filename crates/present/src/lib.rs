//! # rockslide-present — what an engineer reads and what CI trusts
//!
//! Every human output is rendered here from a typed result computed by
//! `rockslide-verify`, through one document model (`report::doc`, rendered to Markdown
//! and HTML) and one palette (`report::figure`):
//!
//! - [`report`]: the case and suite reports (tables, cross-code matrix, time-history
//!   figures, provenance, the MCAP log of a case), and the document model itself;
//! - [`sweep`], [`stability`], [`study`]: the pages, CSV files and figures of a sweep, a
//!   stability study and a records study;
//! - [`gate`]: gate lines, JUnit XML, the GitHub step summary (the verdict itself is
//!   `rockslide_verify::verdict`);
//! - [`stamp`]: the build's version and commit, fixed at build time.

#![warn(missing_docs)]

pub mod gate;
pub mod report;
pub mod stability;
pub mod stamp;
pub mod study;
pub mod sweep;

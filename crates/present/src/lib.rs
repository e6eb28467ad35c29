//! # rockslide-present — what an engineer reads and what CI trusts
//!
//! - [`report`]: a small document model rendered to Markdown and HTML; tables, the
//!   cross-code matrix, SVG figures, provenance, the MCAP log of a case.
//! - [`gate`]: gate lines, JUnit XML, the GitHub step summary (the verdict itself is
//!   `rockslide_verify::verdict`).

#![warn(missing_docs)]

pub mod gate;
pub mod report;

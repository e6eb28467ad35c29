//! The document model every human output is built in — headings, paragraphs, tables,
//! figures ([`Block`]) — and what every page shares: its Markdown and self-contained HTML
//! renderers, the number formats, the figure palette and legend strip, and the writing of
//! a page with its figures and CSV tables. The report, sweep, stability and study pages
//! build on it; it names none of them.

pub(crate) mod figure;
pub(crate) mod files;
pub(crate) mod format;
pub(crate) mod html;
pub(crate) mod markdown;
mod model;

pub(crate) use model::{Block, Cell, Table, Tone};

//! The one stamp of this build — the tool's version and the commit of its sources — fixed
//! at build time (`build.rs`), so that every output of one binary (reports, MCAP files,
//! study summaries) names the same sources, wherever and from whatever folder it runs.

/// The tool's version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The commit the tool was built from: `ROCKSLIDE_GIT_COMMIT` at build time when set,
/// else `git rev-parse HEAD` of the source tree with `+dirty` when tracked files had
/// local changes, else `unknown` (built outside a checkout).
pub const COMMIT: &str = env!("ROCKSLIDE_COMMIT");

/// `rockslide <version>`.
pub fn tool() -> String {
    format!("rockslide {VERSION}")
}

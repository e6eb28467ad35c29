//! External participants: another program's results taking part in a case like an engine
//! run, under their own label. The case holds their declaration and their trace; reading a
//! results file is the file formats' work, handed to the loader as a [`ReadExternal`].

use std::path::{Path, PathBuf};

use crate::error::InputErrors;
use crate::trace::Trace;

/// The variant name of every external participant: its run is `<label>/external`.
pub const EXTERNAL_VARIANT: &str = "external";

/// Results produced by another program, read from a file: a participant of the case like
/// an engine run, under its own label.
#[derive(Debug, Clone, PartialEq)]
pub struct External {
    /// Label, as tolerances name it (`engine = "sap2000"`); never an engine id.
    pub label: String,
    /// The program (and version) that produced it, free text.
    pub program: String,
    /// The element or model used in it, free text.
    pub element: String,
    /// The results file, as resolved (relative to the case file, or as given).
    pub file: PathBuf,
    /// Its time histories in SI, and how they were read.
    pub read: ExternalTrace,
    /// Where it was declared (`external[0]`, or `--external <label>`).
    pub field: String,
}

/// How an external file is laid out.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ExternalFormat {
    /// Foreign header → rockslide header (`"U1 (mm)"` → `"rel_disp [mm]"`). Empty: the
    /// headers are rockslide's. With a map, unmapped columns are ignored (and listed).
    pub columns: Vec<(String, String)>,
    /// Field separator of a CSV: `,` (default), `;`, `\t`, or `' '` for runs of blanks.
    pub delimiter: Option<char>,
    /// Lines before the header line (a foreign program's preamble).
    pub skip_lines: usize,
    /// The state topic of an MCAP file (`/fe/paper/state`); needed when it has several.
    pub topic: Option<String>,
}

/// An external file read: its trace in SI, and what the reader did, in words.
#[derive(Debug, Clone, PartialEq)]
pub struct ExternalTrace {
    /// Time histories, SI, catalogue quantities only.
    pub trace: Trace,
    /// How it was read: format, units converted, columns ignored.
    pub notes: Vec<String>,
}

/// Reads a results file of another program into a trace (an MCAP file or a CSV, in the
/// layout the case states), every problem an input error located in that file. The file
/// formats live outside core: their crate hands its reader to the case loader.
pub type ReadExternal = fn(&Path, &ExternalFormat) -> Result<ExternalTrace, InputErrors>;

/// Longest external label.
const MAX_LABEL_LEN: usize = 40;

/// `Ok` when `label` can name an external participant: a short slug (it names files and
/// MCAP topics), not an engine id, not `reference`.
pub fn check_label(label: &str, engine_ids: &[&str]) -> Result<(), String> {
    let slug = |c: char| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-');
    if label.is_empty() || label.chars().count() > MAX_LABEL_LEN {
        return Err(format!("must have 1 to {MAX_LABEL_LEN} characters"));
    }
    if !label.chars().all(slug) || !label.starts_with(|c: char| c.is_ascii_alphanumeric()) {
        return Err(format!(
            "is {label:?}; a label names files and topics: letters, digits, `.`, `_`, `-`, \
             starting with a letter or a digit"
        ));
    }
    if engine_ids.contains(&label) || label == "reference" {
        return Err(format!(
            "is \"{label}\", which is an engine or the reference; choose another label"
        ));
    }
    Ok(())
}

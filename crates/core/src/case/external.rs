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
    /// The program's layout (`format = "…"`); `None`: recognised from the file (a
    /// SAP2000 `TABLE:` title line, the ANSYS POST26 listing banner), else a CSV.
    pub layout: Option<ExternalLayout>,
    /// Foreign column → rockslide header, with a factor (`"U1 (mm)"` → `"rel_disp [mm]"`,
    /// `"Link 1: P"` → `"normal [kN]"` × −1). Empty: the headers are rockslide's. With a
    /// map, unmapped columns are ignored (and listed).
    pub columns: Vec<ColumnMap>,
    /// Field separator of a CSV: `,` (default), `;`, `\t`, or `' '` for runs of blanks.
    pub delimiter: Option<char>,
    /// Lines before the header line (a foreign program's preamble).
    pub skip_lines: usize,
    /// The state topic of an MCAP file (`/fe/paper/state`); needed when it has several.
    pub topic: Option<String>,
    /// A SAP2000/ETABS/CSiBridge table's `OutputCase` to read (needed when it has several).
    pub output_case: Option<String>,
    /// The OpenSees recorder command that wrote the file (`Node -file d.out -time -node 2
    /// -dof 1 disp`), naming its columns.
    pub recorder: Option<String>,
    /// An OpenSees script (Tcl or Python, resolved) whose recorder command writing the
    /// file names its columns.
    pub script: Option<PathBuf>,
    /// The time between two numbered steps of a SAP2000/ETABS table whose rows are steps
    /// (`StepType` `Step`: time = StepNum × step_dt), s: `step_dt` of the `[[external]]`,
    /// else the case's `run.dt`. `None`: such rows are refused.
    pub step_dt: Option<f64>,
}

/// One column of a foreign file as rockslide reads it: `value × scale`, in `to`'s unit.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnMap {
    /// The column as the program names it (`"U1 (mm)"`, `"Joint 2: U1"`, `"UX_2"`).
    pub from: String,
    /// The rockslide header it becomes (`"rel_disp [mm]"`; without a unit, the file's
    /// own units row or the quantity's SI unit).
    pub to: String,
    /// Factor applied before the unit's conversion: a sign (−1 for a compression-negative
    /// normal force) and a scale.
    pub scale: f64,
}

impl ColumnMap {
    /// A column read as written (scale 1).
    pub fn new(from: impl Into<String>, to: impl Into<String>) -> Self {
        Self {
            from: from.into(),
            to: to.into(),
            scale: 1.0,
        }
    }
}

/// The programs whose result files are read in their own layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExternalLayout {
    /// A CSV (rockslide's headers, or foreign ones with a column map).
    Csv,
    /// SAP2000, ETABS or CSiBridge table export: `TABLE:` title, field names, units row,
    /// long tables (one row per object per step).
    CsiTables,
    /// ANSYS POST26 `PRVAR` listing (the banner repeated on every page).
    AnsysPrvar,
    /// Abaqus XY report (`.rpt`): an `X` column and named curves, `NoValue` gaps.
    AbaqusReport,
    /// OpenSees recorder output: no header, columns named by the recorder command.
    OpenSeesRecorder,
}

impl ExternalLayout {
    /// The layout `format = "…"` names, or `None`.
    pub fn from_key(key: &str) -> Option<Self> {
        Some(match key {
            "csv" => Self::Csv,
            "sap2000" | "etabs" | "csibridge" => Self::CsiTables,
            "ansys" => Self::AnsysPrvar,
            "abaqus" => Self::AbaqusReport,
            "opensees" => Self::OpenSeesRecorder,
            _ => return None,
        })
    }

    /// The accepted keys, in words.
    pub const KEYS: &'static str =
        "\"csv\", \"sap2000\" (also \"etabs\", \"csibridge\"), \"ansys\", \"abaqus\", \"opensees\"";
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
    if engine_ids.contains(&label) || label == super::REFERENCE_LABEL {
        return Err(format!(
            "is \"{label}\", which is an engine or the reference; choose another label"
        ));
    }
    Ok(())
}

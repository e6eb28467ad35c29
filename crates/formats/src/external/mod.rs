//! Results produced by another program, read as a [`Trace`] in SI, each file in the layout
//! its program writes: a CSV (rockslide's own headers, or foreign ones with a column map),
//! SAP2000/ETABS/CSiBridge table exports (`csi`; exported to Excel: `xlsx`), ANSYS POST26 `PRVAR` listings (`ansys`),
//! Abaqus XY reports (`abaqus`), OpenSees recorder files (`opensees`), or a state topic of
//! a rockslide MCAP file. A program's layout is named by `format = "…"` or recognised
//! from the file (a `TABLE:` title line, the POST26 banner; an `.xlsx` workbook by its
//! extension).
//!
//! The column map names the program's own objects and fields (`"Joint 2: U1"`, `"UX_2"`,
//! `"node 2 dof 1 disp"`) and may carry a factor: a sign (SAP2000's link force `P` is
//! tension-positive, rockslide's `normal` compression-positive) and a scale. Values are
//! converted to SI on reading (`value × scale × mul / div`, exact for SI columns at scale
//! 1, so a trace written by rockslide reads back bit for bit), and every conversion is
//! stated in the run's notes. Sizes are checked before anything is allocated: the file's
//! bytes ([`MAX_EXTERNAL_BYTES`]), its columns ([`MAX_EXTERNAL_COLUMNS`]) and rows
//! (`limits::max_steps`). Every problem is an input error naming the file, line, column
//! and reason.

use std::path::Path;

use rockslide_core::case::{ExternalFormat, ExternalLayout, ExternalTrace};
use rockslide_core::error::{InputError, InputErrors, io_reason, line_col};
use rockslide_core::trace::Trace;

use crate::mcap_file::{read_bounded, read_mcap};

mod abaqus;
mod ansys;
mod csi;
mod csv;
mod number;
mod opensees;
mod opensees_xml;
mod sheet;
mod xlsx;

pub use csv::read_external_csv;

/// Largest external results file read, bytes (256 MiB).
pub const MAX_EXTERNAL_BYTES: u64 = 256 << 20;

/// Most columns an external CSV may have.
pub const MAX_EXTERNAL_COLUMNS: usize = 1024;

/// Read an external results file: an MCAP file (by extension `.mcap`), or a text file in
/// the layout `format` names (or the one recognised from its first lines).
pub fn read_external(path: &Path, format: &ExternalFormat) -> Result<ExternalTrace, InputErrors> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
    {
        return read_external_mcap(path, format.topic.as_deref());
    }
    let bytes = read_bytes(path)?;
    parse_external_bytes(path, &bytes, format)
}

/// [`read_external`] from a file's bytes: SAP2000/ETABS/CSiBridge tables exported to
/// Excel when `path` ends in `.xlsx`, an OpenSees `-binary` recorder file when the format
/// names OpenSees and the bytes are binary, else the text ([`parse_external`]).
pub fn parse_external_bytes(
    path: &Path,
    bytes: &[u8],
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    if xlsx::is_workbook(path) {
        if !matches!(format.layout, None | Some(ExternalLayout::CsiTables)) {
            let why = "is an Excel workbook: rockslide reads SAP2000/ETABS/CSiBridge tables \
                       exported to Excel (`format = \"sap2000\"`, or no format); save another \
                       program's results as the text file it writes";
            return Err(InputError::new(path, "format", why).into());
        }
        return xlsx::read(path, bytes, format);
    }
    if format.layout == Some(ExternalLayout::OpenSeesRecorder) && opensees::is_binary(bytes) {
        return opensees::read_binary(path, bytes, format);
    }
    let text = text_of(path, bytes)?;
    parse_external(path, text, format)
}

/// [`read_external`] from a text file's contents (`path` names it in errors; a script the
/// format names is read from its own path).
pub fn parse_external(
    path: &Path,
    text: &str,
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    // a byte-order mark, as spreadsheet programs write it, is not part of the first header
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let layout = match (format.layout, format.skip_lines) {
        (Some(layout), _) => layout,
        (None, 0) => recognise(text),
        (None, _) => ExternalLayout::Csv, // a CSV below a preamble the case skips
    };
    match layout {
        ExternalLayout::Csv => read_external_csv(path, text, format),
        ExternalLayout::CsiTables => csi::read(path, text, format),
        ExternalLayout::AnsysPrvar => ansys::read(path, text, format),
        ExternalLayout::AbaqusReport => abaqus::read(path, text, format),
        ExternalLayout::OpenSeesRecorder => opensees::read(path, text, format),
    }
}

/// A results file's bytes, its size checked first.
fn read_bytes(path: &Path) -> Result<Vec<u8>, InputErrors> {
    read_bounded(path, MAX_EXTERNAL_BYTES).map_err(|e| {
        let why = io_reason(&e);
        InputError::new(path, "", format!("cannot read the results file: {why}")).into()
    })
}

/// A text file's contents (an OpenSees script), its size checked first.
fn read_text(path: &Path) -> Result<String, InputErrors> {
    let bytes = read_bytes(path)?;
    text_of(path, &bytes).map(str::to_owned)
}

/// A results file's bytes as text; not UTF-8 is an error at its place.
fn text_of<'a>(path: &Path, bytes: &'a [u8]) -> Result<&'a str, InputErrors> {
    std::str::from_utf8(bytes).map_err(|e| {
        let (line, col) = line_col(
            &String::from_utf8_lossy(&bytes[..e.valid_up_to()]),
            usize::MAX,
        );
        InputError::new(path, "", "is not UTF-8 text")
            .at(line, col)
            .into()
    })
}

/// The layout a file's first lines show: a SAP2000/ETABS/CSiBridge `TABLE:` title above
/// field names with `OutputCase` and `StepNum`, the ANSYS POST26 listing banner, else a
/// CSV. Abaqus reports and OpenSees recorder files carry no mark of their program: they
/// are named with `format`.
fn recognise(text: &str) -> ExternalLayout {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let (first, second) = (lines.next(), lines.next());
    if first.is_some_and(csi::is_title)
        && second.is_some_and(|l| l.contains("OutputCase") && l.contains("StepNum"))
    {
        return ExternalLayout::CsiTables;
    }
    if text.lines().take(50).any(ansys::is_banner) {
        return ExternalLayout::AnsysPrvar;
    }
    ExternalLayout::Csv
}

/// The state topic of a rockslide MCAP file as an external trace.
fn read_external_mcap(path: &Path, topic: Option<&str>) -> Result<ExternalTrace, InputErrors> {
    let contents = read_mcap(path)?;
    let candidates: Vec<&(String, Trace)> = contents
        .states
        .iter()
        .filter(|(t, _)| t != "/reference/state")
        .collect();
    let chosen = match topic {
        Some(t) => contents.states.iter().find(|(name, _)| name == t),
        None if candidates.len() == 1 => Some(candidates[0]),
        None => None,
    };
    let Some((name, trace)) = chosen else {
        let topics: Vec<&str> = contents.states.iter().map(|(t, _)| t.as_str()).collect();
        let what = match topic {
            Some(t) => format!("has no state topic \"{t}\""),
            None => format!(
                "has several state topics: name one (`{}#<topic>` on the command line, `topic = \"<topic>\"` in an [[external]] section)",
                path.display()
            ),
        };
        return Err(InputError::new(
            path,
            "topic",
            format!("{what}; its state topics: {}", topics.join(", ")),
        )
        .into());
    };
    if trace.is_empty() {
        return Err(InputError::new(path, "topic", format!("\"{name}\" has no messages")).into());
    }
    check_times(path, name, &trace.time)?;
    // the state alone, as from a CSV file: the contacts its messages carry stay out
    let notes = vec![format!(
        "rockslide MCAP topic {name}, {} samples",
        trace.len()
    )];
    let mut trace = trace.clone();
    trace.contacts = Default::default();
    Ok(ExternalTrace { trace, notes })
}

/// Times of an MCAP topic must be finite and strictly increasing (message `i`, 1-based).
fn check_times(path: &Path, topic: &str, time: &[f64]) -> Result<(), InputErrors> {
    for i in 0..time.len() {
        if !(time[i].is_finite() && (i == 0 || time[i] > time[i - 1])) {
            return Err(InputError::new(
                path,
                "topic",
                format!(
                    "{topic}: message {}: time {} s does not increase",
                    i + 1,
                    time[i]
                ),
            )
            .into());
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;

//! Scene export: a case's scene written as another program's input, so that the program's
//! results can come back as an external participant. This crate shares the scene
//! (`rockslide-core`), never physics: it writes what the other program must model, and
//! the other program solves it.
//!
//! - [`opensees`]: an OpenSeesPy script (PEPO single and double, RPEPO single,
//!   pulses and records) that writes a CSV in rockslide's own trace format.
//! - [`ansys`]: an ANSYS APDL deck of the paper's CONTA178 models (PEPO single and
//!   double, RPEPO on its supports) that writes rockslide's CSV; not executed by rockslide.
//! - [`calculix`]: a CalculiX `.inp` deck of the PEPO (single and double) and the RPEPO
//!   (single, [`calculix_rocking`]), penalty contact with Coulomb friction, whose `.dat`
//!   output rockslide reads back (CalculiX live).
//! - [`abaqus`]: an Abaqus/Standard deck of the PEPO (single and double) and the RPEPO,
//!   penalty contact with Coulomb friction, and a script that writes rockslide's CSV from
//!   its results; not executed by rockslide.
//! - [`inp`]: the Abaqus input syntax CalculiX shares, and the PEPO's contact model in it.
//! - [`deck`]: what the decks share (numbers that read back exactly, settings, the scenes
//!   they model).
//!
//! An export is a list of [`ExportFile`]s (names and bytes); the caller writes them
//! atomically inside its output folder. A scene the exporter cannot represent is an
//! [`InputError`] naming the case field and the reason.

pub mod abaqus;
pub mod ansys;
pub mod calculix;
pub mod calculix_rocking;
pub mod deck;
pub mod inp;
pub mod opensees;

use rockslide_core::error::InputError;

/// One file of an export: a bare file name (no folder) and its bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportFile {
    /// File name, without any folder.
    pub name: String,
    /// Contents.
    pub bytes: Vec<u8>,
}

/// The files of one export, the main one (the script) first.
#[derive(Debug, Clone, PartialEq)]
pub struct Export {
    /// Files to write, the script first.
    pub files: Vec<ExportFile>,
    /// Name of the results file the script writes beside itself.
    pub results: String,
}

impl Export {
    /// An export of one deck file, `name`, whose run writes `results` beside it.
    pub fn deck(name: String, text: String, results: String) -> Export {
        Export {
            files: vec![ExportFile {
                name,
                bytes: text.into_bytes(),
            }],
            results,
        }
    }
}

/// Result of an export: the files, or why the scene cannot be exported.
pub type ExportResult = Result<Export, InputError>;

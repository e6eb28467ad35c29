//! # rockslide-formats — the trace's files
//!
//! What `rockslide-core`'s types look like on disk, and other programs' results read back
//! as them. Engines do not depend on this crate: they fill core's [`Trace`] and
//! [`ContactBlock`](rockslide_core::trace::ContactBlock); the verification and the reports
//! read and write the files.
//!
//! - `csv_file`: a trace as CSV (`time [s],rel_disp [m],…`, shortest round-trip decimals);
//!   `contacts`: the per-contact block as `<run>-contacts.csv`.
//! - `mcap_file`: every run of a case in one MCAP file for Foxglove (our writer in
//!   `mcap_file/writer.rs`; a bounded, checked reader), its step messages in CDR (`cdr`)
//!   and a 3D view of scenes with geometry ([`scene3d`]).
//! - `external`: other programs' results read as traces (rockslide CSV in any catalogued
//!   unit, foreign CSV with a column map, MCAP, and the files SAP2000/ETABS/CSiBridge,
//!   ANSYS, Abaqus and OpenSees write); `case`: a case loaded with them read.
//! - [`calculix_dat`]: CalculiX's `.dat` results file, read as blocks (CalculiX live).
//!
//! [`Trace`]: rockslide_core::trace::Trace

#![warn(missing_docs)]

pub mod calculix_dat;
mod case;
mod cdr;
mod contacts;
mod csv_file;
mod external;
mod mcap_file;
pub mod scene3d;

pub use case::{load_case, parse_case, read_external_participant};
pub use cdr::{
    CDR_LE_HEADER, MESSAGE_ENCODING as STEP_MESSAGE_ENCODING,
    SCHEMA_ENCODING as STEP_SCHEMA_ENCODING, state_definition,
};
pub use contacts::{CONTACTS_SCHEMA, contacts_schema_name, read_contacts_csv, write_contacts_csv};
pub use csv_file::{read_csv, write_csv};
pub use external::{
    MAX_EXTERNAL_BYTES, MAX_EXTERNAL_COLUMNS, parse_external, parse_external_bytes, read_external,
    read_external_csv,
};
pub use mcap_file::{
    CHUNKS, ChunkCompression, ChunkOptions, LoggedRun, MAX_SCENE_FRAMES, McapChannel, McapContents,
    McapWriter, SCENE_PERIOD_NS, STATE_SCHEMA, TraceLog, describe, mcap_bytes, mcap_bytes_with,
    mcap_info, read_mcap, read_mcap_bytes, scene_period_ns, state_schema_name, write_mcap,
};

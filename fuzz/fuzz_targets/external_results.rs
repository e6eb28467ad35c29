//! Another program's results (`[[external]]`) in every layout rockslide reads, as bytes: a
//! CSV (rockslide's headers, or foreign ones through a column map), a SAP2000/ETABS/
//! CSiBridge table export (text, or exported to Excel: bytes that start as a zip archive
//! does, `PK`, are read as the workbook `fuzz.xlsx`), an ANSYS POST26 `PRVAR` listing, an
//! Abaqus XY report, an OpenSees recorder file (text, `-xml` or `-binary`). The first byte
//! picks the layout (or "recognise it from the file"), the delimiter, the preamble lines
//! skipped, the output case and whether a column map in the program's own names applies;
//! for an OpenSees file the first line is the recorder command naming its columns. Any
//! bytes give a trace or a located error, never a panic.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rockslide_core::case::{ColumnMap, ExternalFormat, ExternalLayout};
use rockslide_formats::parse_external_bytes;

/// The column map of each layout, in that program's own names (as its tests use them);
/// `xml`: an OpenSees file's names as its `-xml` header gives them.
fn columns(layout: Option<ExternalLayout>, xml: bool) -> Vec<ColumnMap> {
    let map: &[(&str, &str, f64)] = match layout {
        None | Some(ExternalLayout::Csv) => &[
            ("Time (sec)", "time [s]", 1.0),
            ("U1 (mm)", "rel_disp [mm]", 1.0),
            ("Slip (mm)", "slide [mm]", 1.0),
        ],
        Some(ExternalLayout::CsiTables) => &[
            ("Joint 2: U1", "rel_disp", 1.0),
            ("Link 1: P", "normal", -1.0),
            ("Link 1: V2", "resistance [kN]", 1.0),
        ],
        Some(ExternalLayout::AnsysPrvar) => &[
            ("UX_2", "rel_disp [m]", 1.0),
            ("FX_1", "resistance [N]", -1.0),
            ("SLIP_1", "slide", 1.0),
        ],
        Some(ExternalLayout::AbaqusReport) => &[
            ("U:U1 PI: MASS-1 N: 2", "rel_disp [m]", 1.0),
            ("RF:RF1 PI: GROUND-1 N: 1", "resistance [N]", -1.0),
        ],
        Some(ExternalLayout::OpenSeesRecorder) if xml => &[
            ("node 2 D1", "rel_disp [m]", 1.0),
            ("element 1 Px_1", "normal [kN]", -1.0),
            ("element 1 Vy_1", "resistance [kN]", -1.0),
        ],
        Some(ExternalLayout::OpenSeesRecorder) => &[("node 2 dof 1 disp", "rel_disp [m]", 1.0)],
    };
    map.iter()
        .map(|&(from, to, scale)| ColumnMap {
            from: from.into(),
            to: to.into(),
            scale,
        })
        .collect()
}

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else {
        return;
    };
    let layout = [
        None,
        Some(ExternalLayout::Csv),
        Some(ExternalLayout::CsiTables),
        Some(ExternalLayout::AnsysPrvar),
        Some(ExternalLayout::AbaqusReport),
        Some(ExternalLayout::OpenSeesRecorder),
    ][usize::from(selector % 6)];
    let mapped = selector & 0x80 != 0;
    let mut format = ExternalFormat {
        layout,
        columns: if mapped {
            columns(layout, selector & 0x40 != 0)
        } else {
            Vec::new()
        },
        delimiter: [None, Some(';'), Some('\t'), Some(' ')][usize::from((selector >> 3) % 4)],
        skip_lines: usize::from((selector >> 5) % 4),
        output_case: (selector & 0x40 != 0).then(|| "TH".to_string()),
        ..Default::default()
    };
    let mut body = rest;
    if layout == Some(ExternalLayout::OpenSeesRecorder) {
        let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        format.recorder = Some(String::from_utf8_lossy(&rest[..end]).into_owned());
        body = rest.get(end + 1..).unwrap_or(&[]);
    }
    // a workbook is recognised by its extension: the name follows the zip signature
    let name = if body.starts_with(b"PK") {
        "fuzz.xlsx"
    } else {
        "fuzz.txt"
    };
    let _ = parse_external_bytes(Path::new(name), body, &format);
});

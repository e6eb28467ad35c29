//! Another program's results as a CSV (`[[external]]`): the first byte picks the
//! delimiter (`,`, `;`, tab, blanks), the preamble lines skipped (0–3) and whether the
//! headers go through a column map (a SAP2000-like table: `Time (sec)`, `U1 (mm)`,
//! `Slip (mm)`); any bytes give a trace or a located error, never a panic.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rockslide_core::case::ExternalFormat;
use rockslide_formats::read_external_csv;

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let delimiter = [None, Some(';'), Some('\t'), Some(' ')][usize::from(selector % 4)];
    let mapped = selector & 0x10 != 0;
    let columns = if mapped {
        [
            ("Time (sec)", "time [s]"),
            ("U1 (mm)", "rel_disp [mm]"),
            ("Slip (mm)", "slide [mm]"),
        ]
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
    } else {
        Vec::new()
    };
    let format = ExternalFormat {
        columns,
        delimiter,
        skip_lines: usize::from((selector >> 2) % 4),
        topic: None,
    };
    let _ = read_external_csv(Path::new("fuzz.csv"), text, &format);
});

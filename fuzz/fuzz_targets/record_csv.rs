//! A two-column CSV record's text: any bytes give a record or a located error.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rockslide_core::case::record::{AccelUnit, parse_csv};

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = parse_csv(Path::new("fuzz.csv"), text, AccelUnit::G);
    }
});

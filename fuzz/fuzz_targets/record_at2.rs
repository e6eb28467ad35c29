//! A PEER AT2 record's text: any bytes give a record or a located error, never a panic
//! or an allocation the header asks for but the data does not hold.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rockslide_core::case::record::parse_at2;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = parse_at2(Path::new("fuzz.AT2"), text, None);
    }
});

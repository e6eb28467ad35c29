//! A case file's text through parsing and validation: any bytes give a case or located
//! errors, never a panic.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rockslide_formats::parse_case;

/// The engine ids of the registry (`rockslide_verify::registry::ENGINE_IDS`), kept here so
/// that the target builds without the engines.
const ENGINE_IDS: &[&str] = &["predictor-corrector", "fe", "rapier"];

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = parse_case(Path::new("fuzz/case.toml"), text, ENGINE_IDS);
    }
});

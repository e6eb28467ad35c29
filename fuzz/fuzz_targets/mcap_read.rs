//! An MCAP file's bytes through the reader behind `rockslide trace-info`: any bytes give
//! the contents or an error, never a panic or an unbounded allocation.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rockslide_formats::read_mcap_bytes;

fuzz_target!(|data: &[u8]| {
    let _ = read_mcap_bytes(Path::new("fuzz.mcap"), data);
});

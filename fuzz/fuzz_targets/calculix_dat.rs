//! CalculiX's `.dat` results file (`*NODE PRINT`, `*EL PRINT` blocks), as the CalculiX
//! participant reads it: every block, then one node's series and the totals' series of
//! the quantities it reads. Any bytes give the blocks or a located error, never a panic.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rockslide_formats::calculix_dat::{read_calculix_dat, series};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(blocks) = read_calculix_dat(Path::new("job.dat"), text) else {
        return;
    };
    for quantity in ["displacements", "total force", "stresses"] {
        for column in 0..4 {
            let _ = series(&blocks, quantity, "BODY", Some(2), column);
            let _ = series(&blocks, quantity, "BODY", None, column);
        }
    }
});

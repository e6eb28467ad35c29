//! A strong-motion station file as an agency publishes it — COSMOS V0/V1/V2, a CSMIP
//! volume (the Avol1 `.RAW`/`.V1` and the V2 layouts, several channels a file), a USGS SMC
//! file — read by its first line's layout, then prepared for a run as `[excitation.station]`
//! does (trimmed to one length, an uncorrected record's pre-event mean removed and its
//! baseline corrected, every drift integrated). Any bytes give a station or a located
//! error, never a panic; the preparation of any station read never panics.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rockslide_core::case::record::{Baseline, parse_station, prepare};

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let Ok(station) = parse_station(Path::new("station.v1"), text) else {
        return;
    };
    let baseline = if selector & 1 == 0 {
        Baseline::None
    } else {
        Baseline::Cubic
    };
    let _ = prepare(&station, baseline);
});

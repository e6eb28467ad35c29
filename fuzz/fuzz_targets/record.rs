//! A record's text, as PEER AT2 (first byte even) or CSV in g (odd: two columns, or one
//! acceleration column of several, `record_column` 1–3, chosen by the first byte): any
//! bytes give a record or a located error, never a panic or an allocation the header
//! asks for but the data does not hold.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rockslide_core::case::record::{AccelUnit, parse_at2, parse_csv_column};

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else {
        return;
    };
    if let Ok(text) = std::str::from_utf8(rest) {
        if selector % 2 == 0 {
            let _ = parse_at2(Path::new("fuzz.AT2"), text, None);
        } else {
            let column = match (selector / 2) % 4 {
                0 => None,
                k => Some(usize::from(k)),
            };
            let _ = parse_csv_column(Path::new("fuzz.csv"), text, AccelUnit::G, column);
        }
    }
});

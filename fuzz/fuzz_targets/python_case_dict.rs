//! A case given to the Python package as a dict (`rockslide.case_from_dict`): nested
//! tables, lists, strings, integers, floats (NaN and infinities included) and booleans,
//! written as TOML and then parsed and validated as a case file. Any tree gives a case or
//! located errors, never a panic. The tree is built from the bytes with case-file keys
//! most of the time, so that validation is reached.
#![no_main]

use std::path::Path;

use arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;
use rockslide_formats::parse_case;
use toml::{Table, Value};

/// The engine ids of the registry, as in the `case_toml` target.
const ENGINE_IDS: &[&str] = &["predictor-corrector", "fe", "rapier"];

/// Keys a case file uses, so that a random tree often names real fields.
const KEYS: &[&str] = &[
    "case", "name", "model", "kind", "mass", "gravity", "contact", "kx", "kz", "mu",
    "double", "excitation", "type", "amplitude", "omega", "cycles", "record", "file",
    "scale_to_pga_g", "run", "dt", "duration", "output_dt", "engines", "fe", "rapier",
    "predictor-corrector", "variants", "vertical", "normal_force", "spatial", "azimuth_deg",
    "station", "x_azimuth_deg", "tolerance", "quantity", "relative", "external", "format",
    "columns", "half_width", "half_height", "half_depth", "supports", "damping_ratio",
];

/// Deepest nesting built (the package refuses a dict deeper than 32 levels before this).
const MAX_DEPTH: usize = 6;

fn value(u: &mut Unstructured<'_>, depth: usize) -> arbitrary::Result<Value> {
    let kinds = if depth >= MAX_DEPTH { 5 } else { 7 };
    Ok(match u.int_in_range(0..=kinds - 1)? {
        0 => Value::Boolean(u.arbitrary()?),
        1 => Value::Integer(u.arbitrary()?),
        2 => Value::Float(u.arbitrary()?),
        3 => Value::Float(*u.choose(&[0.0, 1.0, 0.001, 0.2, 9.81, 1e6, f64::NAN, f64::INFINITY, -1.0])?),
        4 => Value::String(if u.arbitrary()? {
            (*u.choose(KEYS)?).to_string()
        } else {
            u.arbitrary()?
        }),
        5 => Value::Table(table(u, depth + 1)?),
        _ => {
            let n = u.int_in_range(0..=4)?;
            Value::Array((0..n).map(|_| value(u, depth + 1)).collect::<arbitrary::Result<_>>()?)
        }
    })
}

fn table(u: &mut Unstructured<'_>, depth: usize) -> arbitrary::Result<Table> {
    let mut t = Table::new();
    for _ in 0..u.int_in_range(0..=6)? {
        let key = if u.ratio(7, 8)? {
            (*u.choose(KEYS)?).to_string()
        } else {
            u.arbitrary()?
        };
        t.insert(key, value(u, depth)?);
    }
    Ok(t)
}

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let Ok(tables) = table(&mut u, 0) else {
        return;
    };
    if let Ok(text) = toml::to_string(&tables) {
        let _ = parse_case(Path::new("<case>.toml"), &text, ENGINE_IDS);
    }
});

//! Typed results as JSON files: the only contract between commands. `sweep` writes a
//! [`SweepResult`](crate::sweep::work_precision::SweepResult), `stability` a
//! [`StabilityResult`](crate::sweep::stability::StabilityResult), a study its points and
//! [`Study`](crate::study::Study); the reports read those structs back — never Markdown,
//! HTML or CSV. Writes are atomic.
//!
//! JSON has no NaN or infinity, and serde_json writes them as `null`, which an `f64` cannot
//! read back. A run that blew up has non-finite energies and errors, and those are results
//! too, so the fields that can hold them go through [`real`] (or [`real_opt`]): a finite
//! number as a JSON number, a non-finite one as the string `"NaN"`, `"inf"` or `"-inf"`.

use std::path::Path;

use serde::Serialize;
use serde::de::DeserializeOwned;

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;

/// Write `value` as pretty JSON to `path`, atomically.
pub fn write<T: Serialize>(path: &Path, value: &T) -> Result<(), Error> {
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Error::Other(format!("{}: cannot serialise: {e}", path.display())))?;
    write_atomically(path, text.as_bytes())
}

/// Read a JSON file written by [`write`]; the error names the file and what is wrong.
pub fn read<T: DeserializeOwned>(path: &Path) -> Result<T, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// An `f64` that may be non-finite: `#[serde(with = "crate::json::real")]` (kept in core,
/// where the study grid's points use it too).
pub use rockslide_core::serde_real::real;
/// An `Option<f64>` whose value may be non-finite: `#[serde(with = "crate::json::real_opt")]`.
pub use rockslide_core::serde_real::real_opt;

#[cfg(test)]
mod tests {
    use serde::{Deserialize, Serialize};

    #[derive(Debug, Serialize, Deserialize)]
    struct T {
        #[serde(with = "super::real")]
        a: f64,
        #[serde(with = "super::real_opt")]
        b: Option<f64>,
        #[serde(with = "super::real_opt")]
        c: Option<f64>,
    }

    #[test]
    fn non_finite_values_survive_the_round_trip() {
        for x in [1.5e-300, -0.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let t = T {
                a: x,
                b: Some(x),
                c: None,
            };
            let text = serde_json::to_string(&t).unwrap();
            let back: T = serde_json::from_str(&text).unwrap();
            let same = |p: f64, q: f64| p.to_bits() == q.to_bits() || (p.is_nan() && q.is_nan());
            assert!(same(back.a, x) && same(back.b.unwrap(), x), "{text}");
            assert_eq!(back.c, None);
        }
        let nan: T = serde_json::from_str(r#"{"a": null, "b": "NaN", "c": null}"#).unwrap();
        assert!(nan.a.is_nan() && nan.b.unwrap().is_nan());
        let bad = serde_json::from_str::<T>(r#"{"a": "lots", "b": null, "c": null}"#);
        assert!(
            bad.unwrap_err()
                .to_string()
                .contains("\"lots\" is not a number")
        );
    }
}

//! Numbers that may be non-finite, in serde formats that have no NaN or infinity (JSON):
//! serde_json writes them as `null`, which an `f64` cannot read back, so a value a case
//! accepts (μ = ∞) or a run produces (a blown-up energy) would not survive the round trip.
//! The fields that can hold one go through [`real`] (or [`real_opt`]): a finite number as
//! a number, a non-finite one as the string `"NaN"`, `"inf"` or `"-inf"`.

/// An `f64` that may be non-finite: `#[serde(with = "rockslide_core::serde_real::real")]`.
pub mod real {
    use serde::{Deserialize, Deserializer, Serializer};

    /// A number, or `"NaN"`, `"inf"`, `"-inf"`.
    #[derive(serde::Deserialize)]
    #[serde(untagged)]
    enum Repr {
        Number(f64),
        Text(String),
        Null(()),
    }

    /// Write a finite value as a number, a non-finite one as text.
    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        if x.is_finite() {
            s.serialize_f64(*x)
        } else if x.is_nan() {
            s.serialize_str("NaN")
        } else if *x > 0.0 {
            s.serialize_str("inf")
        } else {
            s.serialize_str("-inf")
        }
    }

    /// Read what [`serialize`] wrote (and `null` as NaN, as serde_json writes NaN).
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        match Repr::deserialize(d)? {
            Repr::Number(x) => Ok(x),
            Repr::Null(()) => Ok(f64::NAN),
            Repr::Text(t) => match t.as_str() {
                "NaN" => Ok(f64::NAN),
                "inf" => Ok(f64::INFINITY),
                "-inf" => Ok(f64::NEG_INFINITY),
                other => Err(serde::de::Error::custom(format!(
                    "\"{other}\" is not a number (expected a number, \"NaN\", \"inf\" or \"-inf\")"
                ))),
            },
        }
    }
}

/// An `Option<f64>` whose value may be non-finite: `#[serde(with = "rockslide_core::serde_real::real_opt")]`
/// (`null` is `None`).
pub mod real_opt {
    use serde::{Deserialize, Deserializer, Serializer};

    #[derive(serde::Serialize, serde::Deserialize)]
    struct Real(#[serde(with = "super::real")] f64);

    /// `None` as `null`, a value as [`super::real`] writes it.
    pub fn serialize<S: Serializer>(x: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        match x {
            Some(v) => super::real::serialize(v, s),
            None => s.serialize_none(),
        }
    }

    /// Read what [`serialize`] wrote.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        Ok(Option::<Real>::deserialize(d)?.map(|r| r.0))
    }
}

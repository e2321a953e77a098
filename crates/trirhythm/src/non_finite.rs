//! Serde for an `f64` that may be NaN or ±∞, which JSON numbers cannot be: finite values as
//! numbers, the others as the strings `"NaN"`, `"inf"` and `"-inf"`, read back exactly. Use it
//! as `#[serde(with = "trirhythm::non_finite")]` on a field that may be undefined (a boundary
//! not found, a standard error from one unit).

use serde::{Deserialize, Deserializer, Serializer};

/// A number, or the name of a non-finite value.
pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    match *v {
        v if v.is_finite() => s.serialize_f64(v),
        v if v.is_nan() => s.serialize_str("NaN"),
        v if v > 0.0 => s.serialize_str("inf"),
        _ => s.serialize_str("-inf"),
    }
}

/// The inverse of [`serialize`].
pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Repr {
        Number(f64),
        Name(String),
    }
    match Repr::deserialize(d)? {
        Repr::Number(v) => Ok(v),
        Repr::Name(name) => match name.as_str() {
            "NaN" => Ok(f64::NAN),
            "inf" => Ok(f64::INFINITY),
            "-inf" => Ok(f64::NEG_INFINITY),
            _ => Err(serde::de::Error::custom(format!(
                "`{name}` is not a number (NaN, inf and -inf are)"
            ))),
        },
    }
}

/// The same for a list: `#[serde(with = "trirhythm::non_finite::vec")]` on a `Vec<f64>`.
pub mod vec {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// One number of the list, as [`super::serialize`] writes it.
    #[derive(Serialize, Deserialize)]
    struct Item(#[serde(with = "super")] f64);

    /// Each number, or the name of a non-finite value.
    pub fn serialize<S: Serializer>(v: &[f64], s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(v.iter().map(|&x| Item(x)))
    }

    /// The inverse of [`serialize`].
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        Ok(Vec::<Item>::deserialize(d)?
            .into_iter()
            .map(|i| i.0)
            .collect())
    }
}

#[cfg(test)]
mod tests {
    #[derive(serde::Serialize, serde::Deserialize)]
    struct Value(#[serde(with = "super")] f64);

    #[test]
    fn every_float_reads_back() {
        for v in [
            0.1,
            -0.0,
            1e-300,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            let json = serde_json::to_string(&Value(v)).unwrap();
            let back: Value = serde_json::from_str(&json).unwrap();
            assert_eq!(back.0.to_bits(), v.to_bits(), "{json}");
        }
        let json = serde_json::to_string(&Value(f64::NAN)).unwrap();
        assert_eq!(json, "\"NaN\"");
        assert!(serde_json::from_str::<Value>(&json).unwrap().0.is_nan());
        assert!(serde_json::from_str::<Value>("\"nan\"").is_err());
    }
}

//! Serde for floats that may be infinite or NaN (NSGA's crowding distances): JSON has no
//! such numbers and `serde_json` writes them as `null`, which cannot be read back. Finite
//! values stay numbers; the others become the strings `"inf"`, `"-inf"` and `"nan"`.

use serde::de::{self, Deserializer};
use serde::ser::Serializer;
use serde::{Deserialize, Serialize};

#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum Float {
    Number(f64),
    Word(String),
}

fn to_float(x: f64) -> Float {
    match x {
        x if x.is_finite() => Float::Number(x),
        x if x.is_nan() => Float::Word("nan".into()),
        x if x > 0.0 => Float::Word("inf".into()),
        _ => Float::Word("-inf".into()),
    }
}

fn from_float<E: de::Error>(f: Float) -> Result<f64, E> {
    match f {
        Float::Number(x) => Ok(x),
        Float::Word(w) => match w.as_str() {
            "inf" => Ok(f64::INFINITY),
            "-inf" => Ok(f64::NEG_INFINITY),
            "nan" => Ok(f64::NAN),
            other => Err(E::custom(format!(
                "expected a number, \"inf\", \"-inf\" or \"nan\", found \"{other}\""
            ))),
        },
    }
}

/// `#[serde(with = "nonfinite::vec")]` for a `Vec<f64>`.
pub(crate) mod vec {
    use super::*;

    pub(crate) fn serialize<S: Serializer>(v: &[f64], s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(v.iter().map(|&x| to_float(x)))
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        Vec::<Float>::deserialize(d)?
            .into_iter()
            .map(from_float)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    #[derive(serde::Serialize, serde::Deserialize, PartialEq, Debug)]
    struct Holder(#[serde(with = "super::vec")] Vec<f64>);

    #[test]
    fn non_finite_values_round_trip() {
        let v = Holder(vec![1.5, f64::INFINITY, f64::NEG_INFINITY, -0.0, 1e308]);
        let json = serde_json::to_string(&v).unwrap();
        assert_eq!(json, r#"[1.5,"inf","-inf",-0.0,1e+308]"#);
        assert_eq!(serde_json::from_str::<Holder>(&json).unwrap(), v);
        let nan: Holder = serde_json::from_str(r#"["nan"]"#).unwrap();
        assert!(nan.0[0].is_nan());
        assert!(serde_json::from_str::<Holder>(r#"["infinite"]"#).is_err());
        assert!(serde_json::from_str::<Holder>("[null]").is_err());
    }
}

//! Whole numbers over the full `u64` range in scene files (`#[serde(with = …)]`). TOML's
//! integers are signed 64-bit, so a seed or a budget at or above 2^63 cannot be written as
//! one: it is written as a decimal string (`seed = "18446744073709551615"`) and read back
//! from an integer or such a string, in TOML, JSON and `--set` alike.

use serde::de::{self, Visitor};
use serde::{Deserializer, Serializer};
use std::fmt;

/// An integer up to `i64::MAX`, a decimal string above.
pub(crate) fn serialize<S: Serializer>(value: &u64, serializer: S) -> Result<S::Ok, S::Error> {
    match i64::try_from(*value) {
        Ok(v) => serializer.serialize_i64(v),
        Err(_) => serializer.serialize_str(&value.to_string()),
    }
}

/// An integer from 0 to 2^64 − 1, or the same as a decimal string.
pub(crate) fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<u64, D::Error> {
    deserializer.deserialize_any(WholeNumber)
}

struct WholeNumber;

impl Visitor<'_> for WholeNumber {
    type Value = u64;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(
            "a whole number from 0 to 18446744073709551615 (above 2^63 − 1 as a string in TOML)",
        )
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<u64, E> {
        Ok(v)
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<u64, E> {
        u64::try_from(v).map_err(|_| E::invalid_value(de::Unexpected::Signed(v), &self))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<u64, E> {
        let digits = v.trim();
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(E::invalid_value(de::Unexpected::Str(v), &self));
        }
        digits
            .parse()
            .map_err(|_| E::invalid_value(de::Unexpected::Str(v), &self))
    }
}

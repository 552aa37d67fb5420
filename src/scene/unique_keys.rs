//! Maps in a scene file whose keys must differ — a material's `bind: {…}`, the arguments of
//! `Graph("name", {…})` and a phenomenon's `params` —: a key given twice is an error, as a
//! struct field given twice is, instead of the last value silently winning.

use std::collections::BTreeMap;
use std::fmt;
use std::marker::PhantomData;

use serde::de::{Deserialize, Deserializer, MapAccess, Visitor};

/// The message of a key given twice (the RON reader adds its help line by this ending).
pub const GIVEN_TWICE: &str = "is given twice in this map";

/// `#[serde(deserialize_with = "…")]` for a `BTreeMap<String, V>` whose keys must differ:
/// the error is raised at the repeated key, before its value is read.
pub fn deserialize<'de, D, V>(deserializer: D) -> Result<BTreeMap<String, V>, D::Error>
where
    D: Deserializer<'de>,
    V: Deserialize<'de>,
{
    deserializer.deserialize_map(UniqueKeys(PhantomData))
}

struct UniqueKeys<V>(PhantomData<V>);

impl<'de, V: Deserialize<'de>> Visitor<'de> for UniqueKeys<V> {
    type Value = BTreeMap<String, V>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a map of names to values")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut out = BTreeMap::new();
        while let Some(key) = map.next_key::<String>()? {
            if out.contains_key(&key) {
                return Err(serde::de::Error::custom(format!(
                    "key \"{key}\" {GIVEN_TWICE}"
                )));
            }
            let value = map.next_value()?;
            out.insert(key, value);
        }
        Ok(out)
    }
}

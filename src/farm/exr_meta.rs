//! Part-file metadata as one EXR text attribute, `stagelight`, holding `key value` lines in
//! a fixed order. The exr crate keeps custom attributes in a hash map whose iteration order
//! changes from run to run, so one attribute per key would make the same part differ in its
//! bytes; one attribute keeps part files deterministic.

use std::collections::HashMap;

use exr::meta::attribute::{AttributeValue, Text};
use exr::meta::header::LayerAttributes;

/// The name of the attribute.
pub const ATTRIBUTE: &str = "stagelight";

/// Stores `pairs` (keys without spaces; ASCII values without line breaks) as the attribute.
pub fn put(attributes: &mut LayerAttributes, pairs: &[(String, String)]) {
    let text: String = pairs.iter().map(|(k, v)| format!("{k} {v}\n")).collect();
    attributes.other.insert(
        Text::new_or_panic(ATTRIBUTE),
        AttributeValue::Text(Text::new_or_panic(text)),
    );
}

/// The checksum of a part file: FNV-1a over `pairs` as [`put`] writes them and the hash of
/// the file's `data`. A file stores it as its last entry, computed over the other entries;
/// the reader recomputes it over the entries as its decoded content writes them, so an
/// edited entry (a part number, a seed) fails it as a changed pixel does.
pub fn checksum(pairs: &[(String, String)], data: u64) -> u64 {
    let mut h = crate::hash::Fnv64::default();
    for (k, v) in pairs {
        h.bytes(format!("{k} {v}\n").as_bytes());
    }
    h.bytes(&data.to_le_bytes()).finish()
}

/// The pairs stored by [`put`] in these attributes; `None` when there is no such attribute.
pub fn read(other: &exr::meta::header::LayerAttributes) -> Option<HashMap<String, String>> {
    lines(&other.other)
}

/// The pairs of a header's own attributes (for reading metadata without the pixels).
pub fn read_header(header: &exr::meta::header::Header) -> Option<HashMap<String, String>> {
    lines(&header.own_attributes.other)
}

fn lines(other: &HashMap<Text, AttributeValue>) -> Option<HashMap<String, String>> {
    let AttributeValue::Text(text) = other.get(&Text::new_or_panic(ATTRIBUTE))? else {
        return None;
    };
    Some(
        text.to_string()
            .lines()
            .filter_map(|l| l.split_once(' '))
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_round_trip_in_one_attribute() {
        let mut a = LayerAttributes::default();
        put(
            &mut a,
            &[
                ("format".into(), "x y".into()),
                ("seed".into(), "42".into()),
            ],
        );
        assert_eq!(a.other.len(), 1);
        let m = read(&a).unwrap();
        assert_eq!(m["format"], "x y");
        assert_eq!(m["seed"], "42");
        assert!(read(&LayerAttributes::default()).is_none());
    }
}

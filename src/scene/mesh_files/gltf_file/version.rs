//! The glTF version a file declares (`asset.version`, `asset.minVersion`), checked before
//! anything else is read. glTF 2.0 §3.2: a reader loads an asset whose major version it
//! reads (any minor version: newer minor versions only add what a 2.0 reader may ignore)
//! unless `minVersion` asks for a newer minor version; an asset of another major version is
//! not loadable. So `"1.0"` and `"3.0"` are refused, and so is `"minVersion": "2.1"`.
//!
//! A glTF 1.0 file usually fails to parse as 2.0 (its collections are objects keyed by id,
//! its `scene` a string) before its version could be read: [`refusal_of_value`] looks at the
//! JSON as plain values then, so the message says glTF 1.0 instead of a type mismatch.

use super::element;
use crate::scene::mesh_files::MeshFileError;

/// The major and minor version this reader implements.
pub const READ_VERSION: (u32, u32) = (2, 0);

/// `"2.0"` → `(2, 0)`; `None` when the text is not `<major>.<minor>`.
fn parse(text: &str) -> Option<(u32, u32)> {
    let (major, minor) = text.split_once('.')?;
    Some((major.parse().ok()?, minor.parse().ok()?))
}

/// The error for a file declaring `version` (and `min_version`), or `None` when it loads.
fn refusal(version: &str, min_version: Option<&str>) -> Option<MeshFileError> {
    let Some((major, _)) = parse(version) else {
        return Some(element(
            "asset.version",
            format!("\"{version}\" is not a glTF version: expected \"2.0\" (<major>.<minor>)"),
        ));
    };
    if major < READ_VERSION.0 {
        return Some(element(
            "asset.version",
            format!(
                "glTF {version} is not supported (asset.version \"{version}\"): only glTF 2.0 files are read; convert it to glTF 2.0 first (gltf-pipeline does)"
            ),
        ));
    }
    if major > READ_VERSION.0 {
        return Some(element(
            "asset.version",
            format!(
                "glTF {version} is not supported (asset.version \"{version}\"): a file of another major version than 2 is not loadable by a glTF 2.0 reader"
            ),
        ));
    }
    let min = min_version?;
    match parse(min) {
        Some(m) if m <= READ_VERSION => None,
        Some(_) => Some(element(
            "asset.minVersion",
            format!(
                "the file needs a glTF {min} reader (asset.minVersion \"{min}\"); this reader implements glTF 2.0"
            ),
        )),
        None => Some(element(
            "asset.minVersion",
            format!("\"{min}\" is not a glTF version: expected <major>.<minor>, such as \"2.0\""),
        )),
    }
}

/// Refuses a file whose `asset` declares a version this reader cannot load.
pub fn check(asset: &gltf::json::Asset) -> Result<(), MeshFileError> {
    match refusal(&asset.version, asset.min_version.as_deref()) {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// For JSON that did not parse as glTF 2.0: the version refusal its `asset` calls for, or
/// a glTF 1.0 refusal for a file without `asset.version` whose top-level collections are
/// objects (glTF 1.0's dictionaries keyed by id); `None` when neither applies.
pub fn refusal_of_value(root: &serde_json::Value) -> Option<MeshFileError> {
    let asset = root.get("asset");
    if let Some(version) = asset
        .and_then(|a| a.get("version"))
        .and_then(|v| v.as_str())
    {
        let min = asset
            .and_then(|a| a.get("minVersion"))
            .and_then(|v| v.as_str());
        return refusal(version, min);
    }
    let dictionary = ["meshes", "nodes", "scenes", "accessors", "buffers"]
        .into_iter()
        .find(|key| root.get(key).is_some_and(|v| v.is_object()))?;
    Some(element(
        dictionary,
        format!(
            "glTF 1.0 is not supported (no asset.version, and \"{dictionary}\" is an object keyed by id, as in glTF 1.0): only glTF 2.0 files are read; convert it to glTF 2.0 first (gltf-pipeline does)"
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(e: Option<MeshFileError>) -> String {
        e.map(|e| e.to_string()).unwrap_or_default()
    }

    #[test]
    fn minor_versions_load_and_other_majors_and_newer_min_versions_do_not() {
        assert!(refusal("2.0", None).is_none());
        assert!(refusal("2.1", Some("2.0")).is_none());
        assert_eq!(
            text(refusal("2.0", Some("2.1"))),
            "asset.minVersion: the file needs a glTF 2.1 reader (asset.minVersion \"2.1\"); this reader implements glTF 2.0"
        );
        assert_eq!(
            text(refusal("3.0", None)),
            "asset.version: glTF 3.0 is not supported (asset.version \"3.0\"): a file of another major version than 2 is not loadable by a glTF 2.0 reader"
        );
        assert_eq!(
            text(refusal("two", None)),
            "asset.version: \"two\" is not a glTF version: expected \"2.0\" (<major>.<minor>)"
        );
    }

    #[test]
    fn a_version_1_file_without_a_version_is_known_by_its_dictionaries() {
        let root: serde_json::Value =
            serde_json::from_str(r#"{"scene": "s", "meshes": {"m": {}}}"#).unwrap();
        assert_eq!(
            text(refusal_of_value(&root)),
            "meshes: glTF 1.0 is not supported (no asset.version, and \"meshes\" is an object keyed by id, as in glTF 1.0): only glTF 2.0 files are read; convert it to glTF 2.0 first (gltf-pipeline does)"
        );
        let root: serde_json::Value = serde_json::from_str(r#"{"meshes": []}"#).unwrap();
        assert!(refusal_of_value(&root).is_none());
    }
}

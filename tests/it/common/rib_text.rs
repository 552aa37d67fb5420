//! Reading RIB text in tests: the scene, or a panic that shows every message of the reader.

use std::path::Path;

use stagelight::scene::import::rib::{read_rib, RibScene};

/// The scene read from `text` as the file `path`; panics with every error, one a line.
pub fn read_rib_at(path: &Path, text: &str) -> RibScene {
    read_rib(path, text.as_bytes()).unwrap_or_else(|e| {
        panic!(
            "{}",
            e.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("\n")
        )
    })
}

/// The scene read from `text` as `t.rib`; panics with every error, one a line.
pub fn read_rib_text(text: &str) -> RibScene {
    read_rib_at(Path::new("t.rib"), text)
}

//! Locating diagnostics about `options` (photon maps), which have no entity to carry a
//! position: the scene files are read again and the value found in the file that holds
//! `options`.

use std::path::Path;

use crate::scene::Diagnostic;

/// `diagnostics` with those not located yet (no file) placed at the value their message
/// starts with (`options.caustics: …`) in the file that writes `options`, else at the start
/// of the scene file.
pub fn options_located(scene: &Path, diagnostics: Vec<Diagnostic>) -> Vec<Diagnostic> {
    if diagnostics.iter().all(|d| !d.file.as_os_str().is_empty()) {
        return diagnostics;
    }
    let loaded = crate::scene::include::load_files(scene, None, crate::scene::import::FORMATS);
    let file = loaded
        .scenes
        .iter()
        .position(|d| d.as_ref().is_some_and(|d| d.options.is_some()));
    diagnostics
        .into_iter()
        .map(|mut d| {
            if !d.file.as_os_str().is_empty() {
                return d;
            }
            let key = d.message.split(':').next().unwrap_or_default().to_string();
            let pos = match file {
                Some(f) => loaded.sources.pos(f, &key),
                None => crate::scene::import::SourcePos::start(scene),
            };
            (d.file, d.line, d.column) = (pos.file, pos.line, pos.column);
            d
        })
        .collect()
}

/// Where the scene at `scene` writes the option `key` (e.g. `options.photon_map.file`): in the
/// file that holds `options`, else the start of the scene file.
pub fn option_link(scene: &Path, key: &str) -> crate::components::SourceLink {
    let loaded = crate::scene::include::load_files(scene, None, crate::scene::import::FORMATS);
    let pos = match loaded
        .scenes
        .iter()
        .position(|d| d.as_ref().is_some_and(|d| d.options.is_some()))
    {
        Some(f) => loaded.sources.pos(f, key),
        None => crate::scene::import::SourcePos::start(scene),
    };
    crate::components::SourceLink {
        file: pos.file,
        line: pos.line,
        column: pos.column,
    }
}

//! What a merge names when the scene's content hash ([`super::scene_hash`]) no longer
//! matches its parts': the hash covers the scene file and every file it reads (includes,
//! RIB archives, `.mi` `$include`s, meshes, textures, maps), and the parts record only the
//! one hash, so the message names the scene and lists the files it reads.

use std::path::{Path, PathBuf};

/// At most this many files are listed; the rest are counted.
const LISTED: usize = 8;

/// The scene at `scene` as the changed content: `m.mi`, or `m.mi or a file it reads
/// (mat.mi, verts.mi)` when it reads other files (named relative to the scene's directory
/// when they lie under it).
pub fn changed_content(scene: &Path) -> String {
    let others = other_inputs(scene);
    if others.is_empty() {
        return scene.display().to_string();
    }
    let dir = scene.parent().unwrap_or(Path::new(""));
    let mut names: Vec<String> = others
        .iter()
        .take(LISTED)
        .map(|p| p.strip_prefix(dir).unwrap_or(p).display().to_string())
        .collect();
    if others.len() > LISTED {
        names.push(format!("{} more", others.len() - LISTED));
    }
    format!(
        "{} or a file it reads ({})",
        scene.display(),
        names.join(", ")
    )
}

/// The input files of the scene at `scene` other than the scene file, each once, in the
/// order the loader reads them.
fn other_inputs(scene: &Path) -> Vec<PathBuf> {
    let key = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    let mut seen = vec![key(scene)];
    let mut others = Vec::new();
    for input in crate::scene::inputs::scene_inputs(scene, None) {
        // An image inside a glTF file (`model.glb#images[0]`) is that file.
        let input = match input.to_str().and_then(|s| s.split_once('#')) {
            Some((file, _)) if !input.exists() => PathBuf::from(file),
            _ => input,
        };
        let k = key(&input);
        if !seen.contains(&k) {
            seen.push(k);
            others.push(input);
        }
    }
    others
}

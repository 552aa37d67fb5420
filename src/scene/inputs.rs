//! The files a scene reads: every input the loader opens (scene files, includes, RIB
//! archives and `.mi` includes, meshes, OBJ material libraries and their textures, image
//! nodes, displacement and environment maps), and a hash of their bytes for the caches and
//! checks that must notice an edit of any of them (farm parts, sweep references).

use std::path::{Path, PathBuf};

use crate::hash::Fnv64;

/// Every input file of the scene at `scene` (as paths the loader opens): the scene files
/// and each file they name outside their outputs and the `photon_map` file (a cache the
/// run may rewrite). `text` stands in for the root file when
/// the scene was loaded from a string.
pub fn scene_inputs(scene: &Path, text: Option<&str>) -> Vec<PathBuf> {
    let mut loaded = super::include::load_files(scene, text, super::import::FORMATS);
    let mut inputs = Vec::new();
    // OBJ material libraries and the textures they name are inputs too.
    super::obj_materials::expand(&mut loaded.sources, &mut loaded.scenes, &mut inputs);
    for (file, desc) in loaded.sources.files.iter().zip(&loaded.scenes) {
        inputs.push(file.path.clone());
        let Some(desc) = desc else { continue };
        let Ok(mut value) = serde_json::to_value(desc) else {
            continue;
        };
        let mut named = Vec::new();
        super::import::relocate::visit_input_files(&mut value, &mut |s| named.push(s.clone()));
        inputs.extend(named.into_iter().map(|n| file.dir().join(n)));
    }
    inputs.extend(loaded.read_files);
    inputs
}

/// Mesh files whose loaded triangles the content hash covers instead of their bytes
/// (`crate::farm::scene_hash`): reading a large OBJ or PLY twice would cost as much as
/// loading it.
const HASHED_AS_LOADED: &[&str] = &["obj", "ply"];

/// A hash of the bytes of every input file of the scene at `scene` ([`scene_inputs`]) but
/// the OBJ and PLY meshes, each file once, in the order of their real paths; a file that
/// cannot be read counts by the reason. Only contents count, not names: the scene named by
/// another path (relative or absolute, or moved with its files) hashes the same. A name
/// with a `#` part (`model.glb#images[0]`: an image inside a glTF file) counts as its file.
pub fn inputs_hash(scene: &Path) -> u64 {
    let mut files: Vec<PathBuf> = scene_inputs(scene, None)
        .into_iter()
        .map(|p| match p.to_str().and_then(|s| s.split_once('#')) {
            Some((file, _)) if !p.exists() => PathBuf::from(file),
            _ => p,
        })
        .filter(|p| {
            let ext = p.extension().and_then(|e| e.to_str()).unwrap_or_default();
            !HASHED_AS_LOADED.contains(&ext.to_ascii_lowercase().as_str())
        })
        .map(|p| std::fs::canonicalize(&p).unwrap_or(p))
        .collect();
    files.sort();
    files.dedup();
    let mut h = Fnv64::default();
    for file in files {
        match std::fs::read(&file) {
            Ok(bytes) => h.bytes(&(bytes.len() as u64).to_le_bytes()).bytes(&bytes),
            Err(e) => h.bytes(e.to_string().as_bytes()),
        };
    }
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An edit of an included file or of a texture changes the hash; an OBJ is left to the
    /// loaded-mesh hash.
    #[test]
    fn the_hash_follows_includes_and_textures_not_obj_bytes() {
        let dir = std::env::temp_dir().join(format!("stagelight-inputs-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let scene = dir.join("scene.ron");
        std::fs::write(
            &scene,
            r#"Scene(include: ["lib.ron"], environment: (shader: LatLong(file: "sky.exr")),
                objects: [(name: "m", mesh: Obj(file: "m.obj"))])"#,
        )
        .unwrap();
        let write = |name: &str, text: &str| std::fs::write(dir.join(name), text).unwrap();
        write("lib.ron", "Scene()");
        write("sky.exr", "one");
        write("m.obj", "v 0 0 0");
        let first = inputs_hash(&scene);
        write("m.obj", "v 1 0 0");
        let after_obj = inputs_hash(&scene);
        write("sky.exr", "two");
        let after_sky = inputs_hash(&scene);
        write("lib.ron", "Scene( )");
        let after_lib = inputs_hash(&scene);
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!(first, after_obj);
        assert_ne!(after_obj, after_sky);
        assert_ne!(after_sky, after_lib);
    }
}

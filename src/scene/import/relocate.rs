//! The input files a description names, and `stagelight convert`'s move of them to the
//! directory the RON is written to.
//!
//! A description names its inputs by paths relative to the file that declares them:
//! `include` entries, and every `file` of a mesh (OBJ, PLY, glTF), an image node, a
//! displacement image or a lat-long environment. Camera and bake outputs and the photon map
//! file are destinations, resolved elsewhere (the working directory, `-o DIR`), and are left
//! as written. RON written into another directory than the scene's names each relative
//! input through the path from that directory to the scene's, so it loads the same files.

use std::path::{Component, Path, PathBuf};

use crate::scene::desc::SceneDesc;

/// Calls `f` on every string under a `file` key anywhere in `value` (a description as
/// `serde_json` sees it), except inside `outputs` lists (camera and bake outputs) and the
/// photon map file: the input files the description names besides its includes.
pub fn visit_input_files(value: &mut serde_json::Value, f: &mut dyn FnMut(&mut String)) {
    match value {
        serde_json::Value::Object(map) => {
            for (key, v) in map.iter_mut() {
                match (key.as_str(), v) {
                    ("outputs", _) | ("photon_map", _) => {}
                    ("file", serde_json::Value::String(s)) => f(s),
                    (_, v) => visit_input_files(v, f),
                }
            }
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(|v| visit_input_files(v, f)),
        _ => {}
    }
}

/// The path from directory `from` to directory `to`, both absolute and normalised
/// (`..` steps up out of `from`, then down into `to`); empty when they are the same.
fn path_between(from: &Path, to: &Path) -> PathBuf {
    let (from, to): (Vec<Component>, Vec<Component>) =
        (from.components().collect(), to.components().collect());
    let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
    let mut path = PathBuf::new();
    for _ in common..from.len() {
        path.push("..");
    }
    for c in &to[common..] {
        path.push(c);
    }
    path
}

/// A directory as an absolute, normalised path (symbolic links resolved where it exists).
fn real_dir(dir: &Path) -> Result<PathBuf, String> {
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    std::fs::canonicalize(dir).map_err(|e| format!("cannot resolve {}: {e}", dir.display()))
}

/// `desc`, read from `scene`, with its relative input paths rewritten for a file written to
/// `output` (in another directory; unchanged in the same one). An error names a directory
/// that cannot be resolved or a description that does not survive the rewrite.
pub fn relocate_inputs(desc: SceneDesc, scene: &Path, output: &Path) -> Result<SceneDesc, String> {
    let parent = |p: &Path| p.parent().map(Path::to_path_buf).unwrap_or_default();
    let from = real_dir(&parent(output))?;
    let to = real_dir(&parent(scene))?;
    let step = path_between(&from, &to);
    if step.as_os_str().is_empty() {
        return Ok(desc);
    }
    let mut moved = |s: &mut String| {
        if Path::new(s.as_str()).is_relative() {
            *s = step.join(s.as_str()).to_string_lossy().into_owned();
        }
    };
    let mut value = serde_json::to_value(&desc)
        .map_err(|e| format!("cannot rewrite the scene's file paths: {e}"))?;
    visit_input_files(&mut value, &mut moved);
    let mut desc: SceneDesc = serde_json::from_value(value)
        .map_err(|e| format!("cannot rewrite the scene's file paths: {e}"))?;
    desc.include.iter_mut().for_each(&mut moved);
    Ok(desc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_files_skip_outputs_and_the_photon_map() {
        let mut v = serde_json::json!({
            "objects": [{"mesh": {"Obj": {"file": "m.obj"}}}],
            "cameras": [{"outputs": [{"file": "out.png"}]}],
            "options": {"photon_map": {"file": "p.pmap"}},
        });
        let mut out = Vec::new();
        visit_input_files(&mut v, &mut |s| out.push(s.clone()));
        assert_eq!(out, vec!["m.obj".to_string()]);
    }

    #[test]
    fn the_path_between_two_directories_goes_up_then_down() {
        let p = |s: &str| PathBuf::from(s);
        assert_eq!(path_between(&p("/a/b/c"), &p("/a/d")), p("../../d"));
        assert_eq!(path_between(&p("/a"), &p("/a/d/e")), p("d/e"));
        assert_eq!(path_between(&p("/a/b"), &p("/a/b")), p(""));
        assert_eq!(path_between(&p("/x"), &p("/y")), p("../y"));
    }

    /// Only input files move: includes, meshes, images and environments; camera and bake
    /// outputs and the photon map file stay as written, and so do absolute paths.
    #[test]
    fn inputs_move_and_destinations_stay() {
        let text = r#"Scene(
    include: ["lib/materials.ron", "/abs/lights.ron"],
    options: (photon_map: (file: "maps/scene.pmap")),
    environment: (shader: LatLong(file: "sky.exr")),
    objects: [
        (name: "rock", mesh: Obj(file: "meshes/rock.obj")),
        (name: "box", mesh: Ply(file: "/abs/box.ply")),
    ],
    instances: [(name: "rock_1", of: "rock", bake: (resolution: (8, 8),
        outputs: [(kind: Positions, file: "rock_P.exr")]))],
    cameras: [(name: "cam", fov_y: 40, resolution: (8, 8),
        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)), outputs: [(file: "out/image.png")])],
)"#;
        let desc: SceneDesc = ron::Options::default()
            .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
            .from_str(text)
            .unwrap_or_else(|e| panic!("{e}"));
        let tmp = std::env::temp_dir().join(format!("stagelight-relocate-{}", std::process::id()));
        let (scenes, out) = (tmp.join("scenes"), tmp.join("out/deeper"));
        std::fs::create_dir_all(&scenes).unwrap();
        std::fs::create_dir_all(&out).unwrap();
        let moved =
            relocate_inputs(desc.clone(), &scenes.join("a.ron"), &out.join("b.ron")).unwrap();
        let kept = relocate_inputs(desc, &scenes.join("a.ron"), &scenes.join("b.ron")).unwrap();
        let _ = std::fs::remove_dir_all(&tmp);
        let ron = |d: &SceneDesc| crate::scene::import::to_ron::to_ron(d).unwrap();
        let (moved, kept) = (ron(&moved), ron(&kept));
        for (was, now) in [
            (
                "\"lib/materials.ron\"",
                "\"../../scenes/lib/materials.ron\"",
            ),
            ("\"sky.exr\"", "\"../../scenes/sky.exr\""),
            ("\"meshes/rock.obj\"", "\"../../scenes/meshes/rock.obj\""),
        ] {
            assert!(kept.contains(was) && moved.contains(now), "{now}\n{moved}");
            assert!(!moved.contains(was), "{was}\n{moved}");
        }
        for same in [
            "\"/abs/lights.ron\"",
            "\"/abs/box.ply\"",
            "\"maps/scene.pmap\"",
            "\"rock_P.exr\"",
            "\"out/image.png\"",
        ] {
            assert!(
                moved.contains(same) && kept.contains(same),
                "{same}\n{moved}"
            );
        }
    }
}

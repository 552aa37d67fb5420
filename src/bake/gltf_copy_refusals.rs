//! What `--write-gltf` (the baked glTF copy, [`super::gltf_out`]) refuses before anything
//! runs, with the same words in every command that takes it: a scene that is not a glTF file
//! (`bake`, `merge` of bake parts, `farm --bake`), a bake part (`bake --part K/N`, which
//! writes undilated texels, not textures: the merge writes the copy), render parts
//! (`merge`) and a render farm (`farm` without `--bake`). Each message has a `help:` line;
//! the caller prints it after `error: ` and exits with status 2.

use std::path::Path;

/// Why `--write-gltf` cannot copy `scene`: it is not a `.gltf` or `.glb` file.
pub fn scene_refusal(scene: &Path) -> Option<String> {
    let ext = scene
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if matches!(ext.as_deref(), Some("gltf" | "glb")) {
        return None;
    }
    Some(format!(
        "--write-gltf needs a glTF scene (.gltf or .glb), not {}\n  help: the baked copy is a copy of the glTF file with the baked textures wired in; leave out --write-gltf for other scenes",
        scene.display()
    ))
}

/// `bake --part K/N --write-gltf`: a part writes its texels, undilated, into its part file;
/// the textures the copy references exist only after the merge, which writes the copy.
pub fn part_refusal(index: u32, count: u32) -> String {
    format!(
        "--write-gltf cannot be used with --part {index}/{count}: a bake part writes its undilated texels into a part file, not the textures the glTF copy references\n  help: bake the parts without --write-gltf, then `stagelight merge --write-gltf bake_part_*.exr` writes the glTF copy (`stagelight farm --bake --write-gltf` puts it on the merge job)"
    )
}

/// `merge --write-gltf` of render parts (`first` is the first part file given).
pub fn render_parts_refusal(first: &Path) -> String {
    format!(
        "--write-gltf needs bake parts (of `stagelight bake --part K/N`), not render parts: {} is a render part file\n  help: the glTF copy holds baked textures; merge the render without --write-gltf",
        first.display()
    )
}

/// `farm --write-gltf` without `--bake`.
pub fn render_farm_refusal() -> String {
    "--write-gltf needs --bake: the glTF copy holds baked textures, and a render farm bakes none\n  help: add --bake to bake the scene on the farm (the merge job then writes the copy), or leave out --write-gltf".to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gltf_and_glb_scenes_are_copied_in_any_case_of_extension() {
        for ok in ["a.gltf", "dir/b.GLB", "c.Gltf"] {
            assert_eq!(scene_refusal(Path::new(ok)), None, "{ok}");
        }
        for refused in ["a.ron", "b.rib", "c", "d.glb.ron"] {
            let message = scene_refusal(Path::new(refused)).expect(refused);
            assert!(
                message.starts_with(&format!(
                    "--write-gltf needs a glTF scene (.gltf or .glb), not {refused}\n  help: "
                )),
                "{message}"
            );
        }
    }
}

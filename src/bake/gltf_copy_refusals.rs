//! What `--write-gltf` (the baked glTF: the copy of a glTF scene, [`super::gltf_out`], or the
//! standalone file of any other scene, [`super::gltf_export`]) refuses before anything runs,
//! with the same words in every command that takes it: a bake part (`bake --part K/N`, which
//! writes undilated texels, not textures: the merge writes the glTF), render parts (`merge`)
//! and a render farm (`farm` without `--bake`). Any scene can be written. Each message has a `help:` line;
//! the caller prints it after `error: ` and exits with status 2.

use std::path::Path;

/// `bake --part K/N --write-gltf`: a part writes its texels, undilated, into its part file;
/// the textures the baked glTF references exist only after the merge, which writes it.
pub fn part_refusal(index: u32, count: u32) -> String {
    format!(
        "--write-gltf cannot be used with --part {index}/{count}: a bake part writes its undilated texels into a part file, not the textures the baked glTF references\n  help: bake the parts without --write-gltf, then `stagelight merge --write-gltf bake_part_*.exr` writes the baked glTF (`stagelight farm --bake --write-gltf` puts it on the merge job)"
    )
}

/// `merge --write-gltf` of render parts (`first` is the first part file given).
pub fn render_parts_refusal(first: &Path) -> String {
    format!(
        "--write-gltf needs bake parts (of `stagelight bake --part K/N`), not render parts: {} is a render part file\n  help: the baked glTF holds baked textures; merge the render without --write-gltf",
        first.display()
    )
}

/// `farm --write-gltf` without `--bake`.
pub fn render_farm_refusal() -> String {
    "--write-gltf needs --bake: the baked glTF holds baked textures, and a render farm bakes none\n  help: add --bake to bake the scene on the farm (the merge job then writes the baked glTF), or leave out --write-gltf".to_string()
}

//! The baked glTF copy of a bake done in parts: `merge --write-gltf` of the bake parts of a
//! `.glb` or `.gltf` scene writes the copy `bake --write-gltf` writes, byte for byte, beside
//! the same textures; `farm --bake --write-gltf` puts the flag on its merge job (of any
//! scene: a RON scene's merge writes its standalone glTF). Render parts, render farms,
//! `bake --part` and a copy that would overwrite the scene are refused before anything is
//! written.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::cli::{dir_names, run_in, scratch_dir, stderr_of};

/// A quad (two triangles) whose `TEXCOORD_1` bakes a 32 × 32 lightmap and AO (4 texel tiles).
const GLB: &str = "two_uv_sets.glb";

/// Copies the glTF fixtures `names` into `dir/scene/`; returns that directory.
fn fixtures(dir: &Path, names: &[&str]) -> PathBuf {
    let scene = dir.join("scene");
    std::fs::create_dir_all(&scene).unwrap();
    let from = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/gltf");
    for name in names {
        std::fs::copy(from.join(name), scene.join(name)).unwrap();
    }
    scene
}

fn ok(dir: &Path, args: &[&str]) {
    let o = run_in(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

/// Every file of `a` and `b` (both directories) is the same, and there are the same files.
fn same_files(a: &Path, b: &Path) {
    let names = dir_names(a);
    assert_eq!(dir_names(b), names, "{} vs {}", a.display(), b.display());
    for name in &names {
        assert!(
            std::fs::read(a.join(name)).unwrap() == std::fs::read(b.join(name)).unwrap(),
            "{name} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

/// Bakes `scene` in `count` parts into `parts_dir`, then merges them with `--write-gltf`
/// into `out`.
fn bake_in_parts_and_merge(dir: &Path, scene: &str, count: u32, parts_dir: &str, out: &str) {
    for k in 1..=count {
        let part = format!("{k}/{count}");
        ok(
            dir,
            &[
                "bake",
                scene,
                "--part",
                &part,
                "-o",
                parts_dir,
                "--threads",
                "1",
            ],
        );
    }
    let parts: Vec<String> = (1..=count)
        .rev()
        .map(|k| format!("{parts_dir}/bake_part_{k}_of_{count}.exr"))
        .collect();
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["-o", out, "--write-gltf"]);
    ok(dir, &args);
}

/// Two parts of a `.glb` with lightmap UVs (textures in the copy) and of a `.gltf` with an
/// external buffer and no `TEXCOORD_1` (vertex AO as `COLOR_0`): the merge writes the local
/// bake's textures and glTF copy, byte for byte. `merge` had no `--write-gltf`.
#[test]
fn two_bake_parts_merged_with_write_gltf_give_the_local_baked_copy() {
    let dir = scratch_dir("farm-gltf-two-parts");
    fixtures(&dir, &[GLB, "box_external.gltf", "box.bin"]);
    for (scene, copy) in [
        ("scene/two_uv_sets.glb", "two_uv_sets.glb"),
        ("scene/box_external.gltf", "box_external.glb"),
    ] {
        let stem = copy.trim_end_matches(".glb");
        let single = format!("single_{stem}");
        let merged = format!("merged_{stem}");
        ok(&dir, &["bake", scene, "-o", &single, "--write-gltf"]);
        assert!(
            dir_names(&dir.join(&single)).contains(&copy.to_string()),
            "{:?}",
            dir_names(&dir.join(&single))
        );
        bake_in_parts_and_merge(&dir, scene, 2, &format!("parts_{stem}"), &merged);
        same_files(&dir.join(&single), &dir.join(&merged));
    }
    assert_eq!(
        dir_names(&dir.join("merged_two_uv_sets")),
        ["quad_ao.png", "quad_lightmap.png", "two_uv_sets.glb"]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `farm --bake --write-gltf` of a `.glb` in 3 parts: the merge job (and only it) carries
/// `--write-gltf`, and the scripts, run as Slurm would run them, write the local bake's
/// textures and glTF copy byte for byte. `farm` had no `--write-gltf`.
#[test]
fn a_three_part_farm_bake_with_write_gltf_gives_the_local_baked_copy() {
    let dir = scratch_dir("farm-gltf-three-parts");
    fixtures(&dir, &[GLB]);
    let scene = "scene/two_uv_sets.glb";
    ok(&dir, &["bake", scene, "-o", "single", "--write-gltf"]);
    ok(
        &dir,
        &[
            "farm",
            scene,
            "--bake",
            "--write-gltf",
            "--parts",
            "3",
            "--out",
            "job",
            "-o",
            "farmed",
        ],
    );
    let merge = std::fs::read_to_string(dir.join("job/merge.sbatch")).unwrap();
    let exec = merge.lines().find(|l| l.starts_with("exec ")).unwrap();
    // The jobs run where `farm` ran: its paths are absolute from there.
    let at = std::fs::canonicalize(&dir).unwrap();
    assert!(
        exec.ends_with(&format!(
            " merge --scene '{}' \"${{parts[@]}}\" --threads \"${{SLURM_CPUS_PER_TASK:-1}}\" -o '{}' --write-gltf",
            at.join(scene).display(),
            at.join("farmed").display()
        )),
        "{exec}"
    );
    let render = std::fs::read_to_string(dir.join("job/render.sbatch")).unwrap();
    assert!(!render.contains("--write-gltf"), "{render}");
    for k in 1..=3 {
        let s = Command::new("bash")
            .arg(dir.join("job/render.sbatch"))
            .current_dir(&dir)
            .env("SLURM_ARRAY_TASK_ID", k.to_string())
            .env("SLURM_CPUS_PER_TASK", "1")
            .status()
            .unwrap();
        assert!(s.success());
    }
    let s = Command::new("bash")
        .arg(dir.join("job/merge.sbatch"))
        .current_dir(&dir)
        .status()
        .unwrap();
    assert!(s.success());
    same_files(&dir.join("single"), &dir.join("farmed"));
    assert!(dir.join("farmed/two_uv_sets.glb").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A RON scene with one AO bake request and a camera output (one texel tile).
const RON: &str = r#"Scene(
    options: (samples: 1, seed: 3),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
               placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)),
               outputs: [(file: "view.png")])],
    lights: [(name: "sun", kind: Directional(direction: (0.3, 0.2, -1)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "floor", mesh: Inline(
        vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
        uvs: [(0, 0), (1, 0), (1, 1), (0, 1)],
        polygons: [[0, 1, 2, 3]]), material: "grey")],
    instances: [(name: "floor_1", of: "floor", bake: (resolution: (16, 16), uvs: Mesh,
        outputs: [(kind: AmbientOcclusion(samples: 2), format: Png8)]))],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)
"#;

/// `merge --write-gltf` of render parts is a usage error (exit 2) that names why, and writes
/// nothing; the bake parts of a RON scene (the recorded scene, or `--scene`) merge with it
/// (they were refused: `--write-gltf needs a glTF scene`).
#[test]
fn merge_write_gltf_refuses_render_parts_and_takes_bake_parts_of_any_scene() {
    let dir = scratch_dir("farm-gltf-merge-refusals");
    std::fs::write(dir.join("scene.ron"), RON).unwrap();
    for k in 1..=2 {
        let part = format!("{k}/2");
        let file = format!("r{k}.exr");
        ok(&dir, &["render", "scene.ron", "--part", &part, "-o", &file]);
        ok(&dir, &["bake", "scene.ron", "--part", &part, "-o", "parts"]);
    }
    let refused = |args: &[&str], expected: &str| {
        let o = run_in(&dir, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr_of(&o));
        assert_eq!(stderr_of(&o), expected, "{args:?}");
        assert!(!dir.join("out").exists(), "{args:?} wrote something");
        assert!(!dir.join("view.png").exists(), "{args:?} wrote the render");
        assert!(!dir.join("out.png").exists(), "{args:?} wrote the render");
    };
    refused(
        &["merge", "r1.exr", "r2.exr", "-o", "out.png", "--write-gltf"],
        "error: --write-gltf needs bake parts (of `stagelight bake --part K/N`), not render parts: r1.exr is a render part file\n  help: the baked glTF holds baked textures; merge the render without --write-gltf\n",
    );
    refused(
        &["merge", "r2.exr", "r1.exr", "--write-gltf"],
        "error: --write-gltf needs bake parts (of `stagelight bake --part K/N`), not render parts: r2.exr is a render part file\n  help: the baked glTF holds baked textures; merge the render without --write-gltf\n",
    );
    let parts = ["parts/bake_part_1_of_2.exr", "parts/bake_part_2_of_2.exr"];
    assert_eq!(
        dir_names(&dir),
        ["parts", "r1.exr", "r2.exr", "scene.ron"],
        "nothing was written"
    );
    // The bake parts of a RON scene merge with the flag (the standalone glTF of the scene;
    // `tests/it/gltf_export.rs`), through the recorded scene or `--scene`.
    ok(
        &dir,
        &["merge", parts[0], parts[1], "-o", "gltf", "--write-gltf"],
    );
    assert_eq!(
        dir_names(&dir.join("gltf")),
        ["floor_1_ao.png", "scene.glb"]
    );
    ok(
        &dir,
        &[
            "merge",
            parts[1],
            parts[0],
            "--scene",
            "scene.ron",
            "-o",
            "gltf2",
            "--write-gltf",
        ],
    );
    assert!(
        std::fs::read(dir.join("gltf/scene.glb")).unwrap()
            == std::fs::read(dir.join("gltf2/scene.glb")).unwrap()
    );
    // Without the flag the same parts merge.
    ok(&dir, &["merge", parts[0], parts[1], "-o", "out"]);
    assert_eq!(dir_names(&dir.join("out")), ["floor_1_ao.png"]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `bake --part K/N --write-gltf` stays refused (exit 2, nothing written), now pointing to
/// `merge --write-gltf` (clap's conflict message named no way that works).
#[test]
fn bake_part_with_write_gltf_points_to_merge_write_gltf() {
    let dir = scratch_dir("farm-gltf-bake-part");
    fixtures(&dir, &[GLB]);
    let o = run_in(
        &dir,
        &[
            "bake",
            "scene/two_uv_sets.glb",
            "--part",
            "2/3",
            "--write-gltf",
            "-o",
            "parts",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        "error: --write-gltf cannot be used with --part 2/3: a bake part writes its undilated texels into a part file, not the textures the baked glTF references\n  help: bake the parts without --write-gltf, then `stagelight merge --write-gltf bake_part_*.exr` writes the baked glTF (`stagelight farm --bake --write-gltf` puts it on the merge job)\n"
    );
    assert!(!dir.join("parts").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `farm --write-gltf` of a render is a usage error naming why (of a bake of a RON scene it
/// was too; now its merge job carries the flag); a glTF copy that would overwrite the scene (the default texture directory, beside
/// the glb) is refused by `farm` before any script and by `merge` before any texture, as
/// `bake --write-gltf` refuses it.
#[test]
fn farm_and_merge_refuse_a_write_gltf_they_could_not_honour_before_writing() {
    let dir = scratch_dir("farm-gltf-farm-refusals");
    let scene_dir = fixtures(&dir, &[GLB]);
    std::fs::write(dir.join("scene.ron"), RON).unwrap();
    let refused = |at: &Path, args: &[&str], expected: &str| {
        let o = run_in(at, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr_of(&o));
        assert_eq!(stderr_of(&o), expected, "{args:?}");
        assert!(!at.join("job").exists(), "{args:?} wrote scripts");
    };
    refused(
        &dir,
        &["farm", "scene.ron", "--write-gltf", "--parts", "2", "--out", "job"],
        "error: --write-gltf needs --bake: the baked glTF holds baked textures, and a render farm bakes none\n  help: add --bake to bake the scene on the farm (the merge job then writes the baked glTF), or leave out --write-gltf\n",
    );
    // A bake farm of a RON scene takes it (its merge writes the standalone glTF).
    ok(
        &dir,
        &[
            "farm",
            "scene.ron",
            "--bake",
            "--write-gltf",
            "--parts",
            "1",
            "--out",
            "job",
        ],
    );
    let merge = std::fs::read_to_string(dir.join("job/merge.sbatch")).unwrap();
    assert!(merge.contains(" --write-gltf\n"), "{merge}");
    let over_the_scene = "error: --write-gltf ./two_uv_sets.glb would overwrite the scene file two_uv_sets.glb\n  help: give every output its own file, and none the name of an input\n1 error in two_uv_sets.glb; no scripts written\n";
    refused(
        &scene_dir,
        &[
            "farm",
            GLB,
            "--bake",
            "--write-gltf",
            "--parts",
            "2",
            "--out",
            "job",
        ],
        over_the_scene,
    );
    // Without the flag the same farm is fine: the textures do not clash.
    ok(
        &scene_dir,
        &["farm", GLB, "--bake", "--parts", "2", "--out", "job"],
    );
    // The merge, in the glb's directory without -o: refused before a texture is written.
    for k in 1..=2 {
        let part = format!("{k}/2");
        ok(&scene_dir, &["bake", GLB, "--part", &part, "-o", "parts"]);
    }
    let o = run_in(
        &scene_dir,
        &[
            "merge",
            "parts/bake_part_1_of_2.exr",
            "parts/bake_part_2_of_2.exr",
            "--write-gltf",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr_of(&o));
    let source = std::fs::canonicalize(&scene_dir).unwrap().join(GLB);
    assert_eq!(
        stderr_of(&o),
        format!(
            "error: --write-gltf ./two_uv_sets.glb would overwrite the scene file {0}\n  help: give every output its own file, and none the name of an input\n1 error in {0}; nothing merged\n",
            source.display()
        )
    );
    assert_eq!(dir_names(&scene_dir), ["job", "parts", GLB]);
    assert!(
        std::fs::read(&source).unwrap()
            == std::fs::read(
                Path::new(env!("CARGO_MANIFEST_DIR"))
                    .join("tests/fixtures/gltf")
                    .join(GLB)
            )
            .unwrap()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

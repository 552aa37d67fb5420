//! `stagelight bake` end to end: files named `<instance>_<kind>.<ext>` in the output
//! directory, bad requests refused before work with their scene position, and `render`
//! leaving bake requests alone.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_stagelight"))
}

fn scratch(test: &str) -> PathBuf {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight-cli-bake-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(cmd: &mut Command) -> Output {
    cmd.output().expect("run stagelight")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A floor with UVs, a block standing on it, a light, and a bake request on the floor.
fn scene(bake: &str) -> String {
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (16, 16),
               placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0)),
               outputs: [(file: "view.png")])],
    lights: [(name: "sun", kind: Directional(direction: (0.3, 0.2, -1)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [
        (name: "floor", mesh: Inline(
            vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
        (name: "block", mesh: Inline(
            vertices: [(-0.3, -0.3, 0.6), (0.3, -0.3, 0.6), (0.3, 0.3, 0.6), (-0.3, 0.3, 0.6)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
    ],
    instances: [
        (name: "floor_1", of: "floor", bake: {bake}),
        (name: "block_1", of: "block"),
    ],
    groups: [(name: "world", members: ["floor_1", "block_1"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

fn write(path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
}

#[test]
fn bake_writes_named_textures_and_reports() {
    let dir = scratch("ok");
    let scene_path = dir.join("scene.ron");
    write(
        &scene_path,
        &scene(
            "(resolution: (32, 32), mask: true, outputs: [(kind: AmbientOcclusion(samples: 16)), (kind: Lightmap(), format: Png16), (kind: Normals(), file: \"n.exr\")])",
        ),
    );
    let out = dir.join("textures");
    let json = dir.join("stats.json");
    let o = run(bin()
        .arg("bake")
        .arg(&scene_path)
        .arg("-o")
        .arg(&out)
        .args(["--stats", "--threads", "2"])
        .arg("--stats-json")
        .arg(&json));
    assert!(o.status.success(), "{}", stderr(&o));
    for f in [
        "floor_1_ao.exr",
        "floor_1_lightmap.png",
        "n.exr",
        "floor_1_mask.png",
    ] {
        assert!(out.join(f).exists(), "{f} missing; stderr: {}", stderr(&o));
    }
    let png = crate::common::png::read(&out.join("floor_1_lightmap.png"));
    assert_eq!((png.width, png.height, png.channels), (32, 32, 3));
    assert!(matches!(
        png.samples,
        stagelight::image_io::png_codec::Samples::Sixteen(_)
    ));
    // Nothing rendered: the camera's output is not written by a bake.
    assert!(!dir.join("view.png").exists());
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("bake floor_1: 32×32 texels"), "{stdout}");
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let bake = &v["bakes"][0];
    assert_eq!(bake["name"], "floor_1");
    assert_eq!(bake["covered_texels"], 1024);
    assert!(bake["rays"].as_u64().unwrap() > 0);
    let stages = v["stages"].as_array().unwrap();
    let shade = stages.iter().find(|s| s["stage"] == "shade").unwrap();
    assert_eq!(shade["ran"], false);
    assert_eq!(shade["reason"], "this run only bakes");
}

#[test]
fn mesh_uvs_missing_is_refused_at_load_with_its_position() {
    let dir = scratch("nouv");
    let scene_path = dir.join("scene.ron");
    let text = scene("(resolution: (8, 8), outputs: [(kind: Positions)])")
        .replace("(name: \"block_1\", of: \"block\")", "(name: \"block_1\", of: \"block\", bake: (resolution: (8, 8), uvs: Mesh, outputs: [(kind: Positions)]))");
    write(&scene_path, &text);
    let o = run(bin()
        .arg("bake")
        .arg(&scene_path)
        .arg("-o")
        .arg(dir.join("out")));
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(
        err.contains("scene.ron:18:72: error: `uvs: Mesh`, but the mesh of \"block_1\" has no texture coordinates"),
        "{err}"
    );
    assert!(!dir.join("out").exists());
}

#[test]
fn zero_resolution_and_missing_size_are_located_errors() {
    let dir = scratch("zero");
    let scene_path = dir.join("scene.ron");
    write(
        &scene_path,
        &scene("(resolution: (0, 8), outputs: [(kind: Albedo)])"),
    );
    let o = run(bin().arg("check").arg(&scene_path));
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("bake resolution must be 1 … 16384 texels per side, found (0, 8)"),
        "{}",
        stderr(&o)
    );
    write(&scene_path, &scene("(outputs: [(kind: Albedo)])"));
    let o = run(bin().arg("check").arg(&scene_path));
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("help") || stderr(&o).contains("add `resolution"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn render_does_not_bake_unless_asked() {
    let dir = scratch("render");
    let scene_path = dir.join("scene.ron");
    write(
        &scene_path,
        &scene("(resolution: (8, 8), outputs: [(kind: Albedo)])"),
    );
    let o = run(bin()
        .current_dir(&dir)
        .arg("render")
        .arg(&scene_path)
        .arg("--stats"));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.join("view.png").exists());
    assert!(!dir.join("floor_1_albedo.exr").exists());
    let o = run(bin()
        .current_dir(&dir)
        .arg("render")
        .arg(&scene_path)
        .arg("--bake"));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.join("floor_1_albedo.exr").exists());
}

#[test]
fn bake_without_requests_is_an_error() {
    let dir = scratch("none");
    let scene_path = dir.join("scene.ron");
    write(
        &scene_path,
        &scene("(resolution: (8, 8), outputs: [(kind: Albedo)])").replace(
            ", bake: (resolution: (8, 8), outputs: [(kind: Albedo)])",
            "",
        ),
    );
    let o = run(bin().arg("bake").arg(&scene_path));
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("has no bake requests"),
        "{}",
        stderr(&o)
    );
}

/// `bake --part K/N` writes `DIR/bake_part_K_of_N.exr`: a `--stats-json` of that name is
/// refused before anything runs, as other clashing outputs are (it failed after the bake
/// with "file not found" and left the directory behind).
#[test]
fn a_stats_json_on_the_bake_part_file_is_refused_up_front() {
    let dir = scratch("part-stats-clash");
    write(
        &dir.join("scene.ron"),
        &scene("(resolution: (16, 16), outputs: [(kind: AmbientOcclusion(samples: 4))])"),
    );
    let o = run(bin().current_dir(&dir).args([
        "bake",
        "scene.ron",
        "--part",
        "1/2",
        "-o",
        "cj3",
        "--stats-json",
        "cj3/bake_part_1_of_2.exr",
    ]));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        "error: --stats-json cj3/bake_part_1_of_2.exr is also written by --part cj3/bake_part_1_of_2.exr\n  help: give every output its own file, and none the name of an input\n1 error in scene.ron; nothing baked\n"
    );
    assert!(!dir.join("cj3").exists());
}

/// `bake X.glb --write-gltf` into the glb's own directory would overwrite the scene: refused
/// before the first stage (exit 2), as other outputs that overwrite an input are (it was
/// refused only after the whole bake, exit 1).
#[test]
fn write_gltf_over_the_source_glb_is_refused_before_baking() {
    let dir = scratch("write-gltf-over-source");
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/gltf/two_uv_sets.glb");
    std::fs::copy(&fixture, dir.join("two_uv_sets.glb")).unwrap();
    let o = run(bin()
        .current_dir(&dir)
        .args(["bake", "two_uv_sets.glb", "--write-gltf"]));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("error: --write-gltf ./two_uv_sets.glb would overwrite the scene file two_uv_sets.glb\n  help: "),
        "{e}"
    );
    assert!(!e.contains("wrote"), "{e}");
    let names: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(names.len(), 1, "only the source is there");
    assert_eq!(
        std::fs::read(dir.join("two_uv_sets.glb")).unwrap(),
        std::fs::read(&fixture).unwrap()
    );
}

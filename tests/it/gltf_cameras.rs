//! `render --camera NAME`: a glTF file's perspective cameras all become scene cameras (the
//! first is the render camera), `--camera` picks another by name (its resolution and output
//! file follow), and an unknown name is a usage error listing the cameras.

use stagelight::components::{Camera, Name, RenderCamera};

/// One triangle seen by two perspective cameras: "near" (aspect 1) on +Z, "far" (aspect 2)
/// farther out, and an orthographic camera (skipped with a warning).
const TWO_CAMERAS: &str = r#"{
  "asset": {"version": "2.0"},
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}}]}],
  "cameras": [
    {"name": "near", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01, "aspectRatio": 1.0}},
    {"name": "far", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.01, "aspectRatio": 2.0}},
    {"name": "flat", "type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.01, "zfar": 10}}
  ],
  "nodes": [
    {"name": "tri", "mesh": 0},
    {"name": "near_node", "camera": 0, "translation": [0.3, 0.3, 2]},
    {"name": "far_node", "camera": 1, "translation": [0.3, 0.3, 6]},
    {"name": "flat_node", "camera": 2, "translation": [0.3, 0.3, 3]}
  ],
  "scenes": [{"nodes": [0, 1, 2, 3]}]
}"#;

fn write(test: &str) -> std::path::PathBuf {
    let dir = crate::common::cli::scratch_dir(test);
    std::fs::write(dir.join("cams.gltf"), TWO_CAMERAS).unwrap();
    dir
}

#[test]
fn every_perspective_camera_is_read_and_the_first_renders() {
    let dir = write("gltf_cameras_read");
    let scene = stagelight::scene::load_scene(&dir.join("cams.gltf")).unwrap();
    let mut cameras: Vec<(String, u32, u32, bool)> = scene
        .world
        .query::<(&Name, &Camera, Option<&RenderCamera>)>()
        .iter()
        .map(|(n, c, r)| (n.0.clone(), c.width, c.height, r.is_some()))
        .collect();
    cameras.sort();
    assert_eq!(
        cameras,
        vec![
            ("far".to_string(), 640, 320, false),
            ("near".to_string(), 640, 640, true)
        ]
    );
    assert_eq!(
        stagelight::camera_choice::camera_names(&scene.world),
        vec!["near", "far"]
    );
}

#[test]
fn the_cli_renders_the_named_camera_or_lists_the_cameras() {
    let dir = write("gltf_cameras_cli");
    let gltf = dir.join("cams.gltf");
    let run = |camera: &str| {
        crate::common::cli::run(crate::common::cli::bin().current_dir(&dir).args([
            "render",
            gltf.to_str().unwrap(),
            "--spp",
            "1",
            "--camera",
            camera,
        ]))
    };
    let o = run("far");
    assert!(o.status.success(), "{}", crate::common::cli::stderr(&o));
    // The far camera's own output, at its own resolution.
    let png = dir.join("cams_far.png");
    let image = crate::common::png::read(&png);
    assert_eq!((image.width, image.height), (640, 320));
    assert!(!dir.join("cams.png").exists());

    let o = run("top");
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        crate::common::cli::stderr(&o)
            .lines()
            .filter(|l| !l.contains("warning:"))
            .take(2)
            .collect::<Vec<_>>(),
        vec![
            "error: --camera \"top\": the scene has no camera of that name",
            "  help: the scene's cameras: \"near\", \"far\""
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

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

/// `yfov` must be in (0, π) and `aspectRatio` greater than 0 (and give a height the reader
/// makes); each bad value is a located error naming the camera, never clamped in silence.
#[test]
fn unusable_yfov_and_aspect_ratio_are_located_errors() {
    let dir = crate::common::cli::scratch_dir("gltf_cameras_bad_values");
    let text = TWO_CAMERAS
        .replace(
            r#""yfov": 0.8, "znear": 0.01, "aspectRatio": 1.0"#,
            r#""yfov": 0, "znear": 0.01, "aspectRatio": -1"#,
        )
        .replace(
            r#""yfov": 0.5, "znear": 0.01, "aspectRatio": 2.0"#,
            r#""yfov": 3.2, "znear": 0.01, "aspectRatio": 1e-9"#,
        );
    std::fs::write(dir.join("cams.gltf"), text).unwrap();
    let o = crate::common::cli::run_in(&dir, &["check", "cams.gltf"]);
    assert_eq!(o.status.code(), Some(1));
    let yfov_help = "  help: \"yfov\" is the vertical field of view in radians: 0.8 is about 46°\n";
    let aspect_help = "  help: \"aspectRatio\" is the image's width / height: 1.5 for 3:2; leave it out for 4:3\n";
    assert_eq!(
        crate::common::cli::stderr_of(&o),
        format!(
            "cams.gltf:11:5: warning: cameras[2]: ignored an orthographic camera (only perspective cameras are read)\n\
             cams.gltf:9:69: error: cameras[0] (\"near\"): \"yfov\" must be greater than 0 and less than π radians (180°), found 0\n{yfov_help}\
             cams.gltf:9:102: error: cameras[0] (\"near\"): \"aspectRatio\" must be greater than 0, found -1\n{aspect_help}\
             cams.gltf:10:68: error: cameras[1] (\"far\"): \"yfov\" must be greater than 0 and less than π radians (180°), found 3.2\n{yfov_help}\
             cams.gltf:10:103: error: cameras[1] (\"far\"): \"aspectRatio\" 0.000000001 makes the image 640 pixels wide and 640000000000 high; glTF cameras are read 640 wide and 1 … 16384 high\n{aspect_help}\
             4 errors and 1 warning in cams.gltf\n"
        )
    );
}

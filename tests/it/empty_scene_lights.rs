//! A scene without triangles shows its environment and its visible lights to camera rays,
//! as a scene whose only triangle is out of sight does: the same bytes in every output
//! (beauty, coverage, straight-alpha PNG with the environment's share, a component pass,
//! centre passes) with either integrator. `build_accel` still skips ("no instance has
//! triangles") and `shade` says that no ray is traced. Before, every pixel was (0, 0, 0, 0).

use std::path::Path;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

const OUTPUTS: &str = r#"outputs: [
            (file: "beauty.exr", passes: [Beauty, Alpha, Emission]),
            (file: "straight.png", passes: [Beauty, Alpha]),
            (file: "coverage.png", passes: [Alpha]),
            (file: "centres.exr", passes: [Depth, ObjectId])]"#;

/// The tester's scene: a constant environment and a visible sphere light in front of the
/// camera; with `triangle`, one triangle behind the camera.
fn scene(triangle: bool) -> String {
    let (placed, members) = if triangle {
        (
            r#"materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "tri", mesh: Inline(vertices: [(0, 0, 10), (1, 0, 10), (0, 1, 10)],
        polygons: [[0, 1, 2]]), material: "grey")],
    instances: [(name: "tri_1", of: "tri")],"#,
            "\"tri_1\"",
        )
    } else {
        ("", "")
    };
    format!(
        r#"Scene(
    cameras: [ (name: "cam", fov_y: 60, resolution: (8, 8),
        placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0)),
        {OUTPUTS}) ],
    environment: (shader: Constant(color: (0.2, 0.4, 0.6))),
    lights: [ (name: "s", kind: Sphere(center: (0, 0, 0), radius: 1), intensity: 2.0, visible: true) ],
    {placed}
    groups: [ (name: "world", members: [{members}]) ],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// `(ran, reason, rays)` of stage `name` in `dir/stats.json`.
fn stage(dir: &Path, name: &str) -> (bool, String, u64) {
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("stats.json")).unwrap()).unwrap();
    let s = json["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["stage"] == name)
        .unwrap()
        .clone();
    (
        s["ran"].as_bool().unwrap(),
        s["reason"].as_str().unwrap().to_string(),
        s["rays"].as_u64().unwrap(),
    )
}

/// The RGBA of pixel `(x, y)` of an EXR with channels `R G B A`.
fn rgba(path: &Path, x: usize, y: usize) -> [f32; 4] {
    let image = exr::prelude::read_all_flat_layers_from_file(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let layer = &image.layer_data[0];
    let width = layer.size.width();
    let value = |name: &str| {
        let c = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .unwrap();
        c.sample_data.values_as_f32().nth(y * width + x).unwrap()
    };
    [value("R"), value("G"), value("B"), value("A")]
}

#[test]
fn a_scene_without_triangles_renders_its_environment_and_visible_lights() {
    let dir = scratch_dir("empty-scene-lights");
    for integrator in ["direct", "path"] {
        let mut written = Vec::new();
        for triangle in [false, true] {
            std::fs::write(dir.join("s.ron"), scene(triangle)).unwrap();
            let o = run_in(
                &dir,
                &[
                    "render",
                    "s.ron",
                    "--integrator",
                    integrator,
                    "--stats-json",
                    "stats.json",
                ],
            );
            assert!(o.status.success(), "{}", stderr_of(&o));
            let files: Vec<Vec<u8>> = ["beauty.exr", "straight.png", "coverage.png", "centres.exr"]
                .iter()
                .map(|f| std::fs::read(dir.join(f)).unwrap())
                .collect();
            written.push(files);
            let (built, why, _) = stage(&dir, "build_accel");
            let (shaded, reason, rays) = stage(&dir, "shade");
            assert!(shaded);
            if triangle {
                assert!(built, "{why}");
                assert_eq!(reason, "render camera 8×8");
                assert!(rays > 0);
            } else {
                assert_eq!((built, why.as_str()), (false, "no instance has triangles"));
                assert_eq!(
                    reason,
                    "render camera 8×8, no geometry: camera rays meet only the visible lights and the environment, no ray is traced"
                );
                assert_eq!(rays, 0);
                // The corner sees the environment (alpha 0), the centre the sphere light.
                let beauty = dir.join("beauty.exr");
                assert_eq!(rgba(&beauty, 0, 0), [0.2, 0.4, 0.6, 0.0], "{integrator}");
                assert_eq!(rgba(&beauty, 4, 4), [2.0, 2.0, 2.0, 1.0], "{integrator}");
            }
        }
        for (k, name) in ["beauty.exr", "straight.png", "coverage.png", "centres.exr"]
            .iter()
            .enumerate()
        {
            assert!(
                written[0][k] == written[1][k],
                "{integrator}: {name} differs from the render with an off-screen triangle"
            );
        }
    }
}

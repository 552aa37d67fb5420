//! Contours between copies of one object: separately placed instances (and scatter copies)
//! are separate objects to the `Silhouette` and `Curvature` contour shaders, as they are to
//! the contrast's `instance` switch.

use std::path::Path;

use glam::Vec2;
use stagelight::contour::ContourImage;
use stagelight::scene::load_scene_str;

use crate::common::{run_in, scratch_dir, stderr_of};

/// Two balls on a floor seen from above and in front, `ball_2` in front of and overlapping
/// `ball_1`; the balls' material has `contour`, the floor none. `objects` and `ball_2_of`
/// name the objects and which one `ball_2` places.
fn two_balls(contour: &str, objects: &str, ball_2_of: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1),
    cameras: [(name: "cam", fov_y: 40, resolution: (32, 24),
      placement: LookAt(eye: (0, -9, 5), target: (0, 0, 0.7), up: (0, 0, 1)),
      outputs: [(file: "m.svg")])],
    lights: [(name: "key", kind: Point(position: (-4, -5, 7)), intensity: 60)],
    materials: [(name: "floor", shader: Lambert(albedo: (0.8, 0.8, 0.75))),
                (name: "ball", shader: Lambert(albedo: (0.9, 0.35, 0.2)), contour: {contour})],
    objects: [(name: "floor", mesh: Grid(size_x: 14, size_y: 10), material: "floor"),
              (name: "ball", mesh: Sphere(radius: 1.0), material: "ball"){objects}],
    instances: [(name: "floor_1", of: "floor"),
                (name: "ball_1", of: "ball", transform: [Translate((0, 0, 1))]),
                (name: "ball_2", of: "{ball_2_of}", transform: [Translate((1.0, -1.5, 1))])],
    groups: [(name: "world", members: ["floor_1", "ball_1", "ball_2"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// `Silhouette` draws the outline of each ball and the edge where `ball_2` covers `ball_1`:
/// three polygons, as `Simple` draws (a sphere has no creases) and as two different objects
/// in the same places get.
#[test]
fn overlapping_instances_of_one_object_get_a_silhouette_between_them() {
    let dir = scratch_dir("contour-instances");
    let silhouette = "Silhouette(width: 1)";
    let scenes = [
        ("copies.ron", two_balls(silhouette, "", "ball")),
        (
            "objects.ron",
            two_balls(
                silhouette,
                r#", (name: "ball2", mesh: Sphere(radius: 1.0), material: "ball")"#,
                "ball2",
            ),
        ),
        ("simple.ron", two_balls("Simple(width: 1)", "", "ball")),
    ];
    let mut svgs = Vec::new();
    for (name, text) in &scenes {
        std::fs::write(dir.join(name), text).unwrap();
        let o = run_in(&dir, &["render", name]);
        assert!(o.status.success(), "{name}: {}", stderr_of(&o));
        svgs.push(std::fs::read_to_string(dir.join("m.svg")).unwrap());
    }
    let polygons: Vec<usize> = svgs.iter().map(|s| s.matches("<polygon").count()).collect();
    assert_eq!(
        polygons,
        [3, 3, 3],
        "two outlines and the edge between the balls (copies, objects, Simple)"
    );
    assert!(
        svgs[0] == svgs[1],
        "two copies draw as two different objects do"
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// The lines of a scene.
fn contours(text: &str) -> ContourImage {
    let mut scene = load_scene_str(text, Path::new("contour_instances.ron"))
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    crate::common::render(&mut scene.world, scene.settings.clone())
        .outputs
        .contours
        .expect("contours drawn")
}

/// Forty balls scattered over a 2 × 2 square, overlapping one another, seen from above with
/// contour shader `contour`.
fn scattered_balls(contour: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1),
    cameras: [(name: "cam", fov_y: 40, resolution: (40, 40),
      placement: LookAt(eye: (0, -0.5, 7), target: (0, 0, 0), up: (0, 1, 0)),
      outputs: [(file: "s.svg")])],
    materials: [(name: "ball", shader: Constant(color: (0.8, 0.8, 0.8)), contour: {contour})],
    objects: [(name: "ground", mesh: Grid(size_x: 2, size_y: 2)),
              (name: "ball", mesh: Sphere(radius: 0.3), material: "ball"),
              (name: "balls", mesh: Scatter(prototype: "ball", surface: "ground", count: 40, seed: 3))],
    instances: [(name: "balls_1", of: "balls")],
    groups: [(name: "root", members: ["balls_1"])],
    render: (root: "root", camera: "cam"),
)"#
    )
}

/// Every line's points.
fn points(img: &ContourImage) -> Vec<Vec<Vec2>> {
    img.lines
        .iter()
        .map(|l| l.points.iter().map(|p| p.pos).collect())
        .collect()
}

/// Overlapping scatter copies of a sphere: `Silhouette` draws every line `Simple` draws
/// (each one the outline of a copy against the background or another copy), so also where
/// one copy covers another.
#[test]
fn overlapping_scatter_copies_get_a_silhouette_between_them() {
    let simple = contours(&scattered_balls("Simple(width: 1)"));
    let silhouette = contours(&scattered_balls("Silhouette(width: 1)"));
    assert!(
        simple.lines.len() > 10,
        "the copies overlap: {} lines",
        simple.lines.len()
    );
    assert_eq!(points(&silhouette), points(&simple));
}

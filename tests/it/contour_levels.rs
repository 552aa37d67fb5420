//! Contour levels (`ray_depth`, `.mi` `max_level`): the contour store walks each pixel's path
//! once through the levels and no further than it goes, so `shade` traces one ray per level
//! a path reaches — none past a background pixel or a surface without a delta branch — and
//! the lines are the bytes the per-level walks from the camera drew.

use std::path::Path;

use stagelight::contour::eps::encode_eps;
use stagelight::contour::svg::encode_svg;
use stagelight::frame::Frame;
use stagelight::hash::Fnv64;
use stagelight::scene::load_scene_str;

/// Renders `text` (every stage but `write_output`).
fn render(text: &str) -> Frame {
    let mut scene = load_scene_str(text, Path::new("contour_levels.ron"))
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    crate::common::render(&mut scene.world, scene.settings.clone())
}

/// The closest-hit and occlusion rays `shade` traced rendering `text`.
fn shade_rays(text: &str) -> (u64, u64) {
    let frame = render(text);
    let shade = frame.report.stage("shade").expect("shade ran");
    assert!(frame.outputs.contours.is_some(), "contours drawn");
    (shade.rays_closest, shade.rays_occlusion)
}

/// An 8×6 camera at `eye` looking along +y with `ray_depth`, one sample per pixel, trace
/// depth 1 and no reflections (no rays past the camera rays' hits), no lights; `body` the materials, objects,
/// instances and group `root`.
fn scene(eye: (f32, f32, f32), ray_depth: u32, body: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, max_depth: 1, reflection_depth: 0, contours: (ray_depth: {ray_depth})),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 6),
        placement: LookAt(eye: ({}, {}, {}), target: ({}, {}, {}), up: (0, 0, 1)),
        outputs: [(file: "levels.svg")])],
    {body}
    render: (root: "root", camera: "cam"),
)"#,
        eye.0,
        eye.1,
        eye.2,
        eye.0,
        eye.1 + 1.0,
        eye.2
    )
}

/// Two opaque quads (`Constant`: no delta branch) side by side at y = 0, the image's top rows
/// seeing the background.
const TWO_QUADS: &str = r#"
    materials: [(name: "a", shader: Constant(color: (0.8, 0.2, 0.2)),
                 contour: Simple(color: (0, 0, 0, 1), width: 5.0)),
                (name: "b", shader: Constant(color: (0.2, 0.8, 0.2)),
                 contour: Simple(color: (0, 0, 0, 1), width: 5.0))],
    objects: [(name: "left", mesh: Inline(vertices: [(-9, 0, -9), (0, 0, -9), (0, 0, 0.5), (-9, 0, 0.5)],
               polygons: [[0, 1, 2, 3]]), material: "a"),
              (name: "right", mesh: Inline(vertices: [(0, 0, -9), (9, 0, -9), (9, 0, 0.5), (0, 0, 0.5)],
               polygons: [[0, 1, 2, 3]]), material: "b")],
    instances: [(name: "l", of: "left"), (name: "r", of: "right")],
    groups: [(name: "root", members: ["l", "r"])],
"#;

/// On two opaque quads no path goes past its first hit: `shade` traces the same rays at
/// `ray_depth` 0 and 8 — per pixel (48) the centre-sample ray, the one sample's camera ray
/// and the contour store's level-0 ray, 3 · 48 = 144, no shadow rays (no lights). The
/// per-level walk from the camera traced one more camera ray per pixel and level,
/// background pixels included: 144 + 8 · 48 = 528 at `ray_depth` 8.
#[test]
fn levels_behind_opaque_surfaces_and_the_background_trace_no_rays() {
    for depth in [0, 1, 8] {
        assert_eq!(
            shade_rays(&scene((0.0, -5.0, 0.0), depth, TWO_QUADS)),
            (3 * 48, 0),
            "ray_depth {depth}"
        );
    }
}

/// Two facing mirrors, 4 apart, wide enough that every path bounces between them past
/// level 8: mirror A at y = 1 faces the camera at y = −1, mirror B at y = −3 behind the
/// camera faces A.
const MIRRORS: &str = r#"
    materials: [(name: "mirror", shader: Mirror(color: (0.9, 0.9, 0.9)),
                 contour: Simple(color: (0, 0, 0, 1), width: 5.0))],
    objects: [(name: "a", mesh: Inline(vertices: [(-50, 1, -50), (50, 1, -50), (50, 1, 50), (-50, 1, 50)],
               polygons: [[0, 1, 2, 3]]), material: "mirror"),
              (name: "b", mesh: Inline(vertices: [(-50, -3, -50), (-50, -3, 50), (50, -3, 50), (50, -3, -50)],
               polygons: [[0, 1, 2, 3]]), material: "mirror")],
    instances: [(name: "a_1", of: "a"), (name: "b_1", of: "b")],
    groups: [(name: "root", members: ["a_1", "b_1"])],
"#;

/// Between two mirrors every pixel's path reaches every level, each one ray further: at
/// `ray_depth` k `shade` traces per pixel (48) the centre-sample ray, the sample's camera ray
/// (`reflection_depth: 0`: the render follows no mirror) and k + 1 store rays, (3 + k) · 48 —
/// linear in the levels. Walking each level from the camera traced (k + 1)(k + 2)/2 store
/// rays per pixel: 96 + 45 · 48 = 2256 at k = 8, not 528.
#[test]
fn levels_between_mirrors_cost_one_ray_each() {
    for k in [0u64, 1, 2, 8] {
        assert_eq!(
            shade_rays(&scene((0.0, -1.0, 0.0), k as u32, MIRRORS)),
            ((3 + k) * 48, 0),
            "ray_depth {k}"
        );
    }
}

/// A 32×24 scene of every kind of level — a ball behind a transparent sheet, a glass ball,
/// three mirrors that reflect each other — at `ray_depth: 8`: its SVG and EPS are the bytes
/// the per-level walks from the camera drew (FNV-1a of the files the release binary wrote
/// before the walk was shared: 49149 and 54993 bytes).
#[test]
fn lines_of_every_level_are_the_bytes_of_the_per_level_walks() {
    let text = r#"Scene(
    options: (samples: 1, contours: (ray_depth: 8, contrast: (normal_angle: 40, depth: 0.2))),
    cameras: [(name: "cam", fov_y: 50.0, resolution: (32, 24),
        placement: LookAt(eye: (0.5, -6, 1.5), target: (0, 0, 0.5), up: (0, 0, 1)),
        outputs: [(file: "mirrors.svg"), (file: "mirrors.eps")])],
    lights: [(name: "key", kind: Point(position: (-2, -4, 6)), intensity: 40)],
    materials: [(name: "ink", shader: Lambert(albedo: (0.8, 0.4, 0.3)),
                 contour: Layered(color: (0, 0, 0, 1), width: 1.0, thinning: 0.7)),
                (name: "glass", shader: Dielectric(ior: 1.5), contour: Simple(color: (0, 0, 1, 1), width: 0.6)),
                (name: "sheet", shader: Opacity(opacity: (0.3, 0.3, 0.3), input: Constant(color: (1, 1, 1)))),
                (name: "mirror", shader: Mirror(color: (0.9, 0.9, 0.9)), contour: Curvature(color: (0.3, 0, 0, 1), min_width: 0.2, max_width: 1.0))],
    objects: [(name: "ball", mesh: Sphere(radius: 0.6), material: "ink", approximation: Parametric(u: 32, v: 16)),
              (name: "gball", mesh: Sphere(radius: 0.5), material: "glass", approximation: Parametric(u: 32, v: 16)),
              (name: "sheet", mesh: Inline(vertices: [(0.2, -2, -1), (3, -2, -1), (3, -2, 3), (0.2, -2, 3)], polygons: [[0, 1, 2, 3]]), material: "sheet"),
              (name: "wall", mesh: Inline(vertices: [(-4, 3, -1), (4, 3, -1), (4, 3, 4), (-4, 3, 4)], polygons: [[0, 1, 2, 3]]), material: "mirror"),
              (name: "side", mesh: Inline(vertices: [(-2.5, -8, -1), (-2.5, 8, -1), (-2.5, 8, 4), (-2.5, -8, 4)], polygons: [[0, 1, 2, 3]]), material: "mirror"),
              (name: "side2", mesh: Inline(vertices: [(2.5, -8, -1), (2.5, 8, -1), (2.5, 8, 4), (2.5, -8, 4)], polygons: [[0, 3, 2, 1]]), material: "mirror")],
    instances: [(name: "ball_1", of: "ball", transform: [Translate((-0.8, 0, 0.6))]),
                (name: "gball_1", of: "gball", transform: [Translate((0.9, -0.5, 0.5))]),
                (name: "sheet_1", of: "sheet"), (name: "wall_1", of: "wall"),
                (name: "side_1", of: "side"), (name: "side_2", of: "side2")],
    groups: [(name: "root", members: ["ball_1", "gball_1", "sheet_1", "wall_1", "side_1", "side_2"])],
    render: (root: "root", camera: "cam"),
)"#;
    let image = render(text).outputs.contours.expect("contours drawn");
    let fnv = |s: &str| Fnv64::default().bytes(s.as_bytes()).finish();
    let (svg, eps) = (encode_svg(&image), encode_eps(&image));
    assert_eq!((svg.len(), fnv(&svg)), (49149, 0x6f18_56c0_ec92_ab1f));
    assert_eq!((eps.len(), fnv(&eps)), (54993, 0x0a72_75dd_bf90_3a3a));
}

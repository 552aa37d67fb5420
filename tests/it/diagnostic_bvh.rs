//! Issue 13: the BVH diagnostic (`options.diagnostic: Bvh(quantity: Depth | Size, max: …)`,
//! mental ray `diagnostic bsp depth|size`, CLI `--diagnostic bvh:depth`). One quad is a
//! one-level tree: its depth view is red exactly where the quad is seen and black elsewhere.
//! A cloud of small triangles beside it makes a deeper tree there, and rays through the cloud
//! test more triangles: both views rank the two halves of the image as the hierarchy's work
//! does.

use std::path::Path;

use glam::Vec3;
use stagelight::scene::desc::{BvhQuantityDesc, DiagnosticDesc};
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene_str;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

const SIDE: usize = 60;

/// A 2 × 2 quad at z = 0 right of centre and, when `cloud`, [`CLOUD`] small triangles
/// scattered through the box x ∈ (−2.4, −0.4), |y| < 1, |z| < 1 left of centre, seen straight
/// down from height 5 (60°, 60 × 60 pixels).
fn scene(diagnostic: &str, cloud: bool) -> String {
    let (object, member) = if cloud {
        (cloud_object(), r#"(name: "cloud_1", of: "cloud"),"#)
    } else {
        (String::new(), "")
    };
    format!(
        r#"Scene(
    options: (samples: 1, diagnostic: {diagnostic}),
    cameras: [(name: "cam", fov_y: 60, resolution: ({SIDE}, {SIDE}),
        placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "bvh.png")])],
    lights: [(name: "sun", kind: Directional(direction: (0, 0, -1)), intensity: 1)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [
        (name: "quad", mesh: Grid(size_x: 2, size_y: 2), material: "grey"),
        {object}
    ],
    instances: [
        (name: "quad_1", of: "quad", transform: [Translate((1.4, 0, 0))]),
        {member}
    ],
    groups: [(name: "world", members: ["quad_1"{more}])],
    render: (root: "world", camera: "cam"),
)"#,
        more = if cloud { r#", "cloud_1""# } else { "" },
    )
}

/// Triangles in the cloud.
const CLOUD: usize = 3000;

/// The cloud as an inline mesh: triangles of about 0.06 units at fixed pseudo-random places.
fn cloud_object() -> String {
    let mut state = 12345u64;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 40) as f64 / (1u64 << 24) as f64
    };
    let mut vertices = Vec::new();
    let mut polygons = Vec::new();
    for k in 0..CLOUD as u32 {
        let c = [
            -2.4 + 2.0 * uniform(),
            2.0 * uniform() - 1.0,
            2.0 * uniform() - 1.0,
        ];
        for _ in 0..3 {
            let v: Vec<f64> = c.iter().map(|x| x + 0.06 * (uniform() - 0.5)).collect();
            vertices.push(format!("({:.5}, {:.5}, {:.5})", v[0], v[1], v[2]));
        }
        polygons.push(format!("[{}, {}, {}]", 3 * k, 3 * k + 1, 3 * k + 2));
    }
    format!(
        r#"(name: "cloud", mesh: Inline(vertices: [{}], polygons: [{}]), material: "grey"),"#,
        vertices.join(", "),
        polygons.join(", ")
    )
}

fn beauty(text: &str) -> Vec<Vec3> {
    let mut scene = load_scene_str(text, Path::new("bvh.ron")).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    frame.outputs.image.expect("an image").beauty
}

/// Pixel indices whose centre ray crosses the plane z = `h` within x ∈ (`lo`, `lo` + 2),
/// |y| < 1.
fn seen(h: f64, lo: f64) -> Vec<usize> {
    let half = SIDE as f64 / 2.0;
    let tan = 30f64.to_radians().tan();
    (0..SIDE * SIDE)
        .filter(|&i| {
            let (u, v) = ((i % SIDE) as f64 + 0.5, (i / SIDE) as f64 + 0.5);
            // Eye (0, 0, 5), direction ((u − half)/half·tan, (half − v)/half·tan, −1).
            let (x, y) = (
                (5.0 - h) * (u - half) / half * tan,
                (5.0 - h) * (half - v) / half * tan,
            );
            x > lo && x < lo + 2.0 && y.abs() < 1.0
        })
        .collect()
}

fn mean_red(view: &[Vec3], pixels: &[usize]) -> f32 {
    pixels.iter().map(|&i| view[i].x).sum::<f32>() / pixels.len() as f32
}

#[test]
fn one_quads_depth_view_is_red_exactly_where_the_quad_is_seen() {
    let view = beauty(&scene("Some(Bvh(quantity: Depth))", false));
    let quad = seen(0.0, 0.4);
    assert!(quad.len() > 300, "{} quad pixels", quad.len());
    for (i, &v) in view.iter().enumerate() {
        let want = if quad.contains(&i) {
            Vec3::X
        } else {
            Vec3::ZERO
        };
        assert_eq!(v, want, "pixel ({}, {})", i % SIDE, i / SIDE);
    }
}

#[test]
fn rays_through_the_cloud_go_deeper_and_test_more_triangles() {
    // Rays entering the cloud's box through its top face, and rays meeting the quad.
    let (cloud, quad) = (seen(1.0, -2.4), seen(0.0, 0.4));
    assert!(
        quad.len() > 300 && cloud.len() > 300,
        "{} {}",
        quad.len(),
        cloud.len()
    );
    let depth = beauty(&scene("Some(Bvh(quantity: Depth))", true));
    let size = beauty(&scene("Some(Bvh(quantity: Size))", true));
    // Measured on the binned tree: depth 0.74 vs 0.20, size 0.25 vs 0.12 (PLOC tree: 0.75 vs
    // 0.20, 0.23 vs 0.13).
    for (view, ratio) in [(&depth, 2.0), (&size, 1.3)] {
        let (q, c) = (mean_red(view, &quad), mean_red(view, &cloud));
        assert!(c > ratio * q, "cloud {c} vs quad {q}");
        // Scaled to the tree's depth / the image's largest count: something reaches red.
        assert!(view.contains(&Vec3::X));
        // Nothing in reach of the background rays' boxes: black.
        assert_eq!(view[0], Vec3::ZERO);
        assert!(view
            .iter()
            .all(|v| v.y == 0.0 && (v.x + v.z - 1.0).abs() < 1e-6 || *v == Vec3::ZERO));
    }
    // A maximum of one triangle: every pixel whose ray tested one is red.
    let capped = beauty(&scene("Some(Bvh(quantity: Size, max: 1))", true));
    assert!(quad.iter().all(|&i| capped[i] == Vec3::X));
}

#[test]
fn mi_diagnostic_bsp_maps_onto_the_bvh_view() {
    let seed =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_controls/caustic_filter.mi");
    let text = std::fs::read_to_string(seed).unwrap();
    let at = "caustic on\ncaustic filter tent\n";
    for (statement, want) in [
        ("diagnostic bsp depth\n", Some(BvhQuantityDesc::Depth)),
        ("diagnostic bsp size\n", Some(BvhQuantityDesc::Size)),
        ("diagnostic bsp size\ndiagnostic bsp off\n", None),
    ] {
        let read = read_mi(Path::new("d.mi"), text.replace(at, statement).as_bytes()).unwrap();
        assert!(read.warnings.is_empty(), "{:?}", read.warnings);
        assert_eq!(
            read.desc.options.unwrap().diagnostic,
            want.map(|quantity| DiagnosticDesc::Bvh {
                quantity,
                max: None
            }),
            "{statement}"
        );
    }
    let errors = read_mi(
        Path::new("d.mi"),
        text.replace(at, "diagnostic bsp leaves\n").as_bytes(),
    )
    .unwrap_err();
    assert_eq!(
        errors[0].to_string(),
        "d.mi:3:16: error: expected off, depth or size after diagnostic bsp, found \"leaves\""
    );
}

#[test]
fn the_cli_draws_the_bvh_view_and_refuses_an_unknown_quantity() {
    let dir = scratch_dir("diagnostic-bvh");
    std::fs::write(dir.join("scene.ron"), scene("None", true)).unwrap();
    let o = run_in(&dir, &["render", "scene.ron", "--diagnostic", "bvh:size:8"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert!(dir.join("bvh.png").is_file());
    let o = run_in(&dir, &["render", "scene.ron", "--diagnostic", "bvh:leaves"]);
    assert!(!o.status.success());
    assert!(
        stderr_of(&o).contains("unknown bvh diagnostic \"leaves\" (expected depth or size)"),
        "{}",
        stderr_of(&o)
    );
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    std::fs::write(
        dir.join("zero.ron"),
        scene("Some(Bvh(quantity: Size, max: 0))", false),
    )
    .unwrap();
    let o = run_in(&dir, &["check", "zero.ron"]);
    assert!(!o.status.success());
    assert!(
        stderr_of(&o).contains("max must be positive, found 0"),
        "{}",
        stderr_of(&o)
    );
}

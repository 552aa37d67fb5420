//! Fast final gathering (`global_illumination: (precompute: true)`, `photon::irradiance`):
//! final-gather rays landing on Lambertian surfaces read irradiance precomputed at every
//! fourth photon instead of running a `gather`-photon estimate each. The render agrees with
//! the per-ray estimate (`precompute: false`) within the lookup's blur, and surfaces with
//! other lobes keep the per-ray estimate bit for bit.

use std::path::Path;

use glam::Vec3;
use stagelight::scene::load_scene_str;

/// An open box (floor, back wall, left wall) under a square area light, all surfaces of
/// `shader`, with a global map read by final gathering.
fn scene(shader: &str, precompute: bool) -> String {
    format!(
        r#"Scene(
    options: (samples: 4, seed: 3, global_illumination: (photons: 20000, gather: 50,
        final_gather: 8, precompute: {precompute})),
    cameras: [(name: "cam", fov_y: 50, resolution: (24, 18),
        placement: LookAt(eye: (0, -4, 2.5), target: (0, 0, 1), up: (0, 0, 1)),
        outputs: [(file: "fg.png")])],
    lights: [(name: "panel", kind: Rect(corner: (-0.5, -0.5, 2.9), edge_u: (0, 1, 0),
        edge_v: (1, 0, 0)), intensity: 10, samples: 2)],
    materials: [
        (name: "white", shader: {shader}),
        (name: "red", shader: {shader}),
    ],
    objects: [
        (name: "floor", mesh: Grid(size_x: 4, size_y: 4), material: "white"),
        (name: "back", mesh: Grid(size_x: 4, size_y: 3), material: "white"),
        (name: "left", mesh: Grid(size_x: 4, size_y: 3), material: "red"),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "back_1", of: "back",
         transform: [Rotate(axis: (1, 0, 0), degrees: 90), Translate((0, 2, 1.5))]),
        (name: "left_1", of: "left",
         transform: [Rotate(axis: (0, 1, 0), degrees: 90), Rotate(axis: (0, 0, 1), degrees: 90),
                     Translate((-2, 0, 1.5))]),
    ],
    groups: [(name: "world", members: ["floor_1", "back_1", "left_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// The beauty image of `text`.
fn render(text: &str) -> Vec<Vec3> {
    let mut scene = load_scene_str(text, Path::new("fg.ron")).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    frame.outputs.image.expect("image").beauty
}

fn mean(image: &[Vec3]) -> Vec3 {
    image.iter().copied().sum::<Vec3>() / image.len() as f32
}

#[test]
fn precomputed_irradiance_agrees_with_the_per_ray_estimate() {
    let lambert = "Lambert(albedo: (0.7, 0.7, 0.7))";
    let fast = render(&scene(lambert, true));
    let exact = render(&scene(lambert, false));
    assert!(fast.iter().all(|p| p.is_finite()));
    assert_ne!(fast, exact, "the precomputed lookup is in use");
    // The same sampler draws in both: only the lookup differs, so the images agree pixel
    // by pixel up to its blur. Whole-image means within 2 %, relMSE under 1 %.
    let (f, e) = (mean(&fast), mean(&exact));
    println!("fast {f}, per ray {e}");
    assert!(((f - e).abs() / e).max_element() < 0.02, "{f} vs {e}");
    let rel_mse = fast
        .iter()
        .zip(&exact)
        .map(|(a, b)| ((*a - *b) * (*a - *b) / (*b * *b + Vec3::splat(0.01))).element_sum() / 3.0)
        .sum::<f32>()
        / fast.len() as f32;
    println!("relMSE fast vs per ray: {rel_mse:.3e}");
    assert!(rel_mse < 1e-2, "{rel_mse}");
}

#[test]
fn surfaces_with_a_glossy_lobe_keep_the_per_ray_estimate() {
    let phong = "Phong(diffuse: (0.5, 0.5, 0.5), specular: (0.3, 0.3, 0.3), spec_exp: 10)";
    let fast = render(&scene(phong, true));
    let exact = render(&scene(phong, false));
    assert!(mean(&fast).x > 0.0);
    assert_eq!(fast, exact);
}

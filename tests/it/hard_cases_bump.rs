//! Hard cases H11 and H12 (`HARDCASES.md`) with strong bump maps: bent shading normals must
//! neither paint black spots (H11) nor let light through closed surfaces (H12).

use std::path::Path;

use glam::Vec3;
use stagelight::scene::load_scene_str;

fn render(text: &str) -> (usize, Vec<Vec3>) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scene = load_scene_str(text, &dir.join("scene.ron")).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("image");
    (image.width as usize, image.beauty)
}

/// The strong bump of both cases: noise heights whose slopes reach about tan 85°.
const STRONG_BUMP: &str = "bump: (height: Fbm(frequency: 6, octaves: 2), scale: 1.2)";

/// A 20 × 20 quad (Ng = +z) with `shader` and [`STRONG_BUMP`] inside a two-sided emissive
/// sphere of radiance 1 (a white furnace), seen from elevation `elev` degrees.
fn furnace(shader: &str, elev: f32, integrator: &str) -> String {
    let (s, c) = elev.to_radians().sin_cos();
    let eye = (3.0 * c, 0.0, 3.0 * s.max(0.02));
    format!(
        r#"(
    options: (samples: 16, integrator: {integrator}, max_depth: 3),
    cameras: [(name: "cam", fov_y: 20, resolution: (12, 12),
               placement: LookAt(eye: {eye:?}, target: (0, 0, 0), up: (0, 0, 1)))],
    materials: [
        (name: "m", shader: {shader}, {STRONG_BUMP}),
        (name: "sky", shader: Lambert(albedo: (0, 0, 0)), emission: (1, 1, 1), two_sided: true),
    ],
    objects: [
        (name: "quad", material: "m",
         mesh: Inline(vertices: [(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)],
                      polygons: [[0, 1, 2, 3]], uvs: [(0, 0), (1, 0), (1, 1), (0, 1)])),
        (name: "dome", material: "sky", mesh: Sphere(radius: 50),
         approximation: Parametric(u: 8, v: 8)),
    ],
    instances: [(name: "q", of: "quad"), (name: "d", of: "dome")],
    groups: [(name: "world", members: ["q", "d"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

fn stats(img: &[Vec3]) -> (f32, f32, f32) {
    let lum: Vec<f32> = img.iter().map(|c| c.element_sum() / 3.0).collect();
    let n = lum.len() as f32;
    let mean = lum.iter().sum::<f32>() / n;
    let var = lum.iter().map(|l| (l - mean) * (l - mean)).sum::<f32>() / (n - 1.0);
    let min = img.iter().map(|c| c.min_element()).fold(f32::MAX, f32::min);
    (mean, (var / n).sqrt(), min)
}

/// H11 (b): strong bump on a mirror, a glossy conductor and a Lambert surface in a white
/// furnace, seen from 90°, 30° and 5°: no pixel darker than 0.05, none non-finite, and no
/// energy gain (image mean ≤ 1 + 3σ).
#[test]
fn h11_strong_bump_in_a_white_furnace_has_no_black_or_nan_pixel() {
    let shaders = [
        "Mirror(color: (1, 1, 1))",
        "CookTorrance(diffuse: (0, 0, 0), specular: (1, 1, 1), roughness: 0.1, ior: (20, 20, 20))",
        "Lambert(albedo: (0.8, 0.8, 0.8))",
    ];
    for integrator in ["Direct", "Path"] {
        for shader in shaders {
            if integrator == "Direct" && shader.starts_with("Cook") {
                continue; // glossy interreflection is the path tracer's job
            }
            for elev in [90.0, 30.0, 5.0] {
                let (_, img) = render(&furnace(shader, elev, integrator));
                assert!(
                    img.iter().all(|c| c.is_finite()),
                    "{shader} {elev}° non-finite"
                );
                let (mean, se, min) = stats(&img);
                assert!(
                    min >= 0.05,
                    "{integrator} {shader} at {elev}°: darkest {min}"
                );
                assert!(
                    mean <= 1.0 + 3.0 * se + 1e-4,
                    "{shader} {elev}°: mean {mean} ± {se}"
                );
            }
        }
    }
}

/// H12 (a): a closed box whose inside walls carry an extreme bump, lit by a sun outside:
/// the bent normals face the sun in places, but the geometry does not let the light in —
/// every interior pixel is exactly 0.
#[test]
fn h12_closed_box_with_strong_bump_leaks_no_light() {
    for integrator in ["Direct", "Path"] {
        let text = format!(
            r#"(
    options: (samples: 4, integrator: {integrator}, max_depth: 4),
    cameras: [(name: "cam", fov_y: 90, resolution: (16, 16),
               placement: LookAt(eye: (0.2, 0.1, 0.3), target: (1, 0.5, -1)))],
    lights: [(name: "sun", kind: Directional(direction: (-0.3, -1, -0.2)), intensity: 10),
             (name: "spot", kind: Point(position: (0, 5, 0)), intensity: 100)],
    materials: [(name: "wall", shader: Dgs(diffuse: (0.5, 0.5, 0.5), glossy: (0.3, 0.3, 0.3), shiny: 30),
                 two_sided: true, {STRONG_BUMP})],
    objects: [(name: "box", material: "wall",
               mesh: Inline(vertices: [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                                       (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)],
                            polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4],
                                       [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]]))],
    instances: [(name: "b", of: "box")],
    groups: [(name: "world", members: ["b"])],
    render: (root: "world", camera: "cam"),
)"#
        );
        let (_, img) = render(&text);
        let lit = img.iter().filter(|c| **c != Vec3::ZERO).count();
        assert_eq!(lit, 0, "{integrator}: {lit} interior pixels received light");
    }
}

/// A `Bump`-mode displacement on the object bends shading normals like a material bump:
/// the lit image changes, the silhouette (coverage) does not.
#[test]
fn bump_displacement_mode_perturbs_shading() {
    let scene = |disp: &str| {
        format!(
            r#"(
    options: (samples: 1),
    cameras: [(name: "cam", fov_y: 30, resolution: (16, 16),
               placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (-0.5, 0, -1)), intensity: 3)],
    materials: [(name: "m", shader: Lambert(albedo: (0.8, 0.8, 0.8)))],
    objects: [(name: "quad", material: "m", {disp}
               mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
                            polygons: [[0, 1, 2, 3]], uvs: [(0, 0), (1, 0), (1, 1), (0, 1)]))],
    instances: [(name: "q", of: "quad")],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
)"#
        )
    };
    let (_, flat) = render(&scene(""));
    let (_, bumped) = render(&scene(
        "displacement: (shader: Sine(amplitude: 0.02, factor: 20), mode: Bump),",
    ));
    // Flat: every pixel the same Lambert value 0.8/π · 3 · cos.
    let want = 0.8 / std::f32::consts::PI * 3.0 * (1.0 / 1.25f32.sqrt());
    assert!(
        flat.iter().all(|c| (c.x - want).abs() < 1e-4),
        "{}",
        flat[0]
    );
    let changed = bumped.iter().filter(|c| (c.x - want).abs() > 0.01).count();
    assert!(changed > bumped.len() / 2, "{changed}");
    assert!(bumped.iter().all(|c| c.is_finite() && c.x > 0.0));
}

/// H11 (c): a coarse sphere (10 × 10 segments) with smooth interpolated normals, mirror and
/// glossy, in the white furnace: the rim, where the view falls behind the interpolated
/// normal, has no black pixel. The mirror is rendered with one sample per pixel so a single
/// black sample would show (without the normal correction 9 of its ~2,400 pixels are black).
#[test]
fn h11_coarse_smooth_sphere_has_no_black_rim() {
    for (shader, spp) in [
        ("Mirror(color: (1, 1, 1))", 1),
        (
            "CookTorrance(diffuse: (0, 0, 0), specular: (1, 1, 1), roughness: 0.1, ior: (20, 20, 20))",
            16,
        ),
    ] {
        let text = format!(
            r#"(
    options: (samples: {spp}, integrator: Path, max_depth: 3),
    cameras: [(name: "cam", fov_y: 32, resolution: (64, 64),
               placement: LookAt(eye: (0, -4, 0.3), target: (0, 0, 0), up: (0, 0, 1)))],
    materials: [
        (name: "m", shader: {shader}),
        (name: "sky", shader: Lambert(albedo: (0, 0, 0)), emission: (1, 1, 1), two_sided: true),
    ],
    objects: [
        (name: "ball", material: "m", mesh: Sphere(radius: 1), approximation: Parametric(u: 10, v: 10)),
        (name: "dome", material: "sky", mesh: Sphere(radius: 50), approximation: Parametric(u: 8, v: 8)),
    ],
    instances: [(name: "b", of: "ball"), (name: "d", of: "dome")],
    groups: [(name: "world", members: ["b", "d"])],
    render: (root: "world", camera: "cam"),
)"#
        );
        let (_, img) = render(&text);
        let (mean, se, min) = stats(&img);
        assert!(img.iter().all(|c| c.is_finite()));
        let dark = img.iter().filter(|c| c.min_element() < 0.05).count();
        assert!(min >= 0.05, "{shader}: darkest {min}, {dark} dark pixels");
        assert!(mean <= 1.0 + 3.0 * se + 1e-4, "{shader}: mean {mean} ± {se}");
    }
}

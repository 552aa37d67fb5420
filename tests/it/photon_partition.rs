//! Issue 16 item 7, hard case H23: the path-space partition of the photon/final-gather
//! render (`Direct` + caustic map + global map with final gathering, which follows gather
//! rays through glass: `L … D S* D E`) counts every path once. On a diffuse floor with a
//! coloured wall and a glass ball under an off-axis area light, the region means of the
//! hybrid render over three masks (caustic spot, shadowed floor, directly lit floor) equal
//! the path tracer's within `2 % + 3σ`: double counting would show as a large excess in the
//! caustic, missing paths as a deficit.

use std::path::Path;

use glam::{Vec2, Vec3};
use stagelight::components::Camera;
use stagelight::scene::load_scene_str;
use stagelight::shading::camera::CameraRays;

const BALL: Vec3 = Vec3::new(0.0, 0.0, 0.7);
const RADIUS: f32 = 0.5;
const LIGHT: Vec3 = Vec3::new(-2.5, 0.0, 3.0);
const WIDTH: u32 = 24;
const HEIGHT: u32 = 18;

fn scene(options: &str) -> String {
    format!(
        r#"Scene(
    options: ({options}),
    cameras: [(name: "cam", fov_y: 34, resolution: ({WIDTH}, {HEIGHT}),
        placement: LookAt(eye: (0.4, -0.6, 5), target: (0.4, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "h23.png")])],
    lights: [(name: "panel", kind: Rect(corner: (-3, 0.5, 3), edge_u: (1, 0, 0),
        edge_v: (0, -1, 0)), intensity: 10, samples: 4, visible: true)],
    materials: [
        (name: "floor", shader: Lambert(albedo: (0.7, 0.7, 0.7))),
        (name: "wall", shader: Lambert(albedo: (0.7, 0.3, 0.2))),
        (name: "glass", shader: Dielectric(ior: 1.5)),
    ],
    objects: [
        (name: "floor", mesh: Grid(size_x: 8, size_y: 8), material: "floor"),
        (name: "wall", mesh: Grid(size_x: 8, size_y: 3), material: "wall"),
        (name: "ball", mesh: Sphere(radius: {RADIUS}), material: "glass",
         approximation: Parametric(u: 32, v: 16)),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "wall_1", of: "wall",
         transform: [Rotate(axis: (1, 0, 0), degrees: 90), Translate((0, 1.3, 1.5))]),
        (name: "ball_1", of: "ball", transform: [Translate(({}, {}, {}))]),
    ],
    groups: [(name: "world", members: ["floor_1", "wall_1", "ball_1"])],
    render: (root: "world", camera: "cam"),
)"#,
        BALL.x, BALL.y, BALL.z
    )
}

/// Renders `scene(options)`; returns the beauty image and the camera.
fn render(options: &str) -> (Vec<Vec3>, Camera) {
    let text = scene(options);
    let mut scene = load_scene_str(&text, Path::new("h23.ron")).unwrap_or_else(|e| panic!("{e}"));
    let camera = scene
        .world
        .query::<&Camera>()
        .iter()
        .next()
        .expect("camera")
        .clone();
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    (frame.outputs.image.expect("image").beauty, camera)
}

/// Whether the segment from `p` toward `q` passes within `r` of the ball's centre.
fn blocked(p: Vec3, q: Vec3, r: f32) -> bool {
    let d = q - p;
    let t = ((BALL - p).dot(d) / d.length_squared()).clamp(0.0, 1.0);
    (p + d * t - BALL).length() < r
}

/// The pixels' masks `(caustic, shadowed, lit)`: pixels that see the floor (not through or
/// past the ball, away from the wall) by where they see it.
fn masks(camera: &Camera) -> [Vec<usize>; 3] {
    let rays = CameraRays::new(camera);
    // The caustic's centre: where the line from the light through the ball's centre meets
    // the floor.
    let d = BALL - LIGHT;
    let focus = BALL + d * (-BALL.z / d.z);
    let mut out: [Vec<usize>; 3] = Default::default();
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let ray = rays
                .ray(x as f32 + 0.5, y as f32 + 0.5, Vec2::splat(0.5))
                .expect("pinhole ray");
            let floor = ray.origin + ray.dir * (-ray.origin.z / ray.dir.z);
            if blocked(ray.origin, floor, 1.05 * RADIUS) || floor.y > 1.0 || floor.y < -1.6 {
                continue;
            }
            let i = (y * WIDTH + x) as usize;
            if (floor - focus).length() < 0.4 {
                out[0].push(i);
            } else if blocked(floor, LIGHT, 0.8 * RADIUS) {
                out[1].push(i);
            } else if !blocked(floor, LIGHT, 1.4 * RADIUS) {
                out[2].push(i);
            }
        }
    }
    out
}

/// Mean and standard error of a region's mean luminance over renders with different seeds.
fn region(images: &[Vec<Vec3>], mask: &[usize]) -> (f64, f64) {
    let means: Vec<f64> = images
        .iter()
        .map(|img| {
            let sum: f64 = mask
                .iter()
                .map(|&i| f64::from(img[i].dot(Vec3::new(0.2126, 0.7152, 0.0722))))
                .sum();
            sum / mask.len() as f64
        })
        .collect();
    let n = means.len() as f64;
    let mean = means.iter().sum::<f64>() / n;
    let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

#[test]
fn h23_photon_render_equals_the_path_tracer_on_every_region() {
    let seeds = 4;
    let path: Vec<Vec<Vec3>> = (0..seeds)
        .map(|s| {
            render(&format!(
                "samples: 96, seed: {s}, integrator: Path, max_depth: 8"
            ))
            .0
        })
        .collect();
    let mut camera = None;
    let hybrid: Vec<Vec<Vec3>> = (0..seeds)
        .map(|s| {
            let (img, cam) = render(&format!(
                "samples: 4, seed: {s}, max_depth: 8, refraction_depth: 8, \
                 caustics: (photons: 20000, gather: 40), \
                 global_illumination: (photons: 20000, gather: 40, final_gather: 8)"
            ));
            camera = Some(cam);
            img
        })
        .collect();
    let masks = masks(&camera.unwrap());
    for (name, mask) in ["caustic", "shadowed", "lit"].iter().zip(&masks) {
        assert!(mask.len() >= 8, "{name} mask has {} pixels", mask.len());
        let (p, sp) = region(&path, mask);
        let (h, sh) = region(&hybrid, mask);
        let sigma = (sp * sp + sh * sh).sqrt() / p;
        let ratio = h / p;
        println!(
            "{name:8} ({:3} px): path {p:.4} ± {sp:.4}, photons {h:.4} ± {sh:.4}, \
             ratio {ratio:.4} (allowed ±{:.4})",
            mask.len(),
            0.02 + 3.0 * sigma
        );
        assert!(
            (ratio - 1.0).abs() <= 0.02 + 3.0 * sigma,
            "{name}: photons/path = {ratio}"
        );
    }
}

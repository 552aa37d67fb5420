//! Analytic radiometry: rendered pixels against closed-form radiance.

use crate::common;

use glam::{Affine3A, DVec3, Vec3};
use stagelight::components::{LightShape, Shader};
use stagelight::settings::RenderSettings;

/// Radiance of a Lambert plane z = 0 under an isotropic point light: albedo/π · I · cosθ / d².
fn point_lit_plane(p: DVec3, light: DVec3, intensity: f64, albedo: f64) -> f64 {
    let d = light - p;
    let r2 = d.length_squared();
    let cos = d.z / r2.sqrt();
    albedo / std::f64::consts::PI * intensity * cos.max(0.0) / r2
}

#[test]
fn lambert_plane_under_point_light_matches_closed_form_per_pixel() {
    let mut world = hecs::World::new();
    let albedo: f64 = 0.7;
    let m = common::material(
        &mut world,
        Shader::Lambert {
            albedo: Vec3::splat(albedo as f32),
        },
    );
    common::instance(&mut world, common::square(4.0), Affine3A::IDENTITY, m);
    let eye = Vec3::new(0.0, 0.0, 5.0);
    let (w, h, fov) = (24u32, 24u32, 40.0f32);
    common::camera(&mut world, eye, Vec3::ZERO, fov, w, h);
    let light = DVec3::new(0.7, -0.4, 1.5);
    let intensity: f64 = 20.0;
    common::light(
        &mut world,
        LightShape::Point {
            position: light.as_vec3(),
        },
        Vec3::splat(intensity as f32),
        1,
    );
    let settings = RenderSettings {
        spp: 64,
        ..RenderSettings::default()
    };
    let frame = common::render(&mut world, settings);
    let fb = frame.outputs.image.as_ref().unwrap();

    // Reference: average of the closed form over the pixel footprint (box filter), 16×16 grid,
    // camera rays intersected with the plane in f64. The camera looks down −Z from `eye` with
    // +Y up, so film (x, y) maps to direction (sx, sy, −1).
    let t = (fov as f64 * 0.5).to_radians().tan();
    let mut worst = 0.0f64;
    for py in 0..h {
        for px in 0..w {
            let mut sum = 0.0;
            let n = 16;
            for j in 0..n {
                for i in 0..n {
                    let fx = px as f64 + (i as f64 + 0.5) / n as f64;
                    let fy = py as f64 + (j as f64 + 0.5) / n as f64;
                    let sx = (2.0 * fx / w as f64 - 1.0) * t;
                    let sy = (1.0 - 2.0 * fy / h as f64) * t;
                    // From z = 5 along (sx, sy, −1): hits z = 0 at parameter 5.
                    let p = DVec3::new(5.0 * sx, 5.0 * sy, 0.0);
                    sum += point_lit_plane(p, light, intensity, albedo);
                }
            }
            let expected = sum / (n * n) as f64;
            let got = fb.beauty[(py * w + px) as usize];
            for c in [got.x, got.y, got.z] {
                let rel = (c as f64 - expected).abs() / expected;
                worst = worst.max(rel);
            }
        }
    }
    assert!(worst < 0.01, "worst relative error {worst}");
}

/// Irradiance at a point from a Lambertian rectangle of radiance `l`, parallel to the
/// receiver at height `h`, with one corner straight above the point and sides `a`, `b`:
/// E = L · π · F with the classical point-to-parallel-rectangle form factor
/// F = 1/(2π) [X/√(1+X²) · atan(Y/√(1+X²)) + Y/√(1+Y²) · atan(X/√(1+Y²))], X = a/h, Y = b/h.
fn corner_rect_irradiance(l: f64, a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let f = (x / (1.0 + x * x).sqrt() * (y / (1.0 + x * x).sqrt()).atan()
        + y / (1.0 + y * y).sqrt() * (x / (1.0 + y * y).sqrt()).atan())
        / (2.0 * std::f64::consts::PI);
    l * std::f64::consts::PI * f
}

#[test]
fn rect_light_irradiance_matches_closed_form() {
    let mut world = hecs::World::new();
    let albedo: f64 = 0.5;
    let m = common::material(
        &mut world,
        Shader::Lambert {
            albedo: Vec3::splat(albedo as f32),
        },
    );
    common::instance(&mut world, common::square(10.0), Affine3A::IDENTITY, m);
    // A 2 × 1 light at height 1.5 centred over the origin, emitting downward
    // (edge_u × edge_v = −Z).
    let (a, b, height, radiance): (f64, f64, f64, f64) = (2.0, 1.0, 1.5, 3.0);
    common::light(
        &mut world,
        LightShape::Rect {
            corner: Vec3::new(-1.0, -0.5, height as f32),
            edge_u: Vec3::new(0.0, 1.0, 0.0),
            edge_v: Vec3::new(2.0, 0.0, 0.0),
        },
        Vec3::splat(radiance as f32),
        64,
    );
    // A camera from below the light's edge, seeing a tiny patch around the origin.
    common::camera(&mut world, Vec3::new(0.0, -3.0, 1.0), Vec3::ZERO, 0.5, 4, 4);
    let settings = RenderSettings {
        spp: 64,
        ..RenderSettings::default()
    };
    let frame = common::render(&mut world, settings);
    let fb = frame.outputs.image.as_ref().unwrap();
    // Four corner rectangles of (a/2) × (b/2) meet above the origin.
    let e = 4.0 * corner_rect_irradiance(radiance, a / 2.0, b / 2.0, height);
    let expected = albedo / std::f64::consts::PI * e;
    let mean: f64 = fb.beauty.iter().map(|c| c.x as f64).sum::<f64>() / fb.beauty.len() as f64;
    let rel = (mean - expected).abs() / expected;
    assert!(rel < 0.01, "mean {mean} expected {expected} (rel {rel})");
}

//! Hard cases of frames and tiny triangles (`../shared/HARDCASES.md`): H7 (tiny triangles and
//! long rays hit their target) and H10 (orthonormal bases near the poles).

use crate::common;

use glam::{DVec3, Quat, Vec3};
use stagelight::accel::{Accel, Ray};
use stagelight::settings::BvhQuality;
use stagelight::shading::frame::ShadingFrame;

/// pbrt's `Vector.CoordinateSystem` error: deviation from unit length and orthogonality.
fn frame_error(n: Vec3) -> f64 {
    let f = ShadingFrame::from_normal(n);
    let (a, b, c) = (f.s.as_dvec3(), f.t.as_dvec3(), n.as_dvec3());
    let unit = |v: DVec3| (v.length() - 1.0).powi(2);
    (unit(a) + unit(b) + unit(c) + a.dot(b).powi(2) + b.dot(c).powi(2) + c.dot(a).powi(2)) / 6.0
}

#[test]
#[allow(clippy::excessive_precision)] // Duff et al.'s vectors, digit for digit
fn h10_orthonormal_basis_near_the_poles() {
    let mut cases = vec![
        Vec3::new(0.000_385_273_16, 0.000_384_600_16, -0.999_999_88),
        Vec3::new(-0.000_198_135_81, -0.000_089_468_39, -0.999_999_88),
        Vec3::X,
        -Vec3::X,
        Vec3::Y,
        -Vec3::Y,
        Vec3::Z,
        -Vec3::Z,
    ];
    // z = −1 + k·ulp, and a million random directions.
    for k in 1..=64u32 {
        let z = f32::from_bits((-1.0f32).to_bits() - k);
        let r = (1.0 - z * z).max(0.0).sqrt();
        cases.push(Vec3::new(r * 0.6, r * 0.8, z));
    }
    let mut rng = common::Rng::new(10);
    for _ in 0..1_000_000 {
        let v = Vec3::new(
            rng.f64() as f32 - 0.5,
            rng.f64() as f32 - 0.5,
            rng.f64() as f32 - 0.5,
        );
        if let Some(n) = v.try_normalize() {
            cases.push(n);
        }
    }
    let worst = cases
        .iter()
        .map(|&n| frame_error(n.normalize()))
        .fold(0.0, f64::max);
    assert!(worst < 1e-10, "worst frame error {worst}");
    // Axis inputs give tangents with exact zeros where the input is non-zero.
    let f = ShadingFrame::from_normal(Vec3::Z);
    assert_eq!((f.s.z, f.t.z), (0.0, 0.0));
}

/// Embree's small-triangle pattern: a randomly rotated 100 × 100-cell plane of size 100,
/// rays from random origins in a cube of half-size R aimed at a random triangle's centroid
/// must hit that triangle (BVH and brute force agree on every ray).
///
/// Rays within 0.6° of the plane (sin θ < 1e-2) are counted but not gated: an f32 direction
/// carries a relative error of ~6e-8, i.e. 6e-4 across 1e4 units, which a grazing angle of
/// sin θ = 1e-4 stretches to 6 units along the plane — no f32 intersector can aim that well.
/// At R = 1e4 about 0.05 % of rays are that grazing and land on a neighbour.
#[test]
fn h07_tiny_triangles_and_long_rays_hit_their_target() {
    let mut rng = common::Rng::new(7);
    let rotation = Quat::from_axis_angle(
        Vec3::new(rng.f64() as f32, rng.f64() as f32, rng.f64() as f32).normalize(),
        rng.f64() as f32 * 6.0,
    );
    let n = 100;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let p =
                |x: usize, y: usize| rotation * Vec3::new(x as f32 - 50.0, y as f32 - 50.0, 0.0);
            tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    let accel = Accel::build(tris.clone(), BvhQuality::Medium);
    for r in [1e1f64, 1e2, 1e3, 1e4] {
        let (mut failures, mut grazing_misses) = (0, 0);
        for _ in 0..20_000 {
            let target = (rng.f64() * tris.len() as f64) as usize % tris.len();
            let t = tris[target];
            let centroid = (t[0].as_dvec3() + t[1].as_dvec3() + t[2].as_dvec3()) / 3.0;
            // The origin is an f32 point; the direction is aimed from it (as Embree's test).
            let origin = (DVec3::new(
                rng.f64() * 2.0 - 1.0,
                rng.f64() * 2.0 - 1.0,
                rng.f64() * 2.0 - 1.0,
            ) * r)
                .as_vec3()
                .as_dvec3();
            let dir = centroid - origin;
            let ray = Ray {
                origin: origin.as_vec3(),
                dir: dir.as_vec3(),
                t_max: f32::INFINITY,
            };
            match accel.intersect(&ray) {
                Some(hit) if hit.prim as usize == target => {}
                other => {
                    let normal = (rotation * Vec3::Z).as_dvec3();
                    if dir.normalize().dot(normal).abs() < 1e-2 {
                        grazing_misses += 1;
                        assert_eq!(
                            other.map(|h| h.prim),
                            stagelight::accel::brute_force_intersect(&tris, &ray).map(|h| h.prim)
                        );
                        continue;
                    }
                    failures += 1;
                    if std::env::var("H7_DEBUG").is_ok() {
                        let normal = (rotation * Vec3::Z).as_dvec3();
                        eprintln!(
                            "R {r}: target {target} got {:?} brute {:?} sin {:.2e}",
                            other.map(|h| h.prim),
                            stagelight::accel::brute_force_intersect(&tris, &ray).map(|h| h.prim),
                            (dir.normalize().dot(normal)).abs()
                        );
                    }
                }
            }
        }
        assert_eq!(
            failures, 0,
            "R = {r}: {failures} rays missed their target triangle"
        );
        assert!(
            grazing_misses <= 20,
            "R = {r}: {grazing_misses} grazing misses"
        );
    }
}

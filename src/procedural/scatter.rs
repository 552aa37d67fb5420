//! Scatter/instancer: seeded, area-uniform placements of a prototype over a mesh.
//!
//! Copy `i` depends only on (`seed`, `i`): its triangle is chosen from the area CDF with one
//! hashed number, its point with two, its rotation and scale with one each. So counts can
//! grow without moving the copies already placed.

use glam::{Affine3A, Quat, Vec3};

use crate::components::{Scatter, TriMesh};
use crate::tessellation::{finite, positive, GeometryError};

/// Largest number of copies.
pub const MAX_COUNT: u32 = 10_000_000;

/// A uniform number in [0, 1) from (seed, index, dimension).
pub fn hash01(seed: u64, index: u64, dim: u64) -> f64 {
    let mut x =
        seed ^ index.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ dim.wrapping_mul(0xc2b2_ae3d_27d4_eb4f);
    for _ in 0..2 {
        x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        x ^= x >> 31;
    }
    (x >> 11) as f64 / (1u64 << 53) as f64
}

/// Placements (prototype space → scatter object space) of every copy.
pub fn placements(s: &Scatter, surface: &TriMesh) -> Result<Vec<Affine3A>, GeometryError> {
    let smin = positive("scale_min", s.scale_min)?;
    let smax = positive("scale_max", s.scale_max)?;
    if smax < smin {
        return Err(GeometryError::OutOfRange {
            parameter: "scale_max",
            value: smax,
            expected: "≥ scale_min",
        });
    }
    let jitter = finite("rotation_jitter", s.rotation_jitter)?
        .abs()
        .min(180.0)
        .to_radians();
    let mut cdf = Vec::with_capacity(surface.triangles.len());
    let mut total = 0.0f64;
    for (i, t) in surface.triangles.iter().enumerate() {
        if t.iter().any(|&k| k as usize >= surface.positions.len()) {
            return Err(GeometryError::BadCount {
                message: format!("scatter surface: triangle {i} has an index out of range"),
            });
        }
        let [a, b, c] = surface.triangle(i).map(|p| p.as_dvec3());
        let area = 0.5 * (b - a).cross(c - a).length();
        total += if area.is_finite() { area } else { 0.0 };
        cdf.push(total);
    }
    if total.is_nan() || total <= 0.0 {
        return Err(GeometryError::MissingData {
            message: "scatter surface has no area to place copies on".into(),
        });
    }
    let count = s.count.min(MAX_COUNT) as u64;
    Ok((0..count)
        .map(|i| {
            let r = |dim| hash01(s.seed, i, dim);
            let target = r(0) * total;
            let t = cdf.partition_point(|&c| c <= target).min(cdf.len() - 1);
            let [a, b, c] = surface.triangle(t);
            let (r1, r2) = (r(1).sqrt() as f32, r(2) as f32);
            let (w0, w1, w2) = (1.0 - r1, r1 * (1.0 - r2), r1 * r2);
            let p = a * w0 + b * w1 + c * w2;
            let ng = (b - a).cross(c - a).normalize_or_zero();
            let n = match &surface.normals {
                Some(ns) => {
                    let [i0, i1, i2] = surface.triangles[t].map(|k| k as usize);
                    (ns[i0] * w0 + ns[i1] * w1 + ns[i2] * w2)
                        .try_normalize()
                        .unwrap_or(ng)
                }
                None => ng,
            };
            let angle = (jitter * (2.0 * r(3) - 1.0)) as f32;
            let scale = (smin + (smax - smin) * r(4)) as f32;
            let align = if s.align_to_normal && n != Vec3::ZERO {
                Quat::from_rotation_arc(Vec3::Z, n)
            } else {
                Quat::IDENTITY
            };
            Affine3A::from_scale_rotation_translation(
                Vec3::splat(scale),
                align * Quat::from_rotation_z(angle),
                p,
            )
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::components::Grid;
    use hecs::Entity;

    #[test]
    fn placements_are_seeded_on_the_surface_and_aligned() {
        let mesh = super::super::stairs::grid(&Grid {
            size_x: 2.0,
            size_y: 2.0,
            nx: 3,
            ny: 3,
        })
        .unwrap();
        let s = Scatter {
            prototype: Entity::DANGLING,
            surface: Entity::DANGLING,
            count: 500,
            seed: 9,
            scale_min: 0.5,
            scale_max: 1.5,
            rotation_jitter: 180.0,
            align_to_normal: true,
        };
        let a = placements(&s, &mesh).unwrap();
        assert_eq!(a, placements(&s, &mesh).unwrap());
        assert_eq!(a.len(), 500);
        let mean: Vec3 = a.iter().map(|x| Vec3::from(x.translation)).sum::<Vec3>() / 500.0;
        assert!(mean.length() < 0.15, "{mean:?}");
        for x in &a {
            let t = Vec3::from(x.translation);
            assert!(t.x.abs() <= 1.0 && t.y.abs() <= 1.0 && t.z == 0.0);
            let up = x.transform_vector3(Vec3::Z);
            assert!(up.normalize().z > 0.9999 && (0.5..=1.5).contains(&up.length()));
        }
        let more = placements(&Scatter { count: 600, ..s }, &mesh).unwrap();
        assert_eq!(&more[..500], &a[..]);
    }
}

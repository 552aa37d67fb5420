//! Ambient occlusion and the inside-geometry probe: cosine-weighted rays about the shading
//! normal from a robustly offset origin.

use glam::Vec3;

use crate::accel::{spawn_ray, SurfacePoint};
use crate::geometry::SceneGeometry;
use crate::sampling::{sample_cosine_hemisphere, Sampler};

/// Two tangents completing an orthonormal basis with `n` as its third axis (the shading
/// library's frame: Duff et al. 2017).
pub fn basis(n: Vec3) -> (Vec3, Vec3) {
    let frame = crate::shading::frame::ShadingFrame::from_normal(n);
    (frame.s, frame.t)
}

/// The result of a batch of hemisphere rays from one point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct HemisphereRays {
    /// Rays traced.
    pub rays: u32,
    /// Rays that escaped (no hit within the distance).
    pub open: u32,
    /// Sum of the escaped directions (for bent normals).
    pub open_dir_sum: Vec3,
    /// Rays whose first hit was the back of a one-sided surface.
    pub backface_hits: u32,
}

/// Traces `count` cosine-weighted rays about `normal` (which faces the side being baked)
/// from `surface`, each drawn from `Sampler::new(seed, first + k)`. Directions below the
/// geometric surface (possible with interpolated normals) count as occluded. Hits farther
/// than `max_distance` do not occlude. With `probe`, rays run to infinity so that
/// `backface_hits` also serves as the inside-geometry test.
#[allow(clippy::too_many_arguments)] // one batch of rays, fully described; two callers
pub fn trace_hemisphere(
    geometry: &SceneGeometry,
    surface: &SurfacePoint,
    normal: Vec3,
    ng_facing: Vec3,
    max_distance: f32,
    seed: u32,
    first: u32,
    count: u32,
    probe: bool,
) -> HemisphereRays {
    let (t, b) = basis(normal);
    let mut out = HemisphereRays::default();
    for k in 0..count {
        let mut sampler = Sampler::new(seed, first + k);
        let local = sample_cosine_hemisphere(sampler.next_2d());
        let dir = t * local.x + b * local.y + normal * local.z;
        out.rays += 1;
        if dir.dot(ng_facing) <= 0.0 {
            continue;
        }
        let mut ray = spawn_ray(surface, dir);
        // As an inside-geometry probe the ray looks for the first surface at any distance;
        // occlusion still counts only hits within `max_distance`.
        ray.t_max = if probe { f32::INFINITY } else { max_distance };
        let hit = geometry.accel.intersect(&ray);
        if let Some(hit) = hit {
            let tri = geometry.accel.triangle(hit.prim);
            let ng = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
            if ng.dot(dir) > 0.0 && !geometry.material_of(hit.prim).two_sided {
                out.backface_hits += 1;
            }
        }
        if hit.is_none_or(|h| h.t >= max_distance) {
            out.open += 1;
            out.open_dir_sum += dir;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.4, 0.866).normalize(),
        ] {
            let (t, b) = basis(n);
            assert!(t.dot(b).abs() < 1e-6 && t.dot(n).abs() < 1e-6 && b.dot(n).abs() < 1e-6);
            assert!((t.length() - 1.0).abs() < 1e-6 && (b.length() - 1.0).abs() < 1e-6);
            assert!((t.cross(b) - n).length() < 1e-5);
        }
    }
}

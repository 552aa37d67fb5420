//! Ambient occlusion and the inside-geometry probe: cosine-weighted rays about the shading
//! normal from a robustly offset origin, generated as one stream per texel (traced one query
//! per ray, or through the batch kernel with `STAGELIGHT_RAY_STREAMS=on`).

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

/// Whether a texel's hemisphere rays go through the batch kernel (`STAGELIGHT_RAY_STREAMS=on`
/// at the first bake) or one query per ray (the default). Same results. One query per ray is
/// the default because it measured faster on `bake_ao.ron` (a texel's rays share their origin,
/// so consecutive single-ray traversals find the upper nodes in cache, and the batch lanes'
/// bookkeeping costs more than the latency they hide: issue 17 note, session 7).
fn streams() -> bool {
    static CHOICE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *CHOICE.get_or_init(|| std::env::var("STAGELIGHT_RAY_STREAMS").as_deref() == Ok("on"))
}

/// One sample position's share of a batch of hemisphere rays (see [`trace_hemispheres`]).
#[derive(Debug, Clone, Copy)]
pub struct HemisphereJob<'a> {
    /// The point the rays leave from.
    pub surface: &'a SurfacePoint,
    /// The shading normal, facing the side being baked.
    pub normal: Vec3,
    /// The geometric normal, on the same side.
    pub ng_facing: Vec3,
    /// Sample index of the first ray (`Sampler::new(seed, first + k)` draws ray `k`).
    pub first: u32,
    /// Rays to trace.
    pub count: u32,
}

/// Traces `count` cosine-weighted rays about `normal` (which faces the side being baked)
/// from `surface`, each drawn from `Sampler::new(seed, first + k)`: [`trace_hemispheres`] for
/// one point.
#[allow(clippy::too_many_arguments)] // one batch of rays, fully described
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
    let job = HemisphereJob {
        surface,
        normal,
        ng_facing,
        first,
        count,
    };
    trace_hemispheres(geometry, &[job], max_distance, seed, probe)[0]
}

/// The hemisphere rays of several points, generated first and then traced as one stream:
/// one query per ray, or with `STAGELIGHT_RAY_STREAMS=on` through the batch kernel
/// ([`crate::accel::Accel::intersect_batch`]: rays interleaved so that their memory misses
/// overlap). Per point: `count` cosine-weighted rays about `normal`, ray `k` drawn from
/// `Sampler::new(seed, first + k)`. Directions below the geometric surface (possible with
/// interpolated normals) count as occluded and are not traced. Hits farther than
/// `max_distance` do not occlude. With `probe`, rays run to infinity so that `backface_hits`
/// also serves as the inside-geometry test. The results are those of one query per ray, bit
/// for bit: each ray's hit is the same, and each point's sums are added in ray order.
pub fn trace_hemispheres(
    geometry: &SceneGeometry,
    jobs: &[HemisphereJob<'_>],
    max_distance: f32,
    seed: u32,
    probe: bool,
) -> Vec<HemisphereRays> {
    let mut out = vec![HemisphereRays::default(); jobs.len()];
    let total: usize = jobs.iter().map(|j| j.count as usize).sum();
    let mut rays = Vec::with_capacity(total);
    // The point and direction of each traced ray.
    let mut owners = Vec::with_capacity(total);
    for (p, job) in jobs.iter().enumerate() {
        let (t, b) = basis(job.normal);
        for k in 0..job.count {
            let mut sampler = Sampler::new(seed, job.first + k);
            let local = sample_cosine_hemisphere(sampler.next_2d());
            let dir = t * local.x + b * local.y + job.normal * local.z;
            out[p].rays += 1;
            if dir.dot(job.ng_facing) <= 0.0 {
                continue;
            }
            let mut ray = spawn_ray(job.surface, dir);
            // As an inside-geometry probe the ray looks for the first surface at any
            // distance; occlusion still counts only hits within `max_distance`.
            ray.t_max = if probe { f32::INFINITY } else { max_distance };
            rays.push(ray);
            owners.push((p, dir));
        }
    }
    let mut hits = vec![None; rays.len()];
    if streams() {
        geometry.accel.intersect_batch(&rays, &mut hits);
    } else {
        for (ray, hit) in rays.iter().zip(hits.iter_mut()) {
            *hit = geometry.accel.intersect(ray);
        }
    }
    for (&(p, dir), hit) in owners.iter().zip(hits) {
        let out = &mut out[p];
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

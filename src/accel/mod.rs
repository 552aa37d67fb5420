//! Ray layer: watertight triangle intersection, robust ray spawning and the BVH over the
//! scene's world-space triangles (a thin layer over `obvhs`).
//!
//! STUB: replaced by the real implementation (helper A). The API below is the contract.

use glam::Vec3;

use crate::settings::BvhQuality;

/// A ray segment `origin + t·dir`, `t ∈ (0, t_max)`. `dir` need not be unit length; `t` is in
/// units of `dir`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Origin.
    pub origin: Vec3,
    /// Direction (not necessarily normalised).
    pub dir: Vec3,
    /// Far end of the segment.
    pub t_max: f32,
}

/// A ray/triangle hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Parametric distance along the ray.
    pub t: f32,
    /// Index of the triangle in the order given to [`Accel::build`].
    pub prim: u32,
    /// Barycentric weight of vertex 1.
    pub b1: f32,
    /// Barycentric weight of vertex 2 (vertex 0 has `1 − b1 − b2`).
    pub b2: f32,
}

/// A point on a surface with its floating-point error bound, from which rays are spawned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Position computed from barycentrics.
    pub p: Vec3,
    /// Conservative per-axis absolute error bound of `p`.
    pub p_err: Vec3,
    /// Unit geometric normal, `(v1 − v0) × (v2 − v0)` normalised.
    pub ng: Vec3,
}

/// BVH over world-space triangles.
pub struct Accel {
    triangles: Vec<[Vec3; 3]>,
}

impl Accel {
    /// Builds the hierarchy. Degenerate triangles are kept in the index space but never hit.
    pub fn build(triangles: Vec<[Vec3; 3]>, _quality: BvhQuality) -> Self {
        Self { triangles }
    }
    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }
    /// True when there are no triangles.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }
    /// Vertices of triangle `prim`.
    pub fn triangle(&self, prim: u32) -> [Vec3; 3] {
        self.triangles[prim as usize]
    }
    /// Closest hit along the ray.
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        brute_force_intersect(&self.triangles, ray)
    }
    /// Whether anything is hit along the ray segment.
    pub fn occluded(&self, ray: &Ray) -> bool {
        self.intersect(ray).is_some()
    }
    /// Surface point of a hit with error bounds.
    pub fn surface_point(&self, hit: &Hit) -> SurfacePoint {
        let [a, b, c] = self.triangle(hit.prim);
        let b0 = 1.0 - hit.b1 - hit.b2;
        SurfacePoint {
            p: a * b0 + b * hit.b1 + c * hit.b2,
            p_err: Vec3::splat(1e-4),
            ng: (b - a).cross(c - a).normalize_or_zero(),
        }
    }
}

/// A ray leaving `from` in direction `dir`, offset so it cannot re-hit the surface.
pub fn spawn_ray(from: &SurfacePoint, dir: Vec3) -> Ray {
    let o = from.p + from.ng * 1e-3 * from.ng.dot(dir).signum();
    Ray {
        origin: o,
        dir,
        t_max: f32::INFINITY,
    }
}

/// A ray from `from` toward the point `target` (a light), ending just before it.
pub fn spawn_ray_to(from: &SurfacePoint, target: Vec3) -> Ray {
    let mut r = spawn_ray(from, target - from.p);
    r.dir = target - r.origin;
    r.t_max = 1.0 - 1e-4;
    r
}

/// Closest hit by testing every triangle (reference for tests).
pub fn brute_force_intersect(triangles: &[[Vec3; 3]], ray: &Ray) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (i, tri) in triangles.iter().enumerate() {
        let e1 = tri[1] - tri[0];
        let e2 = tri[2] - tri[0];
        let pv = ray.dir.cross(e2);
        let det = e1.dot(pv);
        if det.abs() < 1e-12 {
            continue;
        }
        let tv = ray.origin - tri[0];
        let u = tv.dot(pv) / det;
        let qv = tv.cross(e1);
        let v = ray.dir.dot(qv) / det;
        let t = e2.dot(qv) / det;
        if u < 0.0 || v < 0.0 || u + v > 1.0 || t <= 0.0 || t >= ray.t_max {
            continue;
        }
        if best.is_none_or(|h| t < h.t) {
            best = Some(Hit {
                t,
                prim: i as u32,
                b1: u,
                b2: v,
            });
        }
    }
    best
}

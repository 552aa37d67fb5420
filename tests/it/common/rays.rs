//! Shared helpers of the ray-layer tests: a fixed-seed RNG, scene builders (closed UV
//! spheres, height fields, soups), instance transforms and comparison helpers.

use glam::{Affine3A, DVec3, Quat, Vec3};
use rayon::prelude::*;
use stagelight::accel::{brute_force_intersect, Accel, Hit, Ray};
use stagelight::settings::BvhQuality;

/// SplitMix64: tiny, deterministic, good enough for test inputs.
pub struct Rng(u64);

impl Rng {
    /// A generator with a fixed seed.
    pub fn new(seed: u64) -> Self {
        Self(seed ^ 0x9E37_79B9_7F4A_7C15)
    }
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.f64()
    }
    /// Uniform in [0, n).
    pub fn below(&mut self, n: usize) -> usize {
        (self.f64() * n as f64) as usize % n
    }
    /// Uniform direction on the unit sphere (f64).
    pub fn sphere(&mut self) -> DVec3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }
    /// Uniform point in the ball of radius `r` (f64).
    pub fn ball(&mut self, r: f64) -> DVec3 {
        self.sphere() * r * self.f64().cbrt()
    }
    /// A random rotation.
    pub fn rotation(&mut self) -> Quat {
        let axis = self.sphere().as_vec3();
        Quat::from_axis_angle(axis, self.range(0.0, std::f64::consts::TAU) as f32)
    }
}

/// A closed UV sphere (shared poles and seam by index) with `nu` segments around and `nv`
/// along, centred at `centre` (added in f64, then rounded), radius `radius` scaled per vertex
/// by `1 + jitter·U(−1, 1)`. Returns vertices and index triples.
pub fn uv_sphere(
    nu: usize,
    nv: usize,
    centre: DVec3,
    radius: f64,
    jitter: f64,
    rng: &mut Rng,
) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut verts = Vec::new();
    let r = |rng: &mut Rng| radius * (1.0 + jitter * rng.range(-1.0, 1.0));
    for j in 1..nv {
        let theta = j as f64 / nv as f64 * std::f64::consts::PI;
        for i in 0..nu {
            let phi = i as f64 / nu as f64 * std::f64::consts::TAU;
            let d = DVec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            verts.push((centre + d * r(rng)).as_vec3());
        }
    }
    let top = verts.len() as u32;
    verts.push((centre + DVec3::Y * r(rng)).as_vec3());
    let bottom = verts.len() as u32;
    verts.push((centre - DVec3::Y * r(rng)).as_vec3());
    let vid = |j: usize, i: usize| (j * nu + i % nu) as u32;
    let mut idx = Vec::new();
    for i in 0..nu {
        idx.push([top, vid(0, i + 1), vid(0, i)]);
        idx.push([bottom, vid(nv - 2, i), vid(nv - 2, i + 1)]);
    }
    for j in 0..nv - 2 {
        for i in 0..nu {
            let (a, b, c, d) = (vid(j, i), vid(j, i + 1), vid(j + 1, i), vid(j + 1, i + 1));
            idx.push([a, b, d]);
            idx.push([a, d, c]);
        }
    }
    (verts, idx)
}

/// Triangles of an indexed mesh.
pub fn triangles(verts: &[Vec3], idx: &[[u32; 3]]) -> Vec<[Vec3; 3]> {
    idx.iter().map(|t| t.map(|i| verts[i as usize])).collect()
}

/// A height field of `n × n` cells over `[0, n·step]²` in x/z, translated by `offset`; heights
/// are multiples of `step` so every vertex coordinate lies on the `step` grid.
pub fn height_field(n: usize, step: f32, offset: Vec3) -> Vec<[Vec3; 3]> {
    let h = |i: usize, j: usize| {
        let v = ((i as f32 * 0.37).sin() * 3.0 + (j as f32 * 0.23).cos() * 2.0).round();
        v * step
    };
    let p = |i: usize, j: usize| Vec3::new(i as f32 * step, h(i, j), j as f32 * step) + offset;
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    tris
}

/// `n` random triangles with vertices in `centre ± size·U[−1,1]³`, each of extent `tri_size`.
pub fn soup(n: usize, centre: Vec3, size: f32, tri_size: f32, rng: &mut Rng) -> Vec<[Vec3; 3]> {
    (0..n)
        .map(|_| {
            let c = centre + rng.ball(f64::from(size)).as_vec3();
            let e = |rng: &mut Rng| c + rng.ball(f64::from(tri_size)).as_vec3();
            [e(rng), e(rng), e(rng)]
        })
        .collect()
}

/// Applies an instance transform in f32, as the scene flattening does.
pub fn transform(tris: &[[Vec3; 3]], m: &Affine3A) -> Vec<[Vec3; 3]> {
    tris.iter()
        .map(|t| t.map(|v| m.transform_point3(v)))
        .collect()
}

/// Compares BVHs of every quality with brute force on every ray; returns the number of
/// mismatches (closest hit must be identical — t bitwise, primitive, barycentrics — and
/// occlusion must agree). The brute-force reference is computed once per ray.
pub fn mismatches_all_qualities(tris: &[[Vec3; 3]], rays: &[Ray]) -> usize {
    let accels: Vec<Accel> = [BvhQuality::Fast, BvhQuality::Medium, BvhQuality::High]
        .map(|q| Accel::build(tris.to_vec(), q))
        .into();
    mismatches_many(&accels, tris, rays)
}

/// Like [`mismatches_all_qualities`] for one prebuilt hierarchy.
pub fn mismatches(accel: &Accel, tris: &[[Vec3; 3]], rays: &[Ray]) -> usize {
    mismatches_many(std::slice::from_ref(accel), tris, rays)
}

/// Single-ray and batch queries of every accel against brute force.
fn mismatches_many(accels: &[Accel], tris: &[[Vec3; 3]], rays: &[Ray]) -> usize {
    let batches: Vec<(Vec<Option<Hit>>, Vec<bool>)> = accels
        .iter()
        .map(|accel| {
            let mut hits = vec![None; rays.len()];
            let mut occluded = vec![false; rays.len()];
            accel.intersect_batch(rays, &mut hits);
            accel.occluded_batch(rays, &mut occluded);
            (hits, occluded)
        })
        .collect();
    // Brute force (the bulk of the work) runs in parallel over the rays; the mismatches come
    // back in ray order, so the first five printed are the same as a serial loop's.
    let bad: Vec<(usize, Ray, Option<Hit>, Option<Hit>)> = rays
        .par_iter()
        .enumerate()
        .flat_map_iter(|(i, r)| {
            let b = brute_force_intersect(tris, r);
            let batches = &batches;
            accels.iter().enumerate().filter_map(move |(k, accel)| {
                let a = accel.intersect(r);
                let (batch_hits, batch_occluded) = &batches[k];
                (a != b
                    || accel.occluded(r) != b.is_some()
                    || batch_hits[i] != b
                    || batch_occluded[i] != b.is_some())
                .then_some((k, *r, a, b))
            })
        })
        .collect();
    for (k, r, a, b) in bad.iter().take(5) {
        eprintln!("mismatch (accel {k}): ray {r:?}\n  bvh   {a:?}\n  brute {b:?}");
    }
    bad.len()
}

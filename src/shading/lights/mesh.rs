//! Emitting meshes as one light: every triangle of an emitting material, chosen with
//! probability ∝ area × emitted radiance (the material's constant `emission`), then a
//! uniform point on it, whose radiance is the emission times its texture there.
//!
//! What a sample needs of its triangle (vertices, unit normal, area over choice probability,
//! emission) is kept per triangle when the light is made ([`EmittingTriangle`]), so sampling
//! touches neither the scene's materials nor the BVH's triangle copy (except to evaluate an
//! emission texture); the values are computed with the same operations as before, so samples
//! are the same bit for bit.

use glam::{Vec2, Vec3};

use super::{solid_angle_sample, LightSample};
use crate::accel::{geometric_normal, surface_point_with_normal, Hit};
use crate::geometry::SceneGeometry;
use crate::shading::texture::hit::emission_at;

/// One emitting triangle as the light sampler uses it.
#[derive(Debug, Clone, Copy)]
pub struct EmittingTriangle {
    /// World-space vertices.
    pub tri: [Vec3; 3],
    /// Unit geometric normal ([`geometric_normal`]).
    pub ng: Vec3,
    /// Area over the probability of choosing this triangle: the inverse area pdf.
    pub inv_pdf_area: f32,
    /// Emitted radiance.
    pub emission: Vec3,
    /// Whether both faces emit.
    pub two_sided: bool,
    /// Whether the material has an emission texture (evaluated at the sampled point).
    pub textured: bool,
}

/// All triangles of emitting materials, sampled by area × emitted radiance.
#[derive(Debug, Clone)]
pub struct MeshLight {
    /// World triangle ids.
    pub prims: Vec<u32>,
    /// Normalised CDF over `prims` (length `prims.len() + 1`).
    pub cdf: Vec<f32>,
    /// Sum of the sampling weights.
    pub total_weight: f32,
    /// Samples per shading point.
    pub samples: u32,
    /// What sampling needs of each triangle of `prims` (same order).
    pub triangles: Vec<EmittingTriangle>,
}

impl MeshLight {
    /// The light of every emitting triangle of `g`; `None` when nothing emits.
    pub fn new(g: &SceneGeometry, samples: u32) -> Option<Self> {
        let mut prims = Vec::new();
        let mut weights = Vec::new();
        for inst in &g.instances {
            for local in 0..inst.mesh.triangles.len() {
                let m = &g.materials[inst.material_of_local(local) as usize];
                if !m.is_emissive() {
                    continue;
                }
                let lum = m.emission.max_element();
                let prim = inst.first_triangle + local as u32;
                let t = g.accel.triangle(prim);
                let area = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
                if area > 0.0 && area.is_finite() {
                    prims.push(prim);
                    weights.push(area as f64 * lum as f64);
                }
            }
        }
        let total: f64 = weights.iter().sum();
        if prims.is_empty() || total.is_nan() || total <= 0.0 {
            return None;
        }
        let mut cdf = Vec::with_capacity(prims.len() + 1);
        let mut acc = 0.0f64;
        cdf.push(0.0f32);
        for w in &weights {
            acc += w;
            cdf.push((acc / total) as f32);
        }
        *cdf.last_mut().expect("non-empty") = 1.0;
        let total_weight = total as f32;
        let triangles = prims
            .iter()
            .map(|&prim| {
                let material = g.material_of(prim);
                let tri = g.accel.triangle(prim);
                let tri_area = 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]).length();
                let weight = tri_area * material.emission.max_element();
                let prob = weight / total_weight;
                EmittingTriangle {
                    tri,
                    ng: geometric_normal(&tri),
                    inv_pdf_area: tri_area / prob,
                    emission: material.emission,
                    two_sided: material.two_sided,
                    textured: material
                        .graph
                        .as_deref()
                        .is_some_and(|g| g.emission.is_some()),
                }
            })
            .collect();
        Some(Self {
            prims,
            cdf,
            total_weight,
            samples: samples.max(1),
            triangles,
        })
    }

    /// A point on an emitting triangle seen from `p` (`geometry`: the scene the light was
    /// made of, read only for emission textures).
    #[inline(always)]
    pub fn sample(&self, p: Vec3, u: Vec2, geometry: &SceneGeometry) -> Option<LightSample> {
        let cdf = &self.cdf;
        let k = cdf
            .partition_point(|&c| c <= u.x)
            .clamp(1, self.prims.len())
            - 1;
        let (c0, c1) = (cdf[k], cdf[k + 1]);
        let ux = if c1 > c0 {
            ((u.x - c0) / (c1 - c0)).clamp(0.0, 1.0 - f32::EPSILON)
        } else {
            0.5
        };
        let e = &self.triangles[k];
        let (b1, b2) = crate::sampling::sample_triangle(Vec2::new(ux, u.y));
        let sp = surface_point_with_normal(&e.tri, b1, b2, e.ng);
        // pdf in area measure is prob / tri_area.
        let mut s = solid_angle_sample(p, sp, e.two_sided, e.inv_pdf_area)?;
        // Chosen by the constant emission; a texture scales what the chosen point sends.
        s.contribution *= if e.textured {
            let hit = Hit {
                t: 0.0,
                prim: self.prims[k],
                b1,
                b2,
            };
            emission_at(geometry, &hit, geometry.material_of(hit.prim))
        } else {
            e.emission
        };
        Some(s)
    }

    /// Solid-angle pdf with which this light samples the point `q` (geometric normal `ng`,
    /// emitted radiance `emission`, `two_sided` emission) from `p`; 0 when `q` faces away.
    pub fn pdf(&self, p: Vec3, q: Vec3, ng: Vec3, emission: Vec3, two_sided: bool) -> f32 {
        let d = q - p;
        let dist2 = d.length_squared();
        let mut cos_l = ng.dot(-d) / dist2.sqrt();
        if two_sided {
            cos_l = cos_l.abs();
        }
        if cos_l.is_nan() || cos_l <= 0.0 || self.total_weight <= 0.0 {
            return 0.0;
        }
        let pdf = emission.max_element() / self.total_weight * dist2 / cos_l;
        if pdf.is_finite() {
            pdf
        } else {
            0.0
        }
    }
}

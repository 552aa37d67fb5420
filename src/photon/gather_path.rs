//! Where a final-gather ray lands: the first surface with a non-delta lobe along it, after
//! any chain of purely specular surfaces (mirrors, glass) it meets on the way — the `S*` of
//! `L … D S* D E` paths. At each purely specular surface one delta branch is sampled (glass:
//! reflection or refraction by Fresnel), its weight carried in the throughput.

use glam::Vec3;

use crate::accel::Ray;
use crate::sampling::Sampler;
use crate::shading::bsdf::{Bsdf, Scatter};
use crate::shading::integrator::{ShadeContext, Vertex};

/// Most purely specular surfaces a final-gather ray passes before it gives up (a glass ball
/// needs 2; total internal reflection a few more).
pub const MAX_SPECULAR_BOUNCES: u32 = 8;

/// A final-gather ray's landing point.
pub struct Landing<'a> {
    /// The surface it lands on (some lobe is not a delta).
    pub vertex: Vertex<'a>,
    /// Its BSDF.
    pub bsdf: Bsdf,
    /// Weight of the specular chain before it, segment transmittances included.
    pub throughput: Vec3,
}

/// Follows `ray` through purely specular surfaces (delta branches sampled from `sampler`) to
/// the first surface that has a non-delta lobe; `None` when it leaves the scene, meets an
/// invisible face or a surface without a BSDF, or exceeds [`MAX_SPECULAR_BOUNCES`].
pub fn land<'a>(ctx: &ShadeContext<'a>, ray: Ray, sampler: &mut Sampler) -> Option<Landing<'a>> {
    let mut ray = ray;
    let mut throughput = Vec3::ONE;
    for _ in 0..=MAX_SPECULAR_BOUNCES {
        let hit = ctx
            .geometry
            .accel
            .intersect_as(&ray, crate::accel::RayKind::Secondary)?;
        let vertex = Vertex::new(ctx, &ray, &hit);
        if !vertex.visible {
            return None;
        }
        let bsdf = vertex.bsdf()?;
        throughput *= vertex.transmittance;
        if bsdf.has_non_delta() {
            return Some(Landing {
                vertex,
                bsdf,
                throughput,
            });
        }
        let u = Vec3::new(sampler.next_1d(), sampler.next_1d(), sampler.next_1d());
        let s = bsdf.sample(vertex.wo, u)?;
        throughput *= s.weight();
        if !throughput.is_finite() || throughput.max_element() <= 0.0 {
            return None;
        }
        ray = vertex.spawn(s.wi, s.scatter == Scatter::Transmission)?;
    }
    None
}

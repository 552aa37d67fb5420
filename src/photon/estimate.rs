//! Radiance from the photon maps at a diffuse shading point of the `Direct` integrator:
//! caustics by direct visualisation of the caustic map, indirect diffuse by one final-gather
//! bounce into the global map (see the module doc of [`crate::photon`] for the partition).

use glam::Vec3;

use super::{GatherMap, Neighbour, PhotonMaps};
use crate::sampling::Sampler;
use crate::shading::bsdf::Bsdf;
use crate::shading::integrator::{PhotonRadiance, ShadeContext, Vertex};

impl PhotonRadiance for PhotonMaps {
    /// Caustic plus indirect diffuse radiance toward the viewer at `v` (zero without maps).
    /// Draws from `sampler` only when a global map exists.
    fn radiance(
        &self,
        ctx: &ShadeContext<'_>,
        v: &Vertex<'_>,
        bsdf: &Bsdf,
        sampler: &mut Sampler,
    ) -> Vec3 {
        let mut scratch = Vec::new();
        let mut radiance = Vec3::ZERO;
        if let Some(c) = &self.caustics {
            radiance += reflected(c, v, bsdf, &mut scratch);
        }
        if let Some(g) = &self.global {
            radiance += final_gather(ctx, g, v, bsdf, sampler, &mut scratch);
        }
        radiance
    }
}

/// Density estimate of the light `map` reflects at `v` through `bsdf`.
pub fn reflected(
    map: &GatherMap,
    v: &Vertex<'_>,
    bsdf: &Bsdf,
    scratch: &mut Vec<Neighbour>,
) -> Vec3 {
    map.map
        .estimate(v.sp.surface.p, v.ng, map.gather(), scratch, |ph| {
            let wi = v.frame.to_local(ph.incoming);
            if wi.z <= 0.0 {
                Vec3::ZERO
            } else {
                bsdf.eval(v.wo, wi)
            }
        })
}

/// Indirect diffuse light at `v`: `final_gather` BSDF-sampled rays, each reading the global
/// map where it lands on a diffuse surface.
fn final_gather(
    ctx: &ShadeContext<'_>,
    map: &GatherMap,
    v: &Vertex<'_>,
    bsdf: &Bsdf,
    sampler: &mut Sampler,
    scratch: &mut Vec<Neighbour>,
) -> Vec3 {
    let seed = sampler.child_seed();
    let n = map.final_gather.max(1);
    let mut sum = Vec3::ZERO;
    for j in 0..n {
        let mut s = Sampler::new(seed, j);
        let u = Vec3::new(s.next_1d(), s.next_1d(), s.next_1d());
        let Some(bs) = bsdf.sample(v.wo, u) else {
            continue;
        };
        if bs.delta {
            continue;
        }
        let Some(ray) = v.spawn(bs.wi, false) else {
            continue;
        };
        let Some(hit) = ctx.geometry.accel.intersect(&ray) else {
            continue;
        };
        let w = Vertex::new(ctx, &ray, &hit);
        if !w.visible {
            continue;
        }
        let Some(b) = w.bsdf().filter(Bsdf::has_non_delta) else {
            continue;
        };
        let incoming = reflected(map, &w, &b, scratch) * w.transmittance;
        sum += bs.weight() * incoming;
    }
    let l = sum / n as f32;
    if l.is_finite() {
        l
    } else {
        Vec3::ZERO
    }
}

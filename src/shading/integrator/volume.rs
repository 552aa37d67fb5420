//! Integration through media along ray segments for both integrators: transmittance and
//! single scattering on a segment ([`segment`], [`through_segment`]) and shadow rays that
//! pass through fog boundaries ([`shadow_transmittance`]). The media and their sampling
//! functions are [`crate::shading::volume`] (its module doc states the model).

use glam::Vec3;

use super::ShadeContext;
use crate::accel::{spawn_ray, spawn_ray_to, Hit, Ray};
use crate::components::Fog;
use crate::sampling::Sampler;
use crate::shading::lights::Light;
use crate::shading::volume::{distance_sample, equiangular, henyey_greenstein};

/// What a segment does to the radiance travelling along it toward its origin:
/// `L_origin = transmittance · L_end + inscattered`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// `e^(−σt·d)` per channel.
    pub transmittance: Vec3,
    /// Single-scattered radiance gathered along the segment.
    pub inscattered: Vec3,
}

impl Segment {
    /// A segment through vacuum.
    pub const VACUUM: Segment = Segment {
        transmittance: Vec3::ONE,
        inscattered: Vec3::ZERO,
    };

    /// `transmittance · radiance + inscattered`.
    pub fn apply(&self, radiance: Vec3) -> Vec3 {
        self.transmittance * radiance + self.inscattered
    }
}

/// The segment of `ray` that ends at `hit`, in the medium the scene puts there.
pub fn segment(ctx: &ShadeContext<'_>, ray: &Ray, hit: &Hit, sampler: &mut Sampler) -> Segment {
    let Some(volumes) = ctx.volumes else {
        return Segment::VACUUM;
    };
    let Some(fog) = volumes.medium(ctx.geometry, ray, hit) else {
        return Segment::VACUUM;
    };
    let len = ray.dir.length();
    let length = hit.t * len;
    if !(length.is_finite() && length > 0.0) {
        return Segment::VACUUM;
    }
    let dir = ray.dir / len;
    Segment {
        transmittance: fog.transmittance(length),
        inscattered: inscatter(ctx, fog, ray.origin, dir, length, sampler),
    }
}

/// `radiance` arriving at the end of the segment of `ray` that ends at `hit`, as seen from
/// the segment's origin (unchanged, bit for bit, when the scene has no volumes).
pub fn through_segment(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    radiance: Vec3,
    sampler: &mut Sampler,
) -> Vec3 {
    if ctx.volumes.is_none() {
        return radiance;
    }
    segment(ctx, ray, hit, sampler).apply(radiance)
}

/// Single scattering along `origin + t·dir`, `t ∈ [0, length]` (`dir` unit).
fn inscatter(
    ctx: &ShadeContext<'_>,
    fog: &Fog,
    origin: Vec3,
    dir: Vec3,
    length: f32,
    sampler: &mut Sampler,
) -> Vec3 {
    if fog.sigma_s == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let mut sum = Vec3::ZERO;
    for light in &ctx.lights.lights {
        let u_t = sampler.next_1d();
        let u_l = sampler.next_2d();
        let (t, pdf) = light_centre(light)
            .and_then(|c| equiangular(origin, dir, length, c, u_t))
            .unwrap_or_else(|| distance_sample(fog, length, u_t));
        if !(pdf > 0.0 && pdf.is_finite()) {
            continue;
        }
        let x = origin + dir * t;
        let Some(ls) = light.sample(x, u_l, Some(ctx.geometry)) else {
            continue;
        };
        let to_light = ls.target.map(|q| (q.p - x).length());
        let first = Ray {
            origin: x,
            dir: ls.wi,
            t_max: to_light.map_or(f32::INFINITY, |d| d * (1.0 - 1e-3)),
        };
        let target = ls.target.map(|q| q.p);
        let Some(t_light) = shadow_transmittance(ctx, first, Some(fog), target, ls.shadows) else {
            continue;
        };
        let phase = henyey_greenstein(fog.g, dir.dot(ls.wi));
        let c = fog.transmittance(t) * fog.sigma_s * ls.contribution * t_light * (phase / pdf);
        if c.is_finite() {
            sum += c;
        }
    }
    sum
}

/// Most fog boundaries one shadow ray passes through.
const MAX_CROSSINGS: usize = 16;

/// Transmittance along a shadow ray toward a light, or `None` when it is blocked.
///
/// `first` is the ray from the shading point (its `t_max` stops short of the light);
/// `start` is the medium at its origin; `target` is the light sample's position (`None`:
/// infinitely far, whose last segment crosses no medium). The shells of fog-filled
/// materials (those with an `interior`) are volume boundaries, not occluders: the ray
/// passes through them, entering the interior at a front face and returning to the
/// atmosphere at a back face. Transparent surfaces tint (`shading::shadow`); any other
/// surface blocks (unless `occlude` is false: then
/// only the starting medium attenuates, over the straight distance).
pub fn shadow_transmittance(
    ctx: &ShadeContext<'_>,
    first: Ray,
    start: Option<&Fog>,
    target: Option<Vec3>,
    occlude: bool,
) -> Option<Vec3> {
    let along = |fog: Option<&Fog>, from: Vec3| match (fog, target) {
        (Some(f), Some(p)) => f.transmittance((p - from).length()),
        _ => Vec3::ONE,
    };
    if !occlude {
        return Some(along(start, first.origin));
    }
    let Some(volumes) = ctx.volumes else {
        return (!ctx.geometry.accel.occluded(&first)).then_some(Vec3::ONE);
    };
    let mut ray = first;
    let mut medium = start;
    let mut t = Vec3::ONE;
    for _ in 0..MAX_CROSSINGS {
        let Some(hit) = ctx.geometry.accel.intersect(&ray) else {
            return Some(t * along(medium, ray.origin));
        };
        let slot = ctx.geometry.triangle_instance[hit.prim as usize] as usize;
        let material = ctx.geometry.instances[slot].material as usize;
        let interior = volumes.interiors.get(material).and_then(Option::as_ref);
        // A surface without an interior passes light only if its shader lets shadows
        // through (`shading::shadow`); the medium stays the same across it.
        let tint = match interior {
            Some(_) => Vec3::ONE,
            None => crate::shading::shadow::shadow_transmittance(
                &ctx.geometry.materials[material].shader,
            )?,
        };
        if let Some(f) = medium {
            t *= f.transmittance(hit.t * ray.dir.length());
        }
        t *= tint;
        let sp = ctx.geometry.accel.surface_point(&hit);
        if let Some(interior) = interior {
            medium = if sp.ng.dot(ray.dir) < 0.0 {
                Some(interior)
            } else {
                volumes.atmosphere.as_ref()
            };
        }
        ray = match target {
            Some(p) => spawn_ray_to(&sp, p),
            None => spawn_ray(&sp, ray.dir),
        };
    }
    None
}

/// Position equiangular sampling aims at, for lights that have one.
fn light_centre(light: &Light) -> Option<Vec3> {
    match light {
        Light::Point { position, .. } | Light::Spot { position, .. } => Some(*position),
        Light::Area(a) => Some(a.centre()),
        _ => None,
    }
}

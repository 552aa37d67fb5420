//! Direct lighting at a camera-ray hit: emission, unlit shaders, and the light loop with
//! shadow rays for light-dependent shaders.

use glam::Vec3;

use crate::accel::{spawn_ray, spawn_ray_to, spawn_ray_to_surface, Hit, Ray};
use crate::geometry::{SceneGeometry, ShadingPoint};
use crate::sampling::Sampler;
use crate::settings::Face;
use crate::shading::lights::LightSet;
use crate::shading::surface::{brdf, unlit_radiance};

/// What shading a hit needs from the scene.
pub struct ShadeContext<'a> {
    /// Geometry and BVH.
    pub geometry: &'a SceneGeometry,
    /// Lights.
    pub lights: &'a LightSet,
    /// Face visibility option.
    pub face: Face,
}

/// Radiance leaving the hit toward the ray origin, and the shading point (normal facing the
/// viewer).
pub fn shade_hit(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    sampler: &mut Sampler,
) -> (Vec3, ShadingPoint) {
    let mut sp = ctx.geometry.shading_point(hit);
    let material = &ctx.geometry.materials[sp.material as usize];
    let wo = -ray.dir.normalize();
    let front = sp.surface.ng.dot(wo) > 0.0;
    let two_sided = material.two_sided || ctx.face == Face::Both;
    if !front {
        sp.normal = -sp.normal;
    }
    let ng_facing = if front { sp.surface.ng } else { -sp.surface.ng };
    if !front && !two_sided {
        // The back of a one-sided surface: black, but it still blocks light.
        return (Vec3::ZERO, sp);
    }
    let mut radiance = material.emission;
    let cos_view = sp.normal.dot(wo);
    if let Some(unlit) = unlit_radiance(&material.shader, cos_view) {
        return (radiance + unlit, sp);
    }
    let f = brdf(&material.shader);
    if f == Vec3::ZERO {
        return (radiance, sp);
    }
    for light in &ctx.lights.lights {
        let n = light.sample_count();
        let seed = sampler.child_seed();
        let mut sum = Vec3::ZERO;
        for j in 0..n {
            let u = Sampler::new(seed, j).next_2d();
            let Some(ls) = light.sample(sp.surface.p, u, Some(ctx.geometry)) else {
                continue;
            };
            let cos_s = sp.normal.dot(ls.wi);
            if cos_s <= 0.0 || ng_facing.dot(ls.wi) <= 0.0 {
                continue;
            }
            if ls.shadows && occluded(ctx.geometry, &sp, ls.wi, ls.target) {
                continue;
            }
            sum += ls.contribution * cos_s;
        }
        radiance += f * sum / n as f32;
    }
    (radiance, sp)
}

/// Whether the shadow ray from `sp` toward a light sample is blocked.
fn occluded(
    geometry: &SceneGeometry,
    sp: &ShadingPoint,
    wi: Vec3,
    target: Option<crate::accel::SurfacePoint>,
) -> bool {
    let ray = match target {
        None => spawn_ray(&sp.surface, wi),
        Some(t) if t.ng == Vec3::ZERO => spawn_ray_to(&sp.surface, t.p),
        Some(t) => spawn_ray_to_surface(&sp.surface, &t),
    };
    geometry.accel.occluded(&ray)
}

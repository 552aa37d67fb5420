//! The default integrator: emission, mental ray's ambient term, local illumination models
//! ([`super::local`]: RenderMan's standard surfaces with the scene's ambient light), direct
//! light from every light with shadow rays (each light's own sample count), and every delta
//! branch (mirror, both branches of glass, transparency) traced recursively within the trace
//! depths; rays that leave the scene see the environment (and visible area lights they
//! cross).
//! Glossy and diffuse interreflection are not computed (the path tracer does that). Traced
//! segments cross the scene's fog ([`super::volume`]): attenuation and single scattering.
//! With caustics or global illumination on, the photon maps add caustics and one bounce of
//! indirect diffuse light ([`super::PhotonRadiance`], implemented in `crate::photon::estimate`).

use glam::Vec3;

use super::{depth_exceeded, light_loop, local, trace, volume, Depth, ShadeContext, Vertex};
use crate::accel::{Hit, Ray};
use crate::sampling::Sampler;
use crate::shading::surface::unlit_radiance;

/// Radiance toward the origin of `ray`, which hits the scene at `hit` (a camera ray).
pub fn radiance(ctx: &ShadeContext<'_>, ray: &Ray, hit: &Hit, sampler: &mut Sampler) -> Vec3 {
    vertex_radiance(ctx, ray, hit, sampler, Depth::FIRST)
}

fn vertex_radiance(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    sampler: &mut Sampler,
    depth: Depth,
) -> Vec3 {
    let v = Vertex::new(ctx, ray, hit);
    if !v.visible {
        return Vec3::ZERO;
    }
    let mut radiance = v.emitted();
    if let Some(unlit) = unlit_radiance(&v.shader, v.wo.z) {
        return v.transmittance * (radiance + unlit);
    }
    if depth.vertex > ctx.max_depth {
        return v.transmittance * radiance;
    }
    radiance += local::radiance(ctx, &v, sampler);
    let Some(bsdf) = v.bsdf() else {
        return v.transmittance * radiance;
    };
    radiance += v.shader.ambient();
    if bsdf.has_non_delta() {
        radiance += light_loop(ctx, &v, &bsdf, sampler, false);
        radiance += ctx
            .photons
            .map_or(Vec3::ZERO, |p| p.radiance(ctx, &v, &bsdf, sampler));
    }
    for branch in bsdf.delta_branches(v.wo) {
        let Some(next) = depth.after(ctx, !branch.transmits, branch.transmits) else {
            if let Some((le, _)) = depth_exceeded(ctx, v.frame.to_world(branch.wi)) {
                radiance += branch.weight * le;
            }
            continue;
        };
        let Some(ray) = v.spawn(branch.wi, branch.transmits) else {
            continue;
        };
        let (hit, lights, _) = trace(ctx, &ray, true);
        let mut incoming = lights;
        if let Some(h) = hit {
            incoming += vertex_radiance(ctx, &ray, &h, sampler, next);
            incoming = volume::through_segment(ctx, &ray, &h, incoming, sampler);
        }
        radiance += branch.weight * incoming;
    }
    v.transmittance * radiance
}

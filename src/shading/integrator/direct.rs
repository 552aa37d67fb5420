//! The default integrator: emission, mental ray's ambient term, local illumination models
//! ([`super::local`]: RenderMan's standard surfaces with the scene's ambient light), direct
//! light from every light with shadow rays (each light's own sample count), and every delta
//! branch (mirror, both branches of glass, transparency) traced recursively within the trace
//! depths; rays that leave the scene see the environment (the material's own when it has
//! one, see [`super`]) and visible area lights they cross.
//! Glossy and diffuse interreflection are not computed (the path tracer does that). Traced
//! segments cross the scene's fog ([`super::volume`]): attenuation and single scattering.
//! With caustics or global illumination on, the photon maps add caustics and one bounce of
//! indirect diffuse light ([`super::PhotonRadiance`], implemented in `crate::photon::estimate`).

use glam::Vec3;

use super::components::{local_component, note, scale, Component, Components};
use super::{
    depth_exceeded_leaving, light_loop_without_mis, local, trace_leaving, volume, Depth,
    ShadeContext, Vertex,
};
use crate::accel::{Hit, Ray};
use crate::sampling::Sampler;
use crate::shading::surface::unlit_radiance;

/// Radiance toward the origin of `ray`, which hits the scene at `hit` (a camera ray).
pub fn radiance(ctx: &ShadeContext<'_>, ray: &Ray, hit: &Hit, sampler: &mut Sampler) -> Vec3 {
    vertex_radiance(ctx, ray, hit, sampler, Depth::FIRST, None)
}

/// [`radiance`] (the same value, bit for bit), also recording it per component into
/// `parts` when given ([`super::components`]).
pub fn radiance_split(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    sampler: &mut Sampler,
    parts: Option<&mut Components>,
) -> Vec3 {
    vertex_radiance(ctx, ray, hit, sampler, Depth::FIRST, parts)
}

fn vertex_radiance(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    sampler: &mut Sampler,
    depth: Depth,
    mut parts: Option<&mut Components>,
) -> Vec3 {
    let v = Vertex::new(ctx, ray, hit);
    if !v.visible {
        return Vec3::ZERO;
    }
    let mut radiance = v.emitted();
    note(&mut parts, Component::Emission, radiance);
    if let Some(unlit) = unlit_radiance(&v.shader, v.wo.z) {
        note(&mut parts, Component::Emission, unlit);
        scale(&mut parts, v.transmittance);
        return v.transmittance * (radiance + unlit);
    }
    if depth.vertex > ctx.max_depth {
        scale(&mut parts, v.transmittance);
        return v.transmittance * radiance;
    }
    let l = local::radiance(ctx, &v, sampler);
    note(&mut parts, local_component(&v.shader), l);
    radiance += l;
    let mut scratch = None;
    let bsdf = v.bsdf_ref(ctx, &mut scratch);
    if !bsdf.reflects() {
        scale(&mut parts, v.transmittance);
        return v.transmittance * radiance;
    }
    radiance += v.shader.ambient();
    note(&mut parts, Component::DiffuseIndirect, v.shader.ambient());
    if bsdf.has_non_delta() {
        let mut diffuse = Vec3::ZERO;
        let share = parts.is_some().then_some(&mut diffuse);
        let direct = light_loop_without_mis(ctx, &v, bsdf, sampler, share);
        radiance += direct;
        note(&mut parts, Component::DiffuseDirect, diffuse);
        note(&mut parts, Component::Specular, direct - diffuse);
        let photons = ctx
            .photons
            .map_or(Vec3::ZERO, |p| p.radiance(ctx, &v, bsdf, sampler));
        radiance += photons;
        note(&mut parts, Component::DiffuseIndirect, photons);
    }
    let own = v.material.environment.as_deref();
    for branch in bsdf.delta_branches(v.wo) {
        let through = if branch.transmits {
            Component::Transmission
        } else {
            Component::Specular
        };
        let Some(next) = depth.after(ctx, !branch.transmits, branch.transmits) else {
            if let Some((le, _)) = depth_exceeded_leaving(ctx, own, v.frame.to_world(branch.wi)) {
                radiance += branch.weight * le;
                note(&mut parts, through, branch.weight * le);
            }
            continue;
        };
        let Some(ray) = v.spawn(branch.wi, branch.transmits) else {
            continue;
        };
        let (hit, lights, _) = trace_leaving(ctx, &ray, true, own);
        let mut incoming = lights;
        if let Some(h) = hit {
            incoming += vertex_radiance(ctx, &ray, &h, sampler, next, None);
            incoming = volume::through_segment(ctx, &ray, &h, incoming, sampler);
        }
        radiance += branch.weight * incoming;
        note(&mut parts, through, branch.weight * incoming);
    }
    scale(&mut parts, v.transmittance);
    v.transmittance * radiance
}

//! The reference path tracer: at every vertex one sample of every light (next-event
//! estimation) and one BSDF sample, the two combined by the power heuristic; emitters found
//! by BSDF sampling (emitting triangles, area lights, the environment) are weighted against
//! the light strategy, delta scattering keeps full weight. Russian roulette from the third
//! vertex on (survival probability = largest channel of the throughput, at most 0.95) keeps
//! long paths unbiased. Area lights: `visible` is camera visibility (mental ray): the eye's
//! specular chain `E S*` (the camera ray and perfect mirror/refraction rays after it) sees
//! only visible lights, as the `Direct` integrator does; once the path has scattered at a
//! non-delta lobe it carries light, and every light's front face is seen — also through
//! glass and mirrors, so an invisible light's caustics (`L S+ D … E`) are rendered, as the
//! photon map renders them. Rays leaving the scene see the environment (black without one); a
//! bounce beyond a reflection/refraction budget sees what the environment's
//! `depth_exceeded` says. Every segment that ends at a hit is attenuated by the fog it
//! crosses and adds single scattering from the lights ([`super::volume`]): unbiased for
//! attenuation; light scattered more than once inside a medium is not computed. Local
//! illumination models ([`super::local`]) are shaded as the Direct integrator shades them
//! (ambient term, every light, no MIS) and continue only through their delta lobes.

use glam::Vec3;

use super::{depth_exceeded, light_loop, local, trace, volume, Depth, ShadeContext, Vertex};
use crate::accel::{Hit, Ray};
use crate::sampling::Sampler;
use crate::shading::bsdf::Scatter;
use crate::shading::mis::power_heuristic;
use crate::shading::surface::unlit_radiance;

/// First vertex at which Russian roulette may end a path.
const RR_START: u32 = 3;

/// Radiance toward the origin of the camera ray `ray`, which hits the scene at `hit`.
pub fn radiance(ctx: &ShadeContext<'_>, ray: &Ray, hit: &Hit, sampler: &mut Sampler) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    let mut beta = Vec3::ONE;
    let mut depth = Depth::FIRST;
    let mut ray = *ray;
    let mut hit = Some(*hit);
    // Origin and solid-angle pdf of the last non-delta BSDF sample (None: camera or delta).
    let mut prev: Option<(Vec3, f32)> = None;
    // Whether the path is still the eye's specular chain `E S*` (camera ray, then only delta
    // scattering): only then does `visible` hide area lights (see the module doc).
    let mut eye_chain = true;
    while let Some(h) = hit {
        let v = Vertex::new(ctx, &ray, &h);
        beta *= v.transmittance;
        if !v.visible {
            break;
        }
        let le = v.emitted();
        if le != Vec3::ZERO {
            let w = match prev {
                None => 1.0,
                Some((p, pdf)) => {
                    let m = v.material;
                    let pdf_light = ctx.lights.mesh_pdf(
                        p,
                        v.sp.surface.p,
                        v.sp.surface.ng,
                        m.emission,
                        m.two_sided,
                    );
                    power_heuristic(pdf, pdf_light)
                }
            };
            radiance += beta * le * w;
        }
        if let Some(unlit) = unlit_radiance(&v.shader, v.wo.z) {
            radiance += beta * unlit;
            break;
        }
        if depth.vertex > ctx.max_depth {
            break;
        }
        radiance += beta * local::radiance(ctx, &v, sampler);
        let Some(bsdf) = v.bsdf() else { break };
        if bsdf.has_non_delta() {
            radiance += beta * light_loop(ctx, &v, &bsdf, sampler, true);
        }
        if depth.vertex >= RR_START {
            let q = beta.max_element().min(0.95);
            if sampler.next_1d() >= q {
                break;
            }
            beta /= q;
        }
        let u = Vec3::new(sampler.next_1d(), sampler.next_1d(), sampler.next_1d());
        let Some(s) = bsdf.sample(v.wo, u) else { break };
        let transmits = s.scatter == Scatter::Transmission;
        let mis = |pdf_light: f32| {
            if s.delta {
                1.0
            } else {
                power_heuristic(s.pdf, pdf_light)
            }
        };
        let Some(next) = depth.after(ctx, s.scatter == Scatter::Reflection, transmits) else {
            if let Some((le, pdf_light)) = depth_exceeded(ctx, v.frame.to_world(s.wi)) {
                radiance += beta * s.weight() * le * mis(pdf_light);
            }
            break;
        };
        let Some(next_ray) = v.spawn(s.wi, transmits) else {
            break;
        };
        beta *= s.weight();
        if !s.delta && !transmits {
            beta *= v.bump_shadowing(v.frame.to_world(s.wi));
        }
        if !beta.is_finite() || beta.max_element() <= 0.0 {
            break;
        }
        eye_chain &= s.delta;
        let (next_hit, _, crossed) = trace(ctx, &next_ray, eye_chain);
        if let (Some(h), Some(_)) = (&next_hit, ctx.volumes) {
            let seg = volume::segment(ctx, &next_ray, h, sampler);
            radiance += beta * seg.inscattered;
            beta *= seg.transmittance;
        }
        for (le, pdf_light) in crossed {
            radiance += beta * le * mis(pdf_light);
        }
        prev = (!s.delta).then_some((v.sp.surface.p, s.pdf));
        ray = next_ray;
        hit = next_hit;
        depth = next;
    }
    radiance
}

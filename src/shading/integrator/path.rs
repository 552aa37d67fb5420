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
//! `depth_exceeded` says. Delta rays of a material with its own environment see that one
//! ([`super`]). Every segment that ends at a hit is attenuated by the fog it
//! crosses and adds single scattering from the lights ([`super::volume`]): unbiased for
//! attenuation; light scattered more than once inside a medium is not computed. Local
//! illumination models ([`super::local`]) are shaded as the Direct integrator shades them
//! (ambient term, every light, no MIS) and continue only through their delta lobes.
//! The straight pass-through of a partly transparent surface (`Opacity`) that shadow rays
//! also cross is a null event: the lights found beyond it are weighted against next-event
//! estimation at the last non-delta vertex, with that vertex's pdf, and measured from there
//! ([`crate::shading::lights::Light::hit_from`]).

use glam::Vec3;

use super::components::{local_component, Component, Components, PathLanes};
use super::power::power_weight;
use super::{
    depth_exceeded_leaving, light_loop_split, local, trace_leaving_from, volume, Depth,
    ShadeContext, Vertex,
};
use crate::accel::{Hit, Ray};
use crate::sampling::Sampler;
use crate::shading::bsdf::{Bsdf, Scatter};
use crate::shading::shadow::material_transmits_shadows;
use crate::shading::surface::unlit_radiance;
use crate::shading::texture::hit::is_textured;

/// First vertex at which Russian roulette may end a path.
const RR_START: u32 = 3;

/// Radiance toward the origin of the camera ray `ray`, which hits the scene at `hit`.
pub fn radiance(ctx: &ShadeContext<'_>, ray: &Ray, hit: &Hit, sampler: &mut Sampler) -> Vec3 {
    radiance_split(ctx, ray, hit, sampler, None)
}

/// Whether a vertex at `hit` past the depth limit adds nothing: its material emits nothing
/// and has no unlit shader, and no texture could change either (what [`Vertex::emitted`] and
/// [`unlit_radiance`] read there).
#[inline]
fn adds_nothing_past_the_depth(ctx: &ShadeContext<'_>, hit: &Hit) -> bool {
    let g = ctx.geometry;
    let (inst, local) = g.locate(hit.prim);
    let material = &g.materials[inst.material_of_local(local) as usize];
    material.emission == Vec3::ZERO
        && unlit_radiance(&material.shader, 1.0).is_none()
        && !is_textured(inst, material)
}

/// Records the contribution `x` (before the path throughput `beta`) in `parts`: in `first`
/// at the first hit (no `lanes` yet), else through the first event's `lanes` (`emitted`:
/// light emitted where the contribution starts, see [`PathLanes::record`]).
fn record(
    parts: &mut Option<&mut Components>,
    lanes: &Option<PathLanes>,
    beta: Vec3,
    first: Component,
    x: Vec3,
    emitted: bool,
) {
    let Some(p) = parts.as_deref_mut() else {
        return;
    };
    match lanes {
        None => p.add(first, beta * x),
        Some(l) => l.record(p, x, emitted),
    }
}

/// [`radiance`] (the same value, bit for bit), also recording it per component into
/// `parts` when given ([`super::components`]).
pub fn radiance_split(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    sampler: &mut Sampler,
    mut parts: Option<&mut Components>,
) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    let mut beta = Vec3::ONE;
    let mut depth = Depth::FIRST;
    let mut ray = *ray;
    let mut hit = Some(*hit);
    // Origin and solid-angle pdf of the last non-delta BSDF sample (None: camera or delta).
    // A straight pass-through that shadow rays also cross keeps it (see `null` below).
    let mut prev: Option<(Vec3, f32)> = None;
    // Component passes: the throughput per first event, once the path has scattered.
    let mut lanes: Option<PathLanes> = None;
    // Whether the path is still the eye's specular chain `E S*` (camera ray, then only delta
    // scattering): only then does `visible` hide area lights (see the module doc).
    let mut eye_chain = true;
    // Where a textured vertex builds its BSDF ([`Vertex::bsdf_ref`]), made at the first one.
    let mut scratch: Option<Bsdf> = None;
    while let Some(h) = hit {
        // Past the depth limit a vertex only adds what its surface emits or shows unlit (the
        // light its BSDF sample from the last vertex found); a surface that does neither ends
        // the path before its vertex is built.
        if depth.vertex > ctx.max_depth && adds_nothing_past_the_depth(ctx, &h) {
            break;
        }
        let v = Vertex::new(ctx, &ray, &h);
        beta *= v.transmittance;
        if let Some(l) = &mut lanes {
            l.scale(v.transmittance);
        }
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
                    power_weight(pdf, pdf_light)
                }
            };
            radiance += beta * le * w;
            record(&mut parts, &lanes, beta, Component::Emission, le * w, true);
        }
        if let Some(unlit) = unlit_radiance(&v.shader, v.wo.z) {
            radiance += beta * unlit;
            record(&mut parts, &lanes, beta, Component::Emission, unlit, true);
            break;
        }
        if depth.vertex > ctx.max_depth {
            break;
        }
        let l = local::radiance(ctx, &v, sampler);
        radiance += beta * l;
        record(
            &mut parts,
            &lanes,
            beta,
            local_component(&v.shader),
            l,
            false,
        );
        let bsdf = v.bsdf_ref(ctx, &mut scratch);
        if !bsdf.reflects() {
            break;
        }
        if bsdf.has_non_delta() {
            let mut diffuse = Vec3::ZERO;
            let share = (parts.is_some() && lanes.is_none()).then_some(&mut diffuse);
            let direct = light_loop_split(ctx, &v, bsdf, sampler, true, share);
            radiance += beta * direct;
            let glossy = direct - diffuse;
            record(
                &mut parts,
                &lanes,
                beta,
                Component::DiffuseDirect,
                diffuse,
                false,
            );
            record(&mut parts, &lanes, beta, Component::Specular, glossy, false);
        }
        if depth.vertex >= RR_START {
            let q = beta.max_element().min(0.95);
            if sampler.next_1d() >= q {
                break;
            }
            beta /= q;
            if let Some(l) = &mut lanes {
                l.scale(Vec3::splat(1.0 / q));
            }
        }
        let u = Vec3::new(sampler.next_1d(), sampler.next_1d(), sampler.next_1d());
        let Some(s) = bsdf.sample(v.wo, u) else { break };
        let transmits = s.scatter == Scatter::Transmission;
        // A straight pass-through (`Opacity`) of a surface that shadow rays cross too is a
        // null event: next-event estimation at the last non-delta vertex already reached the
        // lights beyond it through the same surface, so what this ray finds is weighted
        // against that estimate from there — with that vertex's pdf — not counted in full
        // as after a mirror (which counted light through a transparent sheet twice).
        let null = s.pass_through && prev.is_some() && material_transmits_shadows(v.material);
        // The closures below take copies, never `&s`: a borrowed sample must live in memory,
        // and reading the returned `Option<BsdfSample>` back from there stalled (a failed
        // store-to-load forward, ≈ 1 % of a sample).
        let (delta, pdf) = match prev {
            Some((_, pdf)) if null => (false, pdf),
            _ => (s.delta, s.pdf),
        };
        let behind = prev.filter(|_| null).map(|(p, _)| p);
        let mis = move |pdf_light: f32| {
            if delta {
                1.0
            } else {
                power_weight(pdf, pdf_light)
            }
        };
        let next_lanes = parts.is_some().then(|| match &lanes {
            None => {
                let first = s;
                PathLanes::first(beta * first.weight(), &first, bsdf, v.wo)
            }
            Some(l) => l.after(s.weight()),
        });
        // A delta ray of a material with its own environment sees that one (see `super`).
        let own = v.material.environment.as_deref().filter(|_| s.delta);
        let Some(next) = depth.after(ctx, s.scatter == Scatter::Reflection, transmits) else {
            if let Some((le, pdf_light)) = depth_exceeded_leaving(ctx, own, v.frame.to_world(s.wi))
            {
                radiance += beta * s.weight() * le * mis(pdf_light);
                let x = le * mis(pdf_light);
                record(&mut parts, &next_lanes, beta, Component::Emission, x, true);
            }
            break;
        };
        let Some(next_ray) = v.spawn(s.wi, transmits) else {
            break;
        };
        beta *= s.weight();
        lanes = next_lanes;
        if !s.delta && !transmits {
            let b = v.bump_shadowing(v.frame.to_world(s.wi));
            beta *= b;
            if let Some(l) = &mut lanes {
                l.scale(Vec3::splat(b));
            }
        }
        if !beta.is_finite() || beta.max_element() <= 0.0 {
            break;
        }
        eye_chain &= s.delta;
        let (next_hit, _, crossed) = trace_leaving_from(ctx, &next_ray, eye_chain, own, behind);
        if let (Some(h), Some(_)) = (&next_hit, ctx.volumes) {
            let seg = volume::segment(ctx, &next_ray, h, sampler);
            radiance += beta * seg.inscattered;
            let x = seg.inscattered;
            record(&mut parts, &lanes, beta, Component::Volume, x, false);
            beta *= seg.transmittance;
            if let Some(l) = &mut lanes {
                l.scale(seg.transmittance);
            }
        }
        for (le, pdf_light) in crossed {
            radiance += beta * le * mis(pdf_light);
            let x = le * mis(pdf_light);
            record(&mut parts, &lanes, beta, Component::Emission, x, true);
        }
        if !null {
            prev = (!s.delta).then_some((v.sp.surface.p, s.pdf));
        }
        ray = next_ray;
        hit = next_hit;
        depth = next;
    }
    radiance
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::components::Shader;
    use crate::settings::RenderSettings;
    use crate::shading::integrator::fixture::{self, Object};
    use crate::shading::lights::LightSet;

    /// Only a surface that neither emits, nor shows an unlit shader, nor has a texture or
    /// bump that could change either ends a path past the depth limit unbuilt.
    #[test]
    fn only_plain_surfaces_add_nothing_past_the_depth() {
        let panel = |x: f32| {
            fixture::quad(
                Vec3::new(x, -0.2, 1.0),
                Vec3::new(0.4, 0.0, 0.0),
                Vec3::new(0.0, 0.4, 0.0),
            )
        };
        let mut emitter = fixture::lambert(0.5);
        emitter.emission = Vec3::splat(3.0);
        let unlit = fixture::material(Shader::Constant {
            color: Vec3::splat(0.5),
        });
        let cases = [
            (fixture::lambert(0.5), true),
            (emitter, false),
            (unlit, false),
            (fixture::lambert(0.5), false),
        ];
        let mut g = fixture::geometry(
            cases
                .iter()
                .enumerate()
                .map(|(i, (m, _))| Object {
                    triangles: panel(i as f32 - 2.0),
                    material: m.clone(),
                })
                .collect(),
        );
        g.instances[3].bump = Some(fixture::sine_bump());
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&g, &lights, &s);
        for (i, (_, nothing)) in cases.iter().enumerate() {
            let centre = Vec3::new(i as f32 - 1.8, 0.0, 0.0);
            let (_, hit) = fixture::hit(&g, centre, Vec3::Z);
            assert_eq!(
                adds_nothing_past_the_depth(&ctx, &hit),
                *nothing,
                "panel {i}"
            );
        }
    }
}

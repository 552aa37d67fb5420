//! The part of a vertex's radiance that no BSDF carries: local illumination models
//! ([`LocalModel`], RenderMan's standard surfaces as RIB scenes use them) evaluated as their
//! specification writes them, and light-independent shaders blended by `Opacity`.
//!
//! For a `Local` model this is `color·(ka·A + kd·Σ Cl·max(0, N·L)) + ambient +
//! specular·Σ Cl·lobe`, `A` the scene's ambient light ([`crate::shading::LightSet::ambient`]),
//! the sums over every light with its own sample count and shadow rays (RenderMan lights
//! cast none unless asked). The mirror term is a BSDF lobe and traced by the integrator.
//! A material with a photon shader (AIR's caustic attributes) also gets AIR's `caustic`
//! light: the caustic map's irradiance `E` in the diffuse sum, `color·kd·E`.
//! Both integrators call this at every vertex they shade; the path tracer continues only
//! through the delta lobes (mirror, transparency), so a local model gathers no indirect
//! light beyond its ambient term — as in the renderers it comes from.

use glam::Vec3;

use super::{gather, Response, ShadeContext, Vertex};
use crate::components::{LocalModel, Shader};
use crate::sampling::Sampler;
use crate::shading::surface::unlit_radiance;

/// Radiance toward the viewer at `v` that is not a BSDF's: a `Local` model's terms, or an
/// `Opacity` blend's share of a `Local` or light-independent input. Zero (and no sampler
/// dimension used) for every other shader.
pub fn radiance(ctx: &ShadeContext<'_>, v: &Vertex<'_>, sampler: &mut Sampler) -> Vec3 {
    match &*v.shader {
        Shader::Local(m) => model(ctx, v, m, sampler),
        Shader::Opacity { opacity, input } => {
            let o = opacity.clamp(Vec3::ZERO, Vec3::ONE);
            match &**input {
                Shader::Local(m) => o * model(ctx, v, m, sampler),
                other => unlit_radiance(other, v.wo.z).map_or(Vec3::ZERO, |c| o * c),
            }
        }
        _ => Vec3::ZERO,
    }
}

/// The terms of `m` at `v`.
fn model(ctx: &ShadeContext<'_>, v: &Vertex<'_>, m: &LocalModel, sampler: &mut Sampler) -> Vec3 {
    let mut l = m.ambient_term(ctx.lights.ambient);
    // AIR's `caustic` light: a material with a photon shader receives the caustic map's
    // irradiance in its diffuse sum, `color · kd · E` (its `Cl` arrives along the normal).
    if let (Some(_), Some(photons)) = (&v.material.photon, ctx.photons) {
        if m.kd > 0.0 && m.color != Vec3::ZERO {
            l += m.color * m.kd * photons.caustic_irradiance(v);
        }
    }
    if (m.kd > 0.0 && m.color != Vec3::ZERO) || m.specular != Vec3::ZERO {
        let wo = v.wo.normalize_or_zero();
        let f = |wi: Vec3, _: Vec3| m.per_light(wo, wi);
        l += gather(ctx, v, sampler, None, Response::Local(&f));
    }
    l
}

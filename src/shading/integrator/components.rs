//! Component passes: the radiance of a camera sample split by what happened to its light
//! first, seen from the camera (mental ray's output types, RenderMan's AOVs).
//!
//! Each contribution the integrators add to a camera sample is also recorded in one
//! [`Component`], chosen by the first event along the path from the camera:
//!
//! - [`Component::Emission`]: light that reaches the camera without scattering — the
//!   emission of the surface the camera ray hits, what a light-independent shader
//!   (`Constant`, `DefaultSurface`, an `Opacity` blend of one) returns there, a visible area
//!   light or the environment (background) seen by the camera ray.
//! - [`Component::DiffuseDirect`]: light from the lights scattered by the diffuse lobes at
//!   the first hit (the light loop's diffuse share; in the path tracer also the lights and
//!   emitting surfaces its diffuse BSDF sample reaches directly, the MIS partner), and a
//!   `Local` (RenderMan) model's terms.
//! - [`Component::DiffuseIndirect`]: everything else the diffuse lobes at the first hit
//!   bring: further bounces, photon-map caustics and final gather, the shader's ambient term.
//! - [`Component::Specular`]: light reflected by the glossy and mirror lobes at the first hit
//!   (direct light and everything the reflected rays see).
//! - [`Component::Transmission`]: light through the first hit — refraction and transparency.
//! - [`Component::Volume`]: light scattered by fog on the camera ray's segment.
//!
//! A non-delta BSDF sample's weight is split between the diffuse and the glossy share by
//! the value of the diffuse lobes ([`crate::shading::bsdf::Bsdf::eval_diffuse`]) over the
//! whole BSDF. Attenuation after a component is recorded (the first hit inside a dielectric,
//! the camera segment's fog) scales every component alike, so the components sum to the
//! sample's radiance up to rounding. The sample's radiance itself is computed exactly as
//! without components (the same operations in the same order), so asking for components
//! never changes the beauty.

use glam::Vec3;

use super::{shade_hit_split, volume, ShadeContext};
use crate::accel::{Hit, Ray};
use crate::components::Shader;
use crate::sampling::Sampler;
use crate::shading::bsdf::{Bsdf, BsdfSample, Scatter};

/// What happened first to the light of a contribution (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Component {
    /// Seen without scattering.
    Emission,
    /// Direct light through the diffuse lobes of the first hit.
    DiffuseDirect,
    /// Indirect light through the diffuse lobes of the first hit.
    DiffuseIndirect,
    /// Light through the glossy and mirror lobes of the first hit.
    Specular,
    /// Light refracted or passed through at the first hit.
    Transmission,
    /// Light scattered by fog on the camera segment.
    Volume,
}

impl Component {
    /// Every component, in the order of [`Components::parts`].
    pub const ALL: [Component; 6] = [
        Component::Emission,
        Component::DiffuseDirect,
        Component::DiffuseIndirect,
        Component::Specular,
        Component::Transmission,
        Component::Volume,
    ];

    /// Index of the component in [`Components::parts`].
    pub fn index(self) -> usize {
        self as usize
    }
}

/// One camera sample's radiance per component.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Components {
    /// Radiance per component, indexed by [`Component::index`].
    pub parts: [Vec3; 6],
}

impl Components {
    /// Adds `radiance` to `component`.
    pub fn add(&mut self, component: Component, radiance: Vec3) {
        self.parts[component.index()] += radiance;
    }

    /// Multiplies every component by `factor` (attenuation after the split).
    pub fn scale(&mut self, factor: Vec3) {
        for p in &mut self.parts {
            *p *= factor;
        }
    }

    /// The sum of the components.
    pub fn total(&self) -> Vec3 {
        self.parts.iter().fold(Vec3::ZERO, |s, p| s + *p)
    }
}

/// Records `radiance` in `component` when components are being recorded.
pub(crate) fn note(parts: &mut Option<&mut Components>, component: Component, radiance: Vec3) {
    if let Some(p) = parts.as_deref_mut() {
        p.add(component, radiance);
    }
}

/// Scales the recorded components by `factor` when components are being recorded.
pub(crate) fn scale(parts: &mut Option<&mut Components>, factor: Vec3) {
    if let Some(p) = parts.as_deref_mut() {
        p.scale(factor);
    }
}

/// The component a `Local` model's (or an `Opacity` blend's) non-BSDF radiance at the first
/// hit belongs to: emission for a blend of a light-independent shader, else diffuse direct.
pub(crate) fn local_component(shader: &Shader) -> Component {
    match shader {
        Shader::Opacity { input, .. } if !matches!(**input, Shader::Local(_)) => {
            Component::Emission
        }
        _ => Component::DiffuseDirect,
    }
}

/// The path tracer's throughput after its first scattering event, per component of that
/// event (what the path brings back is recorded through these).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PathLanes {
    /// Through the diffuse lobes of the first hit.
    diffuse: Vec3,
    /// Through the glossy and mirror lobes of the first hit.
    specular: Vec3,
    /// Refracted or passed through at the first hit.
    transmission: Vec3,
    /// Whether the path has not scattered a second time: emitters it reaches now are direct
    /// light.
    direct: bool,
}

impl PathLanes {
    /// The lanes after the first scattering, sample `s` of `bsdf` (viewer direction `wo`),
    /// with the throughput `beta` after it: a delta sample goes whole into its lane, a
    /// non-delta one is split by the diffuse lobes' share of the BSDF value.
    pub(crate) fn first(beta: Vec3, s: &BsdfSample, bsdf: &Bsdf, wo: Vec3) -> Self {
        let mut lanes = Self {
            diffuse: Vec3::ZERO,
            specular: Vec3::ZERO,
            transmission: Vec3::ZERO,
            direct: true,
        };
        if s.delta {
            match s.scatter {
                Scatter::Transmission => lanes.transmission = beta,
                _ => lanes.specular = beta,
            }
        } else {
            let fd = bsdf.eval_diffuse(wo, s.wi);
            let ratio = Vec3::select(s.f.cmpgt(Vec3::ZERO), fd / s.f, Vec3::ZERO);
            lanes.diffuse = beta * ratio.clamp(Vec3::ZERO, Vec3::ONE);
            lanes.specular = beta - lanes.diffuse;
        }
        lanes
    }

    /// The lanes after a later scattering with throughput weight `weight`: emitters reached
    /// from here on are indirect light.
    pub(crate) fn after(&self, weight: Vec3) -> Self {
        let mut next = *self;
        next.scale(weight);
        next.direct = false;
        next
    }

    /// Multiplies every lane by `factor`.
    pub(crate) fn scale(&mut self, factor: Vec3) {
        self.diffuse *= factor;
        self.specular *= factor;
        self.transmission *= factor;
    }

    /// Adds the radiance `x` arriving along the path to `parts` through each lane; the
    /// diffuse lane's share is direct when `x` was `emitted` at a point the first scattering
    /// sees, else indirect.
    pub(crate) fn record(&self, parts: &mut Components, x: Vec3, emitted: bool) {
        let diffuse = if emitted && self.direct {
            Component::DiffuseDirect
        } else {
            Component::DiffuseIndirect
        };
        parts.add(diffuse, self.diffuse * x);
        parts.add(Component::Specular, self.specular * x);
        parts.add(Component::Transmission, self.transmission * x);
    }
}

/// The radiance of a camera sample whose ray `ray` hits `hit`: the integrator's radiance
/// at the hit through the camera segment's fog — the same value, bit for bit, as
/// [`super::shade_hit`] followed by [`volume::through_segment`] — recorded per component into
/// `parts` when given.
pub fn camera_sample(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    sampler: &mut Sampler,
    mut parts: Option<&mut Components>,
) -> Vec3 {
    let l = shade_hit_split(ctx, ray, hit, sampler, parts.as_deref_mut());
    if ctx.volumes.is_none() {
        return l;
    }
    let seg = volume::segment(ctx, ray, hit, sampler);
    scale(&mut parts, seg.transmittance);
    note(&mut parts, Component::Volume, seg.inscattered);
    seg.apply(l)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn components_add_scale_and_sum() {
        let mut c = Components::default();
        c.add(Component::Emission, Vec3::ONE);
        c.add(Component::Volume, Vec3::new(1.0, 2.0, 3.0));
        c.add(Component::Emission, Vec3::ONE);
        c.scale(Vec3::splat(0.5));
        assert_eq!(c.parts[0], Vec3::ONE);
        assert_eq!(c.parts[5], Vec3::new(0.5, 1.0, 1.5));
        assert_eq!(c.total(), Vec3::new(1.5, 2.0, 2.5));
        assert_eq!(Component::ALL.map(Component::index), [0, 1, 2, 3, 4, 5]);
    }
}

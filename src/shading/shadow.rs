//! Shadow shaders: what a shadow ray keeps when it crosses a surface.
//!
//! mental ray calls the shadow shader of every object between a light and the point being lit;
//! an object without one blocks all light. A material's own shadow shader (`Material::shadow`,
//! RON `shadow:`, `.mi` `mib_shadow_transparency`) decides when it has one: shadow rays keep
//! its colour per channel, whatever the surface shader (black blocks). Without one the rule
//! is derived from the surface shader, so that a shadow matches what a camera sees through
//! the same surface:
//!
//! * `Opacity` (`mib_opacity`) lets `1 − opacity` through per channel — exactly the weight of
//!   its straight pass-through ray — so a partly transparent, coloured sheet tints shadows by
//!   its transparency colour (nested `Opacity` shaders multiply);
//! * every other shader blocks (glass included: light refracted by glass is a caustic, which
//!   shadow rays do not find).
//!
//! A bound opacity (a texture driving `opacity`, e.g. a glTF alpha cut-out) is evaluated
//! at the point the shadow ray crosses, so the shadow has the holes the camera sees.
//!
//! A shadow ray crosses at most [`MAX_CROSSINGS`] transmissive surfaces (then it counts as
//! blocked); the walk is deterministic (closest hits in order along the segment).

use std::borrow::Cow;

use glam::Vec3;

use crate::accel::{
    spawn_ray, spawn_ray_to, spawn_ray_to_surface, Hit, Ray, RayKind, SurfacePoint,
};
use crate::components::{Material, Shader};
use crate::geometry::SceneGeometry;
use crate::shading::texture::hit as textured;

/// Most transmissive surfaces one shadow ray crosses before it counts as blocked.
pub const MAX_CROSSINGS: u32 = 16;

/// Fraction of light a surface with this shader lets through to shadow rays; `None` blocks.
pub fn shadow_transmittance(shader: &Shader) -> Option<Vec3> {
    match shader {
        Shader::Opacity { opacity, input } => {
            let own = (Vec3::ONE - *opacity).clamp(Vec3::ZERO, Vec3::ONE);
            let t = match shadow_transmittance(input) {
                // The input itself is transparent too: what passes the blend's opaque part.
                Some(inner) => own + *opacity * inner,
                None => own,
            };
            (t.max_element() > 0.0).then_some(t)
        }
        _ => None,
    }
}

/// Whether any light passes surfaces with this shader.
pub fn shader_transmits_shadows(shader: &Shader) -> bool {
    shadow_transmittance(shader).is_some()
}

/// What shadow rays keep crossing a material with this shader and shadow shader: the shadow
/// shader's colour when it has one, else what the surface shader implies; `None` blocks.
pub fn material_shadow(shadow: Option<Vec3>, shader: &Shader) -> Option<Vec3> {
    match shadow {
        Some(t) => (t.max_element() > 0.0).then_some(t),
        None => shadow_transmittance(shader),
    }
}

/// Whether shadow rays pass this material's constant shaders (its shadow shader, or its
/// surface shader when it has none), ignoring texture-driven opacity.
pub fn material_passes_shadows(material: &Material) -> bool {
    material_shadow(material.shadow, &material.shader).is_some()
}

/// Whether a graph drives the material's `opacity` (its own or an `Opacity` input's).
fn binds_opacity(material: &Material) -> bool {
    material.graph.as_deref().is_some_and(|g| {
        g.bindings
            .iter()
            .any(|b| b.param == "opacity" || b.param.ends_with(".opacity"))
    })
}

/// Whether shadow rays may pass surfaces of this material somewhere: its shadow shader
/// transmits, or (without one) its shader transmits or a texture drives its opacity.
pub fn material_transmits_shadows(material: &Material) -> bool {
    match material.shadow {
        Some(_) => material_passes_shadows(material),
        None => shader_transmits_shadows(&material.shader) || binds_opacity(material),
    }
}

/// The shader a shadow ray meets at `hit`: the material's, with its bound parameters
/// evaluated there when a texture drives its opacity.
fn shader_at<'a>(geometry: &SceneGeometry, hit: &Hit, material: &'a Material) -> Cow<'a, Shader> {
    if !binds_opacity(material) {
        return Cow::Borrowed(&material.shader);
    }
    let sp = geometry.shading_point(hit);
    match textured::evaluate(geometry, &sp, hit, material) {
        Some(t) => Cow::Owned(t.shader),
        None => Cow::Borrowed(&material.shader),
    }
}

/// The ray from `from` toward `target` (a surface point, an exact point when its normal is
/// zero, or infinity along `wi` when `None`).
#[inline(always)]
pub(crate) fn shadow_ray(from: &SurfacePoint, wi: Vec3, target: Option<&SurfacePoint>) -> Ray {
    match target {
        None => spawn_ray(from, wi),
        Some(t) if t.ng == Vec3::ZERO => spawn_ray_to(from, t.p),
        Some(t) => spawn_ray_to_surface(from, t),
    }
}

/// Transmittance of the shadow segment from `from` toward a light sample: 1 when nothing is
/// in the way, 0 when something opaque is, the product of the crossed surfaces' shadow
/// transmittances otherwise. `tinted`: some material of the scene transmits (otherwise a
/// cheaper any-hit test decides).
#[inline(always)]
pub fn transmittance(
    geometry: &SceneGeometry,
    from: &SurfacePoint,
    wi: Vec3,
    target: Option<SurfacePoint>,
    tinted: bool,
) -> Vec3 {
    let ray = shadow_ray(from, wi, target.as_ref());
    if !tinted {
        return if geometry.accel.occluded_as(&ray, RayKind::Shadow) {
            Vec3::ZERO
        } else {
            Vec3::ONE
        };
    }
    let mut t = Vec3::ONE;
    let mut ray = ray;
    for _ in 0..=MAX_CROSSINGS {
        let Some(hit) = geometry.accel.intersect_as(&ray, RayKind::Shadow) else {
            return t;
        };
        let material = geometry.material_of(hit.prim);
        let tr = match material.shadow {
            Some(_) => material_shadow(material.shadow, &material.shader),
            None => shadow_transmittance(&shader_at(geometry, &hit, material)),
        };
        let Some(tr) = tr else {
            return Vec3::ZERO;
        };
        t *= tr;
        if t.max_element() <= 0.0 {
            return Vec3::ZERO;
        }
        let sp = geometry.accel.surface_point(&hit);
        ray = shadow_ray(&sp, wi, target.as_ref());
    }
    Vec3::ZERO
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn opacity_lets_its_transparency_through() {
        let s = Shader::Opacity {
            opacity: Vec3::new(0.5, 1.0, 0.75),
            input: Box::new(Shader::Lambert { albedo: Vec3::ONE }),
        };
        assert_eq!(shadow_transmittance(&s), Some(Vec3::new(0.5, 0.0, 0.25)));
        assert_eq!(
            shadow_transmittance(&Shader::Lambert { albedo: Vec3::ONE }),
            None
        );
        let opaque = Shader::Opacity {
            opacity: Vec3::ONE,
            input: Box::new(Shader::Lambert { albedo: Vec3::ONE }),
        };
        assert_eq!(shadow_transmittance(&opaque), None);
    }

    #[test]
    fn a_shadow_shader_overrides_the_surface_shader() {
        let lambert = Shader::Lambert { albedo: Vec3::ONE };
        let half = Vec3::splat(0.5);
        assert_eq!(material_shadow(Some(half), &lambert), Some(half));
        let sheet = Shader::Opacity {
            opacity: half,
            input: Box::new(lambert.clone()),
        };
        assert_eq!(material_shadow(Some(Vec3::ZERO), &sheet), None);
        assert_eq!(material_shadow(None, &sheet), Some(half));
        assert_eq!(material_shadow(None, &lambert), None);
    }
}

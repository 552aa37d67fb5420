//! Microfacet reflection `F(wo·h) · D(h) · G / (4 cosθo cosθi)` with V-cavity masking, used
//! by Blinn, Cook–Torrance, blong, Fresnel-weighted specular and the RenderMan `specular()`
//! highlight. Sampled by the distribution of normals (pdf `D cosθh / (4 wo·h)`).

use glam::{Vec2, Vec3};

use crate::shading::fresnel::fr_dielectric;
use crate::shading::microfacet::{g_vcavity, Distribution};

/// The Fresnel factor of a glossy lobe.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Fresnel {
    /// No Fresnel factor (1): the lobe's weight is its colour.
    One,
    /// Dielectric reflectance with a relative index per colour channel.
    Dielectric(Vec3),
}

impl Fresnel {
    fn eval(&self, cos: f32) -> Vec3 {
        match *self {
            Fresnel::One => Vec3::ONE,
            Fresnel::Dielectric(eta) => Vec3::new(
                fr_dielectric(cos, eta.x),
                fr_dielectric(cos, eta.y),
                fr_dielectric(cos, eta.z),
            ),
        }
    }
}

fn half_vector(wo: Vec3, wi: Vec3) -> Option<Vec3> {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return None;
    }
    let h = (wo + wi).normalize_or_zero();
    (h != Vec3::ZERO).then_some(h)
}

/// BRDF value.
pub fn eval(dist: &Distribution, fresnel: &Fresnel, wo: Vec3, wi: Vec3) -> Vec3 {
    let Some(h) = half_vector(wo, wi) else {
        return Vec3::ZERO;
    };
    let g = g_vcavity(wo, wi, h);
    if g <= 0.0 {
        return Vec3::ZERO;
    }
    let v = dist.d(h) * g / (4.0 * wo.z * wi.z);
    if !v.is_finite() {
        return Vec3::ZERO;
    }
    fresnel.eval(wo.dot(h)) * v
}

/// Solid-angle pdf of [`sample`].
pub fn pdf(dist: &Distribution, wo: Vec3, wi: Vec3) -> f32 {
    let Some(h) = half_vector(wo, wi) else {
        return 0.0;
    };
    let oh = wo.dot(h);
    if oh <= 0.0 {
        return 0.0;
    }
    let p = dist.d(h) * h.z / (4.0 * oh);
    if p.is_finite() {
        p
    } else {
        0.0
    }
}

/// Reflects `wo` about a sampled microfacet normal; `None` when the result is below the
/// horizon or the normal faces away from `wo`.
pub fn sample(dist: &Distribution, wo: Vec3, u: Vec2) -> Option<Vec3> {
    if wo.z <= 0.0 {
        return None;
    }
    let h = dist.sample_h(u);
    let oh = wo.dot(h);
    if oh <= 0.0 {
        return None;
    }
    let wi = 2.0 * oh * h - wo;
    (wi.z > 0.0).then_some(wi)
}

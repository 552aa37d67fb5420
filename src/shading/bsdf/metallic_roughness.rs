//! The glTF 2.0 metallic-roughness BRDF (glTF specification, appendix B), as one lobe:
//!
//! ```text
//! α          = roughness²
//! specular   = D_GGX(h; α) · V_Smith(α)              (V = G / (4 cosθo cosθi), height-correlated)
//! dielectric = w(θo) w(θi) / 0.96 · base/π + F(0.04) · specular  (fresnel_mix, ior 1.5)
//! metal      = F(base) · specular                               (conductor_fresnel)
//! f          = (1 − metallic) · dielectric + metallic · metal
//! F(f0)      = f0 + (1 − f0)(1 − |wo·h|)⁵                       (Schlick)
//! w(θ)       = 1 − F(0.04) at cosθ to the normal
//! ```
//!
//! One departure from the specification's `fresnel_mix`: the diffuse term is weighted by
//! `w(θo)·w(θi)/0.96` (the Fresnel transmission into and out of the surface, reciprocal)
//! instead of `1 − F(0.04)` at `wo·h`. The specification's form reflects up to 3 % more than
//! it receives at grazing angles (measured: albedo 1.028 at cosθo = 0.01 for base 0.9,
//! metallic 0.5, roughness 0.4); at normal incidence both weigh the diffuse term by 0.96.
//!
//! Sampled by choosing the GGX lobe (distribution of normals, as [`super::glossy`]) with
//! probability `p = ½ + ½·metallic` and the cosine lobe otherwise; [`pdf`] is the mixture.
//! The smooth limit (roughness below [`SMOOTH_ROUGHNESS`]) is not this lobe: the material
//! becomes a Lambert lobe of weight `(1 − metallic)·0.96·base` plus a mirror of weight
//! `metallic·base + (1 − metallic)·0.04` (Schlick at normal incidence), so a polished metal
//! is our mirror and the direct-lighting integrator traces it.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::{diffuse, glossy};
use crate::shading::microfacet::Distribution;

/// Perceptual roughness below which the specular lobe is a mirror (α = 4·10⁻⁴).
pub const SMOOTH_ROUGHNESS: f32 = 0.02;

/// Reflectance of the dielectric part at normal incidence (ior 1.5).
pub const DIELECTRIC_F0: f32 = 0.04;

/// The lobe's parameters (linear base colour, metallic and α in \[0, 1\]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MetallicRoughness {
    /// Base colour (linear RGB, each in \[0, 1\]).
    pub base: Vec3,
    /// Metalness in \[0, 1\].
    pub metallic: f32,
    /// GGX width `α = roughness²`, at least `SMOOTH_ROUGHNESS²`.
    pub alpha: f32,
}

impl MetallicRoughness {
    fn dist(&self) -> Distribution {
        Distribution::Ggx { alpha: self.alpha }
    }

    fn p_specular(&self) -> f32 {
        0.5 + 0.5 * self.metallic
    }
}

/// Height-correlated Smith visibility `G₂ / (4 cosθo cosθi)` for GGX.
fn visibility(alpha: f32, cos_o: f32, cos_i: f32) -> f32 {
    let a2 = alpha * alpha;
    let go = cos_i * (cos_o * cos_o * (1.0 - a2) + a2).sqrt();
    let gi = cos_o * (cos_i * cos_i * (1.0 - a2) + a2).sqrt();
    let sum = go + gi;
    if sum > 0.0 {
        0.5 / sum
    } else {
        0.0
    }
}

/// `1 − F(0.04)` at the angle whose cosine is `cos` (to the normal).
fn diffuse_weight(cos: f32) -> f32 {
    1.0 - schlick(Vec3::splat(DIELECTRIC_F0), cos).x
}

fn schlick(f0: Vec3, cos: f32) -> Vec3 {
    let m = (1.0 - cos.clamp(0.0, 1.0)).powi(5);
    f0 + (Vec3::ONE - f0) * m
}

/// BRDF value for light from `wi` leaving along `wo` (both local, above the surface).
pub fn eval(m: &MetallicRoughness, wo: Vec3, wi: Vec3) -> Vec3 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return Vec3::ZERO;
    }
    let h = (wo + wi).normalize_or_zero();
    if h == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let vh = wo.dot(h).abs();
    let specular = m.dist().d(h) * visibility(m.alpha, wo.z, wi.z);
    let specular = if specular.is_finite() { specular } else { 0.0 };
    let f_dielectric = schlick(Vec3::splat(DIELECTRIC_F0), vh).x;
    let diffuse = diffuse_weight(wo.z) * diffuse_weight(wi.z) / (1.0 - DIELECTRIC_F0);
    let dielectric = m.base * (diffuse * FRAC_1_PI) + Vec3::splat(f_dielectric * specular);
    let metal = schlick(m.base, vh) * specular;
    dielectric * (1.0 - m.metallic) + metal * m.metallic
}

/// The diffuse base of [`eval`] (its dielectric part's Lambert-like term), for component
/// passes; the rest of [`eval`] is the glossy highlight.
pub fn eval_diffuse(m: &MetallicRoughness, wo: Vec3, wi: Vec3) -> Vec3 {
    if wo.z <= 0.0 || wi.z <= 0.0 || (wo + wi).normalize_or_zero() == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let diffuse = diffuse_weight(wo.z) * diffuse_weight(wi.z) / (1.0 - DIELECTRIC_F0);
    m.base * (diffuse * FRAC_1_PI) * (1.0 - m.metallic)
}

/// Solid-angle pdf of [`sample`].
pub fn pdf(m: &MetallicRoughness, wo: Vec3, wi: Vec3) -> f32 {
    let p = m.p_specular();
    p * glossy::pdf(&m.dist(), wo, wi) + (1.0 - p) * diffuse::pdf(wo, wi)
}

/// Draws `wi`: the GGX lobe with probability `½ + ½·metallic` (`u.x` chooses and is
/// re-used), else a cosine direction.
pub fn sample(m: &MetallicRoughness, wo: Vec3, u: Vec2) -> Option<Vec3> {
    let p = m.p_specular();
    if u.x < p {
        let ux = (u.x / p).min(1.0 - f32::EPSILON);
        glossy::sample(&m.dist(), wo, Vec2::new(ux, u.y))
    } else {
        let ux = ((u.x - p) / (1.0 - p)).clamp(0.0, 1.0 - f32::EPSILON);
        diffuse::sample(wo, Vec2::new(ux, u.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eval_is_reciprocal_and_the_metal_tints_its_highlight() {
        let m = MetallicRoughness {
            base: Vec3::new(0.9, 0.5, 0.2),
            metallic: 1.0,
            alpha: 0.25,
        };
        let wo = Vec3::new(0.3, 0.1, 0.9).normalize();
        let wi = Vec3::new(-0.2, -0.1, 0.95).normalize();
        let a = eval(&m, wo, wi);
        let b = eval(&m, wi, wo);
        assert!(
            (a - b).abs().max_element() < 1e-5 * a.max_element(),
            "{a} {b}"
        );
        assert!(a.x > a.y && a.y > a.z, "{a}");
    }

    #[test]
    fn a_rough_dielectric_is_nearly_lambert() {
        // metallic 0, roughness 1: the diffuse term (1 − F)·base/π dominates.
        let m = MetallicRoughness {
            base: Vec3::splat(0.5),
            metallic: 0.0,
            alpha: 1.0,
        };
        let f = eval(&m, Vec3::Z, Vec3::Z);
        let lambert = 0.5 * FRAC_1_PI;
        assert!((f.x - lambert).abs() < 0.15 * lambert, "{f} vs {lambert}");
    }
}

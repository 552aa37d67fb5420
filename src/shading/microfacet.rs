//! Microfacet normal distributions and the V-cavity masking-shadowing term of the original
//! Cook–Torrance model, in the local shading frame (normal = +Z).
//!
//! Both distributions are normalised (`∫ D(h) cosθh dω = 1`) and sampled exactly in
//! proportion to `D(h) cosθh`; the V-cavity `G` is a valid masking-shadowing function for any
//! `D`, so a microfacet lobe with Fresnel ≤ 1 never reflects more than it receives.

use std::f32::consts::{FRAC_1_PI, PI};

use glam::{Vec2, Vec3};

/// A distribution of microfacet normals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Distribution {
    /// Beckmann with RMS slope `alpha` (Cook–Torrance "roughness" `m`).
    Beckmann {
        /// RMS slope of the microfacets, > 0.
        alpha: f32,
    },
    /// Normalised Blinn–Phong: `D = (n + 2)/(2π) cosⁿθh`.
    BlinnPhong {
        /// Exponent `n` ≥ 0.
        exponent: f32,
    },
    /// GGX / Trowbridge–Reitz (the glTF metallic-roughness model's distribution):
    /// `D = α² / (π cos⁴θh (α² + tan²θh)²)`.
    Ggx {
        /// Width `α` (glTF: perceptual roughness squared), > 0.
        alpha: f32,
    },
}

impl Distribution {
    /// Density of microfacet normal `h` (local, unit, `h.z > 0`), per steradian of projected
    /// area.
    pub fn d(&self, h: Vec3) -> f32 {
        let cos = h.z;
        if cos <= 0.0 {
            return 0.0;
        }
        match *self {
            Distribution::Beckmann { alpha } => {
                let cos2 = cos * cos;
                let tan2 = ((1.0 - cos2) / cos2).max(0.0);
                let a2 = alpha * alpha;
                let v = (-tan2 / a2).exp() * FRAC_1_PI / (a2 * cos2 * cos2);
                if v.is_finite() {
                    v
                } else {
                    0.0
                }
            }
            Distribution::BlinnPhong { exponent } => {
                (exponent + 2.0) * 0.5 * FRAC_1_PI * cos.powf(exponent)
            }
            Distribution::Ggx { alpha } => {
                let a2 = alpha * alpha;
                let cos2 = cos * cos;
                let k = cos2 * (a2 - 1.0) + 1.0;
                let v = a2 * FRAC_1_PI / (k * k);
                if v.is_finite() {
                    v
                } else {
                    0.0
                }
            }
        }
    }

    /// Samples a microfacet normal with pdf `D(h) cosθh` (per steradian of `h`).
    pub fn sample_h(&self, u: Vec2) -> Vec3 {
        let cos = match *self {
            Distribution::Beckmann { alpha } => {
                let tan2 = -alpha * alpha * (1.0 - u.x).max(f32::MIN_POSITIVE).ln();
                1.0 / (1.0 + tan2).sqrt()
            }
            Distribution::BlinnPhong { exponent } => u.x.powf(1.0 / (exponent + 2.0)),
            Distribution::Ggx { alpha } => {
                let tan2 = alpha * alpha * u.x / (1.0 - u.x).max(f32::MIN_POSITIVE);
                1.0 / (1.0 + tan2).sqrt()
            }
        };
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        Vec3::new(sin * phi.cos(), sin * phi.sin(), cos)
    }
}

/// V-cavity masking-shadowing (Cook & Torrance 1982):
/// `min(1, 2 cosθh cosθo / (wo·h), 2 cosθh cosθi / (wo·h))`.
pub fn g_vcavity(wo: Vec3, wi: Vec3, h: Vec3) -> f32 {
    let oh = wo.dot(h);
    if oh <= 0.0 || wi.dot(h) <= 0.0 || wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let k = 2.0 * h.z / oh;
    (k * wo.z).min(k * wi.z).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ D(h) cosθh dω over the hemisphere, midpoint rule in (cosθ, φ).
    fn projected_area(d: &Distribution) -> f64 {
        let n = 4000;
        let mut sum = 0.0f64;
        for i in 0..n {
            let cos = (i as f64 + 0.5) / n as f64;
            let h = Vec3::new((1.0 - cos * cos).sqrt() as f32, 0.0, cos as f32);
            sum += d.d(h) as f64 * cos;
        }
        sum / n as f64 * 2.0 * std::f64::consts::PI
    }

    #[test]
    fn distributions_are_normalised() {
        for d in [
            Distribution::Beckmann { alpha: 0.1 },
            Distribution::Beckmann { alpha: 0.5 },
            Distribution::Beckmann { alpha: 1.0 },
            Distribution::BlinnPhong { exponent: 0.0 },
            Distribution::BlinnPhong { exponent: 10.0 },
            Distribution::BlinnPhong { exponent: 200.0 },
            Distribution::Ggx { alpha: 0.3 },
            Distribution::Ggx { alpha: 1.0 },
        ] {
            let a = projected_area(&d);
            assert!((a - 1.0).abs() < 2e-3, "{d:?}: {a}");
        }
    }
}

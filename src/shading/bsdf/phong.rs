//! The energy-normalised (modified) Phong lobe of mental ray's `mi_phong_specular`:
//! `f = (n + 2)/(2π) · cosⁿα`, α the angle between `wi` and the mirror direction of `wo`.
//! Its albedo is at most 1, reached at normal incidence (Lafortune & Willems 1994).

use std::f32::consts::{FRAC_1_PI, PI};

use glam::{Vec2, Vec3};

use crate::shading::frame::ShadingFrame;

fn mirror(wo: Vec3) -> Vec3 {
    Vec3::new(-wo.x, -wo.y, wo.z)
}

/// BRDF value.
pub fn eval(exponent: f32, wo: Vec3, wi: Vec3) -> f32 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let c = mirror(wo).dot(wi);
    if c <= 0.0 {
        return 0.0;
    }
    (exponent + 2.0) * 0.5 * FRAC_1_PI * c.min(1.0).powf(exponent)
}

/// Solid-angle pdf of [`sample`]: `(n + 1)/(2π) cosⁿα` on the upper hemisphere.
pub fn pdf(exponent: f32, wo: Vec3, wi: Vec3) -> f32 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let c = mirror(wo).dot(wi);
    if c <= 0.0 {
        return 0.0;
    }
    (exponent + 1.0) * 0.5 * FRAC_1_PI * c.min(1.0).powf(exponent)
}

/// Direction distributed as `cosⁿα` about the mirror direction; `None` below the horizon.
pub fn sample(exponent: f32, wo: Vec3, u: Vec2) -> Option<Vec3> {
    if wo.z <= 0.0 {
        return None;
    }
    let cos = u.x.powf(1.0 / (exponent + 1.0));
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    let frame = ShadingFrame::from_normal(mirror(wo));
    let wi = frame.to_world(Vec3::new(sin * phi.cos(), sin * phi.sin(), cos));
    (wi.z > 0.0 && wi.is_finite()).then(|| wi.normalize())
}

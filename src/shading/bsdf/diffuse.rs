//! Lambertian reflection (BRDF `1/π` per unit weight), cosine-weighted sampling.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use crate::sampling::sample_cosine_hemisphere;

/// BRDF value for `wo`, `wi` in the local frame.
#[inline]
pub fn eval(wo: Vec3, wi: Vec3) -> f32 {
    if wo.z > 0.0 && wi.z > 0.0 {
        FRAC_1_PI
    } else {
        0.0
    }
}

/// Solid-angle pdf of [`sample`].
#[inline]
pub fn pdf(wo: Vec3, wi: Vec3) -> f32 {
    if wo.z > 0.0 && wi.z > 0.0 {
        wi.z * FRAC_1_PI
    } else {
        0.0
    }
}

/// Cosine-weighted direction on the upper hemisphere.
#[inline]
pub fn sample(wo: Vec3, u: Vec2) -> Option<Vec3> {
    if wo.z <= 0.0 {
        return None;
    }
    let wi = sample_cosine_hemisphere(u);
    (wi.z > 0.0).then_some(wi)
}

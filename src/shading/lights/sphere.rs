//! Sphere light: uniform sampling of the cone of directions the sphere subtends (pbrt-v4
//! `Sphere::Sample`), so every sample hits the visible cap and the pdf is constant in solid
//! angle; the analytic ray crossing for BSDF-sampled rays.

use std::f32::consts::PI;

use glam::{DVec3, Vec2, Vec3};

use super::{error_target, LightSample};
use crate::accel::Ray;
use crate::shading::frame::ShadingFrame;

/// Below this `sin²θmax` the cone is sampled with the small-angle form (pbrt-v4).
const SMALL_CONE: f32 = 0.000_685_23;

/// A sphere emitting outward.
#[derive(Debug, Clone, Copy)]
pub struct SphereLight {
    /// Centre.
    pub center: Vec3,
    /// Radius.
    pub radius: f32,
}

/// The cone the sphere subtends from a point outside: `(sin²θmax, 1 − cosθmax)`.
fn cone(dc2: f32, r: f32) -> (f32, f32) {
    let sin2_max = (r * r / dc2).min(1.0);
    let one_minus_cos = if sin2_max < SMALL_CONE {
        sin2_max / 2.0
    } else {
        1.0 - (1.0 - sin2_max).max(0.0).sqrt()
    };
    (sin2_max, one_minus_cos)
}

impl SphereLight {
    /// Solid-angle pdf of directions toward the sphere from `p` (outside it).
    pub fn cone_pdf(&self, p: Vec3) -> Option<f32> {
        let dc2 = (self.center - p).length_squared();
        if dc2.is_nan() || dc2 <= self.radius * self.radius {
            return None;
        }
        let (_, one_minus_cos) = cone(dc2, self.radius);
        let pdf = 1.0 / (2.0 * PI * one_minus_cos);
        (pdf.is_finite() && pdf > 0.0).then_some(pdf)
    }

    /// A direction uniform in the subtended cone from `p` and the point of the sphere it meets
    /// (radiance 1). Points inside the sphere see only its back: `None`.
    pub fn sample(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let to_c = self.center - p;
        let dc2 = to_c.length_squared();
        let r = self.radius;
        if !dc2.is_finite() || dc2 <= r * r {
            return None;
        }
        let dc = dc2.sqrt();
        let (sin2_max, one_minus_cos) = cone(dc2, r);
        let sin_max = sin2_max.sqrt();
        let (cos_t, sin2_t) = if sin2_max < SMALL_CONE {
            let s2 = sin2_max * u.x;
            ((1.0 - s2).sqrt(), s2)
        } else {
            let c = 1.0 - one_minus_cos * u.x;
            (c, (1.0 - c * c).max(0.0))
        };
        // Angle at the centre between −axis and the surface point (pbrt-v4).
        let cos_a = sin2_t / sin_max + cos_t * (1.0 - sin2_t / sin2_max).max(0.0).sqrt();
        let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let frame = ShadingFrame::from_normal(to_c / dc);
        // Normal at the sampled point: from the centre back toward p, tilted by α.
        let n = frame.to_world(Vec3::new(-sin_a * phi.cos(), -sin_a * phi.sin(), -cos_a));
        let q = self.center + n * r;
        let d = q - p;
        let dist2 = d.length_squared();
        if dist2.is_nan() || dist2 <= 0.0 {
            return None;
        }
        let dist = dist2.sqrt();
        let pdf = 1.0 / (2.0 * PI * one_minus_cos);
        if !pdf.is_finite() {
            return None;
        }
        Some(LightSample {
            wi: d / dist,
            contribution: Vec3::splat(1.0 / pdf),
            target: Some(error_target(q, n)),
            shadows: true,
            shadow_factor: 0.0,
            pdf,
            distance: dist,
        })
    }

    /// Ray parameter and solid-angle pdf where `ray` (from outside) meets the sphere.
    pub fn hit(&self, ray: &Ray) -> Option<(f32, f32)> {
        // f64: the quadratic cancels badly for small, distant spheres.
        let o = ray.origin.as_dvec3() - self.center.as_dvec3();
        let d: DVec3 = ray.dir.as_dvec3();
        let r = f64::from(self.radius);
        let a = d.length_squared();
        let c = o.length_squared() - r * r;
        if c.is_nan() || c <= 0.0 || a == 0.0 {
            return None; // inside (or on) the sphere: its back faces emit nothing
        }
        let b = o.dot(d);
        if b >= 0.0 {
            return None; // moving away
        }
        // Distance² from the centre to the line, robustly (Hearn–Baker form).
        let perp = o - d * (b / a);
        let disc = r * r - perp.length_squared();
        if disc < 0.0 {
            return None;
        }
        let q = -b + (a * disc).sqrt();
        let t = (c / q) as f32;
        if !(t > 0.0 && t < ray.t_max) {
            return None;
        }
        Some((t, self.cone_pdf(ray.origin)?))
    }
}

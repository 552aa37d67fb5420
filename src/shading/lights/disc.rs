//! One-sided disc light: uniform area sampling (concentric mapping) converted to solid
//! angle, and the analytic ray crossing.

use glam::{Vec2, Vec3};

use super::{solid_angle_sample, surface_target, LightSample};
use crate::accel::Ray;
use crate::sampling::sample_concentric_disk;
use crate::shading::frame::ShadingFrame;

/// A disc of `radius` about `center`, emitting along `normal`.
#[derive(Debug, Clone, Copy)]
pub struct DiscLight {
    /// Centre.
    pub center: Vec3,
    /// Frame whose `n` is the emitting normal.
    pub frame: ShadingFrame,
    /// Radius.
    pub radius: f32,
}

impl DiscLight {
    /// The disc of `radius` about `center` facing `normal` (any length).
    pub fn new(center: Vec3, normal: Vec3, radius: f32) -> Self {
        Self {
            center,
            frame: ShadingFrame::from_normal(normal.normalize_or_zero()),
            radius,
        }
    }

    fn area(&self) -> f32 {
        std::f32::consts::PI * self.radius * self.radius
    }

    /// A uniform point on the disc seen from `p` (radiance 1).
    pub fn sample(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let d = sample_concentric_disk(u) * self.radius;
        let q = self.center + self.frame.s * d.x + self.frame.t * d.y;
        solid_angle_sample(p, surface_target(q, self.frame.n), false, self.area())
    }

    /// Ray parameter and solid-angle pdf where `ray` meets the front face.
    pub fn hit(&self, ray: &Ray) -> Option<(f32, f32)> {
        let n = self.frame.n;
        let denom = ray.dir.dot(n);
        if denom.is_nan() || denom >= 0.0 {
            return None;
        }
        let t = (self.center - ray.origin).dot(n) / denom;
        if !(t > 0.0 && t < ray.t_max) {
            return None;
        }
        let q = ray.origin + ray.dir * t - self.center;
        let r2 = q.length_squared() - q.dot(n).powi(2);
        if r2 > self.radius * self.radius {
            return None;
        }
        let len = ray.dir.length();
        let dist = t * len;
        let cos_l = -denom / len;
        let pdf = dist * dist / (cos_l * self.area());
        (pdf.is_finite() && pdf > 0.0).then_some((t, pdf))
    }
}

//! Cylinder light: an open tube emitting outward. From a point outside, exactly the strip of
//! angles `|φ − φ_p| < acos(r/ρ)` faces the point (ρ: its distance from the axis), so the
//! sampler draws φ uniformly in that arc and the height uniformly: every sample faces the
//! shading point; the area pdf is converted to solid angle. The arc is trimmed by a relative
//! 10⁻² at both ends (rays there graze the tube and rounding decides whether they hit it);
//! the trimmed slivers face the point at cos < 0.02 and send it about 10⁻⁴ of the light,
//! which the light (sampled and hit alike) leaves out.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::{solid_angle_sample, surface_target, LightSample};
use crate::accel::Ray;
use crate::shading::frame::ShadingFrame;

/// Relative trim of the sampled arc at each end.
const ARC_TRIM: f32 = 1e-2;

/// A tube of `radius` from `start` to `start + frame.n · length`.
#[derive(Debug, Clone, Copy)]
pub struct CylinderLight {
    /// Centre of the first end.
    pub start: Vec3,
    /// Frame whose `n` is the unit axis.
    pub frame: ShadingFrame,
    /// Axis length.
    pub length: f32,
    /// Radius.
    pub radius: f32,
}

impl CylinderLight {
    /// The tube from `start` to `end`.
    pub fn new(start: Vec3, end: Vec3, radius: f32) -> Self {
        let axis = end - start;
        Self {
            start,
            frame: ShadingFrame::from_normal(axis.normalize_or_zero()),
            length: axis.length(),
            radius,
        }
    }

    /// Local coordinates of `p`: (distance from the axis, angle φ_p, half-width of the
    /// visible arc); `None` inside the tube.
    fn visible_arc(&self, p: Vec3) -> Option<(f32, f32)> {
        let l = self.frame.to_local(p - self.start);
        let rho = (l.x * l.x + l.y * l.y).sqrt();
        if rho.is_nan() || rho <= self.radius {
            return None;
        }
        let half = (self.radius / rho).clamp(-1.0, 1.0).acos() * (1.0 - ARC_TRIM);
        (half > 0.0).then(|| (l.y.atan2(l.x), half))
    }

    /// A point of the part of the tube facing `p` (radiance 1).
    pub fn sample(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let (phi_p, half) = self.visible_arc(p)?;
        let phi = phi_p + (2.0 * u.x - 1.0) * half;
        let n = self.frame.s * phi.cos() + self.frame.t * phi.sin();
        let q = self.start + self.frame.n * (u.y * self.length) + n * self.radius;
        let area = 2.0 * half * self.radius * self.length;
        solid_angle_sample(p, surface_target(q, n), false, area)
    }

    /// Ray parameter and solid-angle pdf where `ray` (from outside) meets the outer face.
    pub fn hit(&self, ray: &Ray) -> Option<(f32, f32)> {
        let (phi_p, half) = self.visible_arc(ray.origin)?;
        let o = self.frame.to_local(ray.origin - self.start).as_dvec3();
        let d = self.frame.to_local(ray.dir).as_dvec3();
        let r = f64::from(self.radius);
        let a = d.x * d.x + d.y * d.y;
        if a == 0.0 {
            return None;
        }
        let b = o.x * d.x + o.y * d.y;
        let c = o.x * o.x + o.y * o.y - r * r;
        if b >= 0.0 {
            return None; // moving away from the axis: cannot meet the outer face
        }
        let disc = b * b - a * c;
        if disc < 0.0 {
            return None;
        }
        // Entry point (outer face), the numerically stable root.
        let t = c / (-b + disc.sqrt());
        let z = o.z + t * d.z;
        let t = t as f32;
        if !(t > 0.0 && t < ray.t_max && (0.0..=f64::from(self.length)).contains(&z)) {
            return None;
        }
        let len = ray.dir.length();
        let hp = o + d * f64::from(t);
        let n = Vec3::new(hp.x as f32, hp.y as f32, 0.0) / self.radius;
        let dphi = (n.y.atan2(n.x) - phi_p + PI).rem_euclid(2.0 * PI) - PI;
        if dphi.abs() > half {
            return None;
        }
        let cos_l = -n.dot(self.frame.to_local(ray.dir)) / len;
        if cos_l.is_nan() || cos_l <= 0.0 {
            return None;
        }
        let dist = t * len;
        let area = 2.0 * half * self.radius * self.length;
        let pdf = dist * dist / (cos_l * area);
        (pdf.is_finite() && pdf > 0.0).then_some((t, pdf))
    }
}

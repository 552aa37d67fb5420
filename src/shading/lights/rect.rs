//! One-sided parallelogram light: uniform area sampling converted to solid angle, and the
//! analytic ray crossing for BSDF-sampled rays.

use glam::{Vec2, Vec3};

use super::{solid_angle_sample, surface_target, LightSample};
use crate::accel::Ray;

/// A parallelogram `corner + s·edge_u + t·edge_v`, emitting along `edge_u × edge_v`.
#[derive(Debug, Clone, Copy)]
pub struct RectLight {
    /// Corner.
    pub corner: Vec3,
    /// First edge.
    pub edge_u: Vec3,
    /// Second edge.
    pub edge_v: Vec3,
    /// Unit emitting normal `edge_u × edge_v`.
    pub normal: Vec3,
    /// Area, m².
    pub area: f32,
}

impl RectLight {
    /// The light spanned by a corner and two edges.
    pub fn new(corner: Vec3, edge_u: Vec3, edge_v: Vec3) -> Self {
        let c = edge_u.cross(edge_v);
        Self {
            corner,
            edge_u,
            edge_v,
            normal: c.normalize_or_zero(),
            area: c.length(),
        }
    }

    /// A uniform point on the rectangle seen from `p` (radiance 1).
    pub fn sample(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let q = self.corner + self.edge_u * u.x + self.edge_v * u.y;
        solid_angle_sample(p, surface_target(q, self.normal), false, self.area)
    }

    /// Ray parameter and solid-angle pdf where `ray` meets the front face.
    pub fn hit(&self, ray: &Ray) -> Option<(f32, f32)> {
        let denom = ray.dir.dot(self.normal);
        if denom.is_nan() || denom >= 0.0 {
            return None;
        }
        let t = (self.corner - ray.origin).dot(self.normal) / denom;
        if !(t > 0.0 && t < ray.t_max) {
            return None;
        }
        let q = ray.origin + ray.dir * t - self.corner;
        // Coordinates of q in the (edge_u, edge_v) basis via the dual basis.
        let (eu, ev) = (self.edge_u, self.edge_v);
        let (uu, uv, vv) = (eu.dot(eu), eu.dot(ev), ev.dot(ev));
        let det = uu * vv - uv * uv;
        let (qu, qv) = (q.dot(eu), q.dot(ev));
        let s = (qu * vv - qv * uv) / det;
        let r = (qv * uu - qu * uv) / det;
        if !((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&r)) {
            return None;
        }
        let len = ray.dir.length();
        let dist = t * len;
        let cos_l = -denom / len;
        let pdf = dist * dist / (cos_l * self.area);
        (pdf.is_finite() && pdf > 0.0).then_some((t, pdf))
    }
}

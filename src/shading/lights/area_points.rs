//! Points on area-light shapes, uniform by area, and mental ray's non-physical area lights:
//! an area shape on a light shader without distance falloff (`mib_light_point`,
//! `mib_light_spot`) samples a point light at a point of the shape per light sample, its
//! `Cl` the colour at every distance (no 1/d², no emitter cosine), so the light loop's mean
//! over the samples is the tutorial's sum over `mi_sample_light` divided by the samples
//! (seed 001, §3.2.2).

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::{delta_sample, AreaLight, AreaShape, LightSample};

impl AreaShape {
    /// A point on the shape (uniform by area) from `u ∈ [0,1)²` and its outward normal.
    pub fn point(&self, u: Vec2) -> (Vec3, Vec3) {
        match self {
            AreaShape::Rect(r) => (r.corner + r.edge_u * u.x + r.edge_v * u.y, r.normal),
            AreaShape::Disc(d) => {
                let p = crate::sampling::sample_concentric_disk(u) * d.radius;
                (d.center + d.frame.s * p.x + d.frame.t * p.y, d.frame.n)
            }
            AreaShape::Sphere(s) => {
                let n = uniform_sphere(u);
                (s.center + n * s.radius, n)
            }
            AreaShape::Cylinder(c) => {
                let phi = 2.0 * PI * u.y;
                let n = c.frame.s * phi.cos() + c.frame.t * phi.sin();
                (c.start + c.frame.n * (u.x * c.length) + n * c.radius, n)
            }
        }
    }

    /// The emitting area, m².
    pub fn area(&self) -> f32 {
        match self {
            AreaShape::Rect(r) => r.area,
            AreaShape::Disc(d) => PI * d.radius * d.radius,
            AreaShape::Sphere(s) => 4.0 * PI * s.radius * s.radius,
            AreaShape::Cylinder(c) => 2.0 * PI * c.radius * c.length,
        }
    }
}

/// Uniform direction on the unit sphere from `u ∈ [0,1)²`.
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A sample of the non-physical area light `a` ([`AreaLight::points`]) seen from `p`: the
/// point light of intensity `a.radiance` (its `Cl`, not falling off) at the point `u` picks
/// on the shape, with the light's near/far ramp.
pub(super) fn point_sample(a: &AreaLight, p: Vec3, u: Vec2) -> Option<LightSample> {
    let (q, _) = a.shape.point(u);
    delta_sample(
        p,
        q,
        a.radiance,
        (a.shadows, a.shadow_factor),
        (a.attenuation, false),
    )
}

#[cfg(test)]
mod tests {
    use super::super::RectLight;
    use super::*;

    /// A 2 × 2 non-physical rectangle light seen from 3 units below its centre: every sample
    /// is `Cl` = the colour (no 1/d²), from a point of the rectangle, and its mean direction
    /// over a grid of samples points at the centre.
    #[test]
    fn samples_are_point_lights_on_the_shape_without_falloff() {
        let a = AreaLight {
            shape: AreaShape::Rect(RectLight::new(
                Vec3::new(-1.0, -1.0, 3.0),
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::new(0.0, 2.0, 0.0),
            )),
            radiance: Vec3::new(0.5, 1.0, 2.0),
            shadows: true,
            shadow_factor: 0.0,
            samples: 16,
            visible: false,
            attenuation: None,
            points: true,
        };
        let mut mean = Vec3::ZERO;
        for i in 0..8 {
            for j in 0..8 {
                let u = Vec2::new((i as f32 + 0.5) / 8.0, (j as f32 + 0.5) / 8.0);
                let s = point_sample(&a, Vec3::ZERO, u).unwrap();
                assert_eq!(s.contribution, a.radiance);
                assert_eq!(s.pdf, 0.0);
                let q = s.wi * s.distance;
                assert!((q.z - 3.0).abs() < 1e-5 && q.x.abs() <= 1.0 && q.y.abs() <= 1.0);
                mean += s.wi;
            }
        }
        let mean = mean.normalize();
        assert!((mean - Vec3::Z).length() < 1e-5, "{mean}");
        assert!((a.shape.area() - 4.0).abs() < 1e-6);
    }
}

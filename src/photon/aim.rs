//! Aimed emission (Jensen's projection maps, in the form LuxCore and others use): caustic
//! photons leave a light only toward the bounding spheres of the caustic casters, since no
//! other direction can start an `L S+ D` path (its first counted event is a mirror or a
//! refraction at a caster; a pass-through before it keeps the direction).
//!
//! From an emission point `x`, each caster sphere `(cⱼ, rⱼ)` subtends a cone of solid angle
//! `Ωⱼ = 2π(1 − cos θⱼ)`, `sin θⱼ = rⱼ/|cⱼ − x|` (the whole sphere of directions when `x` is
//! inside). A cone is chosen with probability `Ωⱼ/ΣΩ` and a direction drawn uniformly in it,
//! so the direction's density is the mixture `p(ω) = n(ω)/ΣΩ`, `n(ω)` the number of cones
//! containing `ω` (overlaps counted exactly). The photon's power is the light's radiant
//! intensity toward `ω` divided by `p(ω)`: the power the light sends into the union of the
//! cones, shared among the photons — the estimate keeps its expected value while every
//! photon heads for a caster. Directional lights do the same on the plane across the beam:
//! a disc per caster, chosen by area, density `n(x)/Σπrⱼ²`.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use crate::sampling::sample_concentric_disk;
use crate::shading::frame::ShadingFrame;

/// Most caster spheres kept separately; beyond, one sphere around them all is used.
pub const MAX_TARGETS: usize = 64;

/// The caster spheres photons are aimed at.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Aim {
    spheres: Vec<(Vec3, f32)>,
}

/// One cone toward a caster sphere from an emission point.
#[derive(Debug, Clone, Copy)]
struct Cone {
    axis: Vec3,
    /// `1 − cos θ_max` (2 for the whole sphere).
    one_minus_cos: f32,
}

impl Cone {
    fn toward(x: Vec3, (centre, radius): (Vec3, f32)) -> Self {
        let to = centre - x;
        let d = to.length();
        if d <= radius || d == 0.0 || !d.is_finite() {
            return Self {
                axis: Vec3::Z,
                one_minus_cos: 2.0,
            };
        }
        let s2 = (radius / d) * (radius / d);
        // 1 − √(1 − s²) without cancellation for small cones.
        let one_minus_cos = s2 / (1.0 + (1.0 - s2).max(0.0).sqrt());
        Self {
            axis: to / d,
            one_minus_cos,
        }
    }

    /// A direction uniform in the cone from `u`.
    fn sample(&self, u: Vec2) -> Vec3 {
        let cos = 1.0 - u.x * self.one_minus_cos;
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let local = Vec3::new(sin * phi.cos(), sin * phi.sin(), cos);
        ShadingFrame::from_normal(self.axis)
            .to_world(local)
            .normalize()
    }

    fn solid_angle(&self) -> f32 {
        2.0 * PI * self.one_minus_cos
    }

    fn contains(&self, dir: Vec3) -> bool {
        self.one_minus_cos >= 2.0 || 1.0 - dir.dot(self.axis) <= self.one_minus_cos
    }
}

impl Aim {
    /// Aims at `spheres` (centre, radius); more than [`MAX_TARGETS`] become one sphere
    /// around them all.
    pub fn new(spheres: Vec<(Vec3, f32)>) -> Self {
        if spheres.len() <= MAX_TARGETS {
            return Self { spheres };
        }
        let (lo, hi) = spheres.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &(c, r)| (lo.min(c - r), hi.max(c + r)),
        );
        let centre = 0.5 * (lo + hi);
        let radius = spheres
            .iter()
            .fold(0.0f32, |m, &(c, r)| m.max((c - centre).length() + r));
        Self {
            spheres: vec![(centre, radius * (1.0 + 1e-5))],
        }
    }

    /// Whether there is nothing to aim at (no caustic photon can exist).
    pub fn is_empty(&self) -> bool {
        self.spheres.is_empty()
    }

    /// The spheres aimed at.
    pub fn spheres(&self) -> &[(Vec3, f32)] {
        &self.spheres
    }

    /// A unit direction from `x` toward the casters and its solid-angle density, from
    /// `pick ∈ [0,1)` (chooses the cone) and `u ∈ [0,1)²`.
    pub fn direction(&self, x: Vec3, pick: f32, u: Vec2) -> Option<(Vec3, f32)> {
        if let [sphere] = self.spheres[..] {
            // One caster (the common case): its cone once, chosen whatever `pick` is, and no
            // other cone to cover the direction — what the general path computes.
            let cone = Cone::toward(x, sphere);
            let total = cone.solid_angle();
            if total.is_nan() || total <= 0.0 {
                return None;
            }
            let dir = cone.sample(u);
            let pdf = 1.0 / total;
            return (dir.is_finite() && pdf > 0.0).then_some((dir, pdf));
        }
        let total: f32 = self
            .spheres
            .iter()
            .map(|&s| Cone::toward(x, s).solid_angle())
            .sum();
        if total.is_nan() || total <= 0.0 {
            return None;
        }
        let target = pick * total;
        let mut acc = 0.0;
        let mut chosen = self.spheres.len() - 1;
        for (j, &s) in self.spheres.iter().enumerate() {
            acc += Cone::toward(x, s).solid_angle();
            if target < acc {
                chosen = j;
                break;
            }
        }
        let cone = Cone::toward(x, self.spheres[chosen]);
        let dir = cone.sample(u);
        // The chosen cone contains its sample; the others are tested.
        let cover = 1 + self
            .spheres
            .iter()
            .enumerate()
            .filter(|&(j, &s)| j != chosen && Cone::toward(x, s).contains(dir))
            .count();
        let pdf = cover as f32 / total;
        (dir.is_finite() && pdf > 0.0).then_some((dir, pdf))
    }

    /// A point on the plane through `origin` across the unit direction `dir` whose line
    /// along `dir` meets a caster sphere, and its area density on that plane, from `pick` and
    /// `u` (directional lights).
    pub fn beam_point(&self, origin: Vec3, dir: Vec3, pick: f32, u: Vec2) -> Option<(Vec3, f32)> {
        let frame = ShadingFrame::from_normal(dir);
        let onto_plane = |c: Vec3| c - dir * (c - origin).dot(dir);
        let total: f32 = self.spheres.iter().map(|&(_, r)| PI * r * r).sum();
        if total.is_nan() || total <= 0.0 {
            return None;
        }
        let target = pick * total;
        let mut acc = 0.0;
        let mut chosen = self.spheres.len() - 1;
        for (j, &(_, r)) in self.spheres.iter().enumerate() {
            acc += PI * r * r;
            if target < acc {
                chosen = j;
                break;
            }
        }
        let (c, r) = self.spheres[chosen];
        let d = sample_concentric_disk(u) * r;
        let p = onto_plane(c) + frame.s * d.x + frame.t * d.y;
        let cover = 1 + self
            .spheres
            .iter()
            .enumerate()
            .filter(|&(j, &(cj, rj))| j != chosen && (p - onto_plane(cj)).length() <= rj)
            .count();
        let pdf = cover as f32 / total;
        (p.is_finite() && pdf > 0.0).then_some((p, pdf))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Sampler;

    /// Monte Carlo over the sphere of directions: `E[1/p(ω)·[ω ∈ union]]` over aimed samples
    /// equals the union's solid angle, measured by uniform sampling.
    #[test]
    fn aimed_directions_weigh_the_union_of_overlapping_cones_exactly() {
        let aim = Aim::new(vec![
            (Vec3::new(0.0, 0.0, 3.0), 1.0),
            (Vec3::new(0.5, 0.0, 3.0), 1.0),
            (Vec3::new(-4.0, 1.0, 0.0), 0.5),
        ]);
        let x = Vec3::ZERO;
        let n = 200_000u64;
        let mut aimed = 0.0f64;
        let mut uniform_hits = 0u64;
        for i in 0..n {
            let mut s = Sampler::for_item(5, i, 0);
            let (pick, u) = (s.next_1d(), s.next_2d());
            let (dir, pdf) = aim.direction(x, pick, u).unwrap();
            assert!((dir.length() - 1.0).abs() < 1e-5);
            aimed += 1.0 / pdf as f64;
            // Uniform direction: inside any cone?
            let v = s.next_2d();
            let z = 1.0 - 2.0 * v.x;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let w = Vec3::new(r * (2.0 * PI * v.y).cos(), r * (2.0 * PI * v.y).sin(), z);
            if aim
                .spheres()
                .iter()
                .any(|&s| Cone::toward(x, s).contains(w))
            {
                uniform_hits += 1;
            }
        }
        let aimed = aimed / n as f64;
        let uniform = 4.0 * std::f64::consts::PI * uniform_hits as f64 / n as f64;
        println!("union solid angle: aimed {aimed}, uniform {uniform}");
        assert!((aimed / uniform - 1.0).abs() < 0.02, "{aimed} vs {uniform}");
    }

    #[test]
    fn inside_a_sphere_every_direction_is_aimed_and_many_spheres_merge() {
        let aim = Aim::new(vec![(Vec3::ZERO, 2.0)]);
        let (_, pdf) = aim.direction(Vec3::X, 0.3, Vec2::new(0.2, 0.7)).unwrap();
        assert!((pdf - 1.0 / (4.0 * PI)).abs() < 1e-7);
        let many: Vec<_> = (0..100).map(|i| (Vec3::X * i as f32, 0.5)).collect();
        let merged = Aim::new(many);
        assert_eq!(merged.spheres().len(), 1);
        let (c, r) = merged.spheres()[0];
        assert!((c - Vec3::X * 49.5).length() < 1e-4 && r >= 50.0, "{c} {r}");
        assert!(Aim::new(Vec::new())
            .direction(Vec3::ZERO, 0.5, Vec2::ZERO)
            .is_none());
    }
}

//! Integration through media along ray segments for both integrators: transmittance and
//! single scattering on a segment ([`segment`], [`through_segment`]) and shadow rays that
//! pass through fog boundaries ([`shadow_transmittance`]). The media and their sampling
//! functions are [`crate::shading::volume`] (its module doc states the model).

use glam::Vec3;

use super::ShadeContext;
use crate::accel::{spawn_ray, spawn_ray_to, Hit, Ray, RayKind};
use crate::components::{Fade, Fog};
use crate::sampling::Sampler;
use crate::shading::lights::Light;
use crate::shading::medium;
use crate::shading::volume::{distance_sample, equiangular, henyey_greenstein, Volumes};

/// What a segment does to the radiance travelling along it toward its origin:
/// `L_origin = transmittance · L_end + inscattered`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// `e^(−σt·d)` per channel.
    pub transmittance: Vec3,
    /// Single-scattered radiance gathered along the segment.
    pub inscattered: Vec3,
}

impl Segment {
    /// A segment through vacuum.
    pub const VACUUM: Segment = Segment {
        transmittance: Vec3::ONE,
        inscattered: Vec3::ZERO,
    };

    /// `transmittance · radiance + inscattered`.
    pub fn apply(&self, radiance: Vec3) -> Vec3 {
        self.transmittance * radiance + self.inscattered
    }
}

/// The segment of `ray` that ends at `hit`, in the medium the scene puts there.
pub fn segment(ctx: &ShadeContext<'_>, ray: &Ray, hit: &Hit, sampler: &mut Sampler) -> Segment {
    let Some(volumes) = ctx.volumes else {
        return Segment::VACUUM;
    };
    let found = volumes.medium(ctx.geometry, ray, hit);
    if found.is_none() && volumes.fade.is_none() {
        return Segment::VACUUM;
    }
    let len = ray.dir.length();
    let length = hit.t * len;
    if !(length.is_finite() && length > 0.0) {
        return Segment::VACUUM;
    }
    let Some(fog) = found else {
        return volumes.fade.map_or(Segment::VACUUM, |f| fade(&f, length));
    };
    let dir = ray.dir / len;
    Segment {
        transmittance: medium::transmittance(fog, ray.origin, dir, length),
        inscattered: inscatter(ctx, fog, ray.origin, dir, length, sampler),
    }
}

/// A segment of `length` through the camera's fade: `(1 − f)·L + f·color`.
pub fn fade(fade: &Fade, length: f32) -> Segment {
    let f = fade.weight(length);
    Segment {
        transmittance: Vec3::splat(1.0 - f),
        inscattered: fade.color * f,
    }
}

/// `radiance` arriving at the end of the segment of `ray` that ends at `hit`, as seen from
/// the segment's origin (unchanged, bit for bit, when the scene has no volumes).
pub fn through_segment(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    radiance: Vec3,
    sampler: &mut Sampler,
) -> Vec3 {
    if ctx.volumes.is_none() {
        return radiance;
    }
    segment(ctx, ray, hit, sampler).apply(radiance)
}

/// Radiance `le` from `length` along `origin + t·dir` (`dir` unit) through the camera's
/// atmosphere (attenuation only, no in-scattering) or its fade.
pub fn seen_through_atmosphere(
    volumes: &Volumes,
    origin: Vec3,
    dir: Vec3,
    length: f32,
    le: Vec3,
) -> Vec3 {
    match (&volumes.atmosphere, &volumes.fade) {
        (Some(f), _) => le * medium::transmittance(f, origin, dir, length),
        (None, Some(f)) => fade(f, length).apply(le),
        (None, None) => le,
    }
}

/// Single scattering along `origin + t·dir`, `t ∈ [0, length]` (`dir` unit); distances are
/// drawn over the span below the fog's height (`shading::medium::span`), where the ray
/// enters the fog with transmittance 1.
fn inscatter(
    ctx: &ShadeContext<'_>,
    fog: &Fog,
    origin: Vec3,
    dir: Vec3,
    length: f32,
    sampler: &mut Sampler,
) -> Vec3 {
    if fog.sigma_s == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let Some((t0, t1)) = medium::span(fog, origin, dir, length) else {
        return Vec3::ZERO;
    };
    let (origin, length) = (origin + dir * t0, t1 - t0);
    let mut sum = Vec3::ZERO;
    for light in &ctx.lights.lights {
        let u_t = sampler.next_1d();
        let u_l = sampler.next_2d();
        let (t, pdf) = light_centre(light)
            .and_then(|c| equiangular(origin, dir, length, c, u_t))
            .unwrap_or_else(|| distance_sample(fog, length, u_t));
        if !(pdf > 0.0 && pdf.is_finite()) {
            continue;
        }
        let x = origin + dir * t;
        let Some(ls) = light.sample(x, u_l, Some(ctx.geometry)) else {
            continue;
        };
        let to_light = ls.target.map(|q| (q.p - x).length());
        let first = Ray {
            origin: x,
            dir: ls.wi,
            t_max: to_light.map_or(f32::INFINITY, |d| d * (1.0 - 1e-3)),
        };
        let target = ls.target.map(|q| q.p);
        let t_light = match shadow_transmittance(ctx, first, Some(fog), target, ls.shadows) {
            Some(t) => ls.lighten(t),
            None if ls.shadow_factor > 0.0 => ls.lighten(Vec3::ZERO),
            None => continue,
        };
        let phase = henyey_greenstein(fog.g, dir.dot(ls.wi));
        let (t_eye, sigma_s) = if fog.is_homogeneous() {
            (fog.transmittance(t), fog.sigma_s)
        } else {
            let t_eye = medium::transmittance(fog, origin, dir, t);
            (t_eye, fog.sigma_s * medium::density(fog, x))
        };
        let c = t_eye * sigma_s * ls.contribution * t_light * (phase / pdf);
        if c.is_finite() {
            sum += c;
        }
    }
    sum
}

/// Most fog boundaries one shadow ray passes through.
const MAX_CROSSINGS: usize = 16;

/// Transmittance along a shadow ray toward a light, or `None` when it is blocked.
///
/// `first` is the ray from the shading point (its `t_max` stops short of the light);
/// `start` is the medium at its origin; `target` is the light sample's position (`None`:
/// infinitely far, whose last segment crosses no medium). The shells of fog-filled
/// materials (those with an `interior`) are volume boundaries, not occluders: the ray
/// passes through them, entering the interior at a front face and returning to the
/// atmosphere at a back face. Transparent surfaces and shadow shaders tint
/// (`shading::shadow`); any other
/// surface blocks (unless `occlude` is false: then
/// only the starting medium attenuates, over the straight distance).
pub fn shadow_transmittance(
    ctx: &ShadeContext<'_>,
    first: Ray,
    start: Option<&Fog>,
    target: Option<Vec3>,
    occlude: bool,
) -> Option<Vec3> {
    let along = |fog: Option<&Fog>, from: Vec3| match (fog, target) {
        (Some(f), Some(p)) if f.is_homogeneous() => f.transmittance((p - from).length()),
        (Some(f), Some(p)) => {
            let d = (p - from).length();
            if d > 0.0 {
                medium::transmittance(f, from, (p - from) / d, d)
            } else {
                Vec3::ONE
            }
        }
        _ => Vec3::ONE,
    };
    if !occlude {
        return Some(along(start, first.origin));
    }
    let Some(volumes) = ctx.volumes else {
        return (!ctx.geometry.accel.occluded_as(&first, RayKind::Shadow)).then_some(Vec3::ONE);
    };
    let mut ray = first;
    let mut medium = start;
    let mut t = Vec3::ONE;
    for _ in 0..MAX_CROSSINGS {
        let Some(hit) = ctx.geometry.accel.intersect_as(&ray, RayKind::Shadow) else {
            return Some(t * along(medium, ray.origin));
        };
        let material = ctx.geometry.material_slot(hit.prim) as usize;
        let interior = volumes.interiors.get(material).and_then(Option::as_ref);
        // A surface without an interior passes light only if its shader lets shadows
        // through (`shading::shadow`); the medium stays the same across it.
        let tint = match interior {
            Some(_) => Vec3::ONE,
            None => {
                let m = &ctx.geometry.materials[material];
                crate::shading::shadow::material_shadow(m.shadow, &m.shader)?
            }
        };
        if let Some(f) = medium {
            let len = ray.dir.length();
            t *= medium::transmittance(f, ray.origin, ray.dir / len, hit.t * len);
        }
        t *= tint;
        let sp = ctx.geometry.accel.surface_point(&hit);
        if let Some(interior) = interior {
            medium = if sp.ng.dot(ray.dir) < 0.0 {
                Some(interior)
            } else {
                volumes.atmosphere.as_ref()
            };
        }
        ray = match target {
            Some(p) => spawn_ray_to(&sp, p),
            None => spawn_ray(&sp, ray.dir),
        };
    }
    None
}

/// Position equiangular sampling aims at, for lights that have one.
fn light_centre(light: &Light) -> Option<Vec3> {
    match light {
        Light::Point { position, .. } | Light::Spot { position, .. } => Some(*position),
        Light::Area(a) => Some(a.centre()),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixture::{self, Object};
    use super::*;
    use crate::components::{Emitter, LightShape};
    use crate::settings::RenderSettings;
    use crate::shading::lights::LightSet;

    fn fog(sigma_a: f32, sigma_s: f32) -> Fog {
        Fog {
            sigma_a: Vec3::splat(sigma_a),
            sigma_s: Vec3::splat(sigma_s),
            g: 0.0,
            ..Default::default()
        }
    }

    /// A floor at z = 0 and a wall at x = 4 (facing −x), both Lambert.
    fn room() -> crate::geometry::SceneGeometry {
        fixture::geometry(vec![
            Object {
                triangles: fixture::floor(10.0, 0.0),
                material: fixture::lambert(0.5),
            },
            Object {
                triangles: fixture::quad(
                    Vec3::new(4.0, 10.0, -10.0),
                    Vec3::new(0.0, -20.0, 0.0),
                    Vec3::new(0.0, 0.0, 20.0),
                ),
                material: fixture::lambert(0.5),
            },
        ])
    }

    #[test]
    fn shadow_rays_in_fog_follow_beer_lambert_and_stop_at_surfaces() {
        let geometry = room();
        let lights = LightSet::default();
        let f = fog(0.2, 0.1);
        let volumes = Volumes::new(Some(f), vec![None, None]);
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s).with_volumes(volumes.as_ref());
        let from = Vec3::new(0.0, 0.0, 1.0);
        let target = Vec3::new(3.0, 0.0, 1.0);
        let first = Ray {
            origin: from,
            dir: target - from,
            t_max: 1.0 - 1e-3,
        };
        let t = shadow_transmittance(&ctx, first, Some(&f), Some(target), true);
        assert_eq!(t, Some(f.transmittance(3.0)));
        assert!((t.unwrap().x - (-0.3f32 * 3.0).exp()).abs() < 1e-6);
        // Through the floor: blocked, unless occlusion is off (then only the fog counts).
        let below = Vec3::new(0.0, 0.0, -1.0);
        let down = Ray {
            origin: from,
            dir: below - from,
            t_max: 1.0 - 1e-3,
        };
        assert_eq!(
            shadow_transmittance(&ctx, down, Some(&f), Some(below), true),
            None
        );
        assert_eq!(
            shadow_transmittance(&ctx, down, Some(&f), Some(below), false),
            Some(f.transmittance(2.0))
        );
    }

    #[test]
    fn an_absorbing_segment_attenuates_and_vacuum_changes_nothing() {
        let geometry = room();
        let lights = LightSet::default();
        let f = fog(0.25, 0.0);
        let volumes = Volumes::new(Some(f), vec![None, None]);
        let s = RenderSettings::default();
        let foggy = ShadeContext::new(&geometry, &lights, &s).with_volumes(volumes.as_ref());
        let (ray, hit) = fixture::hit(&geometry, Vec3::new(0.0, 0.0, 2.0), -Vec3::Z);
        let seg = segment(&foggy, &ray, &hit, &mut Sampler::new(0, 0));
        assert_eq!(seg.inscattered, Vec3::ZERO);
        assert!(
            (seg.transmittance - Vec3::splat((-0.5f32).exp()))
                .abs()
                .max_element()
                < 1e-6
        );
        let l = Vec3::new(0.3, -0.0, 7.0);
        let vacuum = ShadeContext::new(&geometry, &lights, &s);
        let same = through_segment(&vacuum, &ray, &hit, l, &mut Sampler::new(0, 0));
        assert_eq!(
            same.to_array().map(f32::to_bits),
            l.to_array().map(f32::to_bits)
        );
    }

    #[test]
    fn single_scattering_from_a_point_light_matches_quadrature() {
        // Ray from the origin along +x to the wall at x = 4; point light at (0, 1, 1) (1 m
        // above the floor and 1 m beside the ray, in thin isotropic fog):
        // L = ∫₀⁴ e^(−σt·t) σs/(4π) I/r² e^(−σt·r) dt, r² = t² + 1 + 0.
        let (sigma_s, intensity) = (0.05f32, 2.0f32);
        let geometry = room();
        let position = Vec3::new(0.0, 1.0, 1.0);
        let e = Emitter::new(LightShape::Point { position }, Vec3::splat(intensity));
        let lights = LightSet::new(&[e], None, 1);
        let f = fog(0.0, sigma_s);
        let volumes = Volumes::new(Some(f), vec![None, None]);
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s).with_volumes(volumes.as_ref());
        let origin = Vec3::new(0.0, 0.0, 1.0);
        let (ray, hit) = fixture::hit(&geometry, origin, Vec3::X);
        let n = 4000;
        let mean: f64 = (0..n)
            .map(|i| {
                let mut sampler = Sampler::for_item(5, i, 0);
                f64::from(segment(&ctx, &ray, &hit, &mut sampler).inscattered.x)
            })
            .sum::<f64>()
            / n as f64;
        let steps = 20_000;
        let dt = 4.0 / steps as f64;
        let sigma = f64::from(sigma_s);
        let quadrature: f64 = (0..steps)
            .map(|k| {
                let t = (k as f64 + 0.5) * dt;
                let r2 = t * t + 1.0;
                (-sigma * (t + r2.sqrt())).exp() * sigma / (4.0 * std::f64::consts::PI)
                    * f64::from(intensity)
                    / r2
                    * dt
            })
            .sum();
        println!("in-scattered {mean} (quadrature {quadrature})");
        assert!(
            (mean / quadrature - 1.0).abs() < 0.01,
            "{mean} vs {quadrature}"
        );
    }

    #[test]
    fn single_scattering_in_noisy_height_bounded_fog_matches_nested_quadrature() {
        // As above, in fog whose density varies by a noise (amount 0.8) and that ends at
        // y = 0.6 (the ray runs at y = 0, the light at (0, 1, 1) sits above the top: the
        // part of each shadow ray above it is clear): L = ∫₀⁴ T(0, t) σs d(x) p I/r² T(x → light) dt with
        // T = e^(−σt ∫ d) along each path, the density integrated numerically.
        let (sigma_t, sigma_s, intensity) = (0.6f32, 0.5f32, 2.0f32);
        let geometry = room();
        let position = Vec3::new(0.0, 1.0, 1.0);
        let e = Emitter::new(LightShape::Point { position }, Vec3::splat(intensity));
        let lights = LightSet::new(&[e], None, 1);
        let f = Fog {
            sigma_a: Vec3::splat(sigma_t - sigma_s),
            sigma_s: Vec3::splat(sigma_s),
            g: 0.0,
            height: Some(0.6),
            density: Some(crate::components::DensityNoise {
                amount: 0.8,
                scale: 0.4,
            }),
        };
        let volumes = Volumes::new(Some(f), vec![None, None]);
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s).with_volumes(volumes.as_ref());
        let origin = Vec3::new(0.0, 0.0, 1.0);
        let (ray, hit) = fixture::hit(&geometry, origin, Vec3::X);
        let n = 8000;
        let samples: Vec<f64> = (0..n)
            .map(|i| {
                let mut sampler = Sampler::for_item(9, i, 0);
                f64::from(segment(&ctx, &ray, &hit, &mut sampler).inscattered.x)
            })
            .collect();
        let mean = samples.iter().sum::<f64>() / n as f64;
        let var = samples.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        let optical = |a: Vec3, b: Vec3, steps: usize| -> f64 {
            let d = f64::from((b - a).length()) / steps as f64;
            (0..steps)
                .map(|k| {
                    let p = a.lerp(b, (k as f32 + 0.5) / steps as f32);
                    f64::from(medium::density(&f, p)) * d
                })
                .sum::<f64>()
                * f64::from(sigma_t)
        };
        let steps = 4000;
        let dt = 4.0 / steps as f64;
        let along = |t: f64| origin + Vec3::X * t as f32;
        // Optical depth from the origin to the start of step k (accumulated).
        let mut tau_edge = 0.0;
        let mut quadrature = 0.0;
        for k in 0..steps {
            let (t0, t) = (k as f64 * dt, (k as f64 + 0.5) * dt);
            let x = along(t);
            let tau_eye = tau_edge + optical(along(t0), x, 4);
            let r2 = f64::from((position - x).length_squared());
            quadrature += (-tau_eye - optical(x, position, 400)).exp()
                * f64::from(sigma_s * medium::density(&f, x))
                / (4.0 * std::f64::consts::PI)
                * f64::from(intensity)
                / r2
                * dt;
            tau_edge += optical(along(t0), along(t0 + dt), 8);
        }
        let z = (mean - quadrature) / (var / n as f64).sqrt();
        println!("in-scattered {mean} (quadrature {quadrature}, z {z:.2})");
        assert!(z.abs() < 4.0, "{mean} vs {quadrature}: z = {z}");
        assert!(
            (mean / quadrature - 1.0).abs() < 0.03,
            "{mean} vs {quadrature}"
        );
    }
}

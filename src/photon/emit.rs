//! Photon emission: each light's power in watts and a sampler of photons leaving it.
//!
//! Powers follow from the lights' physical units: point `Φ = 4π·I`; spot
//! `Φ = 2π·I·∫ falloff(cosθ) dcosθ` over its cone (numerical quadrature of the beam and
//! penumbra); area lights `Φ = π·L·A` (rectangle, disc, sphere `A = 4πr²`, cylinder side
//! `A = 2πrh`, each emitting outward with a cosine distribution); emitting triangles
//! `Φ = π·L·A` each (twice for two-sided emission); directional `Φ = E·π·R²` through a disc
//! of the scene's bounding-sphere radius `R` facing the light. With an [`Aim`] (caustic maps),
//! photons leave only toward the caustic casters, powers divided by the density of the
//! aimed directions (see [`super::aim`]). The environment emits no photons. A light's
//! distance terms beyond 1/d² (no inverse-square falloff, near/far `attenuation`) go with its
//! photons as a [`Falloff`] applied at their first hit, unless the light has an `energy`
//! (mental ray's photon power, plain 1/d²). A light is chosen
//! with probability proportional to its (channel-mean) power; every photon's power is its
//! emitted flux divided by that probability, so the mean power per photon is the total power
//! of the scene's lights. A new light shape adds one arm to [`Source::from_light`] and one to
//! [`Source::emit`].

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::aim::Aim;
use crate::accel::{spawn_ray, Hit, Ray, SurfacePoint};
use crate::components::attenuation_factor;
use crate::geometry::SceneGeometry;
use crate::sampling::{sample_cosine_hemisphere, sample_triangle};
use crate::shading::frame::ShadingFrame;
use crate::shading::lights::{spot_falloff, uniform_sphere, Light, LightSet, MeshLight};
use crate::shading::texture::hit::emission_at;

/// A photon leaving a light: its ray and its flux weight, W (not yet divided by the number of
/// photons emitted).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmittedPhoton {
    /// Where it starts and where it goes (unit direction).
    pub ray: Ray,
    /// Flux weight, W.
    pub power: Vec3,
    /// The light's distance terms, applied at the photon's first hit (`None`: plain 1/d²).
    pub falloff: Option<Falloff>,
}

/// What a light's direct contribution does with distance beyond the 1/d² that photon
/// density gives by itself: a photon's power is multiplied by [`Falloff::factor`] of the
/// distance from where it left the light to its first hit, so photon and direct lighting
/// agree for lights without inverse-square falloff (`inverse_square: false`) or with near/far
/// `attenuation`. Not used for lights with an `energy` (mental ray's photon power, which
/// falls off as 1/d² whatever the light shader does).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Falloff {
    /// Whether the light's direct contribution falls off as 1/d².
    pub inverse_square: bool,
    /// Near/far attenuation `(start, end)`.
    pub attenuation: Option<(f32, f32)>,
}

impl Falloff {
    /// The factor at distance `d` from the light: `d²` without inverse-square falloff,
    /// times the attenuation ramp.
    pub fn factor(self, d: f32) -> f32 {
        let spread = if self.inverse_square { 1.0 } else { d * d };
        spread * attenuation_factor(self.attenuation, d)
    }

    /// The falloff of `light` (`None` where it is plain 1/d²).
    fn of(light: &Light) -> Option<Self> {
        let (inverse_square, attenuation) = match light {
            Light::Point {
                inverse_square,
                attenuation,
                ..
            }
            | Light::Spot {
                inverse_square,
                attenuation,
                ..
            } => (*inverse_square, *attenuation),
            Light::Area(a) => (!a.points, a.attenuation),
            _ => (true, None),
        };
        (!inverse_square || attenuation.is_some()).then_some(Self {
            inverse_square,
            attenuation,
        })
    }
}

/// One light prepared for photon emission.
#[derive(Debug, Clone)]
struct Source {
    light: Light,
    /// Index of the light in the [`LightSet`].
    index: usize,
    /// Total emitted power, W (the light's `energy` where it has one).
    power: Vec3,
    /// Total physical power, W (what [`Source::emit`] spreads over the photons).
    physical: Vec3,
    /// Factor from the physical power to `power` per channel (1 without `energy`).
    scale: Vec3,
    /// The distance terms its photons take at their first hit (none with an `energy`).
    falloff: Option<Falloff>,
    /// Directional lights: centre and radius of the scene's bounding sphere.
    bounds: (Vec3, f32),
}

impl Source {
    fn from_light(light: &Light, geometry: &SceneGeometry, bounds: (Vec3, f32)) -> Self {
        let power = match light {
            Light::Point { intensity, .. } => *intensity * (4.0 * PI),
            Light::Spot {
                cos_outer,
                cos_inner,
                beam_distribution,
                intensity,
                ..
            } => *intensity * spot_solid_angle(*cos_outer, *cos_inner, *beam_distribution),
            Light::Directional { irradiance, .. } => *irradiance * (PI * bounds.1 * bounds.1),
            // A non-physical area light is a point light spread over its shape.
            Light::Area(a) if a.points => a.radiance * (4.0 * PI),
            Light::Area(a) => a.radiance * (PI * a.shape.area()),
            // The environment sends no photons (documented limitation); ambient light is
            // not light transport.
            Light::Environment(_) | Light::Ambient { .. } => Vec3::ZERO,
            Light::Mesh(MeshLight { prims, .. }) => prims.iter().fold(Vec3::ZERO, |s, &prim| {
                let m = geometry.material_of(prim);
                let sides = if m.two_sided { 2.0 } else { 1.0 };
                s + m.emission * (PI * sides * triangle_area(geometry, prim))
            }),
        };
        let power = if power.is_finite() {
            power.max(Vec3::ZERO)
        } else {
            Vec3::ZERO
        };
        Self {
            light: light.clone(),
            index: 0,
            power,
            physical: power,
            scale: Vec3::ONE,
            falloff: Falloff::of(light),
            bounds,
        }
    }

    /// The same light emitting `energy` W instead (per channel; a channel the light does not
    /// emit physically stays dark).
    fn with_energy(mut self, energy: Vec3) -> Self {
        let ratio = |e: f32, p: f32| if p > 0.0 { e / p } else { 0.0 };
        self.scale = Vec3::new(
            ratio(energy.x, self.power.x),
            ratio(energy.y, self.power.y),
            ratio(energy.z, self.power.z),
        );
        self.power *= self.scale;
        // mental ray's photon energy falls off as 1/d² whatever the light shader does.
        self.falloff = None;
        self
    }

    /// A photon from `u ∈ [0,1)⁴`; its power is the emitted flux weight `Lₑ·cos/(pdf_A·pdf_ω)`.
    fn emit(&self, geometry: &SceneGeometry, u: [f32; 4]) -> Option<EmittedPhoton> {
        let (u_pos, u_dir) = (Vec2::new(u[0], u[1]), Vec2::new(u[2], u[3]));
        let from_point = |origin: Vec3, dir: Vec3, power: Vec3| EmittedPhoton {
            falloff: None,
            ray: Ray {
                origin,
                dir,
                t_max: f32::INFINITY,
            },
            power,
        };
        let photon = match &self.light {
            Light::Point { position, .. } => {
                from_point(*position, uniform_sphere(u_dir), self.physical)
            }
            Light::Spot {
                position,
                axis,
                cos_outer,
                cos_inner,
                beam_distribution,
                intensity,
                ..
            } => {
                // Uniform in the cone: cosθ uniform in [cos_outer, 1].
                let cos = 1.0 - u_dir.x * (1.0 - cos_outer);
                let sin = (1.0 - cos * cos).max(0.0).sqrt();
                let phi = 2.0 * PI * u_dir.y;
                let local = Vec3::new(sin * phi.cos(), sin * phi.sin(), cos);
                let dir = ShadingFrame::from_normal(*axis).to_world(local);
                let falloff = spot_falloff(cos, *cos_outer, *cos_inner, *beam_distribution);
                let solid_angle = 2.0 * PI * (1.0 - cos_outer);
                from_point(*position, dir, *intensity * (falloff * solid_angle))
            }
            Light::Directional { direction, .. } => {
                let (centre, radius) = self.bounds;
                let frame = ShadingFrame::from_normal(*direction);
                let d = crate::sampling::sample_concentric_disk(u_pos) * radius;
                let origin = centre - *direction * (1.01 * radius) + frame.s * d.x + frame.t * d.y;
                from_point(origin, *direction, self.physical)
            }
            Light::Area(a) if a.points => {
                let (q, _) = a.shape.point(u_pos);
                from_point(q, uniform_sphere(u_dir), self.physical)
            }
            Light::Area(a) => {
                // A point on the shape and its outward normal; light shapes are not scene
                // geometry, so the photon starts exactly there.
                let (q, n) = a.shape.point(u_pos);
                let dir = ShadingFrame::from_normal(n).to_world(sample_cosine_hemisphere(u_dir));
                from_point(q, dir, self.physical)
            }
            Light::Environment(_) | Light::Ambient { .. } => return None,
            Light::Mesh(MeshLight { prims, cdf, .. }) => {
                let (prim, sp, prob, emission) = mesh_point(geometry, prims, cdf, u_pos)?;
                let material = geometry.material_of(prim);
                // Two-sided emitters pick a side by the first direction dimension.
                let (mut n, mut ud, mut sides) = (sp.ng, u_dir, 1.0);
                if material.two_sided {
                    sides = 2.0;
                    if ud.x < 0.5 {
                        ud.x *= 2.0;
                    } else {
                        ud.x = 2.0 * ud.x - 1.0;
                        n = -n;
                    }
                }
                let dir = ShadingFrame::from_normal(n).to_world(sample_cosine_hemisphere(ud));
                let area = triangle_area(geometry, prim);
                EmittedPhoton {
                    falloff: None,
                    ray: spawn_ray(&sp, dir),
                    power: emission * (PI * sides * area / prob),
                }
            }
        };
        valid(photon)
    }

    /// A photon aimed at `aim`'s casters from `u ∈ [0,1)⁵` (`u[0]` chooses among the casters):
    /// power = radiant intensity toward the direction / its density (see [`super::aim`]).
    fn emit_aimed(
        &self,
        geometry: &SceneGeometry,
        aim: &Aim,
        u: [f32; 5],
    ) -> Option<EmittedPhoton> {
        let (pick, u_pos, u_dir) = (u[0], Vec2::new(u[1], u[2]), Vec2::new(u[3], u[4]));
        let ray = |origin: Vec3, dir: Vec3| Ray {
            origin,
            dir,
            t_max: f32::INFINITY,
        };
        let photon = match &self.light {
            Light::Point { position, .. } => {
                let (dir, pdf) = aim.direction(*position, pick, u_dir)?;
                EmittedPhoton {
                    falloff: None,
                    ray: ray(*position, dir),
                    power: self.physical / (4.0 * PI * pdf),
                }
            }
            Light::Spot {
                position,
                axis,
                cos_outer,
                cos_inner,
                beam_distribution,
                intensity,
                ..
            } => {
                let (dir, pdf) = aim.direction(*position, pick, u_dir)?;
                let cos = dir.dot(*axis);
                if cos < *cos_outer {
                    return None;
                }
                let falloff = spot_falloff(cos, *cos_outer, *cos_inner, *beam_distribution);
                EmittedPhoton {
                    falloff: None,
                    ray: ray(*position, dir),
                    power: *intensity * (falloff / pdf),
                }
            }
            Light::Directional { direction, .. } => {
                let (centre, radius) = self.bounds;
                let plane = centre - *direction * (1.01 * radius);
                let (origin, pdf) = aim.beam_point(plane, *direction, pick, u_pos)?;
                // Irradiance E = Φ / (π R²) crossing the plane, over the area density.
                EmittedPhoton {
                    falloff: None,
                    ray: ray(origin, *direction),
                    power: self.physical / (PI * radius * radius * pdf),
                }
            }
            Light::Area(a) if a.points => {
                let (q, _) = a.shape.point(u_pos);
                let (dir, pdf) = aim.direction(q, pick, u_dir)?;
                EmittedPhoton {
                    falloff: None,
                    ray: ray(q, dir),
                    power: self.physical / (4.0 * PI * pdf),
                }
            }
            Light::Area(a) => {
                let (q, n) = a.shape.point(u_pos);
                let (dir, pdf) = aim.direction(q, pick, u_dir)?;
                let cos = n.dot(dir);
                if cos <= 0.0 {
                    return None;
                }
                EmittedPhoton {
                    falloff: None,
                    ray: ray(q, dir),
                    power: a.radiance * (a.shape.area() * cos / pdf),
                }
            }
            Light::Environment(_) | Light::Ambient { .. } => return None,
            Light::Mesh(MeshLight { prims, cdf, .. }) => {
                let (prim, sp, prob, emission) = mesh_point(geometry, prims, cdf, u_pos)?;
                let material = geometry.material_of(prim);
                let (dir, pdf) = aim.direction(sp.p, pick, u_dir)?;
                let cos = sp.ng.dot(dir);
                let cos = if material.two_sided { cos.abs() } else { cos };
                if cos <= 0.0 {
                    return None;
                }
                let area = triangle_area(geometry, prim);
                EmittedPhoton {
                    falloff: None,
                    ray: spawn_ray(&sp, dir),
                    power: emission * (area * cos / (pdf * prob)),
                }
            }
        };
        valid(photon)
    }
}

fn valid(photon: EmittedPhoton) -> Option<EmittedPhoton> {
    (photon.power.is_finite() && photon.ray.dir.is_finite() && photon.ray.origin.is_finite())
        .then_some(photon)
}

/// A point on an emitting mesh: a triangle by the CDF (by emitted power), a point uniform on
/// it; returns the triangle, the point, the triangle's probability and the emitted radiance
/// there (the material's emission times its texture).
fn mesh_point(
    geometry: &SceneGeometry,
    prims: &[u32],
    cdf: &[f32],
    u: Vec2,
) -> Option<(u32, SurfacePoint, f32, Vec3)> {
    let k = cdf.partition_point(|&c| c <= u.x).clamp(1, prims.len()) - 1;
    let (c0, c1) = (cdf[k], cdf[k + 1]);
    if c1 <= c0 {
        return None;
    }
    let ux = ((u.x - c0) / (c1 - c0)).clamp(0.0, 1.0 - f32::EPSILON);
    let prim = prims[k];
    let (b1, b2) = sample_triangle(Vec2::new(ux, u.y));
    let hit = Hit {
        t: 0.0,
        prim,
        b1,
        b2,
    };
    let sp = geometry.accel.surface_point(&hit);
    let emission = emission_at(geometry, &hit, geometry.material_of(prim));
    Some((prim, sp, c1 - c0, emission))
}

/// Every light with power, and the distribution photons are emitted from.
#[derive(Debug, Clone, Default)]
pub struct Emission {
    sources: Vec<Source>,
    /// Normalised CDF over `sources` by channel-mean power (length `sources.len() + 1`).
    cdf: Vec<f32>,
    /// Casters every photon is aimed at (caustic maps), if any.
    aim: Option<Aim>,
}

impl Emission {
    /// The lights of `lights` that emit power into `geometry`.
    pub fn new(lights: &LightSet, geometry: &SceneGeometry) -> Self {
        Self::with_energies(lights, geometry, &[])
    }

    /// [`Emission::new`] where `energies[i]`, when given, replaces the power of light `i` of
    /// `lights` (mental ray `energy`; lights beyond the slice keep their physical power).
    pub fn with_energies(
        lights: &LightSet,
        geometry: &SceneGeometry,
        energies: &[Option<Vec3>],
    ) -> Self {
        let bounds = bounding_sphere(geometry);
        let sources: Vec<Source> = lights
            .lights
            .iter()
            .enumerate()
            .map(|(index, l)| {
                let s = Source {
                    index,
                    ..Source::from_light(l, geometry, bounds)
                };
                match energies.get(index).copied().flatten() {
                    Some(e) => s.with_energy(e),
                    None => s,
                }
            })
            .filter(|s| mean(s.power) > 0.0)
            .collect();
        Self::from_sources(sources)
    }

    /// Only the lights whose index in the [`LightSet`] passes `keep`, powers unchanged.
    pub fn subset(&self, keep: impl Fn(usize) -> bool) -> Self {
        let sources = self
            .sources
            .iter()
            .filter(|s| keep(s.index))
            .cloned()
            .collect();
        Self {
            aim: self.aim.clone(),
            ..Self::from_sources(sources)
        }
    }

    /// Indices (in the [`LightSet`]) of the lights that emit.
    pub fn light_indices(&self) -> Vec<usize> {
        self.sources.iter().map(|s| s.index).collect()
    }

    fn from_sources(sources: Vec<Source>) -> Self {
        let total: f64 = sources.iter().map(|s| mean(s.power) as f64).sum();
        let mut cdf = vec![0.0f32];
        let mut acc = 0.0f64;
        for s in &sources {
            acc += mean(s.power) as f64;
            cdf.push((acc / total) as f32);
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        Self {
            sources,
            cdf,
            aim: None,
        }
    }

    /// The same lights, every photon aimed at `aim`'s casters.
    pub fn aimed(self, aim: Aim) -> Self {
        Self {
            aim: Some(aim),
            ..self
        }
    }

    /// Whether no light emits power.
    pub fn is_empty(&self) -> bool {
        self.sources.is_empty()
    }

    /// Number of lights that emit power.
    pub fn light_count(&self) -> usize {
        self.sources.len()
    }

    /// Total power of every light, W.
    pub fn total_power(&self) -> Vec3 {
        self.sources.iter().fold(Vec3::ZERO, |s, x| s + x.power)
    }

    /// A photon from `u ∈ [0,1)⁵` (`u[0]` picks the light); `None` when the sample is void.
    pub fn sample(&self, geometry: &SceneGeometry, u: [f32; 5]) -> Option<EmittedPhoton> {
        let (k, prob) = self.pick(u[0])?;
        let mut photon = match &self.aim {
            // The light's share of `u[0]`, rescaled to [0,1), picks the caster.
            Some(aim) => {
                let pick = ((u[0] - self.cdf[k]) / prob).clamp(0.0, 1.0 - f32::EPSILON);
                self.sources[k].emit_aimed(geometry, aim, [pick, u[1], u[2], u[3], u[4]])?
            }
            None => self.sources[k].emit(geometry, [u[1], u[2], u[3], u[4]])?,
        };
        photon.power = photon.power * self.sources[k].scale / prob;
        photon.falloff = self.sources[k].falloff;
        Some(photon)
    }
}

impl Emission {
    /// Index in the [`LightSet`] of the light [`Emission::sample`] takes its photon from for
    /// the same `u[0]` (`None` where it emits none).
    pub fn light_index(&self, u0: f32) -> Option<usize> {
        self.pick(u0).map(|(k, _)| self.sources[k].index)
    }

    /// The source `u0` picks and its probability; `None` without one.
    fn pick(&self, u0: f32) -> Option<(usize, f32)> {
        let n = self.sources.len();
        if n == 0 {
            return None;
        }
        let k = self.cdf.partition_point(|&c| c <= u0).clamp(1, n) - 1;
        let prob = self.cdf[k + 1] - self.cdf[k];
        (prob > 0.0).then_some((k, prob))
    }
}

fn mean(v: Vec3) -> f32 {
    (v.x + v.y + v.z) / 3.0
}

fn triangle_area(geometry: &SceneGeometry, prim: u32) -> f32 {
    let t = geometry.accel.triangle(prim);
    0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length()
}

/// `∫ falloff dω` over a spot's cone, sr (midpoint rule in cosθ, 4096 steps).
fn spot_solid_angle(cos_outer: f32, cos_inner: f32, beam: f32) -> f32 {
    const STEPS: usize = 4096;
    let width = (1.0 - cos_outer as f64) / STEPS as f64;
    let sum: f64 = (0..STEPS)
        .map(|i| {
            let c = cos_outer as f64 + (i as f64 + 0.5) * width;
            spot_falloff(c as f32, cos_outer, cos_inner, beam) as f64
        })
        .sum();
    (2.0 * std::f64::consts::PI * sum * width) as f32
}

/// Centre and radius of a sphere around every triangle of `geometry`.
pub fn bounding_sphere(geometry: &SceneGeometry) -> (Vec3, f32) {
    let (lo, hi) = scene_bounds(geometry);
    if lo.cmpgt(hi).any() {
        return (Vec3::ZERO, 1.0);
    }
    let centre = 0.5 * (lo + hi);
    (centre, (0.5 * (hi - lo).length()).max(1e-6))
}

/// Axis-aligned bounds of every triangle of `geometry` (empty: lo > hi).
pub fn scene_bounds(geometry: &SceneGeometry) -> (Vec3, Vec3) {
    (0..geometry.accel.len() as u32).fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), prim| {
            let t = geometry.accel.triangle(prim);
            (
                lo.min(t[0]).min(t[1]).min(t[2]),
                hi.max(t[0]).max(t[1]).max(t[2]),
            )
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::components::{Emitter, LightShape};
    use crate::sampling::Sampler;
    use crate::shading::integrator::fixture::{self, Object};

    #[test]
    fn spot_power_integrates_its_cone() {
        // No penumbra, no beam falloff: the cone's solid angle 2π(1 − cos θ).
        let c = 30f32.to_radians().cos();
        let omega = spot_solid_angle(c, c, 0.0);
        assert!((omega - 2.0 * PI * (1.0 - c)).abs() < 1e-4, "{omega}");
        // cos¹ beam over the full hemisphere: π.
        let omega = spot_solid_angle(0.0, 0.0, 1.0);
        assert!((omega - PI).abs() < 1e-4, "{omega}");
    }

    fn lights(emitters: &[Emitter]) -> LightSet {
        LightSet::new(emitters, None, 1)
    }

    fn grey_floor() -> SceneGeometry {
        fixture::geometry(vec![Object {
            triangles: fixture::floor(2.0, 0.0),
            material: fixture::lambert(0.5),
        }])
    }

    #[test]
    fn light_powers_follow_from_their_units() {
        let geometry = grey_floor();
        let point = Emitter::new(LightShape::Point { position: Vec3::Z }, Vec3::splat(2.0));
        let rect = Emitter::new(
            LightShape::Rect {
                corner: Vec3::new(0.0, 0.0, 3.0),
                edge_u: Vec3::new(0.0, 2.0, 0.0),
                edge_v: Vec3::new(1.5, 0.0, 0.0),
            },
            Vec3::splat(5.0),
        );
        // Point: 4π·I. Rectangle: π·L·A.
        let e = Emission::new(&lights(std::slice::from_ref(&point)), &geometry);
        assert!((e.total_power().x - 8.0 * PI).abs() < 1e-4);
        let e = Emission::new(&lights(std::slice::from_ref(&rect)), &geometry);
        assert!((e.total_power().x - PI * 5.0 * 3.0).abs() < 1e-4);
        let e = Emission::new(&lights(&[point, rect]), &geometry);
        assert_eq!(e.light_count(), 2);
        assert!((e.total_power().x - 23.0 * PI).abs() < 1e-3);
        // The environment emits no photons: nothing to sample.
        assert!(Emission::new(&LightSet::default(), &geometry).is_empty());
    }

    #[test]
    fn every_photon_of_grey_lights_carries_the_total_power() {
        // A light is chosen with probability ∝ its power and the photon's power is divided by
        // that probability: with grey lights every photon carries exactly the total.
        let geometry = grey_floor();
        let emitters = [
            Emitter::new(
                LightShape::Point {
                    position: Vec3::new(0.0, 0.0, 1.0),
                },
                Vec3::splat(1.0),
            ),
            Emitter::new(
                LightShape::Disc {
                    center: Vec3::new(1.0, 0.0, 2.0),
                    normal: -Vec3::Z,
                    radius: 0.5,
                },
                Vec3::splat(3.0),
            ),
        ];
        let e = Emission::new(&lights(&emitters), &geometry);
        let total = e.total_power();
        let mut from_disc = 0;
        for i in 0..4000u64 {
            let mut s = Sampler::for_item(1, i, 0);
            let u = [(); 5].map(|_| s.next_1d());
            let p = e.sample(&geometry, u).unwrap();
            assert!(
                (p.power - total).abs().max_element() < 1e-4 * total.x,
                "{p:?}"
            );
            assert!((p.ray.dir.length() - 1.0).abs() < 1e-5);
            if (p.ray.origin.z - 2.0).abs() < 1e-6 {
                // Disc photons leave its lower face.
                let centre = Vec3::new(1.0, 0.0, 2.0);
                assert!(p.ray.dir.z < 0.0 && (p.ray.origin - centre).length() <= 0.5 + 1e-5);
                from_disc += 1;
            }
        }
        // P(disc) = 3π·π·0.25 / (4π + 0.75π²); photons are independent (σ ≈ 0.008).
        let p_disc = 0.75 * PI * PI / (4.0 * PI + 0.75 * PI * PI);
        let got = from_disc as f32 / 4000.0;
        println!("disc photons: {got} (probability {p_disc})");
        assert!((got - p_disc).abs() < 0.03, "{got} vs {p_disc}");
    }

    #[test]
    fn uniform_sphere_is_unit() {
        for i in 0..16 {
            let d = uniform_sphere(Vec2::new(i as f32 / 16.0, 0.3));
            assert!((d.length() - 1.0).abs() < 1e-5);
        }
    }
}

//! Light sampling: point, spot, directional, the four area-light shapes (rectangle, disc,
//! sphere, cylinder), emitting meshes and the environment.
//!
//! Every light returns samples as `(direction, distance, contribution)` where `contribution`
//! is the incident radiance already divided by the sampling pdf (in solid-angle terms), so the
//! reflected radiance of a BRDF `f` is `f · contribution · cosθ` averaged over samples.
//! Area lights and the environment can also be met by rays ([`Light::hit`],
//! [`LightSet::environment`]), with the pdf their sampler would have had, for MIS.
//!
//! Near/far attenuation (`Emitter::attenuation`) multiplies the radiance reaching a point at
//! distance `d` from the emitting point by a linear ramp, on top of the inverse-square law
//! (which the solid-angle conversion already contains for area lights).

mod area_points;
mod cylinder;
mod disc;
pub mod environment;
mod mesh;
mod rect;
mod sphere;

use std::sync::Arc;

use glam::{Vec2, Vec3};

pub use area_points::uniform_sphere;
pub use cylinder::CylinderLight;
pub use disc::DiscLight;
pub use environment::EnvLight;
pub use mesh::MeshLight;
pub use rect::RectLight;
pub use sphere::SphereLight;

use crate::accel::{gamma, Ray, SurfacePoint};
use crate::components::{attenuation_factor, Emitter, Environment, LightShape};
use crate::geometry::SceneGeometry;
use crate::shading::shadow::material_transmits_shadows;

/// The geometry of an area light.
#[derive(Debug, Clone, Copy)]
pub enum AreaShape {
    /// Parallelogram.
    Rect(RectLight),
    /// Disc.
    Disc(DiscLight),
    /// Sphere.
    Sphere(SphereLight),
    /// Open tube.
    Cylinder(CylinderLight),
}

/// An area light: a shape emitting uniform radiance from its front face.
#[derive(Debug, Clone, Copy)]
pub struct AreaLight {
    /// The shape.
    pub shape: AreaShape,
    /// Radiance, W/(sr·m²).
    pub radiance: Vec3,
    /// Trace shadow rays.
    pub shadows: bool,
    /// Light that passes occluders (mental ray `factor`, see [`LightSample::shadow_factor`]).
    pub shadow_factor: f32,
    /// Samples per shading point.
    pub samples: u32,
    /// Seen by camera rays and perfect mirror / refraction rays.
    pub visible: bool,
    /// Near/far attenuation `(start, end)`.
    pub attenuation: Option<(f32, f32)>,
    /// mental ray's non-physical area light (an area shape on `mib_light_point` or
    /// `mib_light_spot`; [`Emitter::inverse_square`] false): each sample is a point light of
    /// intensity `radiance` at a point of the shape, without distance falloff; rays do not
    /// meet the shape (see `area_points.rs`).
    pub points: bool,
}

impl AreaLight {
    /// The centre of the shape.
    pub fn centre(&self) -> Vec3 {
        match &self.shape {
            AreaShape::Rect(r) => r.corner + 0.5 * (r.edge_u + r.edge_v),
            AreaShape::Disc(d) => d.center,
            AreaShape::Sphere(s) => s.center,
            AreaShape::Cylinder(c) => c.start + c.frame.n * (0.5 * c.length),
        }
    }

    /// Ray parameter and solid-angle pdf (from the ray origin) where `ray` meets the shape's
    /// emitting face.
    #[inline(always)]
    fn shape_hit(&self, ray: &Ray) -> Option<(f32, f32)> {
        match &self.shape {
            AreaShape::Rect(r) => r.hit(ray),
            AreaShape::Disc(d) => d.hit(ray),
            AreaShape::Sphere(s) => s.hit(ray),
            AreaShape::Cylinder(c) => c.hit(ray),
        }
    }
}

/// A light prepared for sampling (world space).
#[derive(Debug, Clone)]
pub enum Light {
    /// Isotropic point light.
    Point {
        /// Position.
        position: Vec3,
        /// Intensity, W/sr.
        intensity: Vec3,
        /// Trace shadow rays.
        shadows: bool,
        /// Light that passes occluders (mental ray `factor`).
        shadow_factor: f32,
        /// Near/far attenuation `(start, end)`.
        attenuation: Option<(f32, f32)>,
        /// Whether `intensity` falls off as 1/d².
        inverse_square: bool,
    },
    /// RenderMan-style spotlight.
    Spot {
        /// Position.
        position: Vec3,
        /// Unit axis.
        axis: Vec3,
        /// cos of the cone half-angle (outer edge).
        cos_outer: f32,
        /// cos of (cone angle − penumbra) (inner edge of the penumbra).
        cos_inner: f32,
        /// Exponent of the cosine beam falloff.
        beam_distribution: f32,
        /// On-axis intensity, W/sr.
        intensity: Vec3,
        /// Trace shadow rays.
        shadows: bool,
        /// Light that passes occluders (mental ray `factor`).
        shadow_factor: f32,
        /// Near/far attenuation `(start, end)`.
        attenuation: Option<(f32, f32)>,
        /// Whether `intensity` falls off as 1/d².
        inverse_square: bool,
    },
    /// Distant light.
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3,
        /// Irradiance on a surface facing the light, W/m².
        irradiance: Vec3,
        /// Trace shadow rays.
        shadows: bool,
        /// Light that passes occluders (mental ray `factor`).
        shadow_factor: f32,
    },
    /// Rectangle, disc, sphere or cylinder.
    Area(AreaLight),
    /// All triangles of emitting materials, sampled by area × emitted radiance.
    Mesh(MeshLight),
    /// The scene's environment (rays that leave the scene).
    Environment(Arc<EnvLight>),
    /// Ambient light: never sampled; its `Cl` is summed into [`LightSet::ambient`].
    Ambient {
        /// `Cl`, the ambient term it adds (RenderMan `intensity · lightcolor`).
        radiance: Vec3,
    },
}

/// One sample toward a light.
#[derive(Debug, Clone, Copy)]
pub struct LightSample {
    /// Unit direction from the shading point toward the light.
    pub wi: Vec3,
    /// Incident radiance divided by the solid-angle pdf.
    pub contribution: Vec3,
    /// Where the shadow ray must reach: a point (`Some`) or infinity along `wi` (`None`).
    pub target: Option<SurfacePoint>,
    /// Whether a shadow ray is needed.
    pub shadows: bool,
    /// The fraction of the light that passes occluders (mental ray's light `factor`, 0 for
    /// full shadows): what reaches the point is `factor + (1 − factor)·T` of it, `T` the
    /// shadow ray's transmittance (see [`LightSample::lighten`]).
    pub shadow_factor: f32,
    /// Solid-angle pdf of the sample; 0 for delta lights (point, spot, directional), which
    /// no other strategy can reach.
    pub pdf: f32,
    /// Distance to the sampled point (infinite for directional lights and the environment).
    pub distance: f32,
}

impl LightSample {
    /// What reaches the point of the light past occluders of transmittance `t`:
    /// `factor + (1 − factor)·t`, `t` itself (bit for bit) when the factor is 0.
    pub fn lighten(&self, t: Vec3) -> Vec3 {
        Self::lighten_by(self.shadow_factor, t)
    }

    /// [`LightSample::lighten`] for a sample of shadow factor `factor`.
    #[inline(always)]
    pub fn lighten_by(factor: f32, t: Vec3) -> Vec3 {
        if factor == 0.0 {
            t
        } else {
            Vec3::splat(factor) + (1.0 - factor) * t
        }
    }
}

impl Light {
    /// Prepares a scene emitter for sampling. A light whose shadow factor is 1 lets all of
    /// its light pass occluders, so it traces no shadow rays: `factor + (1 − factor)·T` is
    /// 1 for every `T`, the value an unshadowed light gives, bit for bit.
    pub fn from_emitter(e: &Emitter) -> Self {
        let e = &Emitter {
            shadows: e.shadows && e.shadow_factor < 1.0,
            ..e.clone()
        };
        let area = |shape| {
            Light::Area(AreaLight {
                shape,
                radiance: e.radiant,
                shadows: e.shadows,
                shadow_factor: e.shadow_factor,
                samples: e.samples.max(1),
                visible: e.visible && e.inverse_square,
                attenuation: e.attenuation,
                points: !e.inverse_square,
            })
        };
        match e.shape {
            LightShape::Ambient => Light::Ambient {
                radiance: e.radiant,
            },
            LightShape::Point { position } => Light::Point {
                position,
                intensity: e.radiant,
                shadows: e.shadows,
                shadow_factor: e.shadow_factor,
                attenuation: e.attenuation,
                inverse_square: e.inverse_square,
            },
            LightShape::Spot {
                position,
                direction,
                cone_angle,
                penumbra,
                beam_distribution,
            } => Light::Spot {
                position,
                axis: direction.normalize_or_zero(),
                cos_outer: cone_angle.cos(),
                cos_inner: (cone_angle - penumbra.max(0.0)).max(0.0).cos(),
                beam_distribution,
                intensity: e.radiant,
                shadows: e.shadows,
                shadow_factor: e.shadow_factor,
                attenuation: e.attenuation,
                inverse_square: e.inverse_square,
            },
            LightShape::Directional { direction } => Light::Directional {
                direction: direction.normalize_or_zero(),
                irradiance: e.radiant,
                shadows: e.shadows,
                shadow_factor: e.shadow_factor,
            },
            LightShape::Rect {
                corner,
                edge_u,
                edge_v,
            } => area(AreaShape::Rect(RectLight::new(corner, edge_u, edge_v))),
            LightShape::Disc {
                center,
                normal,
                radius,
            } => area(AreaShape::Disc(DiscLight::new(center, normal, radius))),
            LightShape::Sphere { center, radius } => {
                area(AreaShape::Sphere(SphereLight { center, radius }))
            }
            LightShape::Cylinder { start, end, radius } => {
                area(AreaShape::Cylinder(CylinderLight::new(start, end, radius)))
            }
        }
    }

    /// Samples this light per shading point (1 for delta lights).
    pub fn sample_count(&self) -> u32 {
        match self {
            Light::Area(a) => a.samples,
            Light::Mesh(m) => m.samples,
            Light::Environment(e) => e.samples,
            _ => 1,
        }
    }

    /// Draws a sample toward the light from `p`; `None` when the light cannot reach `p`.
    pub fn sample(
        &self,
        p: Vec3,
        u: Vec2,
        geometry: Option<&SceneGeometry>,
    ) -> Option<LightSample> {
        match self {
            Light::Point {
                position,
                intensity,
                shadows,
                shadow_factor,
                attenuation,
                inverse_square,
            } => delta_sample(
                p,
                *position,
                *intensity,
                (*shadows, *shadow_factor),
                (*attenuation, *inverse_square),
            ),
            Light::Spot {
                position,
                axis,
                cos_outer,
                cos_inner,
                beam_distribution,
                intensity,
                shadows,
                shadow_factor,
                attenuation,
                inverse_square,
            } => {
                let d = (*position - p).normalize_or_zero();
                let falloff =
                    spot_falloff((-d).dot(*axis), *cos_outer, *cos_inner, *beam_distribution);
                if falloff <= 0.0 {
                    return None;
                }
                delta_sample(
                    p,
                    *position,
                    *intensity * falloff,
                    (*shadows, *shadow_factor),
                    (*attenuation, *inverse_square),
                )
            }
            Light::Directional {
                direction,
                irradiance,
                shadows,
                shadow_factor,
            } => Some(LightSample {
                wi: -*direction,
                contribution: *irradiance,
                target: None,
                shadows: *shadows,
                shadow_factor: *shadow_factor,
                pdf: 0.0,
                distance: f32::INFINITY,
            }),
            Light::Area(a) if a.points => area_points::point_sample(a, p, u),
            Light::Area(a) => {
                let mut s = match &a.shape {
                    AreaShape::Rect(r) => r.sample(p, u),
                    AreaShape::Disc(d) => d.sample(p, u),
                    AreaShape::Sphere(s) => s.sample(p, u),
                    AreaShape::Cylinder(c) => c.sample(p, u),
                }?;
                s.contribution *= a.radiance * attenuation_factor(a.attenuation, s.distance);
                s.shadows = a.shadows;
                s.shadow_factor = a.shadow_factor;
                (s.contribution.max_element() > 0.0 && s.contribution.is_finite()).then_some(s)
            }
            Light::Mesh(m) => m.sample(p, u, geometry?),
            Light::Environment(e) => e.sample(u),
            Light::Ambient { .. } => None,
        }
    }

    /// Where a ray meets this light, if it is an area light (whose front face only is
    /// seen): the ray parameter, the radiance arriving at the ray origin, and the solid-angle
    /// pdf with which [`Light::sample`] would have chosen that direction from the ray origin.
    /// `delta`: the ray is a camera ray or a perfect mirror/refraction ray of the eye's
    /// specular chain, which sees only `visible` lights. Emitting meshes are geometry (see [`LightSet::mesh_pdf`]); the
    /// environment is met by rays that miss everything (see [`LightSet::environment`]).
    pub fn hit(&self, ray: &Ray, delta: bool) -> Option<(f32, Vec3, f32)> {
        let Light::Area(a) = self else {
            return None;
        };
        if (delta && !a.visible) || a.points {
            return None;
        }
        let (t, pdf) = a.shape_hit(ray)?;
        let att = attenuation_factor(a.attenuation, t * ray.dir.length());
        (att > 0.0).then_some((t, a.radiance * att, pdf))
    }

    /// [`Light::hit`] (not the eye's chain) for a ray that goes on, unbent, from a path
    /// vertex at `p` through straight pass-throughs: the same light point, with the distance
    /// ramp and the solid-angle pdf measured from `p` — what next-event estimation at `p`
    /// used for the same direction, so that the two strategies are weighted against each
    /// other as if the pass-throughs were not there.
    pub fn hit_from(&self, ray: &Ray, p: Vec3) -> Option<(f32, Vec3, f32)> {
        let Light::Area(a) = self else {
            return None;
        };
        if a.points {
            return None;
        }
        let (t, pdf) = a.shape_hit(ray)?;
        let near = t * ray.dir.length();
        let far = (ray.origin + ray.dir * t - p).length();
        // The area shapes' pdfs are `d²/(cos·area)` with the same cosine along one line; the
        // sphere's is the cone it subtends from the sampling point.
        let pdf = match &a.shape {
            AreaShape::Sphere(s) => s.cone_pdf(p)?,
            _ => pdf * (far / near) * (far / near),
        };
        let att = attenuation_factor(a.attenuation, far);
        (att > 0.0 && pdf.is_finite() && pdf > 0.0).then_some((t, a.radiance * att, pdf))
    }
}

/// A sample of a point-like light at `q` with intensity `intensity` (W/sr), its near/far
/// ramp and whether it falls off as 1/d² (`falloff`).
fn delta_sample(
    p: Vec3,
    q: Vec3,
    intensity: Vec3,
    (shadows, shadow_factor): (bool, f32),
    falloff: (Option<(f32, f32)>, bool),
) -> Option<LightSample> {
    let (attenuation, inverse_square) = falloff;
    let d = q - p;
    let dist2 = d.length_squared();
    if !dist2.is_finite() || dist2 <= 0.0 {
        return None;
    }
    let dist = dist2.sqrt();
    let att = attenuation_factor(attenuation, dist);
    if att <= 0.0 {
        return None;
    }
    Some(LightSample {
        wi: d / dist,
        contribution: intensity * if inverse_square { att / dist2 } else { att },
        target: Some(SurfacePoint {
            p: q,
            p_err: Vec3::ZERO,
            ng: Vec3::ZERO,
        }),
        shadows,
        shadow_factor,
        pdf: 0.0,
        distance: dist,
    })
}

/// A shadow-ray target on a light's surface at `q` with normal `n`, whose position carries
/// a few roundings of error.
pub(crate) fn surface_target(q: Vec3, n: Vec3) -> SurfacePoint {
    error_target(q, n)
}

/// A target at `q` (normal `n`) with a conservative error bound of a handful of roundings.
pub(crate) fn error_target(q: Vec3, n: Vec3) -> SurfacePoint {
    SurfacePoint {
        p: q,
        p_err: q.abs() * gamma(8),
        ng: n,
    }
}

/// Converts an area-measure sample of an emitter at `target` (normal `target.ng`, sampled with
/// area pdf `1 / inv_pdf_area`) into a solid-angle light sample of radiance 1.
#[inline]
pub(crate) fn solid_angle_sample(
    p: Vec3,
    target: SurfacePoint,
    two_sided: bool,
    inv_pdf_area: f32,
) -> Option<LightSample> {
    let d = target.p - p;
    let dist2 = d.length_squared();
    if dist2.is_nan() || dist2 <= 0.0 {
        return None;
    }
    let dist = dist2.sqrt();
    let wi = d / dist;
    let mut cos_l = target.ng.dot(-wi);
    if two_sided {
        cos_l = cos_l.abs();
    }
    if cos_l.is_nan() || cos_l <= 0.0 {
        return None;
    }
    let pdf = dist2 / (cos_l * inv_pdf_area);
    if !crate::sampling::usable_pdf(pdf) {
        return None;
    }
    Some(LightSample {
        wi,
        contribution: Vec3::splat(1.0 / pdf),
        target: Some(target),
        shadows: true,
        shadow_factor: 0.0,
        pdf,
        distance: dist,
    })
}

/// RenderMan spotlight attenuation: `cos^beam · smoothstep(cos_outer, cos_inner, cos)`.
pub fn spot_falloff(cos_angle: f32, cos_outer: f32, cos_inner: f32, beam: f32) -> f32 {
    if cos_angle <= cos_outer {
        return 0.0;
    }
    let edge = if cos_inner > cos_outer {
        let t = ((cos_angle - cos_outer) / (cos_inner - cos_outer)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    } else {
        1.0
    };
    cos_angle.max(0.0).powf(beam) * edge
}

/// The lights of a scene, ready for sampling.
#[derive(Debug, Clone, Default)]
pub struct LightSet {
    /// Every light: emitters (in entity order), then the emitting-mesh light, then the
    /// environment.
    pub lights: Vec<Light>,
    /// The environment seen by rays that leave the scene.
    pub environment: Option<Arc<EnvLight>>,
    /// Whether some material lets shadow rays through (tinted shadows are traced).
    pub transmissive_shadows: bool,
    /// Whether camera rays that miss everything see the environment (off when the camera's
    /// imager fills the background instead).
    pub camera_sees_environment: bool,
    /// The sum of the ambient lights' `Cl` (RenderMan's `ambient()`), which local
    /// illumination models weight by their `ka`.
    pub ambient: Vec3,
}

impl LightSet {
    /// Lights from scene emitters plus one light for all emitting triangles in `geometry`.
    pub fn new(emitters: &[Emitter], geometry: Option<&SceneGeometry>, mesh_samples: u32) -> Self {
        let mut lights: Vec<Light> = emitters.iter().map(Light::from_emitter).collect();
        if let Some(mesh) = geometry.and_then(|g| MeshLight::new(g, mesh_samples)) {
            lights.push(Light::Mesh(mesh));
        }
        let transmissive_shadows =
            geometry.is_some_and(|g| g.materials.iter().any(material_transmits_shadows));
        let ambient = lights.iter().fold(Vec3::ZERO, |a, l| match l {
            Light::Ambient { radiance } => a + *radiance,
            _ => a,
        });
        Self {
            lights,
            environment: None,
            transmissive_shadows,
            camera_sees_environment: true,
            ambient,
        }
    }

    /// Adds the scene's environment as a light (and as what rays leaving the scene see).
    pub fn with_environment(mut self, environment: Option<&Environment>) -> Self {
        if let Some(env) = environment {
            let light = Arc::new(EnvLight::new(env));
            if light.can_sample() {
                self.lights.push(Light::Environment(light.clone()));
            }
            self.environment = Some(light);
        }
        self
    }

    /// Solid-angle pdf with which the emitting-mesh light samples the point `q` (geometric
    /// normal `ng`, emitted radiance `emission`, `two_sided` emission) from `p`; 0 when no
    /// mesh light exists or `q` faces away.
    pub fn mesh_pdf(&self, p: Vec3, q: Vec3, ng: Vec3, emission: Vec3, two_sided: bool) -> f32 {
        self.lights
            .iter()
            .find_map(|l| match l {
                Light::Mesh(m) => Some(m.pdf(p, q, ng, emission, two_sided)),
                _ => None,
            })
            .unwrap_or(0.0)
    }

    /// Radiance of the environment along `dir` and the solid-angle pdf of its light sampler
    /// for that direction (0 when it is not sampled); `None` without an environment.
    pub fn environment_along(&self, dir: Vec3) -> Option<(Vec3, f32)> {
        let env = self.environment.as_ref()?;
        let d = dir.normalize_or_zero();
        Some((env.radiance(d), env.pdf(d)))
    }

    /// Whether rays beyond a trace-depth budget see the environment (else black).
    pub fn depth_exceeded_sees_environment(&self) -> bool {
        self.environment
            .as_ref()
            .is_some_and(|e| e.depth_exceeded_environment)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spot_is_full_inside_and_zero_outside_the_cone() {
        let (outer, inner) = (30f32.to_radians().cos(), 25f32.to_radians().cos());
        assert_eq!(spot_falloff(1.0, outer, inner, 0.0), 1.0);
        assert_eq!(
            spot_falloff(31f32.to_radians().cos(), outer, inner, 0.0),
            0.0
        );
        let mid = spot_falloff(27.5f32.to_radians().cos(), outer, inner, 0.0);
        assert!(mid > 0.3 && mid < 0.7, "{mid}");
        // Beam distribution: cos² on the axis' neighbourhood.
        let c = 10f32.to_radians().cos();
        assert!((spot_falloff(c, outer, inner, 2.0) - c * c).abs() < 1e-6);
    }

    #[test]
    fn point_light_follows_inverse_square() {
        let l = Light::from_emitter(&Emitter::new(
            LightShape::Point {
                position: Vec3::new(0.0, 0.0, 2.0),
            },
            Vec3::splat(8.0),
        ));
        let s = l.sample(Vec3::ZERO, Vec2::ZERO, None).unwrap();
        assert_eq!(s.contribution, Vec3::splat(2.0));
        assert_eq!(s.wi, Vec3::Z);
    }

    #[test]
    fn near_far_attenuation_ramps_linearly() {
        let mut e = Emitter::new(
            LightShape::Point {
                position: Vec3::new(0.0, 0.0, 2.0),
            },
            Vec3::splat(8.0),
        );
        e.attenuation = Some((1.0, 3.0));
        let l = Light::from_emitter(&e);
        // d = 2: half-way along the ramp, on top of 1/d².
        let s = l.sample(Vec3::ZERO, Vec2::ZERO, None).unwrap();
        assert!((s.contribution.x - 1.0).abs() < 1e-6, "{}", s.contribution);
        assert!(l
            .sample(Vec3::new(0.0, 0.0, -1.5), Vec2::ZERO, None)
            .is_none());
    }

    #[test]
    fn rect_light_is_one_sided() {
        let l = Light::from_emitter(&Emitter::new(
            LightShape::Rect {
                corner: Vec3::new(-0.5, -0.5, 1.0),
                edge_u: Vec3::X,
                edge_v: Vec3::Y,
            },
            Vec3::ONE,
        ));
        // Normal is +Z: a point below the light (z = 0) sees its back.
        assert!(l.sample(Vec3::ZERO, Vec2::splat(0.5), None).is_none());
        assert!(l
            .sample(Vec3::new(0.0, 0.0, 2.0), Vec2::splat(0.5), None)
            .is_some());
    }

    #[test]
    fn samples_and_hits_agree_on_pdf_for_every_shape() {
        let shapes = [
            LightShape::Rect {
                corner: Vec3::new(-0.5, -0.5, 2.0),
                edge_u: Vec3::Y,
                edge_v: Vec3::X,
            },
            LightShape::Disc {
                center: Vec3::new(0.2, 0.0, 2.0),
                normal: Vec3::new(0.1, 0.0, -1.0),
                radius: 0.7,
            },
            LightShape::Sphere {
                center: Vec3::new(0.3, -0.2, 2.5),
                radius: 0.8,
            },
            LightShape::Cylinder {
                start: Vec3::new(-1.0, 0.0, 2.0),
                end: Vec3::new(1.0, 0.3, 2.2),
                radius: 0.4,
            },
        ];
        for shape in shapes {
            let l = Light::from_emitter(&Emitter::new(shape.clone(), Vec3::splat(2.0)));
            let p = Vec3::new(0.05, 0.1, 0.0);
            for i in 0..64 {
                let u = Vec2::new((i % 8) as f32 / 8.0 + 0.06, (i / 8) as f32 / 8.0 + 0.03);
                let s = l
                    .sample(p, u, None)
                    .unwrap_or_else(|| panic!("{shape:?} {u}"));
                let ray = Ray {
                    origin: p,
                    dir: s.wi,
                    t_max: f32::INFINITY,
                };
                let (t, le, pdf) = l.hit(&ray, false).unwrap_or_else(|| panic!("{shape:?}"));
                assert!((t - s.distance).abs() < 1e-3 * s.distance, "{shape:?}");
                assert_eq!(le, Vec3::splat(2.0));
                assert!(
                    (pdf - s.pdf).abs() < 2e-3 * s.pdf,
                    "{shape:?}: {pdf} vs {}",
                    s.pdf
                );
                assert!(l.hit(&ray, true).is_none(), "invisible to delta rays");
            }
        }
    }
}

//! Radiance integrators: what a camera ray that hit the scene sees.
//!
//! [`direct`] is the fast default (direct lighting plus traced mirror/refraction branches);
//! [`path`] is the unbiased reference path tracer. Both share the helpers here: turning a
//! hit into a shading [`Vertex`], the light loop with (tinted) shadow rays, rays crossing
//! area lights or leaving for the environment, and absorption inside dielectrics.
//!
//! Trace depths: the vertex reached by the camera ray has depth 1. A vertex of depth `k`
//! adds its emission; if `k ≤ max_depth` it also gathers light (paths of `k + 1` segments)
//! and continues. Glossy/mirror reflections count against `reflection_depth`, refractions
//! and transparency against `refraction_depth`; a branch beyond its budget is not traced.
//! Area lights are seen by camera rays and perfect mirror/refraction rays only when they are
//! `visible`; BSDF-sampled path-tracer rays see every area light's front face (MIS). A ray
//! beyond a reflection/refraction budget sees the environment or black, as the scene's
//! environment says (`depth_exceeded`).

pub mod direct;
pub mod path;
pub mod volume;

use std::borrow::Cow;

use glam::Vec3;

use crate::accel::{spawn_ray, spawn_ray_to, spawn_ray_to_surface, Hit, Ray, SurfacePoint};
use crate::components::{Material, Shader};
use crate::geometry::{SceneGeometry, ShadingPoint};
use crate::sampling::Sampler;
use crate::settings::{Face, Integrator, RenderSettings};
use crate::shading::bsdf::Bsdf;
use crate::shading::frame::ShadingFrame;
use crate::shading::lights::LightSet;
use crate::shading::mis::power_heuristic;
use crate::shading::shadow::transmittance;
use crate::shading::texture::{bump, hit as textured};
use crate::shading::volume::Volumes;
use volume::shadow_transmittance;

/// What shading a hit needs from the scene.
pub struct ShadeContext<'a> {
    /// Geometry and BVH.
    pub geometry: &'a SceneGeometry,
    /// Lights.
    pub lights: &'a LightSet,
    /// Face visibility option.
    pub face: Face,
    /// Which integrator runs.
    pub integrator: Integrator,
    /// Most surface interactions per path (see the module doc).
    pub max_depth: u32,
    /// Most glossy/mirror reflections per path.
    pub reflection_depth: u32,
    /// Most refractions per path.
    pub refraction_depth: u32,
    /// Photon maps the `Direct` integrator reads (caustics, final gather); `None`: none.
    pub photons: Option<&'a dyn PhotonRadiance>,
    /// Fog around the camera and inside materials (`None`: vacuum everywhere).
    pub volumes: Option<&'a Volumes>,
}

impl<'a> ShadeContext<'a> {
    /// A context with the integrator and depths of `settings`.
    pub fn new(
        geometry: &'a SceneGeometry,
        lights: &'a LightSet,
        settings: &RenderSettings,
    ) -> Self {
        Self {
            geometry,
            lights,
            face: settings.face,
            integrator: settings.integrator,
            max_depth: settings.max_depth,
            reflection_depth: settings.reflection_depth,
            refraction_depth: settings.refraction_depth,
            photons: None,
            volumes: None,
        }
    }

    /// The same context reading `photons` (the photon maps, `photon::PhotonMaps`).
    pub fn with_photons<P: PhotonRadiance>(mut self, photons: Option<&'a P>) -> Self {
        self.photons = photons.map(|p| p as &dyn PhotonRadiance);
        self
    }

    /// The same context with the scene's media.
    pub fn with_volumes(mut self, volumes: Option<&'a Volumes>) -> Self {
        self.volumes = volumes;
        self
    }
}

/// Radiance photon maps add at a diffuse shading point of the `Direct` integrator (caustics
/// and final gather). Implemented by `photon::PhotonMaps`; the trait keeps the shading
/// library free of the photon module, which traces photons with this library's lights,
/// BSDFs and [`Vertex`].
pub trait PhotonRadiance: Sync {
    /// Radiance toward the viewer at `v` through `bsdf` (`bsdf` has a non-delta part).
    fn radiance(
        &self,
        ctx: &ShadeContext<'_>,
        v: &Vertex<'_>,
        bsdf: &Bsdf,
        sampler: &mut Sampler,
    ) -> Vec3;
}

/// Radiance arriving at the origin of the camera ray `ray` from its first hit `hit`.
pub fn shade_hit(ctx: &ShadeContext<'_>, ray: &Ray, hit: &Hit, sampler: &mut Sampler) -> Vec3 {
    match ctx.integrator {
        Integrator::Direct => direct::radiance(ctx, ray, hit, sampler),
        Integrator::Path => path::radiance(ctx, ray, hit, sampler),
    }
}

/// Counts of what a path has done so far.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Depth {
    /// Index of the current vertex (camera-ray hit = 1).
    pub vertex: u32,
    /// Glossy/mirror reflections so far.
    pub reflections: u32,
    /// Refractions so far.
    pub refractions: u32,
}

impl Depth {
    /// The first vertex.
    pub const FIRST: Depth = Depth {
        vertex: 1,
        reflections: 0,
        refractions: 0,
    };

    /// The depth after scattering of the given kind, or `None` when its budget is spent.
    pub fn after(
        self,
        ctx: &ShadeContext<'_>,
        reflection: bool,
        transmission: bool,
    ) -> Option<Depth> {
        let mut d = self;
        d.vertex += 1;
        if transmission {
            d.refractions += 1;
            if d.refractions > ctx.refraction_depth {
                return None;
            }
        } else if reflection {
            d.reflections += 1;
            if d.reflections > ctx.reflection_depth {
                return None;
            }
        }
        Some(d)
    }
}

/// A shading point with its local frame, oriented toward the viewer.
pub struct Vertex<'a> {
    /// Hit point; `normal` faces the viewer, `surface.ng` is the unflipped geometric normal.
    pub sp: ShadingPoint,
    /// Geometric normal on the viewer's side.
    pub ng: Vec3,
    /// Whether the front face was hit.
    pub front: bool,
    /// Whether this face is shaded (false: back of a one-sided surface, black but opaque).
    pub visible: bool,
    /// The material.
    pub material: &'a Material,
    /// The material's shader at this point: its texture-driven parameters evaluated.
    pub shader: Cow<'a, Shader>,
    /// Whether a bump map perturbed `sp.normal`.
    pub bumped: bool,
    /// Frame around `sp.normal`.
    pub frame: ShadingFrame,
    /// Direction toward the viewer, local.
    pub wo: Vec3,
    /// Transmittance of the segment that reached this vertex (absorption inside a dielectric).
    pub transmittance: Vec3,
}

impl<'a> Vertex<'a> {
    /// The vertex where `ray` hits `hit`.
    ///
    /// Texture nodes are evaluated here (the bound shader, the bump-mapped normal). The
    /// shading normal is then made safe (hard case H11): turned toward the viewer's side and
    /// rotated toward the geometric normal just enough that the view direction is above it
    /// and its mirror direction above the geometric surface
    /// ([`bump::ensure_valid_reflection`]), so bent normals never shade black.
    pub fn new(ctx: &ShadeContext<'a>, ray: &Ray, hit: &Hit) -> Self {
        let mut sp = ctx.geometry.shading_point(hit);
        let material = &ctx.geometry.materials[sp.material as usize];
        let (shader, bumped) = match textured::evaluate(ctx.geometry, &sp, hit, material) {
            Some(t) => {
                sp.normal = t.normal;
                (Cow::Owned(t.shader), t.bumped)
            }
            None => (Cow::Borrowed(&material.shader), false),
        };
        let wo_world = -ray.dir.normalize();
        let front = sp.surface.ng.dot(wo_world) > 0.0;
        if !front {
            sp.normal = -sp.normal;
        }
        let ng = if front { sp.surface.ng } else { -sp.surface.ng };
        if sp.normal != ng {
            sp.normal = bump::ensure_valid_reflection(ng, wo_world, sp.normal);
        }
        let visible = front || material.shades_back() || ctx.face == Face::Both;
        let transmittance = match &*shader {
            Shader::Dielectric { col, .. } if !front => {
                let d = hit.t * ray.dir.length();
                Vec3::new(col.x.powf(d), col.y.powf(d), col.z.powf(d))
            }
            _ => Vec3::ONE,
        };
        let frame = ShadingFrame::from_normal(sp.normal);
        Self {
            sp,
            ng,
            front,
            visible,
            material,
            shader,
            bumped,
            frame,
            wo: frame.to_local(wo_world),
            transmittance,
        }
    }

    /// The bump shadowing term for light arriving from the world direction `wi`
    /// ([`bump::shadowing`]); 1 at points without a bump map.
    pub fn bump_shadowing(&self, wi: Vec3) -> f32 {
        if self.bumped {
            bump::shadowing(self.ng, self.sp.normal, wi)
        } else {
            1.0
        }
    }

    /// Radiance emitted toward the viewer.
    pub fn emitted(&self) -> Vec3 {
        if self.visible && (self.front || self.material.two_sided) {
            self.material.emission
        } else {
            Vec3::ZERO
        }
    }

    /// The BSDF of this face.
    pub fn bsdf(&self) -> Option<Bsdf> {
        Bsdf::new(&self.shader, self.front)
    }

    /// A ray leaving along the local direction `wi` if it lies on the geometric side its
    /// kind requires (reflection: the viewer's side; transmission: the other side).
    pub fn spawn(&self, wi_local: Vec3, transmits: bool) -> Option<Ray> {
        let wi = self.frame.to_world(wi_local);
        let side = self.ng.dot(wi);
        let ok = if transmits { side < 0.0 } else { side > 0.0 };
        (ok && wi.is_finite()).then(|| spawn_ray(&self.sp.surface, wi))
    }
}

/// Light gathered at `v` by sampling every light: `samples_per_light` samples each (`None`:
/// the light's own count, with child sequences of `sampler`; `Some(1)`: one sample each from
/// `sampler`'s next dimensions and MIS-weighted against BSDF sampling). Shadow rays pass
/// transmissive surfaces with their shadow tint (see [`crate::shading::shadow`]).
pub fn light_loop(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    bsdf: &Bsdf,
    sampler: &mut Sampler,
    mis: bool,
) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    for light in &ctx.lights.lights {
        let (n, mut child) = if mis {
            (1, None)
        } else {
            (light.sample_count(), Some(sampler.child_seed()))
        };
        let mut sum = Vec3::ZERO;
        for j in 0..n {
            let u = match child.as_mut() {
                Some(seed) => Sampler::new(*seed, j).next_2d(),
                None => sampler.next_2d(),
            };
            let Some(ls) = light.sample(v.sp.surface.p, u, Some(ctx.geometry)) else {
                continue;
            };
            let wi = v.frame.to_local(ls.wi);
            if wi.z <= 0.0 || v.ng.dot(ls.wi) <= 0.0 {
                continue;
            }
            let f = bsdf.eval(v.wo, wi) * v.bump_shadowing(ls.wi);
            if f == Vec3::ZERO {
                continue;
            }
            let shadow = match ctx.volumes {
                // Fog attenuates the shadow ray; fog-filled shells and transparent surfaces
                // let it through.
                Some(_) => {
                    let first = shadow_ray(&v.sp, ls.wi, ls.target);
                    let target = ls.target.map(|t| t.p);
                    let atmosphere = ctx.volumes.and_then(|vol| vol.atmosphere.as_ref());
                    match shadow_transmittance(ctx, first, atmosphere, target, ls.shadows) {
                        Some(t) => t,
                        None => continue,
                    }
                }
                None if ls.shadows => transmittance(
                    ctx.geometry,
                    &v.sp.surface,
                    ls.wi,
                    ls.target,
                    ctx.lights.transmissive_shadows,
                ),
                None => Vec3::ONE,
            };
            if shadow == Vec3::ZERO {
                continue;
            }
            let w = if mis && ls.pdf > 0.0 {
                power_heuristic(ls.pdf, bsdf.pdf(v.wo, wi))
            } else {
                1.0
            };
            sum += f * ls.contribution * shadow * (wi.z * w);
        }
        radiance += sum / n as f32;
    }
    radiance
}

/// The shadow ray from `sp` toward a light sample.
fn shadow_ray(sp: &ShadingPoint, wi: Vec3, target: Option<SurfacePoint>) -> Ray {
    match target {
        None => spawn_ray(&sp.surface, wi),
        Some(t) if t.ng == Vec3::ZERO => spawn_ray_to(&sp.surface, t.p),
        Some(t) => spawn_ray_to_surface(&sp.surface, &t),
    }
}

/// The closest hit along a ray, and the emitters it meets before that hit: the area lights it
/// crosses and, when it hits nothing, the environment — `(radiance, light pdf)` of each, the
/// pdf being the solid-angle density of that light's own sampler (0 if it is not sampled).
///
/// `delta`: a camera ray or a perfect mirror/refraction ray. Those see only `visible` area
/// lights, and a visible light is opaque to them: the nearest one in front of the hit ends
/// the ray (no hit is returned). BSDF-sampled rays see every area light's front face
/// additively and go on (lights never block light, and MIS needs every light reachable).
pub fn trace(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    delta: bool,
) -> (Option<Hit>, Vec3, Vec<(Vec3, f32)>) {
    let hit = ctx.geometry.accel.intersect(ray);
    let mut clipped = *ray;
    if let Some(h) = &hit {
        clipped.t_max = h.t;
    }
    if delta {
        let nearest = ctx
            .lights
            .lights
            .iter()
            .filter_map(|l| l.hit(&clipped, true))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, le, pdf)) = nearest {
            return (None, le, vec![(le, pdf)]);
        }
    }
    let mut direct = Vec3::ZERO;
    let mut crossed = Vec::new();
    if !delta {
        for light in &ctx.lights.lights {
            if let Some((_, radiance, pdf)) = light.hit(&clipped, false) {
                direct += radiance;
                crossed.push((radiance, pdf));
            }
        }
    }
    if hit.is_none() {
        if let Some((le, pdf)) = ctx.lights.environment_along(ray.dir) {
            direct += le;
            crossed.push((le, pdf));
        }
    }
    (hit, direct, crossed)
}

/// Radiance a ray that is not traced because it exceeds a trace-depth budget brings back:
/// the environment along it when the scene says so (with its light pdf), else nothing.
pub fn depth_exceeded(ctx: &ShadeContext<'_>, dir: Vec3) -> Option<(Vec3, f32)> {
    if ctx.lights.depth_exceeded_sees_environment() {
        ctx.lights.environment_along(dir)
    } else {
        None
    }
}

/// What a camera ray meets first.
#[derive(Debug, Clone, Copy)]
pub enum CameraHit {
    /// A surface, to be shaded.
    Surface(Hit),
    /// A visible area light in front of every surface: the radiance reaching the camera
    /// (attenuated by the atmosphere, if any); covers the pixel.
    Light(Vec3),
    /// Nothing: the environment's radiance along the ray (black when there is none, or when
    /// [`LightSet::camera_sees_environment`] is off because a camera imager's background
    /// replaces it). Does not cover the pixel (alpha 0).
    Miss(Vec3),
}

/// What the camera ray `ray` meets first (see [`CameraHit`]).
pub fn camera_hit(ctx: &ShadeContext<'_>, ray: &Ray) -> CameraHit {
    let hit = ctx.geometry.accel.intersect(ray);
    let mut clipped = *ray;
    if let Some(h) = &hit {
        clipped.t_max = h.t;
    }
    let nearest_light = ctx
        .lights
        .lights
        .iter()
        .filter_map(|l| l.hit(&clipped, true))
        .min_by(|a, b| a.0.total_cmp(&b.0));
    match (nearest_light, hit) {
        (Some((t, le, _)), _) => {
            let fog = ctx.volumes.and_then(|v| v.atmosphere.as_ref());
            let att = fog.map_or(Vec3::ONE, |f| f.transmittance(t * ray.dir.length()));
            CameraHit::Light(le * att)
        }
        (None, Some(h)) => CameraHit::Surface(h),
        (None, None) if ctx.lights.camera_sees_environment => CameraHit::Miss(
            ctx.lights
                .environment_along(ray.dir)
                .map_or(Vec3::ZERO, |(le, _)| le),
        ),
        (None, None) => CameraHit::Miss(Vec3::ZERO),
    }
}

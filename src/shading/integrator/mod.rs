//! Radiance integrators: what a camera ray that hit the scene sees.
//!
//! [`direct`] is the fast default (direct lighting plus traced mirror/refraction branches);
//! [`path`] is the unbiased reference path tracer. Both share the helpers here: turning a
//! hit into a shading [`Vertex`], the light loop with shadow rays, rays crossing `Rect`
//! lights, and absorption inside dielectrics.
//!
//! Trace depths: the vertex reached by the camera ray has depth 1. A vertex of depth `k`
//! adds its emission; if `k ≤ max_depth` it also gathers light (paths of `k + 1` segments)
//! and continues. Glossy/mirror reflections count against `reflection_depth`, refractions
//! and transparency against `refraction_depth`; a branch beyond its budget is not traced.
//! `Rect` lights are not seen by camera rays; every other ray sees their front face.

pub mod direct;
pub mod path;

use glam::Vec3;

use crate::accel::{spawn_ray, spawn_ray_to, spawn_ray_to_surface, Hit, Ray, SurfacePoint};
use crate::components::{Material, Shader};
use crate::geometry::{SceneGeometry, ShadingPoint};
use crate::photon::PhotonMaps;
use crate::sampling::Sampler;
use crate::settings::{Face, Integrator, RenderSettings};
use crate::shading::bsdf::Bsdf;
use crate::shading::frame::ShadingFrame;
use crate::shading::lights::LightSet;
use crate::shading::mis::power_heuristic;

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
    pub photons: Option<&'a PhotonMaps>,
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
        }
    }

    /// The same context reading `photons`.
    pub fn with_photons(mut self, photons: Option<&'a PhotonMaps>) -> Self {
        self.photons = photons;
        self
    }
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
    /// Frame around `sp.normal`.
    pub frame: ShadingFrame,
    /// Direction toward the viewer, local.
    pub wo: Vec3,
    /// Transmittance of the segment that reached this vertex (absorption inside a dielectric).
    pub transmittance: Vec3,
}

impl<'a> Vertex<'a> {
    /// The vertex where `ray` hits `hit`.
    pub fn new(ctx: &ShadeContext<'a>, ray: &Ray, hit: &Hit) -> Self {
        let mut sp = ctx.geometry.shading_point(hit);
        let material = &ctx.geometry.materials[sp.material as usize];
        let wo_world = -ray.dir.normalize();
        let front = sp.surface.ng.dot(wo_world) > 0.0;
        if !front {
            sp.normal = -sp.normal;
        }
        let ng = if front { sp.surface.ng } else { -sp.surface.ng };
        let visible = front || material.shades_back() || ctx.face == Face::Both;
        let transmittance = match &material.shader {
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
            frame,
            wo: frame.to_local(wo_world),
            transmittance,
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
        Bsdf::new(&self.material.shader, self.front)
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
/// `sampler`'s next dimensions and MIS-weighted against BSDF sampling).
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
            let f = bsdf.eval(v.wo, wi);
            if f == Vec3::ZERO {
                continue;
            }
            if ls.shadows && occluded(ctx.geometry, &v.sp, ls.wi, ls.target) {
                continue;
            }
            let w = if mis && ls.pdf > 0.0 {
                power_heuristic(ls.pdf, bsdf.pdf(v.wo, wi))
            } else {
                1.0
            };
            sum += f * ls.contribution * (wi.z * w);
        }
        radiance += sum / n as f32;
    }
    radiance
}

/// Whether the shadow ray from `sp` toward a light sample is blocked.
fn occluded(
    geometry: &SceneGeometry,
    sp: &ShadingPoint,
    wi: Vec3,
    target: Option<SurfacePoint>,
) -> bool {
    let ray = match target {
        None => spawn_ray(&sp.surface, wi),
        Some(t) if t.ng == Vec3::ZERO => spawn_ray_to(&sp.surface, t.p),
        Some(t) => spawn_ray_to_surface(&sp.surface, &t),
    };
    geometry.accel.occluded(&ray)
}

/// The closest hit along a ray leaving a surface, and the `Rect` lights it crosses before
/// that hit: `(radiance, pdf)` of each (at most the number of lights).
pub fn trace(ctx: &ShadeContext<'_>, ray: &Ray) -> (Option<Hit>, Vec3, Vec<(Vec3, f32)>) {
    let hit = ctx.geometry.accel.intersect(ray);
    let mut clipped = *ray;
    if let Some(h) = &hit {
        clipped.t_max = h.t;
    }
    let mut direct = Vec3::ZERO;
    let mut crossed = Vec::new();
    for light in &ctx.lights.lights {
        if let Some((_, radiance, pdf)) = light.hit(&clipped) {
            direct += radiance;
            crossed.push((radiance, pdf));
        }
    }
    (hit, direct, crossed)
}

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
//! Area lights are seen by camera rays and perfect mirror/refraction rays of the eye's chain
//! (`E S*`) only when they are `visible`; BSDF-sampled path-tracer rays, and any ray of a
//! path after its first non-delta scattering, see every area light's front face (MIS). A ray
//! beyond a reflection/refraction budget sees the environment or black, as the scene's
//! environment says (`depth_exceeded`).
//!
//! Material environments (`Material::environment`, mental ray's material `environment`
//! shader): a specular (delta: mirror, refraction, transparency) ray spawned at a material
//! that has one sees that environment instead of the scene's when it leaves the scene or
//! exceeds a budget — every traced branch of [`direct`], the delta continuation rays of
//! [`path`]. Glossy and diffuse rays, final gathering and light sampling keep the scene's
//! environment (which stays a light).

pub mod components;
pub mod direct;
#[cfg(test)]
pub(crate) mod fixture;
pub mod local;
pub mod material_bsdfs;
pub(crate) mod orient;
pub mod path;
mod power;
mod shadow_packets;
pub mod triangle_normals;
pub mod volume;

use std::borrow::Cow;

use glam::Vec3;

use crate::accel::{
    spawn_ray, spawn_ray_to, spawn_ray_to_surface, Hit, Ray, RayKind, SurfacePoint,
};
use crate::components::{DepthExceeded, Material, MaterialEnvironment, Shader};
use crate::geometry::{SceneGeometry, ShadingPoint};
use crate::sampling::Sampler;
use crate::settings::{Face, Integrator, RenderSettings};
use crate::shading::bsdf::Bsdf;
use crate::shading::frame::ShadingFrame;
use crate::shading::lights::environment::source_radiance;
use crate::shading::lights::{Light, LightSet};
use crate::shading::shadow::transmittance;
use crate::shading::texture::{bump, hit as textured};
use crate::shading::volume::Volumes;
use material_bsdfs::MaterialBsdfs;
use orient::{bsdf_kept_or_in, kept_bsdf, orient, shading_point, spawn_along, Orientation};
use power::power_weight;
use triangle_normals::TriangleNormals;
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
    /// Most reflections and refractions of one photon (the photon pass's limit).
    pub photon_depth: crate::settings::PhotonDepth,
    /// Photon maps the `Direct` integrator reads (caustics, final gather); `None`: none.
    pub photons: Option<&'a dyn PhotonRadiance>,
    /// Fog around the camera and inside materials (`None`: vacuum everywhere).
    pub volumes: Option<&'a Volumes>,
    /// The triangles' unit normals, when kept for this scene (hit points then skip
    /// recomputing them; the same values).
    pub normals: Option<&'a TriangleNormals>,
    /// The materials' BSDFs, when kept for this scene (untextured hits then read theirs
    /// instead of building it; the same values).
    pub bsdfs: Option<&'a MaterialBsdfs>,
    /// Whether the light loop without MIS traces each light's shadow rays together
    /// ([`shadow_packets::pays`], decided once per context).
    shadow_packets: bool,
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
            photon_depth: settings.photons.depth,
            photons: None,
            volumes: None,
            normals: None,
            bsdfs: None,
            shadow_packets: shadow_packets::pays(geometry, lights, None),
        }
    }

    /// The same context reading untextured hits' BSDFs from `bsdfs` (made of `geometry`).
    pub fn with_bsdfs(mut self, bsdfs: Option<&'a MaterialBsdfs>) -> Self {
        self.bsdfs = bsdfs;
        self
    }

    /// The same context reading the triangles' normals from `normals` (made of `geometry`).
    pub fn with_normals(mut self, normals: Option<&'a TriangleNormals>) -> Self {
        self.normals = normals;
        self
    }

    /// The same context reading `photons` (the photon maps, `photon::PhotonMaps`).
    pub fn with_photons<P: PhotonRadiance>(mut self, photons: Option<&'a P>) -> Self {
        self.photons = photons.map(|p| p as &dyn PhotonRadiance);
        self
    }

    /// The same context with the scene's media.
    pub fn with_volumes(mut self, volumes: Option<&'a Volumes>) -> Self {
        self.volumes = volumes;
        self.shadow_packets = shadow_packets::pays(self.geometry, self.lights, volumes);
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

    /// Irradiance the caustic map gives at `v` from photons arriving on the front of its
    /// shading normal, W/m² (what AIR's `caustic` light delivers to a `Local` model's diffuse
    /// sum); zero without a caustic map.
    fn caustic_irradiance(&self, _v: &Vertex<'_>) -> Vec3 {
        Vec3::ZERO
    }
}

/// Radiance arriving at the origin of the camera ray `ray` from its first hit `hit`.
pub fn shade_hit(ctx: &ShadeContext<'_>, ray: &Ray, hit: &Hit, sampler: &mut Sampler) -> Vec3 {
    shade_hit_split(ctx, ray, hit, sampler, None)
}

/// [`shade_hit`] (the same value, bit for bit), also recording the radiance per component
/// into `parts` when given (see [`components`]).
pub fn shade_hit_split(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    sampler: &mut Sampler,
    parts: Option<&mut components::Components>,
) -> Vec3 {
    match ctx.integrator {
        Integrator::Direct => direct::radiance_split(ctx, ray, hit, sampler, parts),
        Integrator::Path => path::radiance_split(ctx, ray, hit, sampler, parts),
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
    /// Emitted radiance here (the material's `emission` times its texture), W/(sr·m²).
    pub emission: Vec3,
    /// Frame around `sp.normal`.
    pub frame: ShadingFrame,
    /// Direction toward the viewer, local.
    pub wo: Vec3,
    /// Direction toward the viewer, world space (the unit reverse of the arriving ray).
    pub wo_world: Vec3,
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
    /// ([`bump::ensure_valid_reflection`]), so bent normals never shade black — except an
    /// object-space normal under a local illumination model, used as given
    /// ([`textured::Textured::exact`]).
    #[inline(always)]
    pub fn new(ctx: &ShadeContext<'a>, ray: &Ray, hit: &Hit) -> Self {
        let mut sp = shading_point(ctx, hit);
        let material = &ctx.geometry.materials[sp.material as usize];
        let textured = textured::evaluate(ctx.geometry, &sp, hit, material);
        let (bumped, exact, emission) = match &textured {
            Some(t) => {
                sp.normal = t.normal;
                (t.bumped, t.exact, t.emission)
            }
            None => (false, false, material.emission),
        };
        let bound = textured.as_ref().map_or(&material.shader, |t| &t.shader);
        let Orientation {
            ng,
            front,
            visible,
            transmittance,
            frame,
            wo_world,
        } = orient(ctx, ray, hit, &mut sp, material, bound, exact);
        Self {
            sp,
            ng,
            front,
            visible,
            material,
            // Made here, in place: a `Cow` made above and moved in was copied whole (64
            // bytes), its unused bytes read back across older, narrower stores (a stall).
            shader: match textured {
                Some(t) => Cow::Owned(t.shader),
                None => Cow::Borrowed(&material.shader),
            },
            bumped,
            emission,
            frame,
            wo: frame.to_local(wo_world),
            wo_world,
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
            self.emission
        } else {
            Vec3::ZERO
        }
    }

    /// The BSDF of this face.
    #[inline]
    pub fn bsdf(&self) -> Option<Bsdf> {
        Bsdf::new(&self.shader, self.front)
    }

    /// The material's kept BSDF for this face, when the context keeps them and no texture
    /// drives this point's shader (the same value as [`Vertex::bsdf`]); `None` where it must
    /// be built.
    #[inline(always)]
    pub fn kept_bsdf(&self, ctx: &ShadeContext<'a>) -> Option<&'a Bsdf> {
        kept_bsdf(ctx, self.sp.material, self.front, &self.shader)
    }

    /// [`Vertex::bsdf`] without the `Option` (one that reflects nothing, [`Bsdf::reflects`]
    /// false, where `bsdf()` gives `None`): the material's kept BSDF when the context keeps
    /// them and no texture drives this point's shader, else built into `scratch`, made only
    /// then (a path of untextured vertices never builds the 168-byte empty BSDF).
    #[inline]
    pub fn bsdf_ref<'b>(
        &'b self,
        ctx: &ShadeContext<'b>,
        scratch: &'b mut Option<Bsdf>,
    ) -> &'b Bsdf {
        bsdf_kept_or_in(ctx, self.sp.material, self.front, &self.shader, scratch)
    }

    /// A ray leaving along the local direction `wi` if it lies on the geometric side its
    /// kind requires (reflection: the viewer's side; transmission: the other side).
    #[inline(always)]
    pub fn spawn(&self, wi_local: Vec3, transmits: bool) -> Option<Ray> {
        spawn_along(&self.frame, self.ng, &self.sp.surface, wi_local, transmits)
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
    light_loop_split(ctx, v, bsdf, sampler, mis, None)
}

/// [`light_loop`] (the same value, bit for bit), also adding the share of its diffuse lobes
/// ([`Bsdf::eval_diffuse`]) to `diffuse` when given (component passes).
pub fn light_loop_split(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    bsdf: &Bsdf,
    sampler: &mut Sampler,
    mis: bool,
    diffuse: Option<&mut Vec3>,
) -> Vec3 {
    // The bump term's per-point part made once, and only at bumped points (inside the loop,
    // the compiler hoisted it out and computed its division at every point, bumped or not).
    let bump = v
        .bumped
        .then(|| bump::shadowing_roughness(v.ng, v.sp.normal))
        .flatten();
    let shadowing = move |wi_world: Vec3| match bump {
        Some(alpha2) => bump::shadowing_at(alpha2, v.ng, wi_world),
        None => 1.0,
    };
    let f = |wi: Vec3, wi_world: Vec3| bsdf.eval(v.wo, wi) * shadowing(wi_world);
    let fd = |wi: Vec3, wi_world: Vec3| bsdf.eval_diffuse(v.wo, wi) * shadowing(wi_world);
    let share = diffuse.map(|d| (&fd as &dyn Fn(Vec3, Vec3) -> Vec3, d));
    // The BSDF closure passed by value, so the loop evaluates it inline.
    gather_with(ctx, v, sampler, mis.then_some(bsdf), f, true, share)
}

/// [`light_loop_split`] without MIS (the same value, bit for bit), each light's shadow rays
/// traced together where that pays ([`shadow_packets::pays`]; else the per-sample loop). A
/// separate entry for the `Direct` integrator: the choice made inside `light_loop_split`,
/// even where not taken, slowed its per-sample loop by 4–5 % (session 32).
#[inline(always)]
pub fn light_loop_without_mis(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    bsdf: &Bsdf,
    sampler: &mut Sampler,
    diffuse: Option<&mut Vec3>,
) -> Vec3 {
    if ctx.shadow_packets {
        light_loop_in_packets(ctx, v, bsdf, sampler, diffuse)
    } else {
        light_loop_split(ctx, v, bsdf, sampler, false, diffuse)
    }
}

/// [`light_loop_without_mis`] with the shadow rays in packets.
#[inline(never)]
pub(super) fn light_loop_in_packets(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    bsdf: &Bsdf,
    sampler: &mut Sampler,
    diffuse: Option<&mut Vec3>,
) -> Vec3 {
    let (f, fd) = bsdf_responses(v, bsdf);
    let share = diffuse.map(|d| (&fd as &dyn Fn(Vec3, Vec3) -> Vec3, d));
    shadow_packets::gather(ctx, v, sampler, &f, true, share)
}

/// The light loop's responses at `v`: the BSDF, and its diffuse lobes' share, each times the
/// bump shadowing term toward the light (`(wi local, wi world)`).
#[inline(always)]
fn bsdf_responses<'r>(
    v: &'r Vertex<'_>,
    bsdf: &'r Bsdf,
) -> (
    impl Fn(Vec3, Vec3) -> Vec3 + 'r,
    impl Fn(Vec3, Vec3) -> Vec3 + 'r,
) {
    // The bump term's per-point part made once, and only at bumped points (inside the loop,
    // the compiler hoisted it out and computed its division at every point, bumped or not).
    let bump = v
        .bumped
        .then(|| bump::shadowing_roughness(v.ng, v.sp.normal))
        .flatten();
    let shadowing = move |wi_world: Vec3| match bump {
        Some(alpha2) => bump::shadowing_at(alpha2, v.ng, wi_world),
        None => 1.0,
    };
    let f = move |wi: Vec3, wi_world: Vec3| bsdf.eval(v.wo, wi) * shadowing(wi_world);
    let fd = move |wi: Vec3, wi_world: Vec3| bsdf.eval_diffuse(v.wo, wi) * shadowing(wi_world);
    (f, fd)
}

/// What a light sample arriving from `wi` (local; `wi_world` in world space) contributes
/// per unit of its `Cl`.
pub enum Response<'a> {
    /// A BSDF value, times `N·L` by the loop.
    Bsdf(&'a dyn Fn(Vec3, Vec3) -> Vec3),
    /// The whole factor (cosine included), as a local illumination model writes it.
    Local(&'a dyn Fn(Vec3, Vec3) -> Vec3),
}

/// The light loop of [`light_loop`] for any response: every light's samples with their
/// shadow rays, `mis` weighting against the BSDF's own sampling when given.
pub fn gather(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    sampler: &mut Sampler,
    mis: Option<&Bsdf>,
    response: Response<'_>,
) -> Vec3 {
    gather_split(ctx, v, sampler, mis, response, None)
}

/// A share of a light response (its BSDF factor, as in [`Response::Bsdf`]) summed with the
/// same samples as the whole, and where to add it.
pub(super) type Share<'a, 'b> = (&'a dyn Fn(Vec3, Vec3) -> Vec3, &'b mut Vec3);

/// [`gather`], also adding the `share` response's sum (same samples, shadows and weights) to
/// its target when given.
fn gather_split(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    sampler: &mut Sampler,
    mis: Option<&Bsdf>,
    response: Response<'_>,
    share: Option<Share<'_, '_>>,
) -> Vec3 {
    match response {
        Response::Bsdf(f) => gather_with(ctx, v, sampler, mis, f, true, share),
        Response::Local(f) => gather_with(ctx, v, sampler, mis, f, false, share),
    }
}

/// [`gather_split`] with the response `response` (times `N·L` when `cosine`, as
/// [`Response::Bsdf`]; whole, as [`Response::Local`]).
#[inline(always)]
fn gather_with(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    sampler: &mut Sampler,
    mis: Option<&Bsdf>,
    response: impl Fn(Vec3, Vec3) -> Vec3,
    cosine: bool,
    mut share: Option<Share<'_, '_>>,
) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    for (i, light) in ctx.lights.lights.iter().enumerate() {
        if matches!(light, Light::Ambient { .. }) || !v.material.sees_light(i) {
            continue;
        }
        let (n, mut child) = if mis.is_some() {
            (1, None)
        } else {
            (light.sample_count(), Some(sampler.child_seed()))
        };
        let mut sum = Vec3::ZERO;
        let mut shared = Vec3::ZERO;
        for j in 0..n {
            let u = match child.as_mut() {
                Some(seed) => Sampler::new(*seed, j).next_2d(),
                None => sampler.next_2d(),
            };
            // Emitting meshes (the common light of path-traced scenes) sampled inline: the
            // same call `Light::sample` makes, without returning the sample through memory.
            let ls = match light {
                Light::Mesh(m) => m.sample(v.sp.surface.p, u, ctx.geometry),
                _ => light.sample(v.sp.surface.p, u, Some(ctx.geometry)),
            };
            let Some(ls) = ls else {
                continue;
            };
            let wi = v.frame.to_local(ls.wi);
            if wi.z <= 0.0 || v.ng.dot(ls.wi) <= 0.0 {
                continue;
            }
            let f = response(wi, ls.wi);
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
                        Some(t) => ls.lighten(t),
                        None if ls.shadow_factor > 0.0 => ls.lighten(Vec3::ZERO),
                        None => continue,
                    }
                }
                None if ls.shadows => ls.lighten(transmittance(
                    ctx.geometry,
                    &v.sp.surface,
                    ls.wi,
                    ls.target,
                    ctx.lights.transmissive_shadows,
                )),
                None => Vec3::ONE,
            };
            if shadow == Vec3::ZERO {
                continue;
            }
            let w = match mis {
                Some(bsdf) if ls.pdf > 0.0 => power_weight(ls.pdf, bsdf.pdf(v.wo, wi)),
                _ => 1.0,
            };
            let c = if cosine { wi.z * w } else { w };
            sum += f * ls.contribution * shadow * c;
            if let Some((g, _)) = &share {
                shared += g(wi, ls.wi) * ls.contribution * shadow * c;
            }
        }
        radiance += sum / n as f32;
        if let Some((_, target)) = &mut share {
            **target += shared / n as f32;
        }
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
/// `delta`: a camera ray or a perfect mirror/refraction ray of the eye's specular chain
/// (no non-delta scattering since the camera). Those see only `visible` area
/// lights, and a visible light is opaque to them: the nearest one in front of the hit ends
/// the ray (no hit is returned). BSDF-sampled rays see every area light's front face
/// additively and go on (lights never block light, and MIS needs every light reachable).
pub fn trace(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    delta: bool,
) -> (Option<Hit>, Vec3, Vec<(Vec3, f32)>) {
    trace_leaving(ctx, ray, delta, None)
}

/// [`trace`] for a specular ray spawned at a material with its own environment (`own`):
/// when the ray hits nothing it sees that environment (light pdf 0: it is not a light)
/// instead of the scene's.
#[inline(always)]
pub fn trace_leaving(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    delta: bool,
    own: Option<&MaterialEnvironment>,
) -> (Option<Hit>, Vec3, Vec<(Vec3, f32)>) {
    trace_leaving_from(ctx, ray, delta, own, None)
}

/// [`trace_leaving`] for a ray that continues a path from `behind` through straight
/// pass-throughs (`None`: from its own origin): the area lights it meets give their radiance
/// and pdf as seen from there ([`Light::hit_from`]).
#[inline(always)]
pub fn trace_leaving_from(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    delta: bool,
    own: Option<&MaterialEnvironment>,
    behind: Option<Vec3>,
) -> (Option<Hit>, Vec3, Vec<(Vec3, f32)>) {
    let hit = ctx.geometry.accel.intersect_as(ray, RayKind::Secondary);
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
            let found = match behind {
                None => light.hit(&clipped, false),
                Some(p) => light.hit_from(&clipped, p),
            };
            if let Some((_, radiance, pdf)) = found {
                direct += radiance;
                crossed.push((radiance, pdf));
            }
        }
    }
    if let (None, Some(env)) = (&hit, own) {
        let le = source_radiance(&env.source, ray.dir);
        direct += le;
        crossed.push((le, 0.0));
    } else if hit.is_none() {
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
    depth_exceeded_leaving(ctx, None, dir)
}

/// [`depth_exceeded`] for a specular ray of a material with its own environment (`own`):
/// that environment (light pdf 0) or black, as its `depth_exceeded` says.
pub fn depth_exceeded_leaving(
    ctx: &ShadeContext<'_>,
    own: Option<&MaterialEnvironment>,
    dir: Vec3,
) -> Option<(Vec3, f32)> {
    if let Some(env) = own {
        return (env.depth_exceeded == DepthExceeded::Environment)
            .then(|| (source_radiance(&env.source, dir), 0.0));
    }
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
    let hit = ctx.geometry.accel.intersect_as(ray, RayKind::Camera);
    camera_hit_with(ctx, ray, hit)
}

/// [`camera_hit`] for a ray whose closest camera-visible surface hit is `hit` (traced by the
/// caller, e.g. with a pixel's other rays in one packet): the lights and the environment
/// along it.
pub fn camera_hit_with(ctx: &ShadeContext<'_>, ray: &Ray, hit: Option<Hit>) -> CameraHit {
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
            let len = ray.dir.length();
            let seen = match ctx.volumes {
                Some(v) => {
                    volume::seen_through_atmosphere(v, ray.origin, ray.dir / len, t * len, le)
                }
                None => le,
            };
            CameraHit::Light(seen)
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

#[cfg(test)]
mod tests {
    use std::f32::consts::PI;

    use super::fixture::{self, Object};
    use super::*;
    use crate::components::{Emitter, LightShape};

    fn settings(integrator: Integrator, max_depth: u32) -> RenderSettings {
        RenderSettings {
            integrator,
            max_depth,
            ..RenderSettings::default()
        }
    }

    fn point_light(position: Vec3, intensity: f32) -> LightSet {
        let e = Emitter::new(LightShape::Point { position }, Vec3::splat(intensity));
        LightSet::new(&[e], None, 1)
    }

    /// Radiance seen along `dir` from `origin` (the ray must hit).
    fn seen(ctx: &ShadeContext<'_>, origin: Vec3, dir: Vec3, sampler: &mut Sampler) -> Vec3 {
        let (ray, hit) = fixture::hit(ctx.geometry, origin, dir);
        shade_hit(ctx, &ray, &hit, sampler)
    }

    #[test]
    fn lambert_floor_under_a_point_light_matches_the_closed_form() {
        // L = ρ/π · I · cosθ / d² on a floor under a point light at height 2.
        let (rho, intensity) = (0.5, 3.0);
        let geometry = fixture::geometry(vec![Object {
            triangles: fixture::floor(100.0, 0.0),
            material: fixture::lambert(rho),
        }]);
        let lights = point_light(Vec3::new(0.0, 0.0, 2.0), intensity);
        for integrator in [Integrator::Direct, Integrator::Path] {
            let s = settings(integrator, 1);
            let ctx = ShadeContext::new(&geometry, &lights, &s);
            for x in [0.0f32, 0.5, 1.5, 3.0] {
                let d2 = x * x + 4.0;
                let expected = rho / PI * intensity * (2.0 / d2.sqrt()) / d2;
                let mut sampler = Sampler::new(1, 0);
                let l = seen(&ctx, Vec3::new(x, 0.0, 1.0), -Vec3::Z, &mut sampler);
                println!("{integrator:?} x {x}: {l} (closed form {expected})");
                assert!(
                    (l - Vec3::splat(expected)).abs().max_element() < 1e-4 * expected,
                    "{integrator:?} at x = {x}: {l} vs {expected}"
                );
            }
        }
    }

    #[test]
    fn emission_shows_on_the_front_face_only() {
        let mut m = fixture::lambert(0.5);
        m.emission = Vec3::new(2.0, 1.0, 0.5);
        let geometry = fixture::geometry(vec![Object {
            triangles: fixture::floor(10.0, 0.0),
            material: m,
        }]);
        let lights = LightSet::default();
        let s = settings(Integrator::Direct, 4);
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let mut sampler = Sampler::new(0, 0);
        let above = seen(&ctx, Vec3::new(0.3, 0.2, 1.0), -Vec3::Z, &mut sampler);
        assert_eq!(above, Vec3::new(2.0, 1.0, 0.5));
        let below = seen(&ctx, Vec3::new(0.3, 0.2, -1.0), Vec3::Z, &mut sampler);
        assert_eq!(below, Vec3::ZERO);
    }

    /// Mean radiance at the centre of an inward-facing cube whose walls (albedo `rho`) all
    /// emit radiance 1, over `n` camera rays in Sobol directions.
    fn furnace(integrator: Integrator, max_depth: u32, rho: f32, n: u64) -> f64 {
        let mut wall = fixture::lambert(rho);
        wall.emission = Vec3::ONE;
        let geometry = fixture::geometry(vec![Object {
            triangles: fixture::inward_cube(1.0),
            material: wall,
        }]);
        let lights = LightSet::new(&[], Some(&geometry), 4);
        let s = settings(integrator, max_depth);
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let mut sum = 0.0f64;
        for i in 0..n {
            let mut sampler = Sampler::for_item(11, i, 0);
            let u = sampler.next_2d();
            let z = 1.0 - 2.0 * u.x;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = 2.0 * PI * u.y;
            let dir = Vec3::new(r * phi.cos(), r * phi.sin(), z);
            let l = seen(&ctx, Vec3::new(0.01, -0.02, 0.03), dir, &mut sampler);
            assert!(l.is_finite() && l.min_element() >= 0.0, "{l}");
            sum += f64::from(l.x);
        }
        sum / n as f64
    }

    #[test]
    fn path_tracer_in_an_emitting_furnace_sums_the_bounces() {
        // Uniform emission 1 everywhere: each bounce adds ρ^k, so depth D sees Σ_{k≤D} ρ^k.
        let rho = 0.5f64;
        let mean = furnace(Integrator::Path, 2, rho as f32, 4000);
        let expected = 1.0 + rho + rho * rho;
        println!("path furnace: {mean} (expected {expected})");
        assert!((mean / expected - 1.0).abs() < 0.02, "{mean} vs {expected}");
    }

    #[test]
    fn direct_integrator_in_an_emitting_furnace_adds_one_bounce() {
        // Emission plus direct light from the emitting walls: 1 + ρ.
        let rho = 0.5f64;
        let mean = furnace(Integrator::Direct, 4, rho as f32, 2000);
        println!("direct furnace: {mean} (expected {})", 1.0 + rho);
        assert!((mean / (1.0 + rho) - 1.0).abs() < 0.02, "{mean}");
    }

    #[test]
    fn depth_budgets_count_reflections_and_refractions_separately() {
        let geometry = fixture::geometry(vec![Object {
            triangles: fixture::floor(1.0, 0.0),
            material: fixture::lambert(0.5),
        }]);
        let lights = LightSet::default();
        let s = RenderSettings {
            reflection_depth: 1,
            refraction_depth: 2,
            ..RenderSettings::default()
        };
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let r1 = Depth::FIRST.after(&ctx, true, false).unwrap();
        assert_eq!((r1.vertex, r1.reflections, r1.refractions), (2, 1, 0));
        assert_eq!(r1.after(&ctx, true, false), None);
        let t2 = r1
            .after(&ctx, false, true)
            .unwrap()
            .after(&ctx, false, true);
        assert_eq!(t2.map(|d| (d.vertex, d.refractions)), Some((4, 2)));
        assert_eq!(t2.unwrap().after(&ctx, false, true), None);
        // Diffuse scattering counts vertices only.
        let mut d = Depth::FIRST;
        for _ in 0..10 {
            d = d.after(&ctx, false, false).unwrap();
        }
        assert_eq!((d.vertex, d.reflections, d.refractions), (11, 0, 0));
    }

    /// A photon estimate that adds a constant.
    struct Constant(Vec3);

    impl PhotonRadiance for Constant {
        fn radiance(
            &self,
            _: &ShadeContext<'_>,
            _: &Vertex<'_>,
            _: &Bsdf,
            _: &mut Sampler,
        ) -> Vec3 {
            self.0
        }
    }

    #[test]
    fn photon_radiance_is_added_once_at_diffuse_points_only() {
        let lights = point_light(Vec3::new(0.0, 0.0, 2.0), 1.0);
        let s = settings(Integrator::Direct, 4);
        let extra = Constant(Vec3::new(0.25, 0.5, 1.0));
        for (shader_is_diffuse, material) in [
            (true, fixture::lambert(0.7)),
            (
                false,
                fixture::material(Shader::Mirror {
                    color: Vec3::splat(0.9),
                }),
            ),
        ] {
            let geometry = fixture::geometry(vec![Object {
                triangles: fixture::floor(5.0, 0.0),
                material,
            }]);
            let plain = ShadeContext::new(&geometry, &lights, &s);
            let with = ShadeContext::new(&geometry, &lights, &s).with_photons(Some(&extra));
            let o = Vec3::new(0.5, 0.0, 1.0);
            let a = seen(&plain, o, -Vec3::Z, &mut Sampler::new(3, 0));
            let b = seen(&with, o, -Vec3::Z, &mut Sampler::new(3, 0));
            let added = if shader_is_diffuse {
                extra.0
            } else {
                Vec3::ZERO
            };
            assert_eq!(b, a + added, "diffuse {shader_is_diffuse}");
        }
    }
}

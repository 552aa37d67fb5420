//! The contour store's probe: the camera rays that fill the store (what the camera sees at
//! each pixel centre, mental ray's contour store function; the data types live with the
//! frame buffers, which carry the store from `shade`) and that place edges between samples.

use std::collections::HashMap;
use std::sync::Arc;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::accel::{spawn_ray, Hit, Ray, RayKind};
pub use crate::framebuffer::{ContourSample, ContourStore};
use crate::geometry::SceneGeometry;
use crate::shading::frame::ShadingFrame;
use crate::shading::{Bsdf, CameraRays};

/// Traces the rays of the store: the camera's primary ray through a film position, through
/// the aperture centre, against the scene geometry.
pub struct Probe<'a> {
    geometry: Option<&'a SceneGeometry>,
    rays: &'a CameraRays,
    /// Object id (see [`ContourSample::object`]) of each instance.
    objects: Vec<u32>,
    /// The ray level the probe samples (see [`ContourStore::level`]).
    level: u32,
}

impl<'a> Probe<'a> {
    /// A probe of `geometry` (`None`: an empty scene) through `rays`.
    pub fn new(geometry: Option<&'a SceneGeometry>, rays: &'a CameraRays) -> Self {
        let mut first_of_mesh: HashMap<*const crate::components::TriMesh, u32> = HashMap::new();
        let objects = geometry.map_or_else(Vec::new, |g| {
            g.instances
                .iter()
                .enumerate()
                .map(|(i, inst)| {
                    *first_of_mesh
                        .entry(Arc::as_ptr(&inst.mesh))
                        .or_insert(i as u32 + 1)
                })
                .collect()
        });
        Self {
            geometry,
            rays,
            objects,
            level: 0,
        }
    }

    /// The same probe sampling ray level `level`: what the camera sees behind `level`
    /// mirror, refraction or transparency events, following at each surface its strongest
    /// delta branch (the first of equally strong ones).
    pub fn at_level(mut self, level: u32) -> Self {
        self.level = level;
        self
    }

    /// What the camera sees at film position `film` (pixels), colour zero.
    pub fn sample(&self, film: Vec2) -> ContourSample {
        let Some(g) = self.geometry else {
            return ContourSample::BACKGROUND;
        };
        let Some(ray) = self.rays.ray(film.x, film.y, Vec2::splat(0.5)) else {
            return ContourSample::BACKGROUND;
        };
        let Some(mut hit) = g.accel.intersect_as(&ray, RayKind::Camera) else {
            return ContourSample::BACKGROUND;
        };
        let mut ray = ray;
        let mut depth = hit.t;
        if self.level > 0 {
            depth *= ray.dir.length();
        }
        for _ in 0..self.level {
            let Some(next) = delta_continuation(g, &ray, &hit) else {
                return ContourSample::ABSENT;
            };
            ray = next;
            let Some(h) = g.accel.intersect_as(&ray, RayKind::Secondary) else {
                return ContourSample::BACKGROUND;
            };
            hit = h;
            depth += hit.t * ray.dir.length();
        }
        let sp = g.shading_point(&hit);
        ContourSample {
            instance: sp.instance + 1,
            object: self.objects[sp.instance as usize],
            material: sp.material + 1,
            normal: sp.normal,
            depth,
            color: Vec3::ZERO,
        }
    }

    /// The store of a `width × height` image whose pixels were shaded `beauty`.
    pub fn store(&self, width: u32, height: u32, beauty: &[Vec3]) -> ContourStore {
        let samples = (0..height)
            .into_par_iter()
            .flat_map_iter(|y| {
                (0..width).map(move |x| {
                    let mut s = self.sample(ContourStore::position(x, y));
                    if !s.is_background() {
                        s.color = beauty[(y * width + x) as usize];
                    }
                    s
                })
            })
            .collect();
        ContourStore {
            width,
            height,
            samples,
            level: self.level,
            deeper: Vec::new(),
        }
    }
}

/// The ray leaving the hit `hit` of `ray` along the strongest delta branch of its material
/// (mirror, refraction, pass-through; the first of equally strong ones), or `None` when the
/// material has none.
fn delta_continuation(g: &SceneGeometry, ray: &Ray, hit: &Hit) -> Option<Ray> {
    let sp = g.shading_point(hit);
    let material = &g.materials[sp.material as usize];
    let wo = -ray.dir.normalize_or_zero();
    let front = sp.surface.ng.dot(wo) > 0.0;
    let (n, ng) = if front {
        (sp.normal, sp.surface.ng)
    } else {
        (-sp.normal, -sp.surface.ng)
    };
    let frame = ShadingFrame::from_normal(n);
    let bsdf = Bsdf::new(&material.shader, front)?;
    let mut best: Option<(f32, Vec3, bool)> = None;
    for b in bsdf.delta_branches(frame.to_local(wo)) {
        let w = b.weight.max_element();
        if best.is_none_or(|(bw, _, _)| w > bw) {
            best = Some((w, b.wi, b.transmits));
        }
    }
    let (_, wi, transmits) = best?;
    let wi = frame.to_world(wi);
    let side = ng.dot(wi);
    let ok = if transmits { side < 0.0 } else { side > 0.0 };
    (ok && wi.is_finite()).then(|| spawn_ray(&sp.surface, wi))
}

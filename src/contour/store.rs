//! The contour store's probe: the camera rays that fill the store (what the camera sees at
//! each pixel centre, mental ray's contour store function; the data types live with the
//! frame buffers, which carry the store from `shade`) and that place edges between samples.

use std::collections::HashMap;
use std::ops::RangeInclusive;
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

    /// What the camera sees at film position `film` (pixels) on the probe's level, colour
    /// zero: the path from the camera walked to that level (it stops where the path ends).
    pub fn sample(&self, film: Vec2) -> ContourSample {
        let mut last = ContourSample::BACKGROUND;
        self.walk(film, self.level..=self.level, |_, s| last = s);
        last
    }

    /// Walks the path of the pixel centre's ray once, up to the last level of `levels`,
    /// giving `visit` the sample (colour zero) of each level of `levels` in order: level 0
    /// is what the camera ray hits, level `k` what the ray leaving level `k − 1`'s hit along
    /// its strongest delta branch hits. Where the path ends no more rays are traced: the
    /// levels behind a ray that left the scene are [`ContourSample::BACKGROUND`], those
    /// behind a surface without a delta branch [`ContourSample::ABSENT`].
    pub fn walk(
        &self,
        film: Vec2,
        levels: RangeInclusive<u32>,
        mut visit: impl FnMut(u32, ContourSample),
    ) {
        let (first, deepest) = (*levels.start(), *levels.end());
        // The path ended before level `from`: every level from there on is `sample`.
        let ended =
            |from: u32, sample: ContourSample, visit: &mut dyn FnMut(u32, ContourSample)| {
                for level in from.max(first)..=deepest {
                    visit(level, sample);
                }
            };
        let Some(g) = self.geometry else {
            return ended(0, ContourSample::BACKGROUND, &mut visit);
        };
        let Some(mut ray) = self.rays.ray(film.x, film.y, Vec2::splat(0.5)) else {
            return ended(0, ContourSample::BACKGROUND, &mut visit);
        };
        let Some(mut hit) = g.accel.intersect_as(&ray, RayKind::Camera) else {
            return ended(0, ContourSample::BACKGROUND, &mut visit);
        };
        // Level 0's depth is the camera ray's parameter; deeper levels' the length of the
        // path, summed hit by hit.
        if levels.contains(&0) {
            visit(0, self.surface_sample(g, &hit, hit.t));
        }
        let mut path = hit.t * ray.dir.length();
        for level in 1..=deepest {
            let Some(next) = delta_continuation(g, &ray, &hit) else {
                return ended(level, ContourSample::ABSENT, &mut visit);
            };
            ray = next;
            let Some(h) = g.accel.intersect_as(&ray, RayKind::Secondary) else {
                return ended(level, ContourSample::BACKGROUND, &mut visit);
            };
            hit = h;
            path += hit.t * ray.dir.length();
            if level >= first {
                visit(level, self.surface_sample(g, &hit, path));
            }
        }
    }

    /// The sample of the surface at `hit`, `depth` away along the path, colour zero.
    fn surface_sample(&self, g: &SceneGeometry, hit: &Hit, depth: f32) -> ContourSample {
        let sp = g.shading_point(hit);
        ContourSample {
            instance: sp.instance + 1,
            object: self.objects[sp.instance as usize],
            material: sp.material + 1,
            normal: sp.normal,
            depth,
            color: Vec3::ZERO,
        }
    }

    /// The store of a `width × height` image whose pixels were shaded `beauty`, with the
    /// stores of levels `1 ..= ray_depth` behind it (see [`ContourStore::deeper`]). Each
    /// pixel's path is walked once for all levels ([`Probe::walk`]).
    pub fn store(&self, width: u32, height: u32, beauty: &[Vec3], ray_depth: u32) -> ContourStore {
        let levels = ray_depth as usize + 1;
        let w = width as usize;
        // Per row, its samples level by level: level `l` of pixel `x` at `l·width + x`.
        let rows: Vec<Vec<ContourSample>> = (0..height)
            .into_par_iter()
            .map(|y| {
                let mut row = vec![ContourSample::BACKGROUND; levels * w];
                for x in 0..width {
                    self.walk(ContourStore::position(x, y), 0..=ray_depth, |l, mut s| {
                        if !s.is_background() {
                            s.color = beauty[(y * width + x) as usize];
                        }
                        row[l as usize * w + x as usize] = s;
                    });
                }
                row
            })
            .collect();
        let level_store = |l: usize| ContourStore {
            width,
            height,
            samples: rows
                .iter()
                .flat_map(|r| r[l * w..(l + 1) * w].iter().copied())
                .collect(),
            level: l as u32,
            deeper: Vec::new(),
        };
        let mut store = level_store(0);
        store.deeper = (1..levels).map(level_store).collect();
        store
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

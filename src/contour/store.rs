//! The contour store's probe: the camera rays that fill the store (what the camera sees at
//! each pixel centre, mental ray's contour store function; the data types live with the
//! frame buffers, which carry the store from `shade`) and that place edges between samples.

use std::collections::HashMap;
use std::sync::Arc;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::accel::RayKind;
pub use crate::framebuffer::{ContourSample, ContourStore};
use crate::geometry::SceneGeometry;
use crate::shading::CameraRays;

/// Traces the rays of the store: the camera's primary ray through a film position, through
/// the aperture centre, against the scene geometry.
pub struct Probe<'a> {
    geometry: Option<&'a SceneGeometry>,
    rays: &'a CameraRays,
    /// Object id (see [`ContourSample::object`]) of each instance.
    objects: Vec<u32>,
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
        }
    }

    /// What the camera sees at film position `film` (pixels), colour zero.
    pub fn sample(&self, film: Vec2) -> ContourSample {
        let Some(g) = self.geometry else {
            return ContourSample::BACKGROUND;
        };
        let Some(ray) = self.rays.ray(film.x, film.y, Vec2::splat(0.5)) else {
            return ContourSample::BACKGROUND;
        };
        let Some(hit) = g.accel.intersect_as(&ray, RayKind::Camera) else {
            return ContourSample::BACKGROUND;
        };
        let sp = g.shading_point(&hit);
        ContourSample {
            instance: sp.instance + 1,
            object: self.objects[sp.instance as usize],
            material: sp.material + 1,
            normal: sp.normal,
            depth: hit.t,
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
        }
    }
}

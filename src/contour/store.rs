//! The contour store: what the camera sees at each pixel centre, kept for finding contours
//! (mental ray's contour store function). `shade` writes it with the frame buffers; the
//! [`Probe`] that fills it also answers the extra rays that place edges between samples.

use std::collections::HashMap;
use std::sync::Arc;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::geometry::SceneGeometry;
use crate::shading::CameraRays;

/// What one camera ray sees, as contour contrast compares it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContourSample {
    /// 1 + the placed instance's index (as `Pass::ObjectId`); 0 for the background.
    pub instance: u32,
    /// 1 + the index of the first instance showing the same object (mesh); 0 for the
    /// background. Two instances of one object share it.
    pub object: u32,
    /// 1 + the material's index (as `Pass::MaterialId`); 0 for the background.
    pub material: u32,
    /// World-space shading normal; zero for the background.
    pub normal: Vec3,
    /// Distance along the ray to the hit; infinity for the background.
    pub depth: f32,
    /// The shaded colour of the pixel (linear RGB; zero for samples taken between pixels).
    pub color: Vec3,
}

impl ContourSample {
    /// What a ray that hits nothing sees.
    pub const BACKGROUND: ContourSample = ContourSample {
        instance: 0,
        object: 0,
        material: 0,
        normal: Vec3::ZERO,
        depth: f32::INFINITY,
        color: Vec3::ZERO,
    };

    /// Whether the sample sees no surface.
    pub fn is_background(&self) -> bool {
        self.instance == 0
    }
}

/// One sample per pixel centre, row-major (row 0 at the top).
#[derive(Debug, Clone, PartialEq)]
pub struct ContourStore {
    /// Width in samples (the image width).
    pub width: u32,
    /// Height in samples (the image height).
    pub height: u32,
    /// The samples; sample `(x, y)` is at film position `(x + 0.5, y + 0.5)`.
    pub samples: Vec<ContourSample>,
}

impl ContourStore {
    /// Sample `(x, y)`.
    pub fn at(&self, x: u32, y: u32) -> &ContourSample {
        &self.samples[(y * self.width + x) as usize]
    }

    /// Film position of sample `(x, y)`, pixels.
    pub fn position(x: u32, y: u32) -> Vec2 {
        Vec2::new(x as f32 + 0.5, y as f32 + 0.5)
    }
}

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
        let Some(hit) = g.accel.intersect(&ray) else {
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

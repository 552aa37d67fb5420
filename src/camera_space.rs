//! The camera-space passes (`CameraDepth`, `CameraNormal`, `CameraPosition`): RenderMan's
//! output variables `z`, `N` and `P`, derived when an output is written
//! ([`crate::exr_output`], the one EXR writer of camera outputs, which takes the camera) from
//! the centre-sample passes `shade` stores (the distance along each pixel centre's ray, the
//! world-space shading normal) and the camera. Farm parts carry those two already, so a
//! merge writes the single render's bytes without carrying more.
//!
//! Camera space: origin at the camera (the aperture centre), **+x right, +y up, +z forward**
//! along the view axis — left-handed, RenderMan's camera space; stagelight's camera frame
//! (−z forward) with z negated. Positions and depths are in camera-space units, world
//! lengths times the camera's `space_scale` (a RIB camera transformation's uniform scale);
//! normals are unit vectors. A pixel whose centre ray hits nothing has depth +∞ (as
//! `Depth`), normal and position zero (as `Normal`).

use glam::{Mat3, Vec2, Vec3};

use hecs::World;

use crate::components::{Camera, Lens, Pass};
use crate::features::Features;
use crate::framebuffer::FrameBuffers;
use crate::shading::camera::CameraRays;

/// What the camera-space passes of one camera need besides the frame buffers.
#[derive(Debug, Clone)]
pub struct CameraSpace {
    /// The render's camera rays (its lenses as `shade` used them).
    rays: CameraRays,
    /// Rotation from world to stagelight's camera frame.
    camera_from_world: Mat3,
    /// Camera-space length of one world unit.
    scale: f32,
}

/// The EXR channels of each camera-space pass, in the order written.
const CHANNELS: [(Pass, [&str; 3]); 3] = [
    (Pass::CameraDepth, ["Z", "", ""]),
    (Pass::CameraNormal, ["N.X", "N.Y", "N.Z"]),
    (Pass::CameraPosition, ["P.X", "P.Y", "P.Z"]),
];

impl CameraSpace {
    /// The camera space of `camera` seen through `lenses` (those `shade` traced with).
    pub fn new(camera: &Camera, lenses: &[Lens]) -> Self {
        Self {
            rays: CameraRays::with_lenses(camera, lenses),
            camera_from_world: Mat3::from(camera.world_from_camera.matrix3).transpose(),
            scale: camera.space_scale,
        }
    }

    /// The camera space of `world`'s render camera as `shade` traces it: with its lenses,
    /// unless `off` switches lens shaders off; `None` without a render camera.
    pub fn of_render_camera(world: &World, off: Features) -> Option<Self> {
        let view = crate::scene_view::render_view(world)?.without(off);
        Some(Self::new(&view.camera, &view.lenses))
    }

    /// Camera-space position of the hit `depth` along the centre ray of pixel `(x, y)`
    /// (zero where it missed).
    pub fn position(&self, x: u32, y: u32, depth: f32) -> Vec3 {
        if !depth.is_finite() {
            return Vec3::ZERO;
        }
        let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        let Some((origin, dir)) = self
            .rays
            .camera_space_ray(centre.x, centre.y, Vec2::splat(0.5))
        else {
            return Vec3::ZERO;
        };
        // `depth` is the distance along the unit world direction, which is the unit camera
        // direction rotated.
        let p = origin + dir.normalize() * depth;
        Vec3::new(p.x, p.y, -p.z) * self.scale
    }

    /// The camera-space unit normal of the world-space normal `n` (zero stays zero).
    pub fn normal(&self, n: Vec3) -> Vec3 {
        let c = self.camera_from_world * n;
        Vec3::new(c.x, c.y, -c.z)
    }

    /// The EXR channels of the camera-space passes among `passes`, per pixel of `fb`
    /// (written by [`crate::exr_output`]).
    pub(crate) fn exr_channels(
        &self,
        fb: &FrameBuffers,
        passes: &[Pass],
    ) -> Vec<(&'static str, Vec<f32>)> {
        let wants = |p: Pass| passes.contains(&p);
        if !Pass::CAMERA_SPACE.into_iter().any(wants) {
            return Vec::new();
        }
        let positions: Vec<Vec3> = if wants(Pass::CameraDepth) || wants(Pass::CameraPosition) {
            (0..fb.height)
                .flat_map(|y| (0..fb.width).map(move |x| (x, y)))
                .zip(&fb.depth)
                .map(|((x, y), &depth)| self.position(x, y, depth))
                .collect()
        } else {
            Vec::new()
        };
        let mut out = Vec::new();
        for (pass, names) in CHANNELS {
            if !wants(pass) {
                continue;
            }
            match pass {
                Pass::CameraDepth => {
                    let z = positions.iter().zip(&fb.depth).map(|(p, &depth)| {
                        if depth.is_finite() {
                            p.z
                        } else {
                            f32::INFINITY
                        }
                    });
                    out.push((names[0], z.collect()));
                }
                Pass::CameraNormal => {
                    let normals: Vec<Vec3> = fb.normal.iter().map(|&n| self.normal(n)).collect();
                    for (k, name) in names.into_iter().enumerate() {
                        out.push((name, normals.iter().map(|n| n[k]).collect()));
                    }
                }
                _ => {
                    for (k, name) in names.into_iter().enumerate() {
                        out.push((name, positions.iter().map(|p| p[k]).collect()));
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use glam::Affine3A;

    use super::*;

    fn camera(world_from_camera: Affine3A, space_scale: f32) -> Camera {
        Camera {
            world_from_camera,
            fov_y: 90f32.to_radians(),
            width: 4,
            height: 2,
            aspect: 2.0,
            outputs: vec![],
            space_scale,
        }
    }

    #[test]
    fn a_hit_on_the_axis_is_forward_and_a_miss_is_zero() {
        // A 1×1 image: the pixel centre's ray is the view axis.
        let mut c = camera(Affine3A::from_translation(Vec3::new(3.0, 4.0, 5.0)), 2.0);
        (c.width, c.height, c.aspect) = (1, 1, 1.0);
        let s = CameraSpace::new(&c, &[]);
        assert_eq!(s.position(0, 0, 2.5), Vec3::new(0.0, 0.0, 5.0));
        assert_eq!(s.position(0, 0, f32::INFINITY), Vec3::ZERO);
        // Facing the camera: its world normal is +z (toward the eye, which looks down −z).
        assert_eq!(s.normal(Vec3::Z), Vec3::new(0.0, 0.0, -1.0));
        assert_eq!(s.normal(Vec3::ZERO), Vec3::ZERO);
    }

    #[test]
    fn a_turned_camera_keeps_right_and_up() {
        // Looking down world −x with +y up: right is `forward × up` = world −z, and world +x
        // points backward (camera-space −z).
        let w = crate::components::world_from_look_at(Vec3::ZERO, Vec3::NEG_X, Vec3::Y).unwrap();
        let s = CameraSpace::new(&camera(w, 1.0), &[]);
        let n = s.normal(Vec3::new(0.0, 0.0, -1.0));
        assert!((n - Vec3::X).length() < 1e-6, "{n}");
        let n = s.normal(Vec3::X);
        assert!((n - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6, "{n}");
    }
}

//! Primary rays of a pinhole camera.

use glam::{Affine3A, Vec3};

use crate::accel::Ray;
use crate::components::Camera;

/// Generates world-space camera rays through continuous film positions.
#[derive(Debug, Clone, Copy)]
pub struct CameraRays {
    world_from_camera: Affine3A,
    tan_half_fov: f32,
    aspect: f32,
    width: f32,
    height: f32,
}

impl CameraRays {
    /// Ray generator for `camera`.
    pub fn new(camera: &Camera) -> Self {
        Self {
            world_from_camera: camera.world_from_camera,
            tan_half_fov: (camera.fov_y * 0.5).tan(),
            aspect: camera.aspect,
            width: camera.width as f32,
            height: camera.height as f32,
        }
    }

    /// The ray through film position `(x, y)` in pixels (0,0 = top-left corner of the image,
    /// pixel centres at half-integers). The direction is unit length, so `t` is distance.
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        let sx = (2.0 * x / self.width - 1.0) * self.tan_half_fov * self.aspect;
        let sy = (1.0 - 2.0 * y / self.height) * self.tan_half_fov;
        let dir_camera = Vec3::new(sx, sy, -1.0);
        let dir = self
            .world_from_camera
            .transform_vector3(dir_camera)
            .normalize();
        Ray {
            origin: self.world_from_camera.translation.into(),
            dir,
            t_max: f32::INFINITY,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(fov_deg: f32, w: u32, h: u32) -> Camera {
        Camera {
            world_from_camera: Affine3A::IDENTITY,
            fov_y: fov_deg.to_radians(),
            width: w,
            height: h,
            aspect: w as f32 / h as f32,
            outputs: vec![],
        }
    }

    #[test]
    fn centre_ray_looks_down_minus_z() {
        let r = CameraRays::new(&camera(60.0, 64, 32)).ray(32.0, 16.0);
        assert!((r.dir - Vec3::NEG_Z).length() < 1e-6);
    }

    #[test]
    fn top_edge_is_at_half_fov() {
        let r = CameraRays::new(&camera(90.0, 64, 64)).ray(32.0, 0.0);
        // 45° up from the axis.
        assert!((r.dir.y - r.dir.z.abs()).abs() < 1e-6 && r.dir.y > 0.0);
        let r = CameraRays::new(&camera(90.0, 128, 64)).ray(0.0, 32.0);
        // Left edge at atan(aspect · tan 45°) = atan 2.
        assert!((r.dir.x / r.dir.z - 2.0).abs() < 1e-5 && r.dir.x < 0.0);
    }
}

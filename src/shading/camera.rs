//! Primary rays: the pinhole camera and the lens shaders chained after it (thin-lens depth
//! of field, fisheye and spherical projections).
//!
//! Chaining rule: the pinhole (or the projection lens, which must come first and replaces
//! it) maps a film position to a camera-space ray from the camera origin; every `ThinLens`
//! after it then moves that ray's origin across its aperture and re-aims it at the point
//! where the incoming ray meets the focus surface. The lens sample `u` is the same pair of
//! sampler dimensions for every thin lens in the chain.

use glam::{Affine3A, Vec2, Vec3};

use crate::accel::Ray;
use crate::components::{Camera, Lens};
use crate::sampling::sample_concentric_disk;

/// Generates world-space camera rays through continuous film positions.
#[derive(Debug, Clone)]
pub struct CameraRays {
    world_from_camera: Affine3A,
    tan_half_fov: f32,
    aspect: f32,
    width: f32,
    height: f32,
    lenses: Vec<Lens>,
}

impl CameraRays {
    /// Ray generator of the plain pinhole `camera`.
    pub fn new(camera: &Camera) -> Self {
        Self::with_lenses(camera, &[])
    }

    /// Ray generator for `camera` with its lens shaders (in chain order).
    pub fn with_lenses(camera: &Camera, lenses: &[Lens]) -> Self {
        Self {
            world_from_camera: camera.world_from_camera,
            tan_half_fov: (camera.fov_y * 0.5).tan(),
            aspect: camera.aspect,
            width: camera.width as f32,
            height: camera.height as f32,
            lenses: lenses.to_vec(),
        }
    }

    /// Whether rays need a lens sample (some lens has an aperture): the caller then draws
    /// two sampler dimensions for `lens_u`; otherwise `lens_u` is ignored.
    pub fn needs_lens_sample(&self) -> bool {
        self.lenses
            .iter()
            .any(|l| matches!(l, Lens::ThinLens { .. }))
    }

    /// The ray through film position `(x, y)` in pixels (0,0 = top-left corner of the image,
    /// pixel centres at half-integers) and lens sample `lens_u ∈ [0,1)²` (`(0.5, 0.5)` is the
    /// aperture centre). The direction is unit length, so `t` is distance. `None` where a
    /// projection maps the film position to no direction (outside a fisheye's image circle).
    #[inline]
    pub fn ray(&self, x: f32, y: f32, lens_u: Vec2) -> Option<Ray> {
        let (origin, dir) = self.camera_space_ray(x, y, lens_u)?;
        let dir = self.world_from_camera.transform_vector3(dir).normalize();
        let origin = self.world_from_camera.transform_point3(origin);
        (dir.is_finite() && origin.is_finite()).then_some(Ray {
            origin,
            dir,
            t_max: f32::INFINITY,
        })
    }

    /// The ray of [`CameraRays::ray`] in the camera's own frame (−z forward, +y up): its
    /// origin and its direction, not normalised.
    #[inline]
    pub fn camera_space_ray(&self, x: f32, y: f32, lens_u: Vec2) -> Option<(Vec3, Vec3)> {
        let mut projected = false;
        let (mut origin, mut dir) = (Vec3::ZERO, self.pinhole(x, y));
        for lens in &self.lenses {
            match *lens {
                Lens::Fisheye { fov } => {
                    dir = self.fisheye(x, y, fov)?;
                    projected = true;
                }
                Lens::Spherical => {
                    dir = self.spherical(x, y);
                    projected = true;
                }
                Lens::Shift { x: dx, y: dy } => {
                    dir += Vec3::new(dx, dy, 0.0) * self.tan_half_fov;
                }
                Lens::ThinLens {
                    radius,
                    focus_distance,
                } => {
                    (origin, dir) =
                        thin_lens(origin, dir, radius, focus_distance, projected, lens_u)?;
                }
            }
        }
        Some((origin, dir))
    }

    /// Camera-space pinhole direction (not normalised: z = −1).
    fn pinhole(&self, x: f32, y: f32) -> Vec3 {
        let sx = (2.0 * x / self.width - 1.0) * self.tan_half_fov * self.aspect;
        let sy = (1.0 - 2.0 * y / self.height) * self.tan_half_fov;
        Vec3::new(sx, sy, -1.0)
    }

    /// Equidistant fisheye: θ = r · fov/2, r = distance from the centre in half-heights.
    fn fisheye(&self, x: f32, y: f32, fov: f32) -> Option<Vec3> {
        let u = (2.0 * x / self.width - 1.0) * self.aspect;
        let v = 1.0 - 2.0 * y / self.height;
        let r = (u * u + v * v).sqrt();
        let theta = r * fov * 0.5;
        if theta > std::f32::consts::PI {
            return None;
        }
        let (sin_t, cos_t) = theta.sin_cos();
        let (cos_p, sin_p) = if r > 0.0 { (u / r, v / r) } else { (1.0, 0.0) };
        Some(Vec3::new(sin_t * cos_p, sin_t * sin_p, -cos_t))
    }

    /// Lat-long: azimuth from x, elevation from y.
    fn spherical(&self, x: f32, y: f32) -> Vec3 {
        let az = (x / self.width - 0.5) * std::f32::consts::TAU;
        let el = (0.5 - y / self.height) * std::f32::consts::PI;
        let (sin_el, cos_el) = el.sin_cos();
        let (sin_az, cos_az) = az.sin_cos();
        Vec3::new(cos_el * sin_az, sin_el, -cos_el * cos_az)
    }
}

/// One thin lens applied to the camera-space ray `(origin, dir)`: the focus point is where
/// the ray meets the plane `z = −focus` (`projected == false`; the aperture disk lies in the
/// camera's xy plane) or the sphere of radius `focus` about the ray origin (after a
/// projection; the disk is perpendicular to the ray).
fn thin_lens(
    origin: Vec3,
    dir: Vec3,
    radius: f32,
    focus: f32,
    projected: bool,
    lens_u: Vec2,
) -> Option<(Vec3, Vec3)> {
    let disk = sample_concentric_disk(lens_u) * radius;
    // `toward` reaches the focus point from the pinhole: `focus_point = origin + toward * t`.
    let (toward, t, offset) = if projected {
        let d = dir.normalize();
        let (t, b) = d.any_orthonormal_pair();
        (d, focus, t * disk.x + b * disk.y)
    } else {
        if dir.z >= 0.0 {
            return None;
        }
        let t = (-origin.z - focus) / dir.z;
        (dir, t, Vec3::new(disk.x, disk.y, 0.0))
    };
    let focus_point = origin + toward * t;
    let start = origin + offset;
    // Beyond about 1.8e19 the squared length of `focus_point - start` overflows f32 and the
    // ray would be lost (a blank image); the same direction, scaled by 1/t, stays finite.
    let new_dir = (focus_point - start)
        .try_normalize()
        .or_else(|| (toward - offset / t).try_normalize())?;
    Some((start, new_dir))
}

#[cfg(test)]
mod tests {
    use super::*;

    use std::f32::consts::PI;

    const C: Vec2 = Vec2::splat(0.5);

    fn camera(fov_deg: f32, w: u32, h: u32) -> Camera {
        Camera {
            world_from_camera: Affine3A::IDENTITY,
            fov_y: fov_deg.to_radians(),
            width: w,
            height: h,
            aspect: w as f32 / h as f32,
            outputs: vec![],
            space_scale: 1.0,
        }
    }

    #[test]
    fn centre_ray_looks_down_minus_z() {
        let r = CameraRays::new(&camera(60.0, 64, 32))
            .ray(32.0, 16.0, C)
            .unwrap();
        assert!((r.dir - Vec3::NEG_Z).length() < 1e-6);
    }

    #[test]
    fn top_edge_is_at_half_fov() {
        let r = CameraRays::new(&camera(90.0, 64, 64))
            .ray(32.0, 0.0, C)
            .unwrap();
        // 45° up from the axis.
        assert!((r.dir.y - r.dir.z.abs()).abs() < 1e-6 && r.dir.y > 0.0);
        let r = CameraRays::new(&camera(90.0, 128, 64))
            .ray(0.0, 32.0, C)
            .unwrap();
        // Left edge at atan(aspect · tan 45°) = atan 2.
        assert!((r.dir.x / r.dir.z - 2.0).abs() < 1e-5 && r.dir.x < 0.0);
    }

    #[test]
    fn fisheye_and_spherical_map_film_positions_to_directions() {
        let cam = camera(60.0, 64, 64);
        let fish = CameraRays::with_lenses(&cam, &[Lens::Fisheye { fov: PI }]);
        let centre = fish.ray(32.0, 32.0, C).unwrap();
        assert!((centre.dir - Vec3::NEG_Z).length() < 1e-6);
        // Top edge of a 180° fisheye: 90° up.
        let top = fish.ray(32.0, 0.0, C).unwrap();
        assert!((top.dir - Vec3::Y).length() < 1e-6, "{}", top.dir);
        let sphere = CameraRays::with_lenses(&camera(60.0, 128, 64), &[Lens::Spherical]);
        // Three quarters across: azimuth +90° (toward +X); the left edge looks backwards.
        let right = sphere.ray(96.0, 32.0, C).unwrap();
        assert!((right.dir - Vec3::X).length() < 1e-6, "{}", right.dir);
        let back = sphere.ray(0.0, 32.0, C).unwrap();
        assert!((back.dir - Vec3::Z).length() < 1e-5, "{}", back.dir);
    }

    #[test]
    fn thin_lens_rays_of_a_pixel_meet_on_the_focus_plane() {
        let lens = [Lens::ThinLens {
            radius: 0.3,
            focus_distance: 5.0,
        }];
        let rays = CameraRays::with_lenses(&camera(40.0, 32, 32), &lens);
        let pinhole = CameraRays::new(&camera(40.0, 32, 32))
            .ray(10.0, 20.0, C)
            .unwrap();
        let target = pinhole.dir * (5.0 / -pinhole.dir.z);
        for u in [
            Vec2::new(0.1, 0.2),
            Vec2::new(0.9, 0.5),
            Vec2::new(0.4, 0.99),
        ] {
            let r = rays.ray(10.0, 20.0, u).unwrap();
            assert!(r.origin.z == 0.0 && r.origin.length() <= 0.3 + 1e-6);
            let t = (-5.0 - r.origin.z) / r.dir.z;
            assert!((r.origin + r.dir * t - target).length() < 1e-5);
        }
    }

    /// A focus plane so far away that `focus_point - start` overflows when squared (above
    /// about 1.8e19) still gives every ray, along the pinhole's direction to within the
    /// lens offset's angle (the image was blank).
    #[test]
    fn a_focus_plane_beyond_f32_squares_still_gives_rays() {
        for (radius, focus_distance) in [(0.01, 1e20), (0.01, 1e30), (1e-30, 1e30)] {
            let lens = [Lens::ThinLens {
                radius,
                focus_distance,
            }];
            let rays = CameraRays::with_lenses(&camera(60.0, 32, 32), &lens);
            let pinhole = CameraRays::new(&camera(60.0, 32, 32));
            for (x, y) in [(0.0, 0.0), (16.0, 16.0), (31.0, 0.0)] {
                let r = rays.ray(x, y, Vec2::new(0.3, 0.7)).expect("a ray");
                let p = pinhole.ray(x, y, C).unwrap();
                assert!(r.dir.is_finite() && (r.dir.length() - 1.0).abs() < 1e-6);
                assert!(
                    r.dir.dot(p.dir.normalize()) > 1.0 - 1e-6,
                    "{radius} {focus_distance}"
                );
            }
        }
    }
}

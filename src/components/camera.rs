//! Cameras and the outputs they write.

use std::path::PathBuf;

use glam::Affine3A;

/// Image passes a camera output can carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Pass {
    /// Shaded colour (RGB) with alpha.
    Beauty,
    /// Coverage: 1 where a surface was hit, 0 for the background.
    Alpha,
    /// Camera-space distance along the ray to the first hit (`Z`); infinity for misses.
    Depth,
    /// World-space shading normal at the first hit (`N.x`, `N.y`, `N.z`).
    Normal,
    /// Which placed object the pixel centre sees (`id.object`, u32): 1 + the instance's index
    /// in the flattened scene (instances in entity order, i.e. declaration order of the DAG
    /// leaves); 0 for the background.
    ObjectId,
    /// Which material the pixel centre sees (`id.material`, u32): 1 + the material's index
    /// among the materials in use; 0 for the background.
    MaterialId,
}

/// File formats for outputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// 8-bit sRGB PNG (beauty + alpha only).
    Png,
    /// OpenEXR, linear, with layers for every requested pass.
    Exr,
}

/// One output file of a camera.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputSpec {
    /// Destination path (relative paths resolve against the working directory).
    pub path: PathBuf,
    /// File format.
    pub format: ImageFormat,
    /// Passes written into the file.
    pub passes: Vec<Pass>,
}

/// A pinhole camera looking down its local −Z axis, +Y up.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// Camera-to-world placement (rigid).
    pub world_from_camera: Affine3A,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Image aspect ratio (width / height of the image plane); `width / height` for square
    /// pixels.
    pub aspect: f32,
    /// Files to write.
    pub outputs: Vec<OutputSpec>,
}

/// Marks the camera named by the scene's `render` entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderCamera;

/// Camera-to-world transform of a camera at `eye` looking at `target` with `up` roughly up:
/// the camera's −Z points at the target, +Y toward `up`. `None` when the directions are
/// degenerate (eye = target, or `up` parallel to the view direction).
pub fn world_from_look_at(eye: glam::Vec3, target: glam::Vec3, up: glam::Vec3) -> Option<Affine3A> {
    let forward = (target - eye).try_normalize()?;
    let right = forward.cross(up).try_normalize()?;
    let true_up = right.cross(forward);
    Some(Affine3A::from_cols(
        right.into(),
        true_up.into(),
        (-forward).into(),
        eye.into(),
    ))
}

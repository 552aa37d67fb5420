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

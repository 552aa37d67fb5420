//! Contours: mental ray's non-photorealistic line output. The `draw_contours` stage runs
//! these steps in order:
//!
//! 1. [`store`]: what the camera sees at each pixel centre (written by `shade`);
//! 2. [`contrast`]: edges between neighbouring samples, placed by bisection;
//! 3. [`linking`]: edge crossings joined into polylines;
//! 4. [`shaders`]: each point's colour and width from the front material's contour shader;
//! 5. [`raster`]: the anti-aliased RGBA contour layer;
//!
//! and the writers read the result: [`svg`] and [`eps`] (vector lines, both from the shapes
//! of [`outline`]) and [`output`] (the EXR layer and the PNG composite). [`stacking`] is
//! the one order lines are drawn in, bottom to top, by the raster layer and both vector
//! writers alike.

pub mod contrast;
pub mod eps;
pub mod linking;
pub mod outline;
pub mod output;
pub mod raster;
pub mod shaders;
pub mod stacking;
pub mod store;
pub mod svg;

use glam::{Vec2, Vec4};

pub use store::{ContourSample, ContourStore, Probe};

/// One point of a contour line (what mental ray's `mi_get_contour_line` gives per point).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContourPoint {
    /// Film position, pixels (0,0 the top-left corner of the image).
    pub pos: Vec2,
    /// Linear RGBA colour, straight alpha.
    pub color: Vec4,
    /// Line width, pixels.
    pub width: f32,
}

/// A contour polyline, all of one material.
#[derive(Debug, Clone, PartialEq)]
pub struct ContourLine {
    /// 1 + the index of the material on its front side (as `Pass::MaterialId`).
    pub material: u32,
    /// Whether the last point joins back to the first.
    pub closed: bool,
    /// The points, at least two.
    pub points: Vec<ContourPoint>,
}

/// The output of `draw_contours`: the lines and their rasterised layer.
#[derive(Debug, Clone, PartialEq)]
pub struct ContourImage {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// The lines, in a deterministic order.
    pub lines: Vec<ContourLine>,
    /// Name of each material (index `material − 1`), for the SVG groups.
    pub material_names: Vec<String>,
    /// The contour layer: premultiplied linear RGBA per pixel, row-major.
    pub layer: Vec<Vec4>,
}

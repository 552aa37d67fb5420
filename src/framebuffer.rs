//! Frame buffers: the per-pixel passes the `shade` stage produces.

use glam::Vec3;

use crate::contour::ContourStore;
use crate::exact_sum::ExactSum;

/// Linear, row-major (row 0 at the top) pass buffers of one camera.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameBuffers {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear RGB radiance (W/(sr·m²)).
    pub beauty: Vec<Vec3>,
    /// Coverage in [0, 1].
    pub alpha: Vec<f32>,
    /// Distance along the camera ray to the first hit of the pixel centre; `f32::INFINITY`
    /// where nothing was hit.
    pub depth: Vec<f32>,
    /// World-space shading normal at the pixel centre; zero where nothing was hit.
    pub normal: Vec<Vec3>,
    /// Object id at the pixel centre (see `Pass::ObjectId`); 0 for the background.
    pub object_id: Vec<u32>,
    /// Material id at the pixel centre (see `Pass::MaterialId`); 0 for the background.
    pub material_id: Vec<u32>,
    /// Camera samples the pixel took (the uniform count, or what adaptive sampling chose).
    pub samples: Vec<u32>,
    /// The exact sample sums behind `beauty` and `alpha`, kept only when the run renders a
    /// farm part (`crate::farm`), which writes them instead of the image.
    pub sums: Option<PixelSums>,
    /// What the camera sees at each pixel centre, for `draw_contours`; kept only when some
    /// material has a contour shader (and not in a farm part).
    pub contour_store: Option<ContourStore>,
}

/// Exact per-pixel sample sums and counts (see [`FrameBuffers::sums`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PixelSums {
    /// Exact sums of the finite R, G, B samples.
    pub sums: Vec<[ExactSum; 3]>,
    /// Samples whose camera ray hit something.
    pub covered: Vec<u32>,
    /// Non-finite samples dropped.
    pub dropped: Vec<u32>,
}

impl FrameBuffers {
    /// Buffers of `width × height` pixels, all zero (depth infinite).
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            beauty: vec![Vec3::ZERO; n],
            alpha: vec![0.0; n],
            depth: vec![f32::INFINITY; n],
            normal: vec![Vec3::ZERO; n],
            object_id: vec![0; n],
            material_id: vec![0; n],
            samples: vec![0; n],
            sums: None,
            contour_store: None,
        }
    }
}

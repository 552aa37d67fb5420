//! Frame buffers: the per-pixel passes the `shade` stage produces, and the contour store it
//! keeps for `draw_contours` (what each pixel centre sees).

use glam::{Vec2, Vec3};

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
    /// The component passes per pixel (linear RGB, in the order of `Pass::COMPONENTS`;
    /// they sum to `beauty`), kept only when an output asks for one.
    pub components: Option<Vec<[Vec3; 6]>>,
    /// The environment's share of `beauty` per pixel: the radiance of the camera samples
    /// that missed every surface (alpha 0), summed like the beauty (its part of the same
    /// plain average of the pixel's samples), so `beauty − environment` is what the pixel's
    /// surfaces contribute. Kept only when an output writes straight alpha (a PNG with
    /// `Beauty` and `Alpha`) and the camera can see an environment, or in a farm part's
    /// merge (see [`PixelSums::environment`]).
    pub environment: Option<Vec<Vec3>>,
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
    /// Exact sums of the R, G, B radiance of the samples that missed every surface (the
    /// environment's share, [`FrameBuffers::environment`]), kept whenever the camera can
    /// see an environment, so that any merge output can use them.
    pub environment: Option<Vec<[ExactSum; 3]>>,
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
            components: None,
            environment: None,
        }
    }
}

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

    /// What a sample of a deeper level sees where the path ended before that level (no
    /// mirror, refraction or transparency to follow): no contour runs next to it.
    pub const ABSENT: ContourSample = ContourSample {
        instance: u32::MAX,
        object: u32::MAX,
        material: 0,
        normal: Vec3::ZERO,
        depth: f32::INFINITY,
        color: Vec3::ZERO,
    };

    /// Whether the sample sees no surface.
    pub fn is_background(&self) -> bool {
        self.instance == 0
    }

    /// Whether the sample's path ended before its level ([`ContourSample::ABSENT`]).
    pub fn is_absent(&self) -> bool {
        self.instance == u32::MAX
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
    /// The ray level of the samples: 0 for what the camera sees, `k` for what it sees
    /// behind `k` mirror, refraction or transparency events (the layers in front).
    pub level: u32,
    /// The stores of levels 1, 2, … (the contours' `ray_depth`; empty by default).
    pub deeper: Vec<ContourStore>,
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

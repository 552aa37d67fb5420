//! Render settings: the scene's `options` after command-line overrides.

/// Pixel reconstruction filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PixelFilter {
    /// Unweighted average of samples inside the pixel.
    Box,
    /// Gaussian of standard deviation `sigma` pixels, truncated at `radius` pixels; samples are
    /// importance-sampled from the filter so every sample has weight one.
    Gaussian {
        /// Standard deviation in pixels.
        sigma: f32,
        /// Truncation radius in pixels.
        radius: f32,
    },
}

/// Which faces of one-sided surfaces are visible to rays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Face {
    /// Only front faces (counter-clockwise) are shaded; back faces of one-sided materials
    /// render black but still block light.
    Front,
    /// Every surface is treated as two-sided.
    Both,
}

/// BVH build quality: more time building for faster tracing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BvhQuality {
    /// Cheapest build.
    Fast,
    /// Balanced (default).
    Medium,
    /// Slowest build, best hierarchy.
    High,
}

/// Settings every stage can read.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderSettings {
    /// Samples per pixel.
    pub spp: u32,
    /// Pixel filter.
    pub filter: PixelFilter,
    /// Seed of every random decision.
    pub seed: u64,
    /// Maximum trace depth (1 = camera rays and their shadow rays only).
    pub max_depth: u32,
    /// Face visibility.
    pub face: Face,
    /// BVH build quality.
    pub bvh_quality: BvhQuality,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            spp: 4,
            filter: PixelFilter::Box,
            seed: 0,
            max_depth: 4,
            face: Face::Front,
            bvh_quality: BvhQuality::Medium,
        }
    }
}

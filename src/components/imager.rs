//! Output shaders of a camera (RenderMan `Exposure`, `Imager "background"` and the seed
//! tutorial's `Imager "myImager"`, mental ray output shaders): what turns scene-linear
//! radiance into display values for 8-bit outputs. Applying it is `image_io::imager` and
//! `image_io::imager_pattern`.

use glam::{Vec2, Vec3};

/// Tone-mapping operator applied after the gain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToneMap {
    /// Values above 1 clip.
    None,
    /// Reinhard's `x / (1 + x)` per channel.
    Reinhard,
}

/// A pattern of raster position that an imager paints over every pixel, as an RSL imager
/// shader that sets `Ci`, `Oi = 1` and `alpha = 1` whatever the pixel held. Positions are
/// normalised by the resolution: `(x + ½, y + ½) / (width, height)` for the pixel in column
/// `x` and row `y` (row 0 at the top, RenderMan's raster space). Its colours are display
/// values, as RenderMan runs the imager after `Exposure` and before quantization.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ImagerPattern {
    /// The seed tutorial's disk (`myImager`, §3.2.3): `mix(outside, inside, 1 −
    /// smoothstep(radius − fuzz, radius + fuzz, |here − center|))`.
    Disk {
        /// Centre, normalised raster coordinates.
        center: Vec2,
        /// Radius, in units of the resolution.
        radius: f32,
        /// Half-width of the soft edge (≥ 0).
        fuzz: f32,
        /// Colour inside the disk.
        inside: Vec3,
        /// Colour outside it.
        outside: Vec3,
    },
}

/// A camera's imager: background fill, exposure gain, tone map, display gamma and a pattern
/// painted over every pixel. Applied to PNG outputs only; EXR outputs keep scene-linear
/// radiance for compositing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Imager {
    /// Colour composited behind partly covered pixels: `c + (1 − alpha) · background`, after
    /// which the pixel is opaque. `None` leaves the background black (transparent).
    pub background: Option<Vec3>,
    /// Multiplier on radiance (RenderMan `Exposure gain …`).
    pub gain: f32,
    /// Tone-mapping operator.
    pub tone_map: ToneMap,
    /// Display gamma (RenderMan `Exposure … gamma`): values are encoded as `v^(1/gamma)`.
    /// `None` uses the sRGB transfer curve.
    pub gamma: Option<f32>,
    /// A pattern replacing every pixel's colour (display values) and alpha (1), `None` for
    /// none.
    pub pattern: Option<ImagerPattern>,
}

impl Default for Imager {
    fn default() -> Self {
        Self {
            background: None,
            gain: 1.0,
            tone_map: ToneMap::None,
            gamma: None,
            pattern: None,
        }
    }
}

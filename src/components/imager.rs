//! Output shaders of a camera (RenderMan `Exposure` and `Imager "background"`, mental ray
//! output shaders): what turns scene-linear radiance into display values for 8-bit outputs.
//! Applying it is `image_io::imager`.

use glam::Vec3;

/// Tone-mapping operator applied after the gain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToneMap {
    /// Values above 1 clip.
    None,
    /// Reinhard's `x / (1 + x)` per channel.
    Reinhard,
}

/// A camera's imager: background fill, exposure gain, tone map and display gamma. Applied to
/// PNG outputs only; EXR outputs keep scene-linear radiance for compositing.
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
}

impl Default for Imager {
    fn default() -> Self {
        Self {
            background: None,
            gain: 1.0,
            tone_map: ToneMap::None,
            gamma: None,
        }
    }
}

//! Scene description of contours: a material's `contour:` shader and the options'
//! `contours: (...)` (see `docs/scene-format.md`, "Contours").

use serde::{Deserialize, Serialize};

/// A colour with alpha as written: `(r, g, b, a)`, linear, straight alpha.
pub type V4 = (f64, f64, f64, f64);

/// `contour: …` on a material: its contour shader. Widths are in percent of
/// `min(x resolution, y resolution)`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Contour", deny_unknown_fields)]
pub enum ContourDesc {
    /// Constant colour and width.
    Simple {
        /// Colour, default `(0, 0, 0, 1)`.
        #[serde(default = "black")]
        color: V4,
        /// Width, percent, default 0.5, > 0.
        #[serde(default = "half")]
        width: f64,
    },
    /// Constant colour and width on the outline only (the other side is the background or
    /// another object).
    Silhouette {
        /// Colour, default `(0, 0, 0, 1)`.
        #[serde(default = "black")]
        color: V4,
        /// Width, percent, default 0.5, > 0.
        #[serde(default = "half")]
        width: f64,
    },
    /// Colour and width interpolated between a near and a far distance.
    DepthFade {
        /// Distance of the near values, scene units (≥ 0).
        near: f64,
        /// Distance of the far values, scene units (> `near`).
        far: f64,
        /// Colour at `near`, default `(0, 0, 0, 1)`.
        #[serde(default = "black")]
        near_color: V4,
        /// Colour at `far`, default `(0, 0, 0, 1)`.
        #[serde(default = "black")]
        far_color: V4,
        /// Width at `near`, percent, default 1.
        #[serde(default = "one")]
        near_width: f64,
        /// Width at `far`, percent, default 0.25.
        #[serde(default = "quarter")]
        far_width: f64,
    },
    /// Width from the angle between the normals across the edge.
    Curvature {
        /// Colour, default `(0, 0, 0, 1)`.
        #[serde(default = "black")]
        color: V4,
        /// Width at 0°, percent, default 0.1.
        #[serde(default = "tenth")]
        min_width: f64,
        /// Width at 180° and silhouettes, percent, default 1.
        #[serde(default = "one")]
        max_width: f64,
    },
    /// Colour = factor × the material's shaded colour.
    FactorColor {
        /// Multiplier, default 0.5, ≥ 0.
        #[serde(default = "half_factor")]
        factor: f64,
        /// Width, percent, default 0.5.
        #[serde(default = "half")]
        width: f64,
    },
    /// Width from the illumination at the edge.
    WidthFromLight {
        /// Colour, default `(0, 0, 0, 1)`.
        #[serde(default = "black")]
        color: V4,
        /// Width on a black surface, percent, default 1.
        #[serde(default = "one")]
        dark_width: f64,
        /// Width on a white surface, percent, default 0.25.
        #[serde(default = "quarter")]
        lit_width: f64,
    },
    /// Width thinning by the layers in front: `width · thinning^k`.
    Layered {
        /// Colour, default `(0, 0, 0, 1)`.
        #[serde(default = "black")]
        color: V4,
        /// Width with no layer in front, percent, default 0.5.
        #[serde(default = "half")]
        width: f64,
        /// Factor per layer in front, default 0.5, in (0, 1].
        #[serde(default = "half_factor")]
        thinning: f64,
    },
}

/// `contours: (...)` in `options`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize, Serialize)]
#[serde(rename = "Contours", deny_unknown_fields, default)]
pub struct ContoursDesc {
    /// Which sample differences make a contour.
    pub contrast: ContrastDesc,
    /// Mirror/refraction/transparency levels behind the first hit that get contours too,
    /// default 0, at most 8.
    pub ray_depth: u32,
}

/// `contrast: (...)` in `contours`: mental ray's contour contrast.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Contrast", deny_unknown_fields, default)]
pub struct ContrastDesc {
    /// Between different instances, default `true`.
    pub instance: bool,
    /// Between different objects, default `true`.
    pub object: bool,
    /// Between different materials, default `true`.
    pub material: bool,
    /// Normal angle threshold, degrees, default 60 (in (0, 180]; 180: off).
    pub normal_angle: f64,
    /// Relative depth jump threshold, default 0.25 (> 0); `None`: depth jumps make no
    /// contour.
    pub depth: Option<f64>,
    /// Silhouettes against the background, default `true`.
    pub background: bool,
}

impl Default for ContrastDesc {
    fn default() -> Self {
        Self {
            instance: true,
            object: true,
            material: true,
            normal_angle: 60.0,
            depth: Some(0.25),
            background: true,
        }
    }
}

fn black() -> V4 {
    (0.0, 0.0, 0.0, 1.0)
}
fn half() -> f64 {
    0.5
}
fn half_factor() -> f64 {
    0.5
}
fn one() -> f64 {
    1.0
}
fn quarter() -> f64 {
    0.25
}
fn tenth() -> f64 {
    0.1
}

//! Contours (mental ray's non-photorealistic line output): the contour shader a material
//! carries and the contour contrast of the scene.
//!
//! Widths are in percent of `min(x resolution, y resolution)`, as mental ray gives them;
//! colours are linear RGBA, not premultiplied.

use glam::Vec4;

/// A material's contour shader: the colour and width of the lines drawn where this material
/// is on the front side of an edge. A material without one gets no contours around it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContourShader {
    /// Constant `color` and `width`.
    Simple {
        /// Line colour (linear RGBA).
        color: Vec4,
        /// Line width, percent of the smaller image dimension.
        width: f32,
    },
    /// Constant `color` and `width`, drawn only on the outline: where the other side of the
    /// edge is the background or another object (mental ray's
    /// `contour_shader_silhouette`); creases and material edges inside an object get no line.
    Silhouette {
        /// Line colour (linear RGBA).
        color: Vec4,
        /// Line width, percent of the smaller image dimension.
        width: f32,
    },
    /// Colour and width interpolated linearly between `near` and `far` camera distances:
    /// `t = clamp((d − near) / (far − near), 0, 1)`, colour `= near_color + t·(far_color −
    /// near_color)`, width likewise.
    DepthFade {
        /// Distance (scene units) where the near values hold.
        near: f32,
        /// Distance (scene units, > `near`) where the far values hold.
        far: f32,
        /// Colour at `near` and closer.
        near_color: Vec4,
        /// Colour at `far` and beyond.
        far_color: Vec4,
        /// Width at `near` and closer (percent).
        near_width: f32,
        /// Width at `far` and beyond (percent).
        far_width: f32,
    },
    /// Width from the angle `θ` between the normals on the two sides of the edge:
    /// `width = min_width + (max_width − min_width)·θ/180°`; against the background or
    /// another object `θ` counts as 180°.
    Curvature {
        /// Line colour.
        color: Vec4,
        /// Width of an edge between parallel normals (percent).
        min_width: f32,
        /// Width of a fold back onto itself, and of silhouettes (percent).
        max_width: f32,
    },
    /// Colour from the material's shaded colour at the edge: `rgb = factor · shaded`,
    /// alpha 1.
    FactorColor {
        /// Multiplier of the shaded colour.
        factor: f32,
        /// Line width (percent).
        width: f32,
    },
    /// Width from the illumination at the edge (toon ink: thick in shadow, thin in light):
    /// with `L` the Rec. 709 luminance of the shaded colour clamped to [0, 1],
    /// `width = dark_width + (lit_width − dark_width)·L`.
    WidthFromLight {
        /// Line colour.
        color: Vec4,
        /// Width where the surface is black (percent).
        dark_width: f32,
        /// Width where the surface is white or brighter (percent).
        lit_width: f32,
    },
    /// Width thinning with the layers in front: with `k` the number of surfaces the camera
    /// ray passed, or was reflected or refracted by, before reaching the line's surface
    /// (0 for what the camera sees directly; contours behind the first hit need the
    /// contrast's `ray_depth`), `width = width · thinning^k`.
    Layered {
        /// Line colour.
        color: Vec4,
        /// Width with no layer in front (percent).
        width: f32,
        /// Factor per layer in front, in (0, 1].
        thinning: f32,
    },
}

impl ContourShader {
    /// Every width the shader may produce, percent (for validation).
    pub fn widths(&self) -> Vec<f32> {
        match *self {
            ContourShader::Simple { width, .. }
            | ContourShader::Silhouette { width, .. }
            | ContourShader::FactorColor { width, .. }
            | ContourShader::Layered { width, .. } => vec![width],
            ContourShader::DepthFade {
                near_width,
                far_width,
                ..
            } => vec![near_width, far_width],
            ContourShader::Curvature {
                min_width,
                max_width,
                ..
            } => vec![min_width, max_width],
            ContourShader::WidthFromLight {
                dark_width,
                lit_width,
                ..
            } => vec![dark_width, lit_width],
        }
    }
}

/// Which differences between neighbouring samples make a contour (mental ray's contour
/// contrast). Carried by the scene's `contours` entity; defaults when the scene gives none.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContourContrast {
    /// Between different placed instances (default on).
    pub instance: bool,
    /// Between different objects (meshes; default on).
    pub object: bool,
    /// Between different materials (default on).
    pub material: bool,
    /// Where the normals differ by more than this angle, degrees (default 60; 180 or more:
    /// never).
    pub normal_angle: f32,
    /// Where the depths differ by more than this fraction of the nearer one (default 0.25;
    /// `None`: never).
    pub depth: Option<f32>,
    /// Between a surface and the background: silhouettes (default on).
    pub background: bool,
    /// How many mirror, refraction or transparency levels behind the first hit also get
    /// contours (default 0: only what the camera sees directly). Level `k` follows the
    /// strongest delta branch (mirror, refraction, pass-through) of each surface `k` times.
    pub ray_depth: u32,
}

impl Default for ContourContrast {
    fn default() -> Self {
        Self {
            instance: true,
            object: true,
            material: true,
            normal_angle: 60.0,
            depth: Some(0.25),
            background: true,
            ray_depth: 0,
        }
    }
}

impl ContourContrast {
    /// Whether some criterion can make an edge: with every one off (no instance, object,
    /// material or background switch, a `normal_angle` of 180° or more, no `depth`) no
    /// contour is ever drawn.
    pub fn any_on(&self) -> bool {
        self.instance
            || self.object
            || self.material
            || self.normal_angle < 180.0
            || self.depth.is_some()
            || self.background
    }
}

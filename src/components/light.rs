//! Light emitters: point, spot, directional and rectangular area lights.

use glam::Vec3;

/// The geometry of a light and its shape-specific parameters (world space).
#[derive(Debug, Clone, PartialEq)]
pub enum LightShape {
    /// Isotropic point light; `Emitter::radiant` is intensity in W/sr.
    Point {
        /// Position.
        position: Vec3,
    },
    /// RenderMan-style spotlight; `Emitter::radiant` is on-axis intensity in W/sr.
    Spot {
        /// Position.
        position: Vec3,
        /// Unit axis direction (where the light points).
        direction: Vec3,
        /// Half-angle of the cone, radians.
        cone_angle: f32,
        /// Width of the penumbra inside the cone edge, radians (`conedeltaangle`).
        penumbra: f32,
        /// Exponent of `cos` falloff from the axis (`beamdistribution`).
        beam_distribution: f32,
    },
    /// Distant light; `Emitter::radiant` is irradiance in W/m² on a surface facing it.
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3,
    },
    /// One-sided parallelogram emitting along `edge_u × edge_v`; `Emitter::radiant` is
    /// radiance in W/(sr·m²).
    Rect {
        /// One corner.
        corner: Vec3,
        /// First edge vector from `corner`.
        edge_u: Vec3,
        /// Second edge vector from `corner`.
        edge_v: Vec3,
    },
}

/// A light entity's data.
#[derive(Debug, Clone, PartialEq)]
pub struct Emitter {
    /// Shape and placement.
    pub shape: LightShape,
    /// Colour × intensity, in the unit the shape states (W/sr, W/m² or W/(sr·m²)).
    pub radiant: Vec3,
    /// Whether shadow rays are traced toward this light.
    pub shadows: bool,
    /// Samples per shading point for area lights (1 for delta lights).
    pub samples: u32,
}

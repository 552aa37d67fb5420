//! How finely a surface is diced: mental ray's approximation statement.

/// Where a spatial edge length is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LengthSpace {
    /// Object-space units.
    Object,
    /// Raster pixels of the render camera (view dependent; the object's instance nearest to
    /// needing detail decides, i.e. the largest projected length over its instances).
    Raster,
}

/// A tessellation technique (mental ray `approximate surface …`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Technique {
    /// `parametric u v`: every patch is cut into `u × v` equal parameter steps.
    /// Counts are clamped to `1..=4096`; `min_subdiv`/`max_subdiv` do not apply.
    Parametric {
        /// Segments per patch along u.
        u: u32,
        /// Segments per patch along v.
        v: u32,
    },
    /// `regular parametric u v`: the whole surface is cut into `u × v` equal parameter steps,
    /// shared out over its patches (each patch gets `ceil(u / patches_u)`). Clamped like
    /// `Parametric`.
    Regular {
        /// Segments over the whole surface along u.
        u: u32,
        /// Segments over the whole surface along v.
        v: u32,
    },
    /// `spatial [view] edge`: no triangle edge longer than `edge` (object units, or raster
    /// pixels with [`LengthSpace::Raster`]). Measured on the displaced surface.
    Spatial {
        /// Maximum edge length (> 0).
        edge: f32,
        /// Units of `edge`.
        space: LengthSpace,
    },
    /// `curvature distance angle`: the chord of every edge deviates from the surface by at
    /// most `distance` (object units) and turns by at most `angle` degrees. A zero disables
    /// that criterion (not both).
    Curvature {
        /// Maximum distance from the true (displaced) surface, object units (≥ 0).
        distance: f32,
        /// Maximum angle between neighbouring normals along an edge, degrees (≥ 0).
        angle: f32,
    },
}

/// The approximation of an object's surfaces and displacement. Objects without one use
/// [`Approximation::default`].
///
/// Rates are decided per edge from the edge alone, so neighbouring patches always agree;
/// adaptive rates (spatial, curvature) lie in `[2^min_subdiv, 2^max_subdiv]` segments per
/// patch edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Approximation {
    /// The technique.
    pub technique: Technique,
    /// Minimum subdivision level (segments ≥ 2^min), clamped to `0..=12`. Default 0.
    pub min_subdiv: u32,
    /// Maximum subdivision level (segments ≤ 2^max), clamped to `min..=12`. Default 7.
    pub max_subdiv: u32,
}

impl Default for Approximation {
    /// Curvature with distance 0.01 (object units) and 10°, levels 0…7.
    fn default() -> Self {
        Self {
            technique: Technique::Curvature {
                distance: 0.01,
                angle: 10.0,
            },
            min_subdiv: 0,
            max_subdiv: 7,
        }
    }
}

/// Where an object's `approximation` is written (on objects that write one), so that a
/// refusal of the triangles it would make points at the value to change; objects without
/// one are located at their own `SourceLink`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ApproximationLink(pub super::SourceLink);

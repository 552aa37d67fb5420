//! Displacement shaders and surface derivatives.

use std::sync::Arc;

use glam::Vec3;

/// Which texture coordinate a pattern reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UvAxis {
    /// `s` (u).
    U,
    /// `t` (v).
    V,
}

/// A greyscale image sampled bilinearly at the surface uv (repeat wrap), already decoded.
/// Texel `(x, y)` is at `texels[y·width + x]`, y = 0 at v = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct ImageMap {
    /// Width in texels (≥ 1).
    pub width: u32,
    /// Height in texels (≥ 1).
    pub height: u32,
    /// Texel values (`width × height`).
    pub texels: Arc<Vec<f32>>,
    /// Multiplier applied to the sampled value.
    pub scale: f32,
    /// Added after scaling (e.g. −0.5·scale to centre an 8-bit map).
    pub offset: f32,
}

/// A scalar shader node: the displacement amount (object units) as a function of the
/// surface point. Nodes form a tree; every node is deterministic.
#[derive(Debug, Clone, PartialEq)]
pub enum ScalarNode {
    /// A constant offset.
    Constant(f32),
    /// The seed's pattern `amplitude · sin(coord · factor · π)` over `s` or `t`.
    Sine {
        /// Amplitude (object units).
        amplitude: f32,
        /// Frequency factor (the seed uses 50–60).
        factor: f32,
        /// Coordinate read.
        axis: UvAxis,
    },
    /// Fractal Brownian motion of Perlin gradient noise over object-space position:
    /// `amplitude · Σ gain^i · noise(frequency · lacunarity^i · P + offset(seed, i))`, each
    /// octave in about [−1, 1].
    Noise {
        /// Amplitude (object units).
        amplitude: f32,
        /// Base frequency (cycles per object unit).
        frequency: f32,
        /// Octaves, clamped to `1..=12`.
        octaves: u32,
        /// Frequency multiplier per octave (default 2).
        lacunarity: f32,
        /// Amplitude multiplier per octave (default 0.5).
        gain: f32,
        /// Seed: different seeds give unrelated patterns.
        seed: u64,
    },
    /// An image map over uv (see [`ImageMap`]).
    Image(ImageMap),
    /// The sum of the inputs.
    Sum(Vec<ScalarNode>),
    /// The product of the inputs.
    Product(Vec<ScalarNode>),
}

/// True displacement moves vertices; bump only perturbs shading normals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DisplacementMode {
    /// Move vertices along the normal (changes silhouettes, shadows, photon paths).
    True,
    /// Perturb shading normals only. The geometry stays as it is; the component stays on the
    /// object for the shading library's bump hook (not wired up yet: see `docs/geometry.md`).
    Bump,
}

/// A displacement shader on an object entity.
#[derive(Debug, Clone, PartialEq)]
pub struct Displacement {
    /// The scalar displacement (object units along the unit normal).
    pub shader: ScalarNode,
    /// Maximum |displacement| (object units); values beyond are clamped. `None`: the
    /// shader's own bound (see `crate::tessellation::displace::node_bound`).
    pub bound: Option<f32>,
    /// True or bump.
    pub mode: DisplacementMode,
}

/// Marker: store [`SurfaceDerivatives`] when this object is tessellated (mental ray's
/// `derivative 1` request).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DerivativeRequest;

/// First surface derivatives of a tessellated object, one per mesh vertex (same indexing as
/// `TriMesh::positions`), in object space, per unit of the patch's texture coordinates
/// (`dP/du`, `dP/dv` where (u, v) is the mesh uv). Of the undisplaced surface.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurfaceDerivatives {
    /// ∂P/∂u per vertex.
    pub dpdu: Vec<Vec3>,
    /// ∂P/∂v per vertex.
    pub dpdv: Vec<Vec3>,
}

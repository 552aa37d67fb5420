//! Compiled shader graphs of materials, as plain data: the flat [`Program`] of [`Op`]s the
//! scene loader compiles a material's node trees into, the parameters it drives
//! ([`Binding`]) and its bump height ([`BumpMap`]), with the values the ops carry (noise
//! parameters, colour spaces, decoded image textures).
//!
//! Evaluation lives in the shading library (`shading::texture`: `Program::run`,
//! `MaterialGraph::bind`, the node functions); the compiler in `scene::nodes`.

use std::sync::Arc;

use glam::{Vec2, Vec3};

/// A register index (an earlier op's output).
pub type Reg = u32;

/// Which noise a [`Op::Noise`] computes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoiseKind {
    /// One octave of Perlin noise (signed, about [−1, 1]).
    Perlin,
    /// Fractal Brownian motion (signed).
    Fbm,
    /// Turbulence (sum of absolute octaves, ≥ 0).
    Turbulence,
}

/// One node of a compiled graph; inputs are registers of earlier ops. Scalar inputs read
/// channel 0; coordinates (`uv`) read channels 0 and 1.
#[derive(Debug, Clone, PartialEq)]
pub enum Op {
    /// A constant.
    Const(Vec3),
    /// `(u, v, 0)`.
    Uv,
    /// Object-space position.
    Position,
    /// World-space shading normal.
    Normal,
    /// The mesh's interpolated vertex colour (white without vertex colours).
    VertexColour,
    /// `a` where `⌊u·scale⌋ + ⌊v·scale⌋` is even, `b` where odd.
    Checker {
        /// Coordinates.
        uv: Reg,
        /// Squares per unit.
        scale: Reg,
        /// Even squares.
        a: Reg,
        /// Odd squares.
        b: Reg,
    },
    /// The seed's disk: `mix(outside, inside, 1 − smoothstep(r − fuzz, r + fuzz, |uv − c|))`.
    Disk {
        /// Coordinates.
        uv: Reg,
        /// Centre in uv.
        center: Vec2,
        /// Radius.
        radius: Reg,
        /// Half-width of the soft edge.
        fuzz: Reg,
        /// Colour inside.
        inside: Reg,
        /// Colour outside.
        outside: Reg,
    },
    /// The tutorial's stairs blend over v: the weight of a step's tread (`up`) normal
    /// (`shading::texture::pattern::steps`).
    Steps {
        /// Coordinates (v read).
        uv: Reg,
        /// Steps per unit of v.
        steps: Reg,
        /// Half-width of the blend at each edge, in steps.
        fuzz: Reg,
    },
    /// `(mod(u·scale, 1), mod(v·scale, 1), 0)`.
    Repeat {
        /// Coordinates.
        uv: Reg,
        /// Repetitions per unit.
        scale: Reg,
    },
    /// Solid noise of a point.
    Noise {
        /// The point.
        p: Reg,
        /// Which noise.
        kind: NoiseKind,
        /// Frequency, octaves, seed.
        fractal: Fractal,
    },
    /// An image texture at `uv`.
    Image {
        /// Coordinates.
        uv: Reg,
        /// The decoded image (shared between materials).
        texture: Arc<Texture>,
    },
    /// An image texture's alpha at `uv`, as a scalar (1 where the image has no alpha).
    ImageAlpha {
        /// Coordinates.
        uv: Reg,
        /// The decoded image (shared between materials).
        texture: Arc<Texture>,
    },
    /// `a·(1 − t) + b·t`.
    Mix {
        /// Value at t = 0.
        a: Reg,
        /// Value at t = 1.
        b: Reg,
        /// Blend.
        t: Reg,
    },
    /// `smoothstep(edge0, edge1, x)`.
    Smoothstep {
        /// Lower edge.
        edge0: Reg,
        /// Upper edge.
        edge1: Reg,
        /// Input.
        x: Reg,
    },
    /// `a + b`.
    Add(Reg, Reg),
    /// `a − b`.
    Sub(Reg, Reg),
    /// `a · b` (per channel).
    Mul(Reg, Reg),
    /// One channel of a colour, as a scalar.
    Channel(Reg, u8),
    /// Rec. 709 luminance of a colour, as a scalar.
    Luminance(Reg),
    /// A colour from three scalars.
    Combine(Reg, Reg, Reg),
    /// Colour-space conversion.
    Convert {
        /// The colour.
        input: Reg,
        /// Space it is in.
        from: ColourSpace,
        /// Space to convert to.
        to: ColourSpace,
    },
}

/// A compiled graph: ops in dependency order; op `i` writes register `i`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Program {
    /// The ops.
    pub ops: Vec<Op>,
}

impl Program {
    /// Appends an op and returns its register.
    pub fn push(&mut self, op: Op) -> Reg {
        self.ops.push(op);
        (self.ops.len() - 1) as Reg
    }

    /// Whether some op reads the object-space position.
    pub fn uses_position(&self) -> bool {
        self.ops.iter().any(|op| matches!(op, Op::Position))
    }
}

/// A shader parameter driven by a register.
#[derive(Debug, Clone, PartialEq)]
pub struct Binding {
    /// Parameter name as written in the scene (`albedo`, `input.color`).
    pub param: String,
    /// Register holding its value.
    pub reg: Reg,
}

/// Bump mapping of a material: the height (object units along the normal) is `scale` times
/// a scalar register.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BumpMap {
    /// Register holding the height.
    pub height: Reg,
    /// Multiplier of the height.
    pub scale: f32,
}

/// A tangent-space normal map (glTF's `normalTexture`): a colour register holding the
/// texel `c` in \[0, 1\]³, read as the normal `(2c − 1)·(scale, scale, 1)` in the frame
/// (tangent, bitangent, normal) of the surface (`shading::texture::normal_map`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalMap {
    /// Register holding the encoded normal.
    pub texel: Reg,
    /// Multiplier of the normal's tangential part.
    pub scale: f32,
}

/// The node graphs of one material: which parameters they drive, the bump height, the
/// normal map, the object-space normal and the emission's texture.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MaterialGraph {
    /// The compiled ops of every binding and of the bump height.
    pub program: Program,
    /// Driven parameters.
    pub bindings: Vec<Binding>,
    /// Bump mapping, if any.
    pub bump: Option<BumpMap>,
    /// Tangent-space normal mapping, if any.
    pub normal_map: Option<NormalMap>,
    /// Register holding an object-space shading normal (`bump: (object_normal: …)`), if
    /// any: it replaces the surface's normal (`shading::texture::object_normal`).
    pub object_normal: Option<Reg>,
    /// Register multiplying the material's `emission` per channel (clamped at 0), if any.
    pub emission: Option<Reg>,
}

impl MaterialGraph {
    /// Whether evaluating the material at a point runs the program beyond the bump height
    /// (bound parameters, a normal map, an object-space normal or an emission texture).
    pub fn runs_at_hits(&self) -> bool {
        !self.bindings.is_empty()
            || self.normal_map.is_some()
            || self.object_normal.is_some()
            || self.emission.is_some()
    }
}

/// Fractal parameters of a noise node, shared by fBm and turbulence
/// (`shading::texture::noise`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fractal {
    /// Base frequency (cycles per unit of the input point).
    pub frequency: f32,
    /// Octaves, clamped to `1..=12`.
    pub octaves: u32,
    /// Frequency multiplier per octave.
    pub lacunarity: f32,
    /// Amplitude multiplier per octave.
    pub gain: f32,
    /// Seed: different seeds give unrelated patterns.
    pub seed: u64,
}

/// A colour space a conversion node reads or writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColourSpace {
    /// Linear red, green, blue.
    Rgb,
    /// Hue, saturation, value.
    Hsv,
    /// Hue, saturation, lightness.
    Hsl,
}

/// What happens outside `[0, 1)` along one texture axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Wrap {
    /// The image tiles the axis.
    Repeat,
    /// Coordinates are clamped: edge texels extend outward.
    Clamp,
    /// The image tiles the axis mirrored every other period (glTF's `MIRRORED_REPEAT`):
    /// `u ∈ [1, 2)` reads `2 − u`, `u ∈ [−1, 0)` reads `−u`; continuous at whole numbers.
    Mirror,
}

/// The wrap of each texture axis: `u` across the image (its columns), `v` up it (its rows).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct UvWrap {
    /// Along u.
    pub u: Wrap,
    /// Along v.
    pub v: Wrap,
}

impl UvWrap {
    /// The same wrap on both axes.
    pub const fn both(wrap: Wrap) -> Self {
        Self { u: wrap, v: wrap }
    }
}

impl From<Wrap> for UvWrap {
    fn from(wrap: Wrap) -> Self {
        Self::both(wrap)
    }
}

/// A decoded texture.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// Width in texels (≥ 1).
    pub width: u32,
    /// Height in texels (≥ 1).
    pub height: u32,
    /// Linear RGB texels, row `y` = 0 at v = 0, `texels[y·width + x]`.
    pub texels: Vec<Vec3>,
    /// Alpha of each texel, in the order of `texels`; empty when the image has no alpha
    /// channel (alpha 1 everywhere).
    pub alpha: Vec<f32>,
    /// Wrap mode of each axis.
    pub wrap: UvWrap,
}

//! The RON form of shader graphs (`*Desc`): node trees bound to material parameters, bump
//! maps, and phenomena (named graphs with interface parameters). Checked and compiled by
//! [`super::nodes`]; documented in `docs/scene-format.md` ("Shader graphs").

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::desc_values::V3;
use super::unique_keys::deserialize as unique;

/// The `bind` key of a material's emission (a colour or scalar node multiplying the
/// constant `emission`), next to the shader's parameters.
pub const EMISSION: &str = "emission";

/// A node input: a number, a colour `(r, g, b)` or a node.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(untagged)]
pub enum InputDesc {
    /// A constant number (a scalar; fed to a colour input it fills all three channels).
    Number(f64),
    /// A constant colour.
    Colour(V3),
    /// A node.
    Node(Box<NodeDesc>),
    /// Anything else: kept so the loader can report it at its position with a suggestion.
    Invalid(ron::Value),
}

impl InputDesc {
    fn node(n: NodeDesc) -> Self {
        InputDesc::Node(Box::new(n))
    }
}

fn uv() -> InputDesc {
    InputDesc::node(NodeDesc::Uv)
}
fn position() -> InputDesc {
    InputDesc::node(NodeDesc::Position)
}
fn num(x: f64) -> InputDesc {
    InputDesc::Number(x)
}
fn one() -> InputDesc {
    num(1.0)
}
fn zero() -> InputDesc {
    num(0.0)
}
fn two() -> InputDesc {
    num(2.0)
}
fn ten() -> InputDesc {
    num(10.0)
}
fn radius() -> InputDesc {
    num(0.4)
}
fn blue() -> InputDesc {
    InputDesc::Colour((0.0, 0.0, 1.0))
}
fn red() -> InputDesc {
    InputDesc::Colour((1.0, 0.0, 0.0))
}
fn centre() -> (f64, f64) {
    (0.5, 0.5)
}
fn one_f() -> f64 {
    1.0
}
fn two_f() -> f64 {
    2.0
}
fn half_f() -> f64 {
    0.5
}
fn four() -> u32 {
    4
}
fn four_steps() -> InputDesc {
    num(4.0)
}
fn stair_fuzz() -> InputDesc {
    num(0.05)
}

/// A shader node.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Node", deny_unknown_fields)]
pub enum NodeDesc {
    /// Texture coordinates `(u, v, 0)` (colour).
    Uv,
    /// Object-space position (colour).
    Position,
    /// World-space shading normal (colour).
    Normal,
    /// The mesh's interpolated vertex colour (colour, linear; white for meshes without
    /// vertex colours).
    VertexColor,
    /// Checkerboard over uv: `a` on even squares, `b` on odd ones.
    Checker {
        /// Coordinates, default `Uv`.
        #[serde(default = "uv")]
        uv: InputDesc,
        /// Squares per unit of u and v (scalar), default 2.
        #[serde(default = "two")]
        scale: InputDesc,
        /// Even squares, default 1.
        #[serde(default = "one")]
        a: InputDesc,
        /// Odd squares, default 0.
        #[serde(default = "zero")]
        b: InputDesc,
    },
    /// The seed's disk with a soft edge.
    Disk {
        /// Coordinates, default `Uv`.
        #[serde(default = "uv")]
        uv: InputDesc,
        /// Centre in uv, default `(0.5, 0.5)`.
        #[serde(default = "centre")]
        center: (f64, f64),
        /// Radius (scalar), default 0.4.
        #[serde(default = "radius")]
        radius: InputDesc,
        /// Half-width of the soft edge (scalar), default 0.
        #[serde(default = "zero")]
        fuzz: InputDesc,
        /// Inside, default `(0, 0, 1)`.
        #[serde(default = "blue")]
        inside: InputDesc,
        /// Outside, default `(1, 0, 0)`.
        #[serde(default = "red")]
        outside: InputDesc,
    },
    /// The tutorial's stairs over v (seed 001 §4.2): how much of a step's tread (`up`)
    /// rather than its riser (`front`) shades the point, 0…1 (scalar), with the printed
    /// linear blend of half-width `fuzz` (in steps) around each edge.
    Steps {
        /// Coordinates (v read), default `Uv`.
        #[serde(default = "uv")]
        uv: InputDesc,
        /// Steps per unit of v (scalar), default 4.
        #[serde(default = "four_steps")]
        steps: InputDesc,
        /// Half-width of the blend at each edge, in steps (scalar), default 0.05.
        #[serde(default = "stair_fuzz")]
        fuzz: InputDesc,
    },
    /// Repeated coordinates `(mod(u·scale, 1), mod(v·scale, 1), 0)` (colour).
    Repeat {
        /// Coordinates, default `Uv`.
        #[serde(default = "uv")]
        uv: InputDesc,
        /// Repetitions per unit (scalar), default 10.
        #[serde(default = "ten")]
        scale: InputDesc,
    },
    /// One octave of Perlin noise (scalar, about [−1, 1]).
    Noise {
        /// Point, default `Position`.
        #[serde(default = "position")]
        p: InputDesc,
        /// Frequency, default 1.
        #[serde(default = "one_f")]
        frequency: f64,
        /// Seed, default 0.
        #[serde(default)]
        seed: u64,
    },
    /// Fractal Brownian motion (scalar, signed).
    Fbm {
        /// Point, default `Position`.
        #[serde(default = "position")]
        p: InputDesc,
        /// Base frequency, default 1.
        #[serde(default = "one_f")]
        frequency: f64,
        /// Octaves, default 4, in 1…12.
        #[serde(default = "four")]
        octaves: u32,
        /// Frequency multiplier per octave, default 2.
        #[serde(default = "two_f")]
        lacunarity: f64,
        /// Amplitude multiplier per octave, default 0.5.
        #[serde(default = "half_f")]
        gain: f64,
        /// Seed, default 0.
        #[serde(default)]
        seed: u64,
    },
    /// Turbulence (scalar, ≥ 0).
    Turbulence {
        /// Point, default `Position`.
        #[serde(default = "position")]
        p: InputDesc,
        /// Base frequency, default 1.
        #[serde(default = "one_f")]
        frequency: f64,
        /// Octaves, default 4, in 1…12.
        #[serde(default = "four")]
        octaves: u32,
        /// Frequency multiplier per octave, default 2.
        #[serde(default = "two_f")]
        lacunarity: f64,
        /// Amplitude multiplier per octave, default 0.5.
        #[serde(default = "half_f")]
        gain: f64,
        /// Seed, default 0.
        #[serde(default)]
        seed: u64,
    },
    /// An image file at uv (colour).
    Image {
        /// PNG or EXR file, relative to the declaring scene file.
        file: String,
        /// Coordinates, default `Uv`.
        #[serde(default = "uv")]
        uv: InputDesc,
        /// `Repeat` (default), `Clamp`, `Mirror` or `PerAxis(u: …, v: …)`.
        #[serde(default)]
        wrap: WrapDesc,
        /// `Srgb` or `Linear`; default sRGB for PNG, linear for EXR.
        #[serde(default)]
        color_space: Option<EncodingDesc>,
    },
    /// The alpha channel of an image file at uv (scalar; 1 for images without alpha).
    Alpha {
        /// PNG or EXR file, relative to the declaring scene file.
        file: String,
        /// Coordinates, default `Uv`.
        #[serde(default = "uv")]
        uv: InputDesc,
        /// `Repeat` (default), `Clamp`, `Mirror` or `PerAxis(u: …, v: …)`.
        #[serde(default)]
        wrap: WrapDesc,
    },
    /// `a·(1 − t) + b·t`.
    Mix {
        /// Value at t = 0.
        a: InputDesc,
        /// Value at t = 1.
        b: InputDesc,
        /// Blend (scalar).
        t: InputDesc,
    },
    /// `smoothstep(edge0, edge1, x)` (scalar).
    Smoothstep {
        /// Lower edge.
        edge0: InputDesc,
        /// Upper edge.
        edge1: InputDesc,
        /// Input.
        x: InputDesc,
    },
    /// `a + b`.
    Add(InputDesc, InputDesc),
    /// `a − b`.
    Sub(InputDesc, InputDesc),
    /// `a · b` per channel.
    Mul(InputDesc, InputDesc),
    /// Channel 0, 1 or 2 of a colour (scalar).
    Channel(InputDesc, u32),
    /// Rec. 709 luminance of a colour (scalar).
    Luminance(InputDesc),
    /// A colour from three scalars.
    Combine(InputDesc, InputDesc, InputDesc),
    /// Colour-space conversion (colour).
    Convert {
        /// The colour.
        input: InputDesc,
        /// Space it is in, default `Rgb`.
        #[serde(default)]
        from: ColourSpaceDesc,
        /// Space to convert to, default `Rgb`.
        #[serde(default)]
        to: ColourSpaceDesc,
    },
    /// A phenomenon with arguments for some of its interface parameters.
    Graph(
        String,
        #[serde(default, deserialize_with = "unique")] BTreeMap<String, InputDesc>,
    ),
    /// An interface parameter of the enclosing phenomenon.
    Param(String),
}

/// Names of every node, for suggestions.
pub const NODE_NAMES: &[&str] = &[
    "Uv",
    "Position",
    "Normal",
    "VertexColor",
    "Checker",
    "Disk",
    "Steps",
    "Repeat",
    "Noise",
    "Fbm",
    "Turbulence",
    "Image",
    "Alpha",
    "Mix",
    "Smoothstep",
    "Add",
    "Sub",
    "Mul",
    "Channel",
    "Luminance",
    "Combine",
    "Convert",
    "Graph",
    "Param",
];

/// Image wrap mode: one for both axes (`wrap: Mirror`), or one per axis
/// (`wrap: PerAxis(u: Mirror, v: Clamp)`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Wrap", deny_unknown_fields)]
pub enum WrapDesc {
    /// Tile.
    #[default]
    Repeat,
    /// Extend the edge texels.
    Clamp,
    /// Tile, mirrored every other period (glTF's `MIRRORED_REPEAT`).
    Mirror,
    /// A wrap per axis.
    PerAxis {
        /// Along u (across the image), default `Repeat`.
        #[serde(default)]
        u: AxisWrapDesc,
        /// Along v (up the image), default `Repeat`.
        #[serde(default)]
        v: AxisWrapDesc,
    },
}

impl WrapDesc {
    /// The wrap of the u and the v axis.
    pub fn axes(self) -> (AxisWrapDesc, AxisWrapDesc) {
        let both = |a| (a, a);
        match self {
            WrapDesc::Repeat => both(AxisWrapDesc::Repeat),
            WrapDesc::Clamp => both(AxisWrapDesc::Clamp),
            WrapDesc::Mirror => both(AxisWrapDesc::Mirror),
            WrapDesc::PerAxis { u, v } => (u, v),
        }
    }

    /// The description of wrapping u and v so: one mode when they agree, else `PerAxis`.
    pub fn from_axes(u: AxisWrapDesc, v: AxisWrapDesc) -> Self {
        match (u, v) {
            (AxisWrapDesc::Repeat, AxisWrapDesc::Repeat) => WrapDesc::Repeat,
            (AxisWrapDesc::Clamp, AxisWrapDesc::Clamp) => WrapDesc::Clamp,
            (AxisWrapDesc::Mirror, AxisWrapDesc::Mirror) => WrapDesc::Mirror,
            (u, v) => WrapDesc::PerAxis { u, v },
        }
    }
}

/// The wrap of one image axis in `PerAxis(u: …, v: …)`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Deserialize, Serialize)]
#[serde(rename = "AxisWrap")]
pub enum AxisWrapDesc {
    /// Tile.
    #[default]
    Repeat,
    /// Extend the edge texel.
    Clamp,
    /// Tile, mirrored every other period.
    Mirror,
}

/// How an image's numbers are encoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "ColorSpace")]
pub enum EncodingDesc {
    /// sRGB curve.
    Srgb,
    /// Linear.
    Linear,
}

/// A colour space of `Convert`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Space")]
pub enum ColourSpaceDesc {
    /// Red, green, blue.
    #[default]
    Rgb,
    /// Hue, saturation, value (hue in [0, 1)).
    Hsv,
    /// Hue, saturation, lightness (hue in [0, 1)).
    Hsl,
}

/// `bump: (...)` on a material: a height map, a tangent-space normal map or an object-space
/// normal (one of the three).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Bump", deny_unknown_fields)]
pub struct BumpDesc {
    /// Height along the normal (scalar node), object units before `scale`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<InputDesc>,
    /// Tangent-space normal map (colour node, e.g. a linear `Image`): the texel `c` is the
    /// normal `(2c − 1)·(scale, scale, 1)` in the frame (∂P/∂u, bitangent, normal).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal_map: Option<InputDesc>,
    /// Object-space shading normal (colour node, e.g. `Mix` of two directions): transformed
    /// like the object's normals, normalised and turned onto the side being shaded — the
    /// RenderMan `ntransform("object", "current", …)` of a shader that sets its own `Nf`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub object_normal: Option<InputDesc>,
    /// Multiplier of the height, or of the normal map's tangential part; default 1 (must
    /// be 1 with an `object_normal`).
    #[serde(default = "one_f")]
    pub scale: f64,
}

/// `phenomena: [(...)]`: a named graph with interface parameters.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Phenomenon", deny_unknown_fields)]
pub struct PhenomenonDesc {
    /// Unique phenomenon name.
    pub name: String,
    /// Interface parameters and their defaults (the default fixes the type: a number is a
    /// scalar, `(r, g, b)` a colour), default none.
    #[serde(default, deserialize_with = "unique")]
    pub params: BTreeMap<String, InputDesc>,
    /// The graph's result.
    pub output: InputDesc,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> InputDesc {
        ron::Options::default()
            .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
            .from_str(text)
            .unwrap()
    }

    #[test]
    fn inputs_parse_as_numbers_colours_and_nodes() {
        assert!(matches!(parse("8"), InputDesc::Number(x) if x == 8.0));
        assert!(matches!(parse("(0.9, 0.9, 1)"), InputDesc::Colour(_)));
        assert!(matches!(parse("Uv"), InputDesc::Node(n) if matches!(*n, NodeDesc::Uv)));
        let InputDesc::Node(n) = parse("Checker(scale: 8, a: (0.9, 0.9, 0.9), b: Fbm(seed: 3))")
        else {
            panic!()
        };
        let NodeDesc::Checker { scale, a, b, .. } = *n else {
            panic!()
        };
        assert!(matches!(scale, InputDesc::Number(x) if x == 8.0));
        assert!(matches!(a, InputDesc::Colour(_)));
        assert!(matches!(b, InputDesc::Node(_)));
        let InputDesc::Node(n) = parse(r#"Graph("marble", {"vein": (1, 0, 0), "scale": 3})"#)
        else {
            panic!()
        };
        assert!(
            matches!(*n, NodeDesc::Graph(ref name, ref args) if name == "marble" && args.len() == 2)
        );
        assert!(matches!(parse("Add(Uv, 1)"), InputDesc::Node(_)));
    }

    #[test]
    fn unknown_nodes_are_kept_for_the_loader() {
        assert!(matches!(parse("Chekcer(scale: 8)"), InputDesc::Invalid(_)));
        assert!(matches!(parse("Checker(scael: 8)"), InputDesc::Invalid(_)));
        assert!(matches!(parse("\"text\""), InputDesc::Invalid(_)));
        // Nodes with every field defaulted land here too; the loader re-parses them.
        assert!(matches!(parse("Fbm()"), InputDesc::Invalid(_)));
        assert!(matches!(parse("Checker"), InputDesc::Invalid(_)));
    }

    fn image_wrap(text: &str) -> WrapDesc {
        let InputDesc::Node(n) = parse(text) else {
            panic!("{text}")
        };
        let NodeDesc::Image { wrap, .. } = *n else {
            panic!("{text}")
        };
        wrap
    }

    #[test]
    fn wraps_parse_for_both_axes_or_per_axis_and_write_back_as_read() {
        use AxisWrapDesc as A;
        assert_eq!(image_wrap(r#"Image(file: "t.png")"#), WrapDesc::Repeat);
        assert_eq!(
            image_wrap(r#"Image(file: "t.png", wrap: Mirror)"#),
            WrapDesc::Mirror
        );
        assert_eq!(WrapDesc::Mirror.axes(), (A::Mirror, A::Mirror));
        let per_axis = WrapDesc::PerAxis {
            u: A::Mirror,
            v: A::Clamp,
        };
        assert_eq!(
            image_wrap(r#"Image(file: "t.png", wrap: PerAxis(u: Mirror, v: Clamp))"#),
            per_axis
        );
        // An axis left out repeats.
        assert_eq!(
            image_wrap(r#"Image(file: "t.png", wrap: PerAxis(v: Clamp))"#).axes(),
            (A::Repeat, A::Clamp)
        );
        // One mode where the axes agree.
        assert_eq!(WrapDesc::from_axes(A::Clamp, A::Clamp), WrapDesc::Clamp);
        assert_eq!(WrapDesc::from_axes(A::Mirror, A::Clamp), per_axis);
        // `convert` writes what the reader reads back.
        for wrap in [WrapDesc::Clamp, WrapDesc::Mirror, per_axis] {
            let text = ron::ser::to_string_pretty(
                &wrap,
                ron::ser::PrettyConfig::default().struct_names(true),
            )
            .unwrap();
            assert_eq!(ron::from_str::<WrapDesc>(&text).unwrap(), wrap, "{text}");
        }
    }
}

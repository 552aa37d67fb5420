//! The RIB graphics state: the current transformation and the attributes that primitives
//! and lights pick up, with the `AttributeBegin`/`TransformBegin` stacks.
//!
//! Matrices are column-vector matrices (`p' = M·p`). RenderMan concatenates a new
//! transformation so that it applies to points first: `Translate`, `Rotate`, `Scale` and
//! `ConcatTransform` all give `ctm = ctm · T`. `ConcatTransform` and `Transform` take the
//! 16 numbers of RenderMan's row-vector matrix, whose transpose is `T`.

use glam::{DMat4, DVec3};

use super::super::located::Pos;
use super::atmosphere::RiFog;
use super::params::Param;
use crate::scene::desc::{BasisDesc, V3};

/// A shader named by `Surface`, `Displacement`, `LightSource`, … with its parameters.
#[derive(Debug, Clone)]
pub struct ShaderCall {
    /// Shader name.
    pub name: String,
    /// Where the request is.
    pub pos: Pos,
    /// Index of the file the request is in.
    pub file: usize,
    /// Its parameters.
    pub params: Vec<Param>,
}

/// One direction's patch basis (`Basis`): one of ours and its step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BasisState {
    /// The basis.
    pub basis: BasisDesc,
    /// The step between patches.
    pub step: usize,
    /// Where `Basis` set it.
    pub pos: Option<Pos>,
}

impl Default for BasisState {
    fn default() -> Self {
        Self {
            basis: BasisDesc::Bezier,
            step: 3,
            pos: None,
        }
    }
}

/// The attributes (RI spec 3.2 defaults).
#[derive(Debug, Clone)]
pub struct Attributes {
    /// Current transformation: object → world inside the world block, current → camera
    /// before it.
    pub ctm: DMat4,
    /// `Color`, default white.
    pub color: V3,
    /// `Opacity`, default opaque.
    pub opacity: V3,
    /// `Surface`, default `defaultsurface`.
    pub surface: Option<ShaderCall>,
    /// `Displacement`, default none.
    pub displacement: Option<ShaderCall>,
    /// `AreaLightSource` in effect, default none.
    pub area_light: Option<ShaderCall>,
    /// The area light (see [`super::area_lights`]) whose surfaces the primitives that
    /// follow are.
    pub area_light_id: Option<usize>,
    /// Area lights switched off by `Illuminate handle 0` for the primitives that follow.
    pub area_lights_off: Vec<usize>,
    /// `Sides`, default 2.
    pub sides: u32,
    /// Whether the current orientation differs from the handedness of the current
    /// coordinate system (primitives are inside out), default false (`Orientation
    /// "outside"`). No transformation changes it (see [`super::orientation`]).
    pub inside_out: bool,
    /// `Attribute "render" "truedisplacement"`, default off (bump).
    pub true_displacement: bool,
    /// `Attribute "displacementbound" "sphere"` and where it was written.
    pub displacement_bound: Option<(f64, Pos)>,
    /// `Attribute "identifier" "name"`.
    pub name: Option<String>,
    /// `ShadingRate` and where, when written.
    pub shading_rate: Option<(f64, Pos)>,
    /// `Basis` in u and v.
    pub basis: (BasisState, BasisState),
    /// `Attribute "light" "shadows"`: whether lights declared from here cast shadows.
    pub light_shadows: bool,
    /// Lights switched off by `Illuminate handle 0`, or declared inside an attribute block
    /// that has ended (indices into the light list).
    pub lights_off: Vec<usize>,
    /// How many lights were declared when these attributes were current: the lights
    /// declared later inside a block are off once it ends (the light list is an attribute).
    pub lights_known: usize,
    /// AIR's caustic attributes of the primitives that follow.
    pub caustic: CausticAttributes,
    /// `Atmosphere "fog"`, default none.
    pub atmosphere: Option<RiFog>,
}

/// AIR's `Attribute "caustic" …` of a primitive, each with where it was written.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CausticAttributes {
    /// `"color specularcolor"`: the reflected fraction of a photon's power.
    pub specular: Option<(V3, Pos)>,
    /// `"color refractioncolor"`: the refracted fraction.
    pub refraction: Option<(V3, Pos)>,
    /// `"float refractionindex"`.
    pub ior: Option<(f64, Pos)>,
    /// `"integer ngather"`: the primitive receives caustics.
    pub ngather: Option<Pos>,
}

impl CausticAttributes {
    /// Whether any photon attribute (the colours, the index) is written.
    pub fn shapes_photons(&self) -> bool {
        self.specular.is_some() || self.refraction.is_some() || self.ior.is_some()
    }

    /// The primitive's caustic flag (mental ray's `caustic`: 1 casts, 2 receives): it casts
    /// where a colour is not black, receives where `ngather` is written.
    pub fn flag(&self) -> u8 {
        let lit = |c: Option<(V3, Pos)>| c.is_some_and(|((r, g, b), _)| r.max(g).max(b) > 0.0);
        u8::from(lit(self.specular) || lit(self.refraction))
            | (u8::from(self.ngather.is_some()) << 1)
    }
}

impl Default for Attributes {
    fn default() -> Self {
        Self {
            ctm: DMat4::IDENTITY,
            color: (1.0, 1.0, 1.0),
            opacity: (1.0, 1.0, 1.0),
            surface: None,
            displacement: None,
            area_light: None,
            area_light_id: None,
            area_lights_off: Vec::new(),
            sides: 2,
            inside_out: false,
            true_displacement: false,
            displacement_bound: None,
            name: None,
            shading_rate: None,
            basis: (BasisState::default(), BasisState::default()),
            light_shadows: false,
            lights_off: Vec::new(),
            lights_known: 0,
            caustic: CausticAttributes::default(),
            atmosphere: None,
        }
    }
}

/// What an entry of the block stack opened.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Block {
    /// `FrameBegin`.
    Frame,
    /// `WorldBegin`.
    World,
    /// `AttributeBegin`.
    Attribute,
    /// `TransformBegin`.
    Transform,
    /// `ObjectBegin`: an object definition, with attributes of its own.
    Object,
}

impl Block {
    /// The request that opens it.
    pub fn begin(self) -> &'static str {
        match self {
            Block::Frame => "FrameBegin",
            Block::World => "WorldBegin",
            Block::Attribute => "AttributeBegin",
            Block::Transform => "TransformBegin",
            Block::Object => "ObjectBegin",
        }
    }

    /// The request that closes it.
    pub fn end(self) -> &'static str {
        match self {
            Block::Frame => "FrameEnd",
            Block::World => "WorldEnd",
            Block::Attribute => "AttributeEnd",
            Block::Transform => "TransformEnd",
            Block::Object => "ObjectEnd",
        }
    }
}

/// The attribute state and the block stack.
#[derive(Debug, Clone, Default)]
pub struct GraphicsState {
    /// Current attributes.
    pub attrs: Attributes,
    /// Open blocks with what they saved.
    stack: Vec<(Block, Pos, Attributes)>,
}

impl GraphicsState {
    /// Opens a block, saving the attributes (a transform block restores only the
    /// transformation).
    pub fn begin(&mut self, block: Block, pos: Pos) {
        self.stack.push((block, pos, self.attrs.clone()));
    }

    /// Closes the innermost block, which must be `block`. `Err` names what is open
    /// instead (and where) — the blocks inside `block` are then closed with it — or that
    /// `block` is not open at all (nothing is closed). A block opened outside an object
    /// definition is not closed from inside it.
    pub fn end(&mut self, block: Block) -> Result<(), String> {
        let Some(at) = self.stack.iter().rposition(|(b, _, _)| *b == block) else {
            return Err(format!("{} without {}", block.end(), block.begin()));
        };
        if let Some((_, pos, _)) = self.stack[at + 1..]
            .iter()
            .rev()
            .find(|(b, _, _)| *b == Block::Object)
        {
            return Err(format!(
                "{} inside the object definition opened by ObjectBegin at {}:{}",
                block.end(),
                pos.line,
                pos.column
            ));
        }
        let inner = (at + 1 < self.stack.len()).then(|| {
            let (b, pos, _) = &self.stack[self.stack.len() - 1];
            format!(
                "{} closes a block opened by {} at {}:{}",
                block.end(),
                b.begin(),
                pos.line,
                pos.column
            )
        });
        let Some((_, _, saved)) = self.stack.drain(at..).next() else {
            unreachable!("`at` indexes the stack");
        };
        if block == Block::Transform {
            self.attrs.ctm = saved.ctm;
        } else {
            self.attrs = saved;
        }
        inner.map_or(Ok(()), Err)
    }

    /// Blocks still open (innermost last).
    pub fn open(&self) -> impl Iterator<Item = (Block, Pos)> + '_ {
        self.stack.iter().map(|(b, p, _)| (*b, *p))
    }

    /// Whether `block` is open.
    pub fn inside(&self, block: Block) -> bool {
        self.stack.iter().any(|(b, _, _)| *b == block)
    }

    /// `ctm = ctm · t`.
    pub fn concat(&mut self, t: DMat4) {
        self.attrs.ctm *= t;
    }
}

/// `Rotate angle dx dy dz`: `angle` degrees about the axis (`None` for a zero axis).
pub fn rotate(degrees: f64, axis: DVec3) -> Option<DMat4> {
    let len = axis.length();
    (len > 0.0 && len.is_finite()).then(|| DMat4::from_axis_angle(axis / len, degrees.to_radians()))
}

/// The column-vector matrix of RenderMan's 16 row-vector matrix numbers.
pub fn from_rib(m: &[f64]) -> DMat4 {
    // The numbers, read row by row, are the columns of the column-vector matrix.
    let mut a = [0.0; 16];
    a.copy_from_slice(&m[..16]);
    DMat4::from_cols_array(&a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn concatenation_applies_the_newest_transform_first() {
        let mut g = GraphicsState::default();
        g.concat(DMat4::from_translation(DVec3::new(0.0, 0.0, 5.0)));
        g.concat(rotate(90.0, DVec3::X).unwrap());
        // (0, 1, 0) rotates to (0, 0, 1), then moves to (0, 0, 6).
        let p = g.attrs.ctm.transform_point3(DVec3::Y);
        assert!((p - DVec3::new(0.0, 0.0, 6.0)).length() < 1e-12, "{p}");
    }

    #[test]
    fn rib_matrices_are_row_vector_matrices() {
        // Translation by (1, 2, 3) is written with the translation in the last row.
        let m = from_rib(&[
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 2.0, 3.0, 1.0,
        ]);
        assert_eq!(m.transform_point3(DVec3::ZERO), DVec3::new(1.0, 2.0, 3.0));
    }

    #[test]
    fn blocks_restore_what_they_saved() {
        let mut g = GraphicsState::default();
        let p = Pos { line: 3, column: 1 };
        g.begin(Block::Attribute, p);
        g.attrs.color = (1.0, 0.0, 0.0);
        g.begin(Block::Transform, p);
        g.attrs.color = (0.0, 1.0, 0.0);
        g.concat(DMat4::from_scale(DVec3::splat(2.0)));
        assert_eq!(
            g.end(Block::Attribute).unwrap_err(),
            "AttributeEnd closes a block opened by TransformBegin at 3:1"
        );
        // The mismatched AttributeEnd closed the inner TransformBegin with it and restored
        // what AttributeBegin saved.
        assert_eq!(g.attrs.ctm, DMat4::IDENTITY);
        assert_eq!(g.attrs.color, (1.0, 1.0, 1.0));
        assert_eq!(
            g.end(Block::Transform).unwrap_err(),
            "TransformEnd without TransformBegin"
        );
        g.begin(Block::Attribute, p);
        g.begin(Block::Transform, p);
        g.attrs.color = (0.0, 0.0, 1.0);
        g.concat(DMat4::from_scale(DVec3::splat(2.0)));
        g.end(Block::Transform).unwrap();
        assert_eq!(
            g.attrs.ctm,
            DMat4::IDENTITY,
            "TransformEnd restores the transform"
        );
        assert_eq!(g.attrs.color, (0.0, 0.0, 1.0), "but keeps the attributes");
        g.end(Block::Attribute).unwrap();
        assert_eq!(g.attrs.color, (1.0, 1.0, 1.0));
        assert_eq!(
            g.end(Block::World).unwrap_err(),
            "WorldEnd without WorldBegin"
        );
    }
}

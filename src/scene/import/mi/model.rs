//! The scene as the statements wrote it, before the instance tree is resolved: one record
//! per `options`, `camera`, `light`, `material`, `object`, `instance`, `instgroup`, named
//! `shader` and `declare phenomenon`, each with where it was written.

use std::collections::HashMap;

use super::super::located::Located;
use super::cursor::ShaderCall;
use super::value_positions::ValuePositions;
use crate::scene::desc::{
    ApproximationDesc, EnvironmentDesc, MaterialDesc, OptionsDesc, OutputDesc, V3,
};

/// Camera space (mental ray's default: instance transformations have no effect) or object
/// space.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Space {
    /// Geometry is given in camera space.
    Camera,
    /// Geometry is placed by instances.
    Object,
}

/// An `options` block.
#[derive(Debug, Clone)]
pub struct RawOptions {
    /// Where the block starts.
    pub at: Located,
    /// What maps onto the description's options.
    pub desc: OptionsDesc,
    /// `object space` / `camera space`.
    pub space: Space,
    /// `shadow off` turns every light's shadows off.
    pub shadows: bool,
    /// Where its values were written (below `options`).
    pub values: ValuePositions,
}

/// A `camera` block.
#[derive(Debug, Clone)]
pub struct RawCamera {
    /// Where the block starts.
    pub at: Located,
    /// Vertical field of view, degrees.
    pub fov_y: f64,
    /// `resolution w h`.
    pub resolution: (u32, u32),
    /// `aspect`, when written.
    pub aspect: Option<f64>,
    /// `output` statements.
    pub outputs: Vec<OutputDesc>,
    /// `environment` shader, mapped.
    pub environment: Option<EnvironmentDesc>,
    /// `frame N`: the frame number (0 when not written).
    pub frame: f64,
    /// `volume` shader, mapped: the camera's atmosphere.
    pub atmosphere: Option<crate::scene::desc::VolumeDesc>,
    /// Where its values were written (below `cameras[i]`).
    pub values: ValuePositions,
}

/// `contour_shader_framefade`: colour and width from the frame number, resolved against
/// the render camera's `frame` when the scene is assembled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameFade {
    /// Frame of the first values.
    pub frame1: f64,
    /// Frame of the second values.
    pub frame2: f64,
    /// Colour at `frame1` and before.
    pub color1: (f64, f64, f64, f64),
    /// Colour at `frame2` and after.
    pub color2: (f64, f64, f64, f64),
    /// Width at `frame1` and before, percent.
    pub width1: f64,
    /// Width at `frame2` and after, percent.
    pub width2: f64,
}

/// What a light shader made of its parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightModel {
    /// `mib_light_point`, `physical_light` without direction: a point.
    Point,
    /// A spot: needs `direction` and `spread`; `cone` the inner cosine (penumbra start).
    Spot {
        /// Cosine of the angle where the falloff starts (`cone`), if written.
        cone: Option<f64>,
    },
    /// `mib_light_infinite`, `physical_light` with only a direction: distant.
    Infinite,
}

/// An area light shape, in the light's object space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AreaShape {
    /// `rectangle ex ey ez  fx fy fz`: edges from a corner at `origin − (e+f)/2`.
    Rectangle(V3, V3),
    /// `disc nx ny nz r`.
    Disc(V3, f64),
    /// `sphere r`.
    Sphere(f64),
    /// `cylinder ax ay az r`: axis from `origin − a/2` to `origin + a/2`.
    Cylinder(V3, f64),
}

/// A `light` block.
#[derive(Debug, Clone)]
pub struct RawLight {
    /// Where the block starts.
    pub at: Located,
    /// What the shader is.
    pub model: LightModel,
    /// Colour (linear RGB), already scaled as the shader's semantics ask.
    pub color: V3,
    /// Whether it casts shadows.
    pub shadows: bool,
    /// The fraction of the light that passes occluders (`factor`, 0 when shadows are off).
    pub shadow_factor: f64,
    /// Whether the inverse-square law applies (`physical_light`) or not (`mib_light_*`).
    pub inverse_square: bool,
    /// `atten` with `start`/`stop`.
    pub attenuation: Option<(f64, f64)>,
    /// `origin`.
    pub origin: Option<V3>,
    /// `direction`.
    pub direction: Option<V3>,
    /// `spread` (cosine of the outer cone).
    pub spread: Option<f64>,
    /// Area shape and its `(u, v)` samples.
    pub area: Option<(AreaShape, u32)>,
    /// `visible`.
    pub visible: bool,
    /// `energy r g b`: photon power, W (photons only).
    pub energy: Option<V3>,
    /// `caustic photons N`.
    pub caustic_photons: Option<u32>,
    /// `globillum photons N`.
    pub globillum_photons: Option<u32>,
    /// Where its values were written (below `lights[i]`).
    pub values: ValuePositions,
}

/// A `material` block.
#[derive(Debug, Clone)]
pub struct RawMaterial {
    /// Where the block starts.
    pub at: Located,
    /// The material, without its light list.
    pub desc: MaterialDesc,
    /// `"lights" [...]` of its shader, with where each name was written.
    pub lights: Option<Vec<(String, Located)>>,
    /// `"mode" 2`: the list names the lights to leave out.
    pub exclusive: bool,
    /// A `contour_shader_framefade` contour, made a `Simple` one for the render frame.
    pub frame_fade: Option<FrameFade>,
    /// `displace "myDisplacement" (…)` (the tutorial's library): the displacement of the
    /// objects drawn in this material.
    pub displace: Option<crate::scene::desc::ScalarDesc>,
    /// Where its values were written (below `materials[i]`).
    pub values: ValuePositions,
}

/// One polygon of a group: its material, vertex indices (into the `v` list) and position.
#[derive(Debug, Clone)]
pub struct RawPolygon {
    /// `p "material"`, or the previous polygon's material when omitted.
    pub material: Option<String>,
    /// Vertex indices.
    pub vertices: Vec<u32>,
    /// Where `p` is.
    pub at: Located,
}

/// Visibility flags of an object or instance (`None`: not written, inherited).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Flags {
    /// `visible`.
    pub visible: Option<bool>,
    /// `shadow`.
    pub shadow: Option<bool>,
    /// `trace`.
    pub trace: Option<bool>,
    /// `caustic N`: caustic photon mode 0–3 (none, casts, receives, both).
    pub caustic: Option<u8>,
    /// `globillum N`: global-illumination photon mode 0–3.
    pub globillum: Option<u8>,
    /// `tag [label] N`: the object's label (read on instances too, not used there).
    pub label: Option<u32>,
}

/// An `object` block with its polygon group.
#[derive(Debug, Clone)]
pub struct RawObject {
    /// Where the block starts.
    pub at: Located,
    /// Vertex positions (the `v` list resolved against the vector list).
    pub vertices: Vec<V3>,
    /// Per vertex, its first texture vector (`v i t k`: the x and y of vector `k`).
    pub uvs: Vec<Option<(f64, f64)>>,
    /// Polygons.
    pub polygons: Vec<RawPolygon>,
    /// Free-form surfaces, in file order.
    pub surfaces: Vec<RawSurface>,
    /// The polygons' `approximate` statement: how a displaced object is diced.
    pub approximation: Option<ApproximationDesc>,
    /// Flags.
    pub flags: Flags,
}

/// One direction of a free-form surface, as a NURBS axis.
#[derive(Debug, Clone, PartialEq)]
pub struct RawAxis {
    /// Polynomial degree (1…7).
    pub degree: u32,
    /// Control points along the direction.
    pub count: u32,
    /// `count + degree + 1` knots.
    pub knots: Vec<f64>,
}

/// A `surface` of a group, as a NURBS surface (`docs/mi.md`, *Free-form surfaces*).
#[derive(Debug, Clone)]
pub struct RawSurface {
    /// The surface's name (what `approximate surface` names).
    pub name: String,
    /// Where `surface` is.
    pub at: Located,
    /// Its material, when written.
    pub material: Option<String>,
    /// Where the material name is.
    pub material_at: Option<Located>,
    /// The u direction.
    pub u: RawAxis,
    /// The v direction.
    pub v: RawAxis,
    /// `u.count × v.count` control points `(x, y, z, w)`, u fastest, weight not premultiplied.
    pub points: Vec<(f64, f64, f64, f64)>,
    /// `approximate surface …` naming it.
    pub approximation: Option<ApproximationDesc>,
}

/// An `instance` block.
#[derive(Debug, Clone)]
pub struct RawInstance {
    /// Where the block starts.
    pub at: Located,
    /// The element placed.
    pub of: String,
    /// Where that name is.
    pub of_at: Located,
    /// `transform`: 16 numbers, row by row, world → object with row vectors.
    pub transform: Option<[f64; 16]>,
    /// Where the `transform`'s first number is (errors about the matrix point there).
    pub transform_at: Option<Located>,
    /// `material "m"` override.
    pub material: Option<(String, Located)>,
    /// Flags.
    pub flags: Flags,
}

/// An `instgroup` block.
#[derive(Debug, Clone)]
pub struct RawGroup {
    /// Where the block starts.
    pub at: Located,
    /// Member instance names and where each is written.
    pub members: Vec<(String, Located)>,
}

/// `render "root" "camera" "options"`.
#[derive(Debug, Clone)]
pub struct RawRender {
    /// Where `render` is.
    pub at: Located,
    /// Root instance group.
    pub root: (String, Located),
    /// Camera instance.
    pub camera: (String, Located),
    /// Options block.
    pub options: (String, Located),
}

/// Everything the statements of all files wrote, by name (the first definition of a name
/// wins; a second one is reported, unless it is `incremental`: then it replaces the first).
#[derive(Debug, Clone, Default)]
pub struct RawScene {
    /// `options` blocks.
    pub options: HashMap<String, RawOptions>,
    /// `camera` blocks.
    pub cameras: HashMap<String, RawCamera>,
    /// `light` blocks.
    pub lights: HashMap<String, RawLight>,
    /// `material` blocks, in file order.
    pub materials: Vec<(String, RawMaterial)>,
    /// `object` blocks, in file order.
    pub objects: Vec<(String, RawObject)>,
    /// `instance` blocks, in file order.
    pub instances: Vec<(String, RawInstance)>,
    /// `instgroup` blocks, in file order.
    pub groups: Vec<(String, RawGroup)>,
    /// Named shaders (`shader "n" "type" (…)`) and phenomenon roots, by name.
    pub shaders: HashMap<String, ShaderCall>,
    /// `color|scalar|vector texture "name" "file"`: the file (as written) and where.
    pub textures: HashMap<String, (String, Located)>,
    /// `render`.
    pub render: Option<RawRender>,
    /// `link`ed shader libraries that are built in beyond base, physics and contour (the
    /// tutorial's `myDisplacement`).
    pub linked: Vec<String>,
}

impl RawScene {
    /// Forgets the element `name`, whatever its kind (an `incremental` definition replaces
    /// it).
    pub fn forget(&mut self, name: &str) {
        self.options.remove(name);
        self.cameras.remove(name);
        self.lights.remove(name);
        self.materials.retain(|(n, _)| n != name);
        self.objects.retain(|(n, _)| n != name);
        self.instances.retain(|(n, _)| n != name);
        self.groups.retain(|(n, _)| n != name);
        self.shaders.remove(name);
        self.textures.remove(name);
    }
}

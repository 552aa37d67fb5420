//! Serde types of an object's geometry: its `mesh` (loaded meshes, geometry shaders,
//! parametric surfaces, subdivision meshes, scatters), `approximation` and `displacement`.
//!
//! Like [`super::desc`], these are the file as written: every struct denies unknown fields,
//! every default is documented here and in `docs/scene-format.md`; the checks live in
//! [`super::geometry`]. Field names follow the components of `docs/geometry.md`; the
//! RenderMan spellings (`rmajor`, `thetamax`, …) are accepted as aliases.

use serde::{Deserialize, Serialize};

use super::desc_values::V3;

/// Mesh source of an object.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Mesh", deny_unknown_fields)]
pub enum MeshDesc {
    /// Wavefront OBJ file, relative to the declaring scene file.
    Obj {
        /// Path of the OBJ file.
        file: String,
        /// Only the faces written under `usemtl <name>` (`""`: those before any `usemtl`),
        /// default all faces.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        usemtl: Option<String>,
        /// The scene material of each `usemtl` name's faces (`""`: the faces written before
        /// any `usemtl`), in the order the loader groups the triangles; `""` as material: the
        /// one the instance resolves to. Filled from the OBJ's MTL files by
        /// [`crate::scene::obj_materials`], never read from a scene file.
        #[serde(skip)]
        materials: Option<Vec<(String, String)>>,
    },
    /// PLY file (ASCII or binary), relative to the declaring scene file.
    Ply {
        /// Path of the PLY file.
        file: String,
    },
    /// A mesh of a glTF 2.0 file (`.gltf` or `.glb`), relative to the declaring scene file.
    Gltf {
        /// Path of the glTF file.
        file: String,
        /// The mesh's name (or `"#index"`); default: the file's only mesh.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        mesh: Option<String>,
        /// Only this primitive of the mesh, default all of them.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        primitive: Option<u32>,
    },
    /// Polygons written in the scene.
    Inline {
        /// Vertex positions.
        vertices: Vec<V3>,
        /// Convex polygons as vertex indices (≥ 3 each), fan-triangulated.
        polygons: Vec<Vec<u32>>,
        /// Per-vertex normals (optional).
        #[serde(default)]
        normals: Option<Vec<V3>>,
        /// Per-vertex texture coordinates (optional).
        #[serde(default)]
        uvs: Option<Vec<(f64, f64)>>,
        /// Per-polygon materials (optional): one material name per polygon, `""` for the
        /// material the instance resolves to (its override, else the object's `material`).
        /// A polygon's own material wins over both.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        materials: Option<Vec<String>>,
    },
    /// RenderMan `Sphere radius zmin zmax thetamax`.
    Sphere {
        /// Radius, default 1, > 0.
        #[serde(default = "one")]
        radius: f64,
        /// Lower cut, default `-radius`.
        #[serde(default, alias = "zmin")]
        z_min: Option<f64>,
        /// Upper cut, default `radius`.
        #[serde(default, alias = "zmax")]
        z_max: Option<f64>,
        /// Sweep about +Z, degrees, default 360, in (0, 360].
        #[serde(default = "full_turn", alias = "thetamax")]
        theta_max: f64,
    },
    /// RenderMan `Cylinder radius zmin zmax thetamax` (open tube).
    Cylinder {
        /// Radius, default 1, > 0.
        #[serde(default = "one")]
        radius: f64,
        /// Bottom height, default −1.
        #[serde(default = "minus_one", alias = "zmin")]
        z_min: f64,
        /// Top height, default 1, ≠ `z_min`.
        #[serde(default = "one", alias = "zmax")]
        z_max: f64,
        /// Sweep about +Z, degrees, default 360.
        #[serde(default = "full_turn", alias = "thetamax")]
        theta_max: f64,
    },
    /// RenderMan `Cone height radius thetamax` (base in z = 0, open).
    Cone {
        /// Apex height, default 1, ≠ 0.
        #[serde(default = "one")]
        height: f64,
        /// Base radius, default 1, > 0.
        #[serde(default = "one")]
        radius: f64,
        /// Sweep about +Z, degrees, default 360.
        #[serde(default = "full_turn", alias = "thetamax")]
        theta_max: f64,
    },
    /// RenderMan `Disk height radius thetamax` (faces +Z).
    Disk {
        /// Height of the plane, default 0.
        #[serde(default)]
        height: f64,
        /// Radius, default 1, > 0.
        #[serde(default = "one")]
        radius: f64,
        /// Sweep about +Z, degrees, default 360.
        #[serde(default = "full_turn", alias = "thetamax")]
        theta_max: f64,
    },
    /// RenderMan `Torus rmajor rminor phimin phimax thetamax`.
    Torus {
        /// Distance from the Z axis to the tube centre, default 1, > 0.
        #[serde(default = "one", alias = "rmajor")]
        r_major: f64,
        /// Tube radius, default 0.25, > 0.
        #[serde(default = "quarter", alias = "rminor")]
        r_minor: f64,
        /// Start angle on the tube, degrees, default 0.
        #[serde(default, alias = "phimin")]
        phi_min: f64,
        /// End angle on the tube, degrees, default 360; `0 < phi_max − phi_min ≤ 360`.
        #[serde(default = "full_turn", alias = "phimax")]
        phi_max: f64,
        /// Sweep about +Z, degrees, default 360.
        #[serde(default = "full_turn", alias = "thetamax")]
        theta_max: f64,
    },
    /// The seed's stairs with real geometry.
    Stairs {
        /// Number of steps, default 10 (clamped to 1…100 000).
        #[serde(default = "ten")]
        steps: u32,
        /// Width along X, default 2, > 0.
        #[serde(default = "two")]
        width: f64,
        /// Run along +Y, default 2, > 0.
        #[serde(default = "two")]
        depth: f64,
        /// Rise along +Z, default 2, > 0.
        #[serde(default = "two")]
        height: f64,
        /// Add sides, back and bottom (a closed solid), default false.
        #[serde(default)]
        closed: bool,
    },
    /// A flat grid of quads in z = 0, facing +Z, uvs 0…1.
    Grid {
        /// Size along X, default 1, > 0.
        #[serde(default = "one")]
        size_x: f64,
        /// Size along Y, default 1, > 0.
        #[serde(default = "one")]
        size_y: f64,
        /// Cells along X, default 1 (clamped to 1…16 384).
        #[serde(default = "one_u32")]
        nx: u32,
        /// Cells along Y, default 1 (clamped to 1…16 384).
        #[serde(default = "one_u32")]
        ny: u32,
    },
    /// RenderMan `PatchMesh`: bilinear or bicubic patches over `nu × nv` control points.
    PatchMesh {
        /// Patch type and basis, default `Bilinear`.
        #[serde(default)]
        basis: BasisDesc,
        /// Control points along u.
        nu: u32,
        /// Control points along v.
        nv: u32,
        /// Periodic in u, default false.
        #[serde(default)]
        u_wrap: bool,
        /// Periodic in v, default false.
        #[serde(default)]
        v_wrap: bool,
        /// `nu × nv` control points, u fastest.
        points: Vec<V3>,
        /// User texture coordinates and normals (RenderMan's `s`, `t`, `N`), default none.
        #[serde(default, skip_serializing_if = "SurfaceVariablesDesc::is_empty")]
        variables: SurfaceVariablesDesc,
    },
    /// A NURBS surface (no trimming curves).
    Nurbs {
        /// Degree in u (1…7).
        degree_u: u32,
        /// Degree in v (1…7).
        degree_v: u32,
        /// Control points along u.
        count_u: u32,
        /// Control points along v.
        count_v: u32,
        /// `count_u + degree_u + 1` non-decreasing knots.
        knots_u: Vec<f64>,
        /// `count_v + degree_v + 1` non-decreasing knots.
        knots_v: Vec<f64>,
        /// `count_u × count_v` points `(x, y, z, w)`, u fastest, weight `w > 0`.
        points: Vec<(f64, f64, f64, f64)>,
        /// User texture coordinates and normals (RenderMan's `s`, `t`, `N`), default none.
        #[serde(default, skip_serializing_if = "SurfaceVariablesDesc::is_empty")]
        variables: SurfaceVariablesDesc,
    },
    /// A Catmull-Clark subdivision surface over a polygon control mesh.
    Subdiv {
        /// Control vertices.
        vertices: Vec<V3>,
        /// Faces (≥ 3 indices each), counter-clockwise seen from outside; manifold.
        polygons: Vec<Vec<u32>>,
        /// User texture coordinates and normals (RenderMan's `s`, `t`, `N`), default none.
        #[serde(default, skip_serializing_if = "SurfaceVariablesDesc::is_empty")]
        variables: SurfaceVariablesDesc,
    },
    /// Copies of another object scattered over the mesh of a third.
    Scatter {
        /// Object whose copies are placed.
        prototype: String,
        /// Object whose mesh the copies are scattered over (Obj, Ply, Inline, Grid or Stairs).
        surface: String,
        /// Copies, default 100 (clamped to 10 000 000).
        #[serde(default = "hundred")]
        count: u32,
        /// Seed of the distribution, default 0.
        #[serde(default)]
        seed: u64,
        /// Range `(min, max)` of the uniform scale of each copy, default `(1, 1)`.
        #[serde(default = "unit_range")]
        scale: (f64, f64),
        /// Random rotation about the placement normal, ± degrees, default 180.
        #[serde(default = "half_turn")]
        rotation_jitter: f64,
        /// Rotate the prototype's +Z onto the surface normal, default true.
        #[serde(default = "yes")]
        align_to_normal: bool,
    },
}

/// Values of one variable of a `PatchMesh`, `Nurbs` or `Subdiv` mesh.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Values")]
pub enum SurfaceValuesDesc<T> {
    /// One per control point, interpolated like the positions.
    Control(Vec<T>),
    /// Four per patch (patch meshes, NURBS: u-fastest patches, every NURBS knot span
    /// counted, empty ones too) at its corners (0,0), (1,0), (0,1), (1,1), or one per face
    /// corner (subdivision meshes), interpolated bilinearly (linearly over a face).
    Corners(Vec<T>),
}

/// User texture coordinates and normals of a `PatchMesh`, `Nurbs` or `Subdiv` mesh; one
/// not given keeps the surface's own (its parameters, its geometric normal).
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Variables", deny_unknown_fields)]
pub struct SurfaceVariablesDesc {
    /// Texture coordinate s (the uv's u).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub s: Option<SurfaceValuesDesc<f64>>,
    /// Texture coordinate t (the uv's v).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t: Option<SurfaceValuesDesc<f64>>,
    /// Shading normals.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normals: Option<SurfaceValuesDesc<V3>>,
}

impl SurfaceVariablesDesc {
    /// No variable given.
    pub fn is_empty(&self) -> bool {
        self.s.is_none() && self.t.is_none() && self.normals.is_none()
    }
}

/// Patch type and basis of a `PatchMesh`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Basis")]
pub enum BasisDesc {
    /// Bilinear: 2×2 points per patch.
    #[default]
    Bilinear,
    /// Bicubic Bézier (patches share a row: 3·k + 1 points).
    Bezier,
    /// Bicubic uniform B-spline.
    BSpline,
    /// Bicubic Catmull-Rom.
    CatmullRom,
}

/// `approximation: …` on an object: how finely its surfaces are diced.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Approximation", deny_unknown_fields)]
pub enum ApproximationDesc {
    /// `u × v` segments per patch.
    Parametric {
        /// Segments along u per patch (clamped to 1…4096).
        u: u32,
        /// Segments along v per patch (clamped to 1…4096).
        v: u32,
    },
    /// `u × v` segments over the whole surface.
    Regular {
        /// Segments along u (clamped to 1…4096).
        u: u32,
        /// Segments along v (clamped to 1…4096).
        v: u32,
    },
    /// No edge longer than `edge`.
    Spatial {
        /// Longest edge, > 0, in the units of `space`.
        edge: f64,
        /// `Object` (default, object units) or `Raster` (pixels of the render camera).
        #[serde(default)]
        space: SpaceDesc,
        /// Minimum subdivision level, default 0 (≤ 12).
        #[serde(default)]
        min_subdiv: u32,
        /// Maximum subdivision level, default 7 (≤ 12).
        #[serde(default = "seven")]
        max_subdiv: u32,
    },
    /// Chord distance and angle tolerances.
    Curvature {
        /// Largest distance from the surface, object units, default 0.01 (≥ 0).
        #[serde(default = "hundredth")]
        distance: f64,
        /// Largest turn between neighbouring normals, degrees, default 10 (≥ 0).
        #[serde(default = "ten_f")]
        angle: f64,
        /// Minimum subdivision level, default 0 (≤ 12).
        #[serde(default)]
        min_subdiv: u32,
        /// Maximum subdivision level, default 7 (≤ 12).
        #[serde(default = "seven")]
        max_subdiv: u32,
    },
}

/// Where a spatial edge length is measured.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Space")]
pub enum SpaceDesc {
    /// Object units.
    #[default]
    Object,
    /// Pixels of the render camera.
    Raster,
}

/// `displacement: (...)` on an object.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Displacement", deny_unknown_fields)]
pub struct DisplacementDesc {
    /// The displacement along the unit normal, object units.
    pub shader: ScalarDesc,
    /// Largest |displacement| (≥ 0), default: the shader's own bound.
    #[serde(default)]
    pub bound: Option<f64>,
    /// `True` (default: move vertices) or `Bump` (shading normals only).
    #[serde(default)]
    pub mode: DisplacementModeDesc,
}

/// True or bump displacement.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "DisplacementMode")]
pub enum DisplacementModeDesc {
    /// Move the vertices.
    #[default]
    True,
    /// Perturb shading normals only.
    Bump,
}

/// A scalar shader node.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Scalar", deny_unknown_fields)]
pub enum ScalarDesc {
    /// A constant.
    Constant(f64),
    /// `amplitude · sin(coord · factor · π)`.
    Sine {
        /// Amplitude, object units.
        amplitude: f64,
        /// Frequency factor.
        factor: f64,
        /// `U` (default, the seed's `s`) or `V`.
        #[serde(default)]
        axis: AxisDesc,
    },
    /// fBm of Perlin noise over object-space position.
    Noise {
        /// Amplitude, object units.
        amplitude: f64,
        /// Base frequency, cycles per object unit, default 1.
        #[serde(default = "one")]
        frequency: f64,
        /// Octaves, default 4 (clamped to 1…12).
        #[serde(default = "four")]
        octaves: u32,
        /// Frequency multiplier per octave, default 2.
        #[serde(default = "two")]
        lacunarity: f64,
        /// Amplitude multiplier per octave, default 0.5.
        #[serde(default = "half")]
        gain: f64,
        /// Seed, default 0.
        #[serde(default)]
        seed: u64,
    },
    /// A height map sampled at the surface uv (bilinear, repeat): a PNG read as grey 0…1,
    /// or an EXR's float heights as stored.
    Image {
        /// PNG or EXR file, relative to the declaring scene file.
        file: String,
        /// Multiplier of the texel value (a PNG's 0…1, an EXR's height), default 1.
        #[serde(default = "one")]
        scale: f64,
        /// Added after scaling, default 0.
        #[serde(default)]
        offset: f64,
    },
    /// Sum of the inputs.
    Sum(Vec<ScalarDesc>),
    /// Product of the inputs.
    Product(Vec<ScalarDesc>),
}

/// Texture coordinate read by `Sine`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Axis")]
pub enum AxisDesc {
    /// `s` (u).
    #[default]
    U,
    /// `t` (v).
    V,
}

fn one() -> f64 {
    1.0
}
fn minus_one() -> f64 {
    -1.0
}
fn two() -> f64 {
    2.0
}
fn half() -> f64 {
    0.5
}
fn quarter() -> f64 {
    0.25
}
fn hundredth() -> f64 {
    0.01
}
fn ten_f() -> f64 {
    10.0
}
fn full_turn() -> f64 {
    360.0
}
fn half_turn() -> f64 {
    180.0
}
fn one_u32() -> u32 {
    1
}
fn four() -> u32 {
    4
}
fn seven() -> u32 {
    7
}
fn ten() -> u32 {
    10
}
fn hundred() -> u32 {
    100
}
fn unit_range() -> (f64, f64) {
    (1.0, 1.0)
}
fn yes() -> bool {
    true
}

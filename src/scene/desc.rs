//! The scene description as plain serde types (`*Desc`): the format-neutral description every
//! reader produces (RON deserialises into it directly, exactly as written by the user).
//!
//! Every struct denies unknown fields; every optional field has a default documented here
//! and in `docs/scene-format.md`. Nothing is validated here: see [`super::validate`].

use serde::{Deserialize, Serialize};

pub use super::desc_camera::{FalloffDesc, LensDesc, SamplesDesc, VolumeDesc};
pub use super::desc_contour::{ContourDesc, ContoursDesc, ContrastDesc};
pub use super::desc_diagnostic::{BvhQuantityDesc, GridSpaceDesc, PhotonQuantityDesc};
pub use super::desc_environment::{
    DepthExceededDesc, EnvironmentDesc, EnvironmentShaderDesc, MaterialEnvironmentDesc,
};
pub use super::desc_geometry::{
    ApproximationDesc, AxisDesc, BasisDesc, DisplacementDesc, DisplacementModeDesc, MeshDesc,
    ScalarDesc, SpaceDesc, SurfaceValuesDesc, SurfaceVariablesDesc,
};
pub use super::desc_material_shaders::{PhotonShaderDesc, ShadowDesc};
pub use super::desc_photon_depth::PhotonDepthDesc;
pub use super::desc_values::{M4, V3};
pub use super::nodes_desc::{BumpDesc, InputDesc, NodeDesc, PhenomenonDesc};

/// One scene file (the root file or an include). Every field is optional.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(rename = "Scene", deny_unknown_fields, default)]
pub struct SceneDesc {
    /// Other scene files merged into this one, relative to this file.
    pub include: Vec<String>,
    /// Render options (at most one across all files).
    pub options: Option<OptionsDesc>,
    /// Cameras.
    pub cameras: Vec<CameraDesc>,
    /// Lights.
    pub lights: Vec<LightDesc>,
    /// Materials.
    pub materials: Vec<MaterialDesc>,
    /// Objects (mesh prototypes).
    pub objects: Vec<ObjectDesc>,
    /// Instances (placed copies of objects or groups).
    pub instances: Vec<InstanceDesc>,
    /// Instance groups.
    pub groups: Vec<GroupDesc>,
    /// What to render (exactly one across all files).
    pub render: Option<RenderDesc>,
    /// Phenomena: named shader graphs with interface parameters (see [`PhenomenonDesc`]).
    pub phenomena: Vec<PhenomenonDesc>,
    /// What rays leaving the scene see, also a light (at most one across all files).
    pub environment: Option<EnvironmentDesc>,
}

/// `options: (...)`: render settings.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Options", deny_unknown_fields, default)]
pub struct OptionsDesc {
    /// Samples per pixel, default 4, at least 1; or adaptive `(min, max, contrast)`.
    pub samples: SamplesDesc,
    /// Pixel filter, default `Box`.
    pub filter: FilterDesc,
    /// Random seed, default 0.
    pub seed: u64,
    /// Maximum trace depth, default 4, at least 1.
    pub max_depth: u32,
    /// Face visibility, default `Front`.
    pub face: FaceDesc,
    /// BVH build quality, default `Medium`.
    pub bvh_quality: BvhQualityDesc,
    /// Radiance integrator, default `Direct`.
    pub integrator: IntegratorDesc,
    /// Most glossy/mirror reflections per path, default 4.
    pub reflection_depth: u32,
    /// Most refractions per path, default 4.
    pub refraction_depth: u32,
    /// Light samples per shading point for emitting meshes, default 16, at least 1.
    pub light_samples: u32,
    /// Caustic photon map, default off.
    pub caustics: Option<PhotonMapDesc>,
    /// Global-illumination photon map with final gathering, default off.
    pub global_illumination: Option<PhotonMapDesc>,
    /// Contour contrast, default [`ContoursDesc::default`].
    pub contours: Option<ContoursDesc>,
    /// Photon map file (mental ray `photonmap file`), default none.
    pub photon_map: Option<PhotonMapFileDesc>,
    /// Features switched off (mental ray `lens off`, `volume off`, …), default none.
    pub disable: Vec<FeatureDesc>,
    /// Diagnostic view replacing the beauty pass (mental ray `diagnostic …`), default none.
    pub diagnostic: Option<DiagnosticDesc>,
    /// Photon trace depth (mental ray `photon trace depth`), default unlimited.
    pub photon_depth: Option<PhotonDepthDesc>,
}

/// `photon_map: (file: "scene.pmap", rebuild: false)` in `options`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(rename = "PhotonMapFile", deny_unknown_fields)]
pub struct PhotonMapFileDesc {
    /// The file, relative to the working directory (like camera outputs).
    pub file: String,
    /// Trace and rewrite even when the file's hash matches, default false.
    #[serde(default)]
    pub rebuild: bool,
}

/// `diagnostic:` in `options` (see [`crate::diagnostic::Diagnostic`]).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Diagnostic", deny_unknown_fields)]
pub enum DiagnosticDesc {
    /// Samples per pixel as grey levels (mental ray `diagnostic samples on`).
    Samples,
    /// Grid lines every `size` units of `space` (mental ray `diagnostic grid`).
    Grid {
        /// Object, world or camera coordinates.
        space: GridSpaceDesc,
        /// Distance between lines, > 0.
        size: f64,
    },
    /// False-colour view of the photon maps (mental ray `diagnostic photon`).
    Photon {
        /// Density or irradiance.
        quantity: PhotonQuantityDesc,
        /// The value shown red, > 0.
        max: f64,
    },
    /// False-colour view of the ray-tracing hierarchy's work (mental ray `diagnostic bsp`).
    Bvh {
        /// Deepest level entered or triangles tested.
        quantity: BvhQuantityDesc,
        /// The value shown red, > 0; absent: the tree's depth (`Depth`) or the image's
        /// largest count (`Size`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        max: Option<u32>,
    },
}

/// An entry of `disable: [...]` in `options`: a kind of shader switched off for the run (see
/// [`crate::features::Feature`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Feature", deny_unknown_fields)]
pub enum FeatureDesc {
    /// Camera lens shaders.
    Lens,
    /// Atmosphere and material interiors.
    Volume,
    /// Geometry shaders and scatters.
    Geometry,
    /// Displacement shaders (true and bump).
    Displacement,
    /// Output shaders (contour drawing).
    Output,
}

/// `caustics: (...)` / `global_illumination: (...)` in `options`: one photon map's knobs.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(rename = "PhotonMap", deny_unknown_fields, default)]
pub struct PhotonMapDesc {
    /// Photons emitted, default 100 000, at least 1.
    pub photons: u32,
    /// Largest gather radius, world units, default 0 (automatic: 2 % of the scene diagonal).
    pub radius: f64,
    /// Photons per estimate (k nearest), default 50, at least 2.
    pub gather: u32,
    /// Final-gather rays per shading point (global illumination only), default 16, at least 1.
    pub final_gather: u32,
    /// Global illumination only: final-gather rays read irradiance at photon positions, each
    /// computed on first use (default true); false runs the full estimate for every ray.
    pub precompute: bool,
    /// Caustics only: emit photons only toward the caustic casters, default true.
    pub aim: bool,
    /// Weighting of photons in an estimate, default `Box`.
    pub filter: PhotonFilterDesc,
    /// Progressive photon mapping, default off.
    pub progressive: Option<ProgressiveDesc>,
}

/// `progressive: (passes: N, alpha: 0.7)` of a photon map.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Progressive", deny_unknown_fields, default)]
pub struct ProgressiveDesc {
    /// Photon passes, default 16, 1 to 65536.
    pub passes: u32,
    /// Fraction of each pass's photons kept when the radius shrinks, default 0.7, in (0, 1].
    pub alpha: f64,
}

impl Default for ProgressiveDesc {
    fn default() -> Self {
        Self {
            passes: 16,
            alpha: 0.7,
        }
    }
}

/// `filter:` of a photon map (mental ray `caustic filter box|cone|gauss`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize, Serialize)]
#[serde(rename = "PhotonFilter", deny_unknown_fields)]
pub enum PhotonFilterDesc {
    /// Every photon weighs 1.
    #[default]
    Box,
    /// Jensen's cone filter, weight `1 − d/(k·r)`, `k ≥ 1`.
    Cone {
        /// Jensen's `k`, ≥ 1 (mental ray's cone filter constant, often 1.1).
        k: f64,
    },
    /// Jensen's (Pavicic's) normalised Gaussian filter.
    Gauss,
}

impl Default for PhotonMapDesc {
    fn default() -> Self {
        Self {
            photons: 100_000,
            radius: 0.0,
            gather: 50,
            final_gather: 16,
            precompute: true,
            aim: true,
            filter: PhotonFilterDesc::Box,
            progressive: None,
        }
    }
}

impl Default for OptionsDesc {
    fn default() -> Self {
        Self {
            samples: SamplesDesc::Fixed(4),
            filter: FilterDesc::Box,
            seed: 0,
            max_depth: 4,
            face: FaceDesc::Front,
            bvh_quality: BvhQualityDesc::Medium,
            integrator: IntegratorDesc::Direct,
            reflection_depth: 4,
            refraction_depth: 4,
            light_samples: 16,
            caustics: None,
            global_illumination: None,
            contours: None,
            photon_map: None,
            disable: Vec::new(),
            diagnostic: None,
            photon_depth: None,
        }
    }
}

/// Pixel filter.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Filter", deny_unknown_fields)]
pub enum FilterDesc {
    /// Box filter over the pixel.
    Box,
    /// Truncated Gaussian.
    Gaussian {
        /// Standard deviation, pixels, default 0.5.
        #[serde(default = "default_sigma")]
        sigma: f64,
        /// Truncation radius, pixels, default 1.5.
        #[serde(default = "default_radius")]
        radius: f64,
    },
}

fn default_sigma() -> f64 {
    0.5
}

fn default_radius() -> f64 {
    1.5
}

/// Face visibility.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Face")]
pub enum FaceDesc {
    /// Front faces only: back faces of one-sided materials are black and block light.
    Front,
    /// Both faces.
    Both,
    /// Back faces of one-sided materials are left out of every ray (mental ray's `face
    /// front`).
    Cull,
}

/// BVH build quality.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "BvhQuality")]
pub enum BvhQualityDesc {
    /// Cheapest build.
    Fast,
    /// Balanced.
    Medium,
    /// Best hierarchy.
    High,
}

/// Radiance integrator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Integrator")]
pub enum IntegratorDesc {
    /// Direct lighting plus traced mirror/refraction rays.
    Direct,
    /// Unbiased path tracing (MIS, Russian roulette).
    Path,
}

/// `cameras: [(...)]`: a pinhole camera.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Camera", deny_unknown_fields)]
pub struct CameraDesc {
    /// Unique camera name.
    pub name: String,
    /// Vertical field of view, degrees, in (0, 180).
    pub fov_y: f64,
    /// Image size in pixels `(width, height)`, both at least 1.
    pub resolution: (u32, u32),
    /// Image-plane aspect ratio, default `width / height`.
    #[serde(default)]
    pub aspect: Option<f64>,
    /// Where the camera is.
    pub placement: PlacementDesc,
    /// Files to write, default none.
    #[serde(default)]
    pub outputs: Vec<OutputDesc>,
    /// Output shader for PNG outputs (background, exposure, tone map, gamma, pattern), default
    /// none.
    #[serde(default)]
    pub imager: Option<ImagerDesc>,
    /// Lens shaders applied in order after the pinhole, default none.
    #[serde(default)]
    pub lens: Vec<LensDesc>,
    /// Volume shader filling the scene around the camera, default none.
    #[serde(default)]
    pub atmosphere: Option<VolumeDesc>,
    /// Camera-space length of one world unit (the unit of `CameraDepth` and
    /// `CameraPosition`), > 0, default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub space_scale: Option<f64>,
}

/// `imager: (...)` on a camera: RenderMan `Exposure gain gamma`, `Imager "background"` and the
/// seed tutorial's `Imager "myImager"` (`pattern`).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Imager", deny_unknown_fields)]
pub struct ImagerDesc {
    /// Colour behind uncovered pixels, default none (black, transparent).
    #[serde(default)]
    pub background: Option<V3>,
    /// Radiance multiplier, default 1.
    #[serde(default = "default_gain")]
    pub gain: f64,
    /// Tone map, default `None`.
    #[serde(default)]
    pub tone_map: ToneMapDesc,
    /// Display gamma, default none (the sRGB curve).
    #[serde(default)]
    pub gamma: Option<f64>,
    /// A pattern of raster position painted over every pixel (colour and alpha 1), default
    /// none: the seed tutorial's `Imager "myImager"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pattern: Option<ImagerPatternDesc>,
}

/// `pattern: …` of an imager: what it paints over every pixel, in raster coordinates
/// normalised by the resolution (`(x + ½, y + ½) / (width, height)`, row 0 at the top).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(rename = "ImagerPattern", deny_unknown_fields)]
pub enum ImagerPatternDesc {
    /// `mix(outside, inside, 1 − smoothstep(radius − fuzz, radius + fuzz, distance))` of the
    /// distance from `center` (the `Disk` shader-graph node's formula, over the image).
    Disk {
        /// Centre, default `(0.5, 0.5)`.
        #[serde(default = "pattern_centre")]
        center: (f64, f64),
        /// Radius ≥ 0, default 0.4.
        #[serde(default = "pattern_radius")]
        radius: f64,
        /// Half-width ≥ 0 of the soft edge, default 0 (a hard edge).
        #[serde(default)]
        fuzz: f64,
        /// Colour inside, default `(0, 0, 1)`.
        #[serde(default = "pattern_blue")]
        inside: V3,
        /// Colour outside, default `(1, 0, 0)`.
        #[serde(default = "pattern_red")]
        outside: V3,
    },
}

fn pattern_centre() -> (f64, f64) {
    (0.5, 0.5)
}

fn pattern_radius() -> f64 {
    0.4
}

fn pattern_blue() -> V3 {
    (0.0, 0.0, 1.0)
}

fn pattern_red() -> V3 {
    (1.0, 0.0, 0.0)
}

fn default_gain() -> f64 {
    1.0
}

/// Tone-mapping operator.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize, Serialize)]
#[serde(rename = "ToneMap", deny_unknown_fields)]
pub enum ToneMapDesc {
    /// Clip above 1.
    #[default]
    None,
    /// `x / (1 + x)`.
    Reinhard,
}

/// Camera placement.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Placement", deny_unknown_fields)]
pub enum PlacementDesc {
    /// Look from `eye` at `target` with `up` (default `(0, 1, 0)`) roughly up.
    LookAt {
        /// Eye position.
        eye: V3,
        /// Point looked at.
        target: V3,
        /// Up hint, default `(0, 1, 0)`.
        #[serde(default = "default_up")]
        up: V3,
    },
    /// Row-major rigid camera-to-world matrix; the camera looks down its −Z axis.
    Matrix(M4),
}

fn default_up() -> V3 {
    (0.0, 1.0, 0.0)
}

/// One output file of a camera.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Output", deny_unknown_fields)]
pub struct OutputDesc {
    /// Destination path, as written (relative to the working directory).
    pub file: String,
    /// Format; default from the extension (`.png`, `.exr`).
    #[serde(default)]
    pub format: Option<FormatDesc>,
    /// Passes, default `[Beauty]`.
    #[serde(default)]
    pub passes: Option<Vec<PassDesc>>,
    /// EXR: whether `Beauty` writes the coverage as channel `A` beside `R G B` (default
    /// true); with `false` only the `Alpha` pass writes it (RIB's `rgb` and `rgbz` displays).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beauty_alpha: Option<bool>,
}

/// Output file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Format")]
pub enum FormatDesc {
    /// 8-bit PNG.
    Png,
    /// OpenEXR.
    Exr,
    /// SVG contour lines.
    Svg,
    /// EPS (PostScript) contour lines.
    Eps,
}

/// Image pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "Pass")]
pub enum PassDesc {
    /// Shaded colour.
    Beauty,
    /// Coverage.
    Alpha,
    /// Distance to the first hit.
    Depth,
    /// World-space normal at the first hit.
    Normal,
    /// Camera-space depth of the first hit, along the view axis (EXR only).
    CameraDepth,
    /// Camera-space normal at the first hit (EXR only).
    CameraNormal,
    /// Camera-space position of the first hit (EXR only).
    CameraPosition,
    /// Object id of the first hit (EXR only).
    ObjectId,
    /// Material id of the first hit (EXR only).
    MaterialId,
    /// The contour layer (EXR), or contours composited (PNG).
    Contours,
    /// Component pass: light seen without scattering (EXR only).
    Emission,
    /// Component pass: direct light through the diffuse lobes (EXR only).
    DiffuseDirect,
    /// Component pass: indirect light through the diffuse lobes (EXR only).
    DiffuseIndirect,
    /// Component pass: light through the glossy and mirror lobes (EXR only).
    Specular,
    /// Component pass: refracted or passed-through light (EXR only).
    Transmission,
    /// Component pass: light scattered by fog on the camera ray (EXR only).
    Volume,
}

/// `lights: [(...)]`: a light.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Light", deny_unknown_fields)]
pub struct LightDesc {
    /// Unique light name.
    pub name: String,
    /// Shape and placement.
    pub kind: LightKindDesc,
    /// Linear RGB colour, default `(1, 1, 1)`, non-negative.
    #[serde(default = "default_white")]
    pub color: V3,
    /// Scale of `color`, default 1, non-negative.
    #[serde(default = "default_one")]
    pub intensity: f64,
    /// Whether the light casts shadows, default `true`.
    #[serde(default = "default_true")]
    pub shadows: bool,
    /// The fraction of the light that passes occluders, in [0, 1] (mental ray's light
    /// `factor`), default 0 (full shadows).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub shadow_factor: f64,
    /// Samples per shading point (area lights, default 16); delta lights accept only 1.
    #[serde(default)]
    pub samples: Option<u32>,
    /// Area lights: seen by camera rays and mirror/refraction rays, default `false`.
    #[serde(default)]
    pub visible: bool,
    /// Linear near/far falloff `(start, end)` on top of the inverse-square law, default none.
    #[serde(default)]
    pub attenuation: Option<(f64, f64)>,
    /// Photon power, W per channel, replacing the physical power for photons only (mental
    /// ray `energy`), default none (physical power).
    #[serde(default)]
    pub energy: Option<V3>,
    /// Caustic photons this light emits (mental ray `caustic photons`), default none (the
    /// lights without a count share the map's `photons` by power).
    #[serde(default)]
    pub caustic_photons: Option<u32>,
    /// Global-illumination photons this light emits (mental ray `globillum photons`).
    #[serde(default)]
    pub globillum_photons: Option<u32>,
    /// Point and spot lights: whether `Cl` falls off as 1/d², default `true`; `false` is
    /// mental ray's `mib_light_point`/`mib_light_spot` (`Cl` = colour at every distance).
    /// Area kinds: `false` makes each light sample a point light of `Cl` = colour at a
    /// point of the shape (mental ray's area shape on those shaders).
    #[serde(default = "default_true")]
    pub inverse_square: bool,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

fn default_white() -> V3 {
    (1.0, 1.0, 1.0)
}

fn default_one() -> f64 {
    1.0
}

fn default_true() -> bool {
    true
}

/// Light shape.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "LightKind", deny_unknown_fields)]
pub enum LightKindDesc {
    /// Ambient light (RenderMan `ambientlight`): `color · intensity` is added to the ambient
    /// term of `Local` shaders (weighted by their `ka`); other shaders do not see it.
    Ambient,
    /// Isotropic point light (W/sr).
    Point {
        /// Position.
        position: V3,
    },
    /// Spotlight (W/sr on its axis).
    Spot {
        /// Position.
        position: V3,
        /// Point the axis goes through.
        target: V3,
        /// Half angle of the cone, degrees, in (0, 90].
        cone_angle: f64,
        /// Penumbra width inside the cone edge, degrees, default 0, in [0, cone_angle].
        #[serde(default)]
        penumbra: f64,
        /// Cosine falloff exponent, default 2, non-negative.
        #[serde(default = "default_beam")]
        beam_distribution: f64,
    },
    /// Distant light (W/m²).
    Directional {
        /// Direction the light travels (normalised by the loader).
        direction: V3,
    },
    /// One-sided parallelogram area light (W/(sr·m²)), emitting along `edge_u × edge_v`.
    Rect {
        /// One corner.
        corner: V3,
        /// First edge.
        edge_u: V3,
        /// Second edge.
        edge_v: V3,
    },
    /// One-sided disc area light (W/(sr·m²)), emitting along `normal`.
    Disc {
        /// Centre.
        center: V3,
        /// Emitting side (normalised by the loader).
        normal: V3,
        /// Radius, > 0.
        radius: f64,
    },
    /// Spherical area light (W/(sr·m²)) emitting outward.
    Sphere {
        /// Centre.
        center: V3,
        /// Radius, > 0.
        radius: f64,
    },
    /// Cylindrical area light (W/(sr·m²)): an open tube emitting outward.
    Cylinder {
        /// Centre of one end.
        start: V3,
        /// Centre of the other end.
        end: V3,
        /// Radius, > 0.
        radius: f64,
    },
}

fn default_beam() -> f64 {
    2.0
}

/// `materials: [(...)]`: a material.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Material", deny_unknown_fields)]
pub struct MaterialDesc {
    /// Unique material name.
    pub name: String,
    /// Surface shader.
    pub shader: ShaderDesc,
    /// Shade both faces, default `false`.
    #[serde(default)]
    pub two_sided: bool,
    /// Emitted radiance, W/(sr·m²), default `(0, 0, 0)`.
    #[serde(default)]
    pub emission: V3,
    /// Shader parameters driven by node graphs (`{"albedo": Checker(…)}`), default none.
    #[serde(default, deserialize_with = "super::unique_keys::deserialize")]
    pub bind: std::collections::BTreeMap<String, InputDesc>,
    /// Bump mapping, default none.
    #[serde(default)]
    pub bump: Option<BumpDesc>,
    /// Volume shader filling the inside of closed meshes with this material, default none.
    #[serde(default)]
    pub interior: Option<VolumeDesc>,
    /// Contour shader, default none (no contours around this material).
    #[serde(default)]
    pub contour: Option<ContourDesc>,
    /// Light list (mental ray's `"lights"`): the names of the only lights this material
    /// sees, default none (every light). Listed lights light it in renders and bakes.
    #[serde(default)]
    pub lights: Option<Vec<String>>,
    /// Shadow shader: what shadow rays keep crossing this material, default none (as the
    /// surface shader implies).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shadow: Option<ShadowDesc>,
    /// Material environment: what this material's specular rays see leaving the scene,
    /// default none (the scene's environment).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub environment: Option<MaterialEnvironmentDesc>,
    /// Photon shader: what photons do at this material, default none (as the surface shader
    /// implies).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub photon: Option<PhotonShaderDesc>,
}

/// Surface shader.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Shader", deny_unknown_fields)]
pub enum ShaderDesc {
    /// Ideal diffuse.
    Lambert {
        /// Reflectance in [0, 1] per channel.
        albedo: V3,
    },
    /// Flat colour.
    Constant {
        /// Colour, non-negative.
        color: V3,
    },
    /// RenderMan `defaultsurface`.
    DefaultSurface {
        /// Ambient weight, default 0.2.
        #[serde(default = "default_ka")]
        ka: f64,
        /// Diffuse weight, default 0.8.
        #[serde(default = "default_kd")]
        kd: f64,
        /// Colour, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        color: V3,
    },
    /// mental ray Phong: diffuse + normalised Phong lobe.
    Phong {
        /// Ambient radiance (Direct integrator only), default `(0, 0, 0)`.
        #[serde(default)]
        ambient: V3,
        /// Diffuse reflectance, default `(0.5, 0.5, 0.5)`.
        #[serde(default = "default_half")]
        diffuse: V3,
        /// Specular weight, default `(0.5, 0.5, 0.5)`.
        #[serde(default = "default_half")]
        specular: V3,
        /// Phong exponent, default 20, ≥ 0.
        #[serde(default = "default_spec_exp")]
        spec_exp: f64,
    },
    /// mental ray Blinn: Cook–Torrance with one index of refraction.
    Blinn {
        /// Ambient radiance (Direct integrator only), default `(0, 0, 0)`.
        #[serde(default)]
        ambient: V3,
        /// Diffuse reflectance, default `(0.5, 0.5, 0.5)`.
        #[serde(default = "default_half")]
        diffuse: V3,
        /// Specular weight, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        specular: V3,
        /// RMS microfacet slope, default 0.2, > 0.
        #[serde(default = "default_roughness_mr")]
        roughness: f64,
        /// Index of refraction, default 1.5, > 0.
        #[serde(default = "default_ior")]
        ior: f64,
    },
    /// mental ray Cook–Torrance: Beckmann microfacets, V-cavity masking, per-channel IOR.
    CookTorrance {
        /// Ambient radiance (Direct integrator only), default `(0, 0, 0)`.
        #[serde(default)]
        ambient: V3,
        /// Diffuse reflectance, default `(0.5, 0.5, 0.5)`.
        #[serde(default = "default_half")]
        diffuse: V3,
        /// Specular weight, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        specular: V3,
        /// RMS microfacet slope, default 0.2, > 0.
        #[serde(default = "default_roughness_mr")]
        roughness: f64,
        /// Index of refraction per channel, default `(1.5, 1.5, 1.5)`, > 0.
        #[serde(default = "default_ior3")]
        ior: V3,
    },
    /// Softimage blong: Blinn half-vector lobe with a Phong exponent.
    Blong {
        /// Ambient radiance (Direct integrator only), default `(0, 0, 0)`.
        #[serde(default)]
        ambient: V3,
        /// Diffuse reflectance, default `(0.5, 0.5, 0.5)`.
        #[serde(default = "default_half")]
        diffuse: V3,
        /// Specular weight, default `(0.5, 0.5, 0.5)`.
        #[serde(default = "default_half")]
        specular: V3,
        /// Exponent, default 20, ≥ 0.
        #[serde(default = "default_spec_exp")]
        spec_exp: f64,
    },
    /// Fresnel-weighted specular (`mi_fresnel_specular`).
    FresnelSpecular {
        /// Ambient radiance (Direct integrator only), default `(0, 0, 0)`.
        #[serde(default)]
        ambient: V3,
        /// Diffuse reflectance, default `(0.5, 0.5, 0.5)`.
        #[serde(default = "default_half")]
        diffuse: V3,
        /// Specular weight, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        specular: V3,
        /// Exponent, default 20, ≥ 0.
        #[serde(default = "default_spec_exp")]
        spec_exp: f64,
        /// Index of refraction inside, default 1.5, > 0.
        #[serde(default = "default_ior")]
        ior_in: f64,
        /// Index of refraction outside, default 1, > 0.
        #[serde(default = "default_one")]
        ior_out: f64,
    },
    /// RenderMan `matte`.
    Matte {
        /// Ambient weight, default 1 (no effect in this stand-in; see `Local`).
        #[serde(default = "default_one")]
        ka: f64,
        /// Diffuse weight, default 1.
        #[serde(default = "default_one")]
        kd: f64,
        /// Colour, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        color: V3,
    },
    /// RenderMan `plastic`.
    Plastic {
        /// Ambient weight, default 1 (no effect in this stand-in; see `Local`).
        #[serde(default = "default_one")]
        ka: f64,
        /// Diffuse weight, default 0.5.
        #[serde(default = "default_half_scalar")]
        kd: f64,
        /// Specular weight, default 0.5.
        #[serde(default = "default_half_scalar")]
        ks: f64,
        /// Roughness (highlight exponent `1/roughness`), default 0.1, > 0.
        #[serde(default = "default_roughness_rm")]
        roughness: f64,
        /// Highlight colour, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        specularcolor: V3,
        /// Colour, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        color: V3,
    },
    /// RenderMan `metal`.
    Metal {
        /// Ambient weight, default 1 (no effect in this stand-in; see `Local`).
        #[serde(default = "default_one")]
        ka: f64,
        /// Specular weight, default 1.
        #[serde(default = "default_one")]
        ks: f64,
        /// Roughness, default 0.1, > 0.
        #[serde(default = "default_roughness_rm")]
        roughness: f64,
        /// Colour, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        color: V3,
    },
    /// RenderMan `shinymetal` (traced mirror reflection stands in for the reflection map).
    ShinyMetal {
        /// Ambient weight, default 1 (no effect in this stand-in; see `Local`).
        #[serde(default = "default_one")]
        ka: f64,
        /// Specular weight, default 1.
        #[serde(default = "default_one")]
        ks: f64,
        /// Reflection weight, default 1.
        #[serde(default = "default_one")]
        kr: f64,
        /// Roughness, default 0.1, > 0.
        #[serde(default = "default_roughness_rm")]
        roughness: f64,
        /// Colour, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        color: V3,
    },
    /// RenderMan `paintedplastic` (white stands in for the texture).
    PaintedPlastic {
        /// Ambient weight, default 1 (no effect in this stand-in; see `Local`).
        #[serde(default = "default_one")]
        ka: f64,
        /// Diffuse weight, default 0.5.
        #[serde(default = "default_half_scalar")]
        kd: f64,
        /// Specular weight, default 0.5.
        #[serde(default = "default_half_scalar")]
        ks: f64,
        /// Roughness, default 0.1, > 0.
        #[serde(default = "default_roughness_rm")]
        roughness: f64,
        /// Highlight colour, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        specularcolor: V3,
        /// Colour, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        color: V3,
    },
    /// The glTF 2.0 metallic-roughness model (what the glTF reader makes of a glTF
    /// material): GGX specular with the glTF specification's base colour / metallic mixing.
    MetallicRoughness {
        /// Base colour (linear), each channel in [0, 1], default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        base_color: V3,
        /// Metalness in [0, 1], default 1 (glTF's default).
        #[serde(default = "default_one")]
        metallic: f64,
        /// Perceptual roughness in [0, 1] (GGX α = roughness²), default 1.
        #[serde(default = "default_one")]
        roughness: f64,
    },
    /// Perfect mirror.
    Mirror {
        /// Reflectance, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        color: V3,
    },
    /// Smooth dielectric (glass).
    Dielectric {
        /// Index of refraction inside, default 1.5, > 0.
        #[serde(default = "default_ior")]
        ior: f64,
        /// Index of refraction outside, default 1, > 0.
        #[serde(default = "default_one")]
        ior_out: f64,
        /// Transmittance per unit length inside, default `(1, 1, 1)`, each in [0, 1].
        #[serde(default = "default_white")]
        col: V3,
    },
    /// mental ray `dgs_material`.
    Dgs {
        /// Diffuse reflectance, default `(0, 0, 0)`.
        #[serde(default)]
        diffuse: V3,
        /// Glossy reflectance, default `(0, 0, 0)`.
        #[serde(default)]
        glossy: V3,
        /// Mirror reflectance, default `(0, 0, 0)`.
        #[serde(default)]
        specular: V3,
        /// Glossy exponent, default 20, ≥ 0.
        #[serde(default = "default_spec_exp")]
        shiny: f64,
    },
    /// A local illumination model as a shading-language specification writes it (what the
    /// RIB reader makes of RenderMan's `matte`, `metal`, `shinymetal`, `plastic` and
    /// `paintedplastic`): `color·(ka·A + kd·Σ Cl·max(0, N·L)) + ambient + specular·Σ Cl·lobe
    /// + reflection·(mirror)`, `A` the scene's `Ambient` lights; no 1/π, no energy clamp.
    /// Defaults are RenderMan `plastic`'s.
    Local {
        /// Surface colour `Cs`, default `(1, 1, 1)`.
        #[serde(default = "default_white")]
        color: V3,
        /// Weight of the ambient light, default 1.
        #[serde(default = "default_one")]
        ka: f64,
        /// Weight of the diffuse sum, default 0.5.
        #[serde(default = "default_half_scalar")]
        kd: f64,
        /// Weight of the highlight sum (`Ks · specularcolor`), default `(0.5, 0.5, 0.5)`.
        #[serde(default = "default_half")]
        specular: V3,
        /// The highlight lobe, default `RenderMan(roughness: 0.1)`.
        #[serde(default)]
        lobe: LocalLobeDesc,
        /// Weight of the traced mirror reflection, default `(0, 0, 0)`.
        #[serde(default)]
        reflection: V3,
        /// Radiance added as it is, default `(0, 0, 0)`.
        #[serde(default)]
        ambient: V3,
    },
    /// mental ray `mib_opacity`: blend `input` over what lies behind.
    Opacity {
        /// Opacity per channel in [0, 1].
        opacity: V3,
        /// The shader blended over what lies behind.
        input: Box<ShaderDesc>,
    },
}

/// The highlight lobe of a `Local` shader.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(rename = "LocalLobe", deny_unknown_fields)]
pub enum LocalLobeDesc {
    /// RenderMan Interface 3.2 `specularbrdf`: `max(0, N·H)^(1/roughness)`.
    RenderMan {
        /// Roughness, default 0.1, > 0.
        #[serde(default = "default_roughness_rm")]
        roughness: f64,
    },
    /// mental ray `mib_illum_phong`: `max(0, R·L)^exponent`, `R` the mirrored view direction.
    Phong {
        /// Exponent, ≥ 0.
        exponent: f64,
    },
    /// mental ray `mib_illum_blinn` (`mi_blinn_specular`): `CookTorrance` with one index.
    Blinn {
        /// Average microfacet slope, > 0.
        roughness: f64,
        /// Relative index of refraction, > 0 (below 1 reflects nothing).
        ior: f64,
    },
    /// mental ray `mib_illum_cooktorr` (`mi_cooktorr_specular`): the Cook–Torrance (1982)
    /// specular term per light, `F·D·G / (π N·V)`, Beckmann `D` of slope `roughness`,
    /// dielectric Fresnel `F` with one relative index per channel.
    CookTorrance {
        /// Average microfacet slope, > 0.
        roughness: f64,
        /// Relative index of refraction per channel, each > 0 (below 1 reflects nothing).
        ior: V3,
    },
}

impl Default for LocalLobeDesc {
    fn default() -> Self {
        LocalLobeDesc::RenderMan {
            roughness: default_roughness_rm(),
        }
    }
}

fn default_ka() -> f64 {
    0.2
}

fn default_kd() -> f64 {
    0.8
}

fn default_half() -> V3 {
    (0.5, 0.5, 0.5)
}

fn default_half_scalar() -> f64 {
    0.5
}

fn default_spec_exp() -> f64 {
    20.0
}

fn default_roughness_mr() -> f64 {
    0.2
}

fn default_roughness_rm() -> f64 {
    0.1
}

fn default_ior() -> f64 {
    1.5
}

fn default_ior3() -> V3 {
    (1.5, 1.5, 1.5)
}

/// `objects: [(...)]`: a mesh prototype.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Object", deny_unknown_fields)]
pub struct ObjectDesc {
    /// Unique name among objects and groups.
    pub name: String,
    /// The geometry.
    pub mesh: MeshDesc,
    /// Material used when no instance overrides it.
    #[serde(default)]
    pub material: Option<String>,
    /// How its surfaces are diced, default curvature 0.01 / 10° (see `docs/geometry.md`).
    #[serde(default)]
    pub approximation: Option<ApproximationDesc>,
    /// Displacement shader, default none.
    #[serde(default)]
    pub displacement: Option<DisplacementDesc>,
    /// Store surface derivatives dP/du, dP/dv when tessellating, default false.
    #[serde(default)]
    pub derivatives: bool,
    /// The front is the object-space back (RenderMan's and pbrt's `ReverseOrientation`):
    /// one-sided materials, emission and the normals that shading, bump and true
    /// displacement use face the other way, default false.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub reverse_orientation: bool,
    /// Caustic photon role (mental ray `caustic`): 0 none, 1 casts, 2 receives, 3 both;
    /// default from the material (specular casts, non-specular receives).
    #[serde(default)]
    pub caustic: Option<u8>,
    /// Global-illumination photon role (mental ray `globillum`), values as `caustic`;
    /// default: every surface casts and non-specular surfaces receive.
    #[serde(default)]
    pub globillum: Option<u8>,
    /// Seen by camera rays (mental ray `visible`), default true.
    #[serde(default)]
    pub visible: Option<bool>,
    /// Casts shadows (mental ray `shadow`), default true.
    #[serde(default)]
    pub shadow: Option<bool>,
    /// Seen by reflection, refraction and gathering rays (mental ray `trace`), default true.
    #[serde(default)]
    pub trace: Option<bool>,
    /// The value the `ObjectId` pass writes where its instances are seen (mental ray's
    /// object `tag`); default none: 1 + the placed instance's index.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub label: Option<u32>,
}

/// `instances: [(...)]`: a placed copy of an object or a group.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Instance", deny_unknown_fields)]
pub struct InstanceDesc {
    /// Unique instance name.
    pub name: String,
    /// Name of an object or a group.
    pub of: String,
    /// Transforms applied in listed order, default none (identity).
    #[serde(default)]
    pub transform: Vec<TransformDesc>,
    /// Material override.
    #[serde(default)]
    pub material: Option<String>,
    /// Textures to bake for this instance (see [`BakeDesc`]).
    #[serde(default)]
    pub bake: Option<BakeDesc>,
    /// Caustic photon role override for everything this instance places (as on objects).
    #[serde(default)]
    pub caustic: Option<u8>,
    /// Global-illumination photon role override (as on objects).
    #[serde(default)]
    pub globillum: Option<u8>,
    /// Camera-ray visibility override for everything this instance places (as on objects).
    #[serde(default)]
    pub visible: Option<bool>,
    /// Shadow-casting override (as on objects).
    #[serde(default)]
    pub shadow: Option<bool>,
    /// Secondary-ray visibility override (as on objects).
    #[serde(default)]
    pub trace: Option<bool>,
}

impl InstanceDesc {
    /// An instance `name` of `of` placed by `transform`, with nothing else overridden (what
    /// the importers write for each object they place).
    pub fn plain(
        name: impl Into<String>,
        of: impl Into<String>,
        transform: Vec<TransformDesc>,
    ) -> Self {
        Self {
            name: name.into(),
            of: of.into(),
            transform,
            material: None,
            bake: None,
            caustic: None,
            globillum: None,
            visible: None,
            shadow: None,
            trace: None,
        }
    }
}

/// `bake: (...)` on an instance of an object: textures to bake (`stagelight bake`).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Bake", deny_unknown_fields)]
pub struct BakeDesc {
    /// Explicit size `(width, height)` in texels; give this or `texels_per_unit`.
    #[serde(default)]
    pub resolution: Option<(u32, u32)>,
    /// Texel density (texels per world unit), rounded up to a power of two.
    #[serde(default)]
    pub texels_per_unit: Option<f64>,
    /// Largest side when sizing from `texels_per_unit`, default 4096.
    #[serde(default = "default_max_size")]
    pub max_size: u32,
    /// UV source, default `Auto` (the mesh's UVs, generated when it has none).
    #[serde(default)]
    pub uvs: UvsDesc,
    /// Sample positions per texel (rounded up to a square number), default 4.
    #[serde(default = "default_texel_samples")]
    pub texel_samples: u32,
    /// Texels of dilation around every chart, default 2.
    #[serde(default = "default_padding")]
    pub padding: u32,
    /// Also write `<instance>_mask.png`, default false.
    #[serde(default)]
    pub mask: bool,
    /// Make AO and lightmap texels continuous across UV seams (least-squares stitch),
    /// default true.
    #[serde(default = "default_stitch_seams")]
    pub stitch_seams: bool,
    /// The textures.
    pub outputs: Vec<BakeOutputDesc>,
}

fn default_max_size() -> u32 {
    4096
}
fn default_texel_samples() -> u32 {
    4
}
fn default_padding() -> u32 {
    2
}
fn default_stitch_seams() -> bool {
    true
}

/// UV source of a bake.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Uvs", deny_unknown_fields)]
pub enum UvsDesc {
    /// The mesh's UVs; generated lightmap UVs when it has none.
    #[default]
    Auto,
    /// The mesh's UVs only (an error when it has none).
    Mesh,
    /// Always generate lightmap UVs.
    Unwrap,
    /// The mesh's UV set 0 (`MeshSet(0)`, as `Mesh`) or 1 (`MeshSet(1)`: glTF `TEXCOORD_1`,
    /// the usual lightmap UVs); an error when the mesh has none.
    MeshSet(u32),
}

/// One baked texture.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "BakeOutput", deny_unknown_fields)]
pub struct BakeOutputDesc {
    /// What to bake.
    pub kind: BakeKindDesc,
    /// File format, default `Exr`.
    #[serde(default)]
    pub format: BakeFormatDesc,
    /// File name (relative to the bake directory), default `<instance>_<kind>.<ext>`.
    #[serde(default)]
    pub file: Option<String>,
    /// Where the values go: `Texture` (default, texels through the bake's UVs) or `Vertices`
    /// (one value per mesh vertex, written as a PLY with vertex colours).
    #[serde(default, skip_serializing_if = "BakeTargetDesc::is_texture")]
    pub target: BakeTargetDesc,
    /// Texel-space denoising of an AO or lightmap texture, default off.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub denoise: Option<DenoiseDesc>,
}

/// `denoise: (passes: 3, sigma_color: 4.0)` on a bake output: the edge-aware à-trous
/// denoiser (`crate::bake::denoise`).
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(rename = "Denoise", deny_unknown_fields)]
pub struct DenoiseDesc {
    /// À-trous passes (steps 1, 2, 4, …), 1 … 8, default 3.
    #[serde(default = "default_denoise_passes")]
    pub passes: u32,
    /// Colour edge-stopping width in noise standard deviations, > 0, default 4.
    #[serde(default = "default_sigma_color")]
    pub sigma_color: f64,
}

fn default_denoise_passes() -> u32 {
    3
}
fn default_sigma_color() -> f64 {
    4.0
}

/// Where a bake output's values go.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize, Serialize)]
#[serde(rename = "BakeTarget", deny_unknown_fields)]
pub enum BakeTargetDesc {
    /// Texels of a texture, through the bake's UVs.
    #[default]
    Texture,
    /// Mesh vertices: area-weighted sample positions around each vertex.
    Vertices,
}

impl BakeTargetDesc {
    fn is_texture(&self) -> bool {
        *self == BakeTargetDesc::Texture
    }
}

/// Kinds of baked texture.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "BakeKind", deny_unknown_fields)]
pub enum BakeKindDesc {
    /// Ambient occlusion.
    AmbientOcclusion {
        /// Rays per texel, default 64.
        #[serde(default = "default_bake_samples")]
        samples: u32,
        /// Occluders farther than this are ignored (world units), default unlimited.
        #[serde(default)]
        max_distance: Option<f64>,
        /// Also write bent normals, default false.
        #[serde(default)]
        bent_normals: bool,
    },
    /// Irradiance from the lights (and optionally interreflection).
    Lightmap {
        /// Add indirect light, default false.
        #[serde(default)]
        indirect: bool,
        /// Gather paths per texel for the indirect part, default 64.
        #[serde(default = "default_bake_samples")]
        samples: u32,
        /// Indirect bounces, default 2.
        #[serde(default = "default_bake_depth")]
        max_depth: u32,
        /// `Irradiance` (default, W/m²), `Radiance` (albedo·E/π) or `IrradianceOverPi` (E/π).
        #[serde(default)]
        store: LightmapStoreDesc,
        /// Multiplies the stored value, default 1 (headroom in an 8-bit PNG: 0.5 stores half
        /// the value; a glTF copy's `lightmapFactor` is its inverse).
        #[serde(
            default = "default_lightmap_scale",
            skip_serializing_if = "is_unit_scale"
        )]
        scale: f64,
    },
    /// Shading normals.
    Normals {
        /// `World` (default) or `Tangent`.
        #[serde(default)]
        space: NormalSpaceDesc,
    },
    /// World positions.
    Positions,
    /// Material albedo.
    Albedo,
}

fn default_bake_samples() -> u32 {
    64
}
fn default_bake_depth() -> u32 {
    2
}
fn default_lightmap_scale() -> f64 {
    1.0
}
fn is_unit_scale(scale: &f64) -> bool {
    *scale == 1.0
}

/// What a lightmap stores.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize, Serialize)]
#[serde(rename = "LightmapStore", deny_unknown_fields)]
pub enum LightmapStoreDesc {
    /// Irradiance, W/m².
    #[default]
    Irradiance,
    /// Outgoing diffuse radiance albedo·E/π.
    Radiance,
    /// E/π: the radiance a white diffuse surface would reflect (1 under a white sky of
    /// radiance 1), the lightmap a viewer multiplies by the base colour.
    IrradianceOverPi,
}

/// Space of baked normals.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize, Serialize)]
#[serde(rename = "NormalSpace", deny_unknown_fields)]
pub enum NormalSpaceDesc {
    /// World space.
    #[default]
    World,
    /// Tangent space.
    Tangent,
}

/// Baked texture file format.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize, Serialize)]
#[serde(rename = "BakeFormat", deny_unknown_fields)]
pub enum BakeFormatDesc {
    /// OpenEXR, linear f32.
    #[default]
    Exr,
    /// 8-bit PNG.
    Png8,
    /// 16-bit PNG.
    Png16,
    /// PLY with vertex colours (the format of `target: Vertices`, and only of it).
    Ply,
}

/// One step of an instance transform.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Transform", deny_unknown_fields)]
pub enum TransformDesc {
    /// Non-uniform scale.
    Scale(V3),
    /// Rotation about an axis through the origin (right-handed), degrees.
    Rotate {
        /// Axis (normalised by the loader).
        axis: V3,
        /// Angle in degrees.
        degrees: f64,
    },
    /// Translation.
    Translate(V3),
    /// Row-major affine 4×4 matrix (last row `(0, 0, 0, 1)`).
    Matrix(M4),
}

/// `groups: [(...)]`: an instance group.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Group", deny_unknown_fields)]
pub struct GroupDesc {
    /// Unique name among objects and groups.
    pub name: String,
    /// Instance names.
    #[serde(default)]
    pub members: Vec<String>,
}

/// `render: (...)`: what to render.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Render", deny_unknown_fields)]
pub struct RenderDesc {
    /// Root group name.
    pub root: String,
    /// Camera name.
    pub camera: String,
}

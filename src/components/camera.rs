//! Cameras and the outputs they write.

use std::path::PathBuf;

use glam::Affine3A;

/// Image passes a camera output can carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Pass {
    /// Shaded colour (RGB) with alpha.
    Beauty,
    /// Coverage: 1 where a surface was hit, 0 for the background.
    Alpha,
    /// Distance along the pixel centre's ray to the first hit (`Z`); infinity for misses.
    Depth,
    /// World-space shading normal at the first hit (`N.x`, `N.y`, `N.z`).
    Normal,
    /// Camera-space depth of the pixel centre's first hit (`Z`): its coordinate along the
    /// view axis, positive in front of the camera, in camera-space units (RenderMan's `z`);
    /// infinity for misses. See [`crate::camera_space`].
    CameraDepth,
    /// The pixel centre's shading normal in camera space (`N.X`, `N.Y`, `N.Z`: +x right, +y
    /// up, +z forward, RenderMan's left-handed camera space); zero for misses.
    CameraNormal,
    /// The pixel centre's first hit in camera space (`P.X`, `P.Y`, `P.Z`, the axes of
    /// `CameraNormal`, camera-space units: RenderMan's `P`); zero for misses.
    CameraPosition,
    /// Which placed object the pixel centre sees (`id.object`, u32): its object's label
    /// ([`crate::components::ObjectLabel`], `.mi` `tag`) where it has one, else 1 + the
    /// instance's index in the flattened scene (instances in entity order, i.e. declaration
    /// order of the DAG leaves); 0 for the background.
    ObjectId,
    /// Which material the pixel centre sees (`id.material`, u32): 1 + the material's index
    /// among the materials in use; 0 for the background.
    MaterialId,
    /// The contour layer (`contour.R`, `contour.G`, `contour.B`, `contour.A`, premultiplied)
    /// in EXR; in PNG the contours composited over the beauty (or, without `Beauty`, over
    /// the imager's background colour, white without one).
    Contours,
    /// Component pass (EXR `emission.R/G/B`): light seen without scattering — surface
    /// emission at the first hit, light-independent shaders, visible lights and the
    /// environment behind everything. The six component passes sum to the beauty.
    Emission,
    /// Component pass (EXR `diffuse_direct.R/G/B`): light from the lights through the diffuse
    /// lobes of the first hit (and a `Local` model's terms).
    DiffuseDirect,
    /// Component pass (EXR `diffuse_indirect.R/G/B`): further bounces through the diffuse
    /// lobes of the first hit, photon maps, ambient terms.
    DiffuseIndirect,
    /// Component pass (EXR `specular.R/G/B`): light through the glossy and mirror lobes of
    /// the first hit.
    Specular,
    /// Component pass (EXR `transmission.R/G/B`): light refracted or passed through at the
    /// first hit.
    Transmission,
    /// Component pass (EXR `volume.R/G/B`): light scattered by fog on the camera ray.
    Volume,
}

impl Pass {
    /// The component passes, in the order of `FrameBuffers::components`.
    pub const COMPONENTS: [Pass; 6] = [
        Pass::Emission,
        Pass::DiffuseDirect,
        Pass::DiffuseIndirect,
        Pass::Specular,
        Pass::Transmission,
        Pass::Volume,
    ];

    /// The camera-space passes, derived from the centre-sample passes when written
    /// ([`crate::camera_space`]).
    pub const CAMERA_SPACE: [Pass; 3] =
        [Pass::CameraDepth, Pass::CameraNormal, Pass::CameraPosition];

    /// The pass that writes this one's EXR channels too, and those channels (`Z` of
    /// `Depth` and `CameraDepth`, `N.X N.Y N.Z` of `Normal` and `CameraNormal`): one file
    /// cannot hold both.
    pub fn same_channels_as(&self) -> Option<(Pass, &'static str)> {
        match self {
            Pass::Depth => Some((Pass::CameraDepth, "channel Z")),
            Pass::CameraDepth => Some((Pass::Depth, "channel Z")),
            Pass::Normal => Some((Pass::CameraNormal, "channels N.X N.Y N.Z")),
            Pass::CameraNormal => Some((Pass::Normal, "channels N.X N.Y N.Z")),
            _ => None,
        }
    }

    /// For a component pass: its index in [`Pass::COMPONENTS`] and its EXR layer name.
    pub fn component(&self) -> Option<(usize, &'static str)> {
        let name = match self {
            Pass::Emission => "emission",
            Pass::DiffuseDirect => "diffuse_direct",
            Pass::DiffuseIndirect => "diffuse_indirect",
            Pass::Specular => "specular",
            Pass::Transmission => "transmission",
            Pass::Volume => "volume",
            _ => return None,
        };
        let index = Pass::COMPONENTS.iter().position(|p| p == self)?;
        Some((index, name))
    }
}

/// File formats for outputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// 8-bit sRGB PNG (beauty + alpha only).
    Png,
    /// OpenEXR, linear, with layers for every requested pass.
    Exr,
    /// SVG vector drawing of the contour lines (no passes).
    Svg,
    /// Encapsulated PostScript drawing of the contour lines (no passes).
    Eps,
}

/// One output file of a camera.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputSpec {
    /// Destination path (relative paths resolve against the working directory).
    pub path: PathBuf,
    /// File format.
    pub format: ImageFormat,
    /// Passes written into the file.
    pub passes: Vec<Pass>,
    /// Whether `Beauty` brings the coverage as the EXR channel `A` (the `Alpha` pass always
    /// writes it; PNG files write alpha only with the `Alpha` pass).
    pub beauty_alpha: bool,
}

/// Where a camera's outputs name their files in the scene (`file:line:column` of each
/// output's `file`, parallel to [`Camera::outputs`]), for messages about an output path.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct OutputLinks(pub Vec<super::SourceLink>);

/// Where a camera's resolution is written (its width: the first number of RON's
/// `resolution`, `.mi`'s `resolution`, RIB's `Format`), or the camera itself when the
/// resolution is the default, so that a refusal of the frame's size points at the value to
/// change.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ResolutionLink(pub super::SourceLink);

impl OutputSpec {
    /// Whether its EXR file holds the coverage as channel `A`: with the `Alpha` pass, or
    /// with `Beauty` unless `beauty_alpha` is false.
    pub fn exr_alpha(&self) -> bool {
        self.passes.contains(&Pass::Alpha)
            || self.beauty_alpha && self.passes.contains(&Pass::Beauty)
    }

    /// Whether the file stores colour beside an alpha channel as straight (unassociated)
    /// colour: a PNG with `Beauty` and `Alpha` (EXR keeps premultiplied colour).
    pub fn writes_straight_alpha(&self) -> bool {
        self.format == ImageFormat::Png
            && self.passes.contains(&Pass::Beauty)
            && self.passes.contains(&Pass::Alpha)
    }
}

/// A pinhole camera looking down its local −Z axis, +Y up.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// Camera-to-world placement (rigid).
    pub world_from_camera: Affine3A,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Image aspect ratio (width / height of the image plane); `width / height` for square
    /// pixels.
    pub aspect: f32,
    /// Files to write.
    pub outputs: Vec<OutputSpec>,
    /// Camera-space length of one world unit, the unit of the `CameraDepth` and
    /// `CameraPosition` passes (1; a RIB camera transformation's uniform scale).
    pub space_scale: f32,
}

/// Marks the camera named by the scene's `render` entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderCamera;

/// Camera-to-world transform of a camera at `eye` looking at `target` with `up` roughly up:
/// the camera's −Z points at the target, +Y toward `up`. `None` when the directions are
/// degenerate (eye = target, or `up` parallel to the view direction).
pub fn world_from_look_at(eye: glam::Vec3, target: glam::Vec3, up: glam::Vec3) -> Option<Affine3A> {
    let forward = (target - eye).try_normalize()?;
    let right = forward.cross(up).try_normalize()?;
    let true_up = right.cross(forward);
    Some(Affine3A::from_cols(
        right.into(),
        true_up.into(),
        (-forward).into(),
        eye.into(),
    ))
}

/// A lens shader: changes the primary rays of a camera. Lenses chain in list order, each
/// receiving the camera-space ray the previous one produced (the first receives the
/// pinhole ray).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lens {
    /// Thin-lens depth of field: rays start on a disk of `radius` and meet where the ray
    /// they replace reaches the focus surface — the plane `focus_distance` in front of the
    /// camera after the pinhole projection, the sphere of that radius around the camera
    /// after a `Fisheye` or `Spherical` projection.
    ThinLens {
        /// Aperture radius, metres (> 0).
        radius: f32,
        /// Distance to the plane (or sphere) in focus, metres (> 0).
        focus_distance: f32,
    },
    /// Equidistant fisheye projection: the angle from the view axis grows linearly with the
    /// distance from the image centre, reaching `fov / 2` at the top and bottom edges (same
    /// horizontal scale, so the image circle of a square image touches all four edges).
    /// Film positions beyond 180° from the axis see nothing.
    Fisheye {
        /// Full field of view across the image height, radians, in (0, 2π].
        fov: f32,
    },
    /// Lat-long (equirectangular) 360° × 180° projection: azimuth −180°…180° left to right
    /// (0 at the image centre, looking down −Z, +90° toward +X), elevation 90°…−90° top to
    /// bottom.
    Spherical,
    /// Off-axis pinhole: the image window moved by `(x, y)` half-heights of the image plane
    /// (+x right, +y up) — RenderMan's off-centre `ScreenWindow`.
    Shift {
        /// Horizontal shift, half-heights.
        x: f32,
        /// Vertical shift, half-heights.
        y: f32,
    },
}

impl Lens {
    /// Whether the lens replaces the pinhole projection (the direction of each film
    /// position) rather than modifying the incoming ray.
    pub fn is_projection(&self) -> bool {
        matches!(
            self,
            Lens::Fisheye { .. } | Lens::Spherical | Lens::Shift { .. }
        )
    }
}

/// A camera's lens shaders, applied in order (at most one projection, and first).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Lenses(pub Vec<Lens>);

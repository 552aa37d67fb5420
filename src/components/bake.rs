//! Bake requests: textures to bake for one object instance (ambient occlusion, lightmaps,
//! normals, positions, albedo), how large, from which UVs, and where to write them.

use std::path::PathBuf;

/// How the bake resolution is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BakeResolution {
    /// Exactly `width × height` texels.
    Fixed {
        /// Width in texels.
        width: u32,
        /// Height in texels.
        height: u32,
    },
    /// From a texel density: `sqrt(world area / UV area) · texels_per_unit` texels per side,
    /// rounded up to a power of two and clamped to `max_size` (LuxCore's auto size).
    Density {
        /// Texels per world unit.
        texels_per_unit: f32,
        /// Largest side, texels.
        max_size: u32,
    },
}

/// Where the bake's texture coordinates come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UvSource {
    /// The mesh's own UV set (OBJ `vt`); an error when the mesh has none.
    Mesh,
    /// The mesh's UVs when it has them, otherwise generated lightmap UVs.
    MeshOrUnwrap,
    /// Always generate lightmap UVs (unique, non-overlapping; `uvunwrap`).
    Unwrap,
    /// The mesh's second UV set (glTF `TEXCOORD_1`, carried as `SecondUvs`).
    SecondSet,
}

/// What irradiance lightmaps contain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LightmapStore {
    /// Irradiance E in W/m² arriving at the surface.
    Irradiance,
    /// Outgoing diffuse radiance `albedo · E / π`, W/(sr·m²) (radiance × albedo).
    Radiance,
    /// `E / π`: the outgoing radiance of a white diffuse surface (1 under a white sky of
    /// radiance 1), independent of the material.
    IrradianceOverPi,
}

/// Space of baked normals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NormalSpace {
    /// World-space unit normals.
    World,
    /// Relative to the triangle's tangent frame (dP/du, dP/dv, geometric normal).
    Tangent,
}

/// One kind of texture to bake.
#[derive(Debug, Clone, PartialEq)]
pub enum BakeKind {
    /// Ambient occlusion: fraction of cosine-weighted rays that escape within `max_distance`
    /// (1 = fully open).
    AmbientOcclusion {
        /// Rays per texel.
        samples: u32,
        /// Occluders farther than this do not count (world units; infinity = unlimited).
        max_distance: f32,
        /// Also write the bent normal (mean unoccluded direction) as `<instance>_bent_normals`.
        bent_normals: bool,
    },
    /// Irradiance from the scene's lights with shadows, optionally plus diffuse
    /// interreflection.
    Lightmap {
        /// Add indirect (interreflected) light.
        indirect: bool,
        /// Gather rays per texel for the indirect part.
        samples: u32,
        /// Bounces of indirect light.
        max_depth: u32,
        /// Irradiance or radiance × albedo.
        store: LightmapStore,
        /// Multiplies the stored value (a baked glTF's `lightmapFactor` undoes it: its inverse
        /// for a PNG, the EXR's largest value over it for an EXR, `crate::bake::gltf_textures`).
        scale: f32,
    },
    /// Shading normals.
    Normals {
        /// Output space.
        space: NormalSpace,
    },
    /// World-space positions.
    Positions,
    /// Surface albedo (base colour of the material).
    Albedo,
}

impl BakeKind {
    /// The file-name suffix of this kind (`<instance>_<suffix>.<ext>`).
    pub fn suffix(&self) -> &'static str {
        match self {
            BakeKind::AmbientOcclusion { .. } => "ao",
            BakeKind::Lightmap { .. } => "lightmap",
            BakeKind::Normals { .. } => "normals",
            BakeKind::Positions => "positions",
            BakeKind::Albedo => "albedo",
        }
    }
}

/// File format of a baked texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BakeFormat {
    /// OpenEXR, linear f32 RGB.
    Exr,
    /// 8-bit PNG (sRGB-encoded for colour kinds, linear for data kinds).
    Png8,
    /// 16-bit PNG (same encoding rules).
    Png16,
    /// Per-vertex values (`target: Vertices`): a binary PLY copy of the mesh with vertex
    /// colours (`crate::bake::vertex_files`).
    Ply,
}

impl BakeFormat {
    /// File extension.
    pub fn extension(self) -> &'static str {
        match self {
            BakeFormat::Exr => "exr",
            BakeFormat::Png8 | BakeFormat::Png16 => "png",
            BakeFormat::Ply => "ply",
        }
    }

    /// Whether this target is baked per vertex rather than per texel.
    pub fn is_per_vertex(self) -> bool {
        self == BakeFormat::Ply
    }
}

/// One texture of a request.
#[derive(Debug, Clone, PartialEq)]
pub struct BakeTarget {
    /// What to bake.
    pub kind: BakeKind,
    /// File format.
    pub format: BakeFormat,
    /// File name overriding `<instance>_<kind>.<ext>` (relative to the bake output directory).
    pub file: Option<PathBuf>,
    /// Edge-aware texel-space denoising of this output (`crate::bake::denoise`), if asked.
    pub denoise: Option<Denoise>,
}

/// Settings of the texel-space denoiser (an edge-aware à-trous filter that never mixes
/// texels of different UV charts).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Denoise {
    /// À-trous passes (step 1, 2, 4, …), 1 … 8.
    pub passes: u32,
    /// Colour edge-stopping width in standard deviations of the texel's estimated noise
    /// (> 0; larger blurs more across value edges).
    pub sigma_color: f32,
}

impl Default for Denoise {
    fn default() -> Self {
        Self {
            passes: 3,
            sigma_color: 4.0,
        }
    }
}

/// A bake request on an instance entity.
#[derive(Debug, Clone, PartialEq)]
pub struct BakeRequest {
    /// Name used in file names and reports (the instance's scene name).
    pub name: String,
    /// Texture size.
    pub resolution: BakeResolution,
    /// UV source.
    pub uvs: UvSource,
    /// Sample positions per texel (rounded up to a square number).
    pub texel_samples: u32,
    /// Texels of dilation outward from every chart.
    pub padding: u32,
    /// Also write `<instance>_mask.png` (255 where a texel is covered and valid).
    pub mask: bool,
    /// Make AO and lightmap texels continuous across UV seams by a least-squares stitch
    /// after dilation (`crate::bake::stitch`).
    pub stitch_seams: bool,
    /// Textures to bake.
    pub targets: Vec<BakeTarget>,
}

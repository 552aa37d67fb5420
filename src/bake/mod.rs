//! Texture baking: UV sources and bake resolution, texel rasterization with conservative
//! coverage, the per-texel estimators (ambient occlusion, irradiance), dilation and texture
//! encoding; request checking ([`request`]), file naming/encoding ([`files`]) and the baked
//! glTF copy ([`gltf_out`]), the standalone baked glTF of other scenes ([`gltf_export`]; where it puts each
//! instance's vertices: [`gltf_translation`]), the
//! GLB pieces both build with ([`glb_build`]), the PNG each embeds for an AO or lightmap
//! output, EXR ones included ([`gltf_textures`]), and what `--write-gltf` refuses ([`gltf_copy_refusals`]); per-vertex bakes lay vertices out as texels ([`vertices`]) and
//! are written as PLY ([`vertex_files`]); PNG outputs that clip their values are counted for a
//! warning ([`clipping`]). UV seams and charts ([`seams`]) drive the
//! least-squares seam stitch ([`stitch`]) and the chart-respecting texel-space denoiser
//! ([`denoise`]). The `bake_lightmaps` stage drives these.
//!
//! Texel convention: texel `(i, j)` of a `W × H` texture (row `j = 0` at the top of the image)
//! has its centre at `uv = ((i + 0.5) / W, 1 − (j + 0.5) / H)` — OBJ/OpenGL UVs with `v` up.

pub mod ao;
pub mod clipping;
pub mod denoise;
pub mod density;
pub mod dilate;
pub mod files;
pub mod finish;
pub mod glb_build;
pub mod gltf_copy_refusals;
pub mod gltf_export;
pub mod gltf_orphans;
pub mod gltf_out;
pub mod gltf_textures;
pub mod gltf_translation;
pub mod hemisphere_lanes;
pub mod irradiance;
pub mod raster;
pub mod report;
pub mod request;
pub mod seams;
pub mod stitch;
pub mod texels;
pub mod texture;
pub mod uv;
pub mod vertex_files;
pub mod vertices;

pub use raster::{rasterize, Coverage, TexelSample};
pub use report::{BakeReport, SeamReport};
pub use texture::TexelImage;
pub use uv::{bake_resolution, corner_uvs, second_set_corner_uvs, BakeUvError};

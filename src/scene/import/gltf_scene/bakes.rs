//! The default bake request of a glTF scene: every instance of a primitive that has a
//! second UV set (`TEXCOORD_1`, lightmap UVs) bakes, on that set, a lightmap of `E / π`
//! (direct plus two bounces of indirect light; the light a white diffuse surface reflects,
//! which a viewer multiplies by the base colour: 1 under the white environment a glTF without
//! lights gets, where the irradiance E = π would clip an 8-bit PNG to white everywhere),
//! stored at [`LIGHTMAP_SCALE`] (half: the sky's 1 and the estimate's noise around it fit the
//! PNG; the `--write-gltf` copy's `lightmapFactor` of 2 restores E / π), and
//! ambient occlusion into 8-bit PNGs at
//! [`TEXELS_PER_UNIT`] texels per unit (at most [`MAX_SIZE`]); every instance of a primitive
//! without it bakes ambient occlusion per vertex ([`default_vertex_bake`]). `stagelight bake
//! model.glb --write-gltf` puts both back into a copy of the file (textures in the
//! materials, vertex AO as `COLOR_0`).

use super::Walk;
use crate::scene::desc::{
    BakeDesc, BakeFormatDesc, BakeKindDesc, BakeOutputDesc, BakeTargetDesc, LightmapStoreDesc,
    UvsDesc,
};

/// The default lightmap's `scale`: E / π is stored halved, so light up to twice the white
/// sky's (and the noise of its estimate) fits an 8-bit PNG.
pub const LIGHTMAP_SCALE: f64 = 0.5;
/// Texel density of the default bakes (texels per world unit).
pub const TEXELS_PER_UNIT: f64 = 32.0;
/// Largest side of a default bake texture.
pub const MAX_SIZE: u32 = 512;
/// AO rays and indirect gather paths per texel of the default bakes.
pub const SAMPLES: u32 = 64;

/// The default request (see the module header).
pub fn default_bake() -> BakeDesc {
    BakeDesc {
        resolution: None,
        texels_per_unit: Some(TEXELS_PER_UNIT),
        max_size: MAX_SIZE,
        uvs: UvsDesc::MeshSet(1),
        texel_samples: 4,
        padding: 2,
        mask: false,
        stitch_seams: true,
        outputs: vec![
            BakeOutputDesc {
                kind: BakeKindDesc::Lightmap {
                    indirect: true,
                    samples: SAMPLES,
                    max_depth: 2,
                    store: LightmapStoreDesc::IrradianceOverPi,
                    scale: LIGHTMAP_SCALE,
                },
                format: BakeFormatDesc::Png8,
                file: None,
                target: BakeTargetDesc::Texture,
                denoise: None,
            },
            BakeOutputDesc {
                kind: BakeKindDesc::AmbientOcclusion {
                    samples: SAMPLES,
                    max_distance: None,
                    bent_normals: false,
                },
                format: BakeFormatDesc::Png8,
                file: None,
                target: BakeTargetDesc::Texture,
                denoise: None,
            },
        ],
    }
}

/// The default request of a primitive without lightmap UVs: [`SAMPLES`] AO rays per vertex
/// over 4 sample positions, written as `<instance>_ao.ply` (and `COLOR_0` of the copy).
pub fn default_vertex_bake() -> BakeDesc {
    BakeDesc {
        resolution: None,
        texels_per_unit: None,
        max_size: MAX_SIZE,
        uvs: UvsDesc::Auto,
        texel_samples: 4,
        padding: 0,
        mask: false,
        stitch_seams: true,
        outputs: vec![BakeOutputDesc {
            kind: BakeKindDesc::AmbientOcclusion {
                samples: SAMPLES,
                max_distance: None,
                bent_normals: false,
            },
            format: BakeFormatDesc::Ply,
            file: None,
            target: BakeTargetDesc::Vertices,
            denoise: None,
        }],
    }
}

/// Gives every primitive instance with `TEXCOORD_1` the default request, and every other
/// one the default per-vertex request.
pub fn default_bakes(w: &mut Walk<'_>) {
    for (name, node, p) in &w.leaves {
        let Some(prim) = w
            .file
            .doc
            .nodes()
            .nth(*node)
            .and_then(|n| n.mesh())
            .and_then(|m| m.primitives().nth(*p))
        else {
            continue;
        };
        let bake = if prim.get(&gltf::Semantic::TexCoords(1)).is_some() {
            default_bake()
        } else {
            default_vertex_bake()
        };
        if let Some(inst) = w.desc.instances.iter_mut().find(|i| &i.name == name) {
            inst.bake = Some(bake);
        }
    }
}

//! Baked glTF: a copy of a glTF scene as one `.glb` whose materials reference the baked
//! textures (`stagelight bake model.glb --write-gltf`).
//!
//! For every baked primitive instance (node, primitive) the copy gets its own material — a
//! clone of the primitive's material (or of glTF's default material) — with the ambient
//! occlusion as `occlusionTexture` and the lightmap as the `MSFT_lightmap` extension's
//! `lightmapTexture`, both on `TEXCOORD_1`, and the node gets its own copy of the mesh
//! (sharing the accessors) pointing at that material; the last user of a mesh (material)
//! takes the original, so none is left unused. The textures are the baked PNG files,
//! byte for byte, embedded as buffer views. All buffers are merged into the one `BIN` chunk
//! and images the source kept in files or `data:` URIs are embedded too, so the copy stands
//! alone. Per-vertex bakes become the primitive's `COLOR_0` (float RGB, [`color_source`]
//! picks which); what a replacement leaves unreferenced (an earlier bake's textures in a
//! baked copy baked again, a replaced `COLOR_0`) goes ([`super::gltf_orphans`]). The JSON is edited as JSON, so everything the reader does not map (animations,
//! skins, extensions) is kept as it was; a top-level array left empty (`images` when every
//! bake is per vertex) is left out, as glTF requires of a defined array (≥ 1 item).

use std::path::Path;

use serde_json::{json, Value};

pub use super::glb_build::TextureSlot;
use super::glb_build::{
    add_float_accessor, add_view, encode_glb, list, pad4, use_lightmap_extension, wire_texture,
};
use super::gltf_orphans::Orphans;
use crate::scene::mesh_files::gltf_file;

/// One baked texture of one primitive instance.
pub struct BakedTexture<'a> {
    /// glTF node index.
    pub node: usize,
    /// Primitive index within the node's mesh.
    pub primitive: usize,
    /// Where the texture goes.
    pub slot: TextureSlot,
    /// The encoded PNG.
    pub png: &'a [u8],
}

/// Per-vertex baked values of one primitive instance, written as its `COLOR_0`.
pub struct BakedColors {
    /// glTF node index.
    pub node: usize,
    /// Primitive index within the node's mesh.
    pub primitive: usize,
    /// One linear RGB value per vertex of the primitive, in [0, 1].
    pub values: Vec<glam::Vec3>,
}

/// The values that become `COLOR_0` among one request's per-vertex targets: the ambient
/// occlusion, else the first lightmap or albedo, clamped to [0, 1] (`COLOR_0` multiplies
/// the base colour); `None` when the request baked none of these.
pub fn color_source(
    targets: &[(crate::components::BakeKind, Vec<glam::Vec3>)],
) -> Option<Vec<glam::Vec3>> {
    use crate::components::BakeKind;
    let ao = targets
        .iter()
        .find(|(k, _)| matches!(k, BakeKind::AmbientOcclusion { .. }));
    let colour = || {
        targets
            .iter()
            .find(|(k, _)| matches!(k, BakeKind::Lightmap { .. } | BakeKind::Albedo))
    };
    let (kind, values) = ao.or_else(colour)?;
    // A lightmap stored at a `scale` other than 1 is undone: `COLOR_0` has no factor.
    let unscale = match kind {
        BakeKind::Lightmap { scale, .. } => 1.0 / scale,
        _ => 1.0,
    };
    Some(
        values
            .iter()
            .map(|v| (*v * unscale).clamp(glam::Vec3::ZERO, glam::Vec3::ONE))
            .map(|v| if v.is_nan() { glam::Vec3::ZERO } else { v })
            .collect(),
    )
}

/// The index of node `node`'s own copy of its mesh (made on first use): the mesh itself when
/// no other node shows it (so the last of the nodes sharing a mesh takes it, and no mesh is
/// left unused), else a copy.
fn mesh_copy(
    json: &mut Value,
    node_mesh: &mut Vec<(usize, usize)>,
    node: usize,
) -> Result<usize, String> {
    if let Some(&(_, m)) = node_mesh.iter().find(|(n, _)| *n == node) {
        return Ok(m);
    }
    let Some(mesh) = json["nodes"][node]["mesh"].as_u64() else {
        return Err(format!("nodes[{node}] has no mesh"));
    };
    let users = list(json, "nodes")
        .iter()
        .filter(|n| n["mesh"].as_u64() == Some(mesh))
        .count();
    if users == 1 {
        node_mesh.push((node, mesh as usize));
        return Ok(mesh as usize);
    }
    let copy = json["meshes"][mesh as usize].clone();
    let meshes = list(json, "meshes");
    meshes.push(copy);
    let m = meshes.len() - 1;
    json["nodes"][node]["mesh"] = json!(m);
    node_mesh.push((node, m));
    Ok(m)
}

/// How many primitives of the file's meshes use material `m`.
fn material_users(json: &Value, m: u64) -> usize {
    json["meshes"].as_array().map_or(0, |meshes| {
        meshes
            .iter()
            .filter_map(|mesh| mesh["primitives"].as_array())
            .flatten()
            .filter(|p| p["material"].as_u64() == Some(m))
            .count()
    })
}

/// Adds `c.values` as a float VEC3 accessor and makes it `COLOR_0` of the primitive in the
/// mesh copy `mesh` (replacing any `COLOR_0` it had: the new accessor takes its index when
/// nothing else uses it). The count must be the primitive's vertex count.
fn add_colors(
    json: &mut Value,
    bin: &mut Vec<u8>,
    orphans: &mut Orphans,
    mesh: usize,
    c: &BakedColors,
) -> Result<(), String> {
    let prim = &json["meshes"][mesh]["primitives"][c.primitive];
    let at = || format!("nodes[{}] primitive {}", c.node, c.primitive);
    let Some(position) = prim["attributes"]["POSITION"].as_u64() else {
        return Err(format!("{}: no POSITION attribute", at()));
    };
    let count = json["accessors"][position as usize]["count"].as_u64();
    if count != Some(c.values.len() as u64) {
        return Err(format!(
            "{}: {} baked vertex values for {} vertices",
            at(),
            c.values.len(),
            count.unwrap_or(0)
        ));
    }
    let replaced = prim["attributes"]["COLOR_0"].as_u64();
    let values: Vec<[f32; 3]> = c.values.iter().map(|v| v.to_array()).collect();
    let accessor = add_float_accessor(json, bin, &values, "VEC3", true, None);
    json["meshes"][mesh]["primitives"][c.primitive]["attributes"]["COLOR_0"] = json!(accessor);
    if let Some(replaced) = replaced {
        let attributes = format!("/meshes/{mesh}/primitives/{}/attributes", c.primitive);
        orphans.reuse_accessor(json, replaced as usize, &attributes);
    }
    Ok(())
}

fn mime(bytes: &[u8]) -> &'static str {
    if bytes.starts_with(&[0xff, 0xd8]) {
        "image/jpeg"
    } else {
        "image/png"
    }
}

/// The source file's JSON chunk (or whole JSON text) as a value.
fn source_json(bytes: &[u8]) -> Result<Value, String> {
    let text = if bytes.starts_with(b"glTF") {
        let len = u32::from_le_bytes([bytes[12], bytes[13], bytes[14], bytes[15]]) as usize;
        &bytes[20..20 + len]
    } else {
        bytes
    };
    serde_json::from_slice(text).map_err(|e| format!("invalid glTF JSON: {e}"))
}

/// Whether `--write-gltf` of `scene` writes the copy of a glTF file (a `.gltf` or `.glb`,
/// in any case) rather than the standalone file of another scene
/// ([`super::gltf_export`]).
pub fn is_gltf_scene(scene: &Path) -> bool {
    let ext = scene
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    matches!(ext.as_deref(), Some("gltf" | "glb"))
}

/// Where `bake --write-gltf` of `source` writes its baked glTF (the copy of a glTF scene, or
/// the standalone file of another scene): `<dir>/<stem>.glb`.
pub fn baked_glb_path(source: &std::path::Path, dir: &std::path::Path) -> std::path::PathBuf {
    let stem = source.file_stem().unwrap_or_default().to_string_lossy();
    dir.join(format!("{stem}.glb"))
}

/// The baked copy of the glTF file at `source` (read again; its buffers beside it) as GLB
/// bytes, with `textures` referenced by the materials and `colors` as the baked
/// primitives' `COLOR_0`.
pub fn baked_glb(
    source: &Path,
    textures: &[BakedTexture<'_>],
    colors: &[BakedColors],
) -> Result<Vec<u8>, String> {
    let bytes = crate::limits::read_file(source, crate::limits::MAX_MESH_FILE_BYTES, "glTF file")
        .map_err(|e| crate::scene::message::io_reason(&e))?;
    let file = gltf_file::open(&bytes, source.parent()).map_err(|e| e.to_string())?;
    let mut json = source_json(&bytes)?;
    // One BIN: every buffer, 4-aligned, views re-pointed.
    let mut bin = Vec::new();
    let mut base = Vec::new();
    for data in &file.buffers {
        pad4(&mut bin, 0);
        base.push(bin.len());
        bin.extend_from_slice(data);
    }
    for view in list(&mut json, "bufferViews").iter_mut() {
        let buffer = view["buffer"].as_u64().unwrap_or(0) as usize;
        let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
        view["buffer"] = json!(0);
        view["byteOffset"] = json!(base.get(buffer).copied().unwrap_or(0) + offset);
    }
    // Images kept in files or data URIs are embedded.
    let image_count = list(&mut json, "images").len();
    for i in 0..image_count {
        let Some(uri) = json["images"][i]["uri"].as_str().map(str::to_string) else {
            continue;
        };
        let data = gltf_file::uri_bytes(&uri, source.parent(), &format!("images[{i}]"))
            .map_err(|e| e.to_string())?;
        let view = add_view(&mut json, &mut bin, &data);
        let image = &mut json["images"][i];
        if let Some(o) = image.as_object_mut() {
            o.remove("uri");
        }
        image["bufferView"] = json!(view);
        image["mimeType"] = json!(mime(&data));
    }
    // Per baked node: a copy of its mesh; per baked primitive: a copy of its material.
    let mut node_mesh: Vec<(usize, usize)> = Vec::new();
    let mut prim_material: Vec<((usize, usize), usize)> = Vec::new();
    let mut lightmaps = false;
    let mut orphans = Orphans::default();
    for c in colors {
        let mesh_copy = mesh_copy(&mut json, &mut node_mesh, c.node)?;
        add_colors(&mut json, &mut bin, &mut orphans, mesh_copy, c)?;
    }
    for t in textures {
        let mesh_copy = mesh_copy(&mut json, &mut node_mesh, t.node)?;
        let key = (t.node, t.primitive);
        let material = match prim_material.iter().find(|(k, _)| *k == key) {
            Some(&(_, m)) => m,
            None => {
                let prim = &json["meshes"][mesh_copy]["primitives"][t.primitive];
                if prim.is_null() {
                    return Err(format!(
                        "nodes[{}]: the mesh has no primitive {}",
                        t.node, t.primitive
                    ));
                }
                let m = match prim["material"].as_u64() {
                    // The material itself when no other primitive uses it (none is left
                    // unused), else a copy.
                    Some(m) if material_users(&json, m) == 1 => m as usize,
                    source => {
                        let copy = match source {
                            Some(m) => json["materials"][m as usize].clone(),
                            None => json!({"name": "default"}),
                        };
                        let materials = list(&mut json, "materials");
                        materials.push(copy);
                        materials.len() - 1
                    }
                };
                json["meshes"][mesh_copy]["primitives"][t.primitive]["material"] = json!(m);
                prim_material.push((key, m));
                m
            }
        };
        let reference = match t.slot {
            TextureSlot::Occlusion => format!("/materials/{material}/occlusionTexture"),
            TextureSlot::Lightmap { .. } => {
                format!("/materials/{material}/extensions/MSFT_lightmap/lightmapTexture")
            }
        };
        let replaced = json.pointer(&reference).and_then(|t| t["index"].as_u64());
        lightmaps |= wire_texture(&mut json, &mut bin, material, t.slot, t.png);
        if let Some(replaced) = replaced {
            orphans.reuse_texture(&mut json, replaced as usize, &reference);
        }
    }
    if lightmaps {
        use_lightmap_extension(&mut json);
    }
    orphans.drop(&mut json, &mut bin);
    encode_glb(json, bin)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gltf_and_glb_scenes_are_copied_in_any_case_of_extension() {
        for copied in ["a.gltf", "dir/b.GLB", "c.Gltf"] {
            assert!(is_gltf_scene(Path::new(copied)), "{copied}");
        }
        for exported in ["a.ron", "b.rib", "c", "d.glb.ron", "e.mi"] {
            assert!(!is_gltf_scene(Path::new(exported)), "{exported}");
        }
    }
}

//! The pieces both baked glTF writers share: the glTF JSON and its one binary buffer as they
//! are built (buffer views, accessors, embedded PNG textures wired into a material's
//! occlusion or `MSFT_lightmap` slot) and the GLB container they are written in. The copy of
//! a glTF scene ([`super::gltf_out`]) and the standalone file of any other scene
//! ([`super::gltf_export`]) write textures, factors and the extension the same way.

use serde_json::{json, Value};

use crate::components::BakeKind;

/// Which material slot a baked texture fills.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TextureSlot {
    /// `occlusionTexture` (red channel, `TEXCOORD_1`).
    Occlusion,
    /// `extensions.MSFT_lightmap.lightmapTexture` (`TEXCOORD_1`), with the `lightmapFactor`
    /// a viewer multiplies it by (the inverse of the bake's `scale`).
    Lightmap {
        /// The `lightmapFactor` of each channel.
        factor: f64,
    },
}

impl TextureSlot {
    /// The slot a PNG of bake kind `kind` fills: ambient occlusion the occlusion texture, a
    /// lightmap the `MSFT_lightmap` texture (factor `1 / scale`); other kinds none.
    pub fn of(kind: &BakeKind) -> Option<TextureSlot> {
        match kind {
            BakeKind::AmbientOcclusion { .. } => Some(TextureSlot::Occlusion),
            BakeKind::Lightmap { scale, .. } => Some(TextureSlot::Lightmap {
                factor: 1.0 / f64::from(*scale),
            }),
            _ => None,
        }
    }
}

/// The `bufferView` target of vertex attributes (`ARRAY_BUFFER`).
pub const ARRAY_BUFFER: u32 = 34962;
/// The `bufferView` target of indices (`ELEMENT_ARRAY_BUFFER`).
pub const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Pads `bytes` with `fill` to a multiple of 4.
pub fn pad4(bytes: &mut Vec<u8>, fill: u8) {
    while !bytes.len().is_multiple_of(4) {
        bytes.push(fill);
    }
}

/// Appends `data` to `bin` as a new buffer view of buffer 0; returns its index.
pub fn add_view(json: &mut Value, bin: &mut Vec<u8>, data: &[u8]) -> usize {
    add_view_for(json, bin, data, None)
}

/// [`add_view`] with the view's `target` (vertex attributes or indices) when given.
pub fn add_view_for(
    json: &mut Value,
    bin: &mut Vec<u8>,
    data: &[u8],
    target: Option<u32>,
) -> usize {
    pad4(bin, 0);
    let offset = bin.len();
    bin.extend_from_slice(data);
    let mut view = json!({"buffer": 0, "byteOffset": offset, "byteLength": data.len()});
    if let Some(t) = target {
        view["target"] = json!(t);
    }
    let views = list(json, "bufferViews");
    views.push(view);
    views.len() - 1
}

/// Adds `values` (each of `N` floats) as a float accessor of type `kind` (`VEC2`, `VEC3`)
/// in a view of its own, with its `min` and `max` when `bounds`; returns its index.
pub fn add_float_accessor<const N: usize>(
    json: &mut Value,
    bin: &mut Vec<u8>,
    values: &[[f32; N]],
    kind: &str,
    bounds: bool,
    target: Option<u32>,
) -> usize {
    let mut data = Vec::with_capacity(values.len() * N * 4);
    let (mut lo, mut hi) = ([f32::INFINITY; N], [f32::NEG_INFINITY; N]);
    for v in values {
        for (k, x) in v.iter().enumerate() {
            lo[k] = lo[k].min(*x);
            hi[k] = hi[k].max(*x);
            data.extend_from_slice(&x.to_le_bytes());
        }
    }
    let view = add_view_for(json, bin, &data, target);
    let mut accessor = json!({
        "bufferView": view,
        "componentType": 5126,
        "count": values.len(),
        "type": kind,
    });
    if bounds {
        accessor["min"] = json!(lo.as_slice());
        accessor["max"] = json!(hi.as_slice());
    }
    let accessors = list(json, "accessors");
    accessors.push(accessor);
    accessors.len() - 1
}

/// Embeds `png` as an image and texture and puts it in material `material`'s `slot`, on
/// `TEXCOORD_1`. Returns whether the slot is the `MSFT_lightmap` extension's (the caller
/// then lists it with [`use_lightmap_extension`]).
pub fn wire_texture(
    json: &mut Value,
    bin: &mut Vec<u8>,
    material: usize,
    slot: TextureSlot,
    png: &[u8],
) -> bool {
    let view = add_view(json, bin, png);
    let images = list(json, "images");
    images.push(json!({"bufferView": view, "mimeType": "image/png"}));
    let image = images.len() - 1;
    let textures = list(json, "textures");
    textures.push(json!({"source": image}));
    let texture = textures.len() - 1;
    let reference = json!({"index": texture, "texCoord": 1});
    let m = &mut json["materials"][material];
    match slot {
        TextureSlot::Occlusion => {
            m["occlusionTexture"] = reference;
            false
        }
        TextureSlot::Lightmap { factor } => {
            if !m["extensions"].is_object() {
                m["extensions"] = json!({});
            }
            m["extensions"]["MSFT_lightmap"] =
                json!({"lightmapTexture": reference, "lightmapFactor": [factor, factor, factor]});
            true
        }
    }
}

/// Lists `MSFT_lightmap` in `extensionsUsed` (not `extensionsRequired`: loaders that do not
/// know it still load the file).
pub fn use_lightmap_extension(json: &mut Value) {
    let used = list(json, "extensionsUsed");
    if !used.iter().any(|e| e == "MSFT_lightmap") {
        used.push(json!("MSFT_lightmap"));
    }
}

/// The array `json[key]`, created empty when missing.
pub fn list<'a>(json: &'a mut Value, key: &str) -> &'a mut Vec<Value> {
    if !json[key].is_array() {
        json[key] = json!([]);
    }
    json[key].as_array_mut().expect("made an array")
}

/// The GLB file of `json` and its binary buffer `bin` (buffer 0): sets `buffers` (none when
/// `bin` is empty: a buffer's `byteLength` is at least 1), leaves out empty top-level arrays
/// and writes the header, the JSON chunk and the `BIN` chunk.
pub fn encode_glb(mut json: Value, mut bin: Vec<u8>) -> Result<Vec<u8>, String> {
    pad4(&mut bin, 0);
    if bin.is_empty() {
        json["buffers"] = json!([]);
    } else {
        json["buffers"] = json!([{"byteLength": bin.len()}]);
    }
    drop_empty_arrays(&mut json);
    let mut text = serde_json::to_vec(&json).map_err(|e| e.to_string())?;
    pad4(&mut text, b' ');
    let bin_chunk = if bin.is_empty() { 0 } else { 8 + bin.len() };
    let total = 12 + 8 + text.len() + bin_chunk;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
    }
    Ok(out)
}

/// Removes every top-level array of `json` that holds nothing (`"images": []`): glTF
/// requires a defined array to have at least one item (the Khronos validator's
/// `EMPTY_ENTITY`).
fn drop_empty_arrays(json: &mut Value) {
    if let Some(o) = json.as_object_mut() {
        o.retain(|_, v| v.as_array().is_none_or(|a| !a.is_empty()));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_top_level_arrays_are_left_out() {
        let mut json = json!({
            "asset": {"version": "2.0"},
            "images": [],
            "textures": [],
            "meshes": [{"primitives": []}],
            "extensionsUsed": [],
        });
        drop_empty_arrays(&mut json);
        assert_eq!(
            json,
            json!({"asset": {"version": "2.0"}, "meshes": [{"primitives": []}]})
        );
    }

    #[test]
    fn a_float_accessor_has_its_bounds_and_a_four_aligned_view() {
        let mut json = json!({});
        let mut bin = vec![1u8];
        let a = add_float_accessor(
            &mut json,
            &mut bin,
            &[[1.0, -2.0], [0.5, 3.0]],
            "VEC2",
            true,
            Some(ARRAY_BUFFER),
        );
        assert_eq!(a, 0);
        assert_eq!(json["accessors"][0]["min"], json!([0.5, -2.0]));
        assert_eq!(json["accessors"][0]["max"], json!([1.0, 3.0]));
        assert_eq!(
            json["bufferViews"][0],
            json!({"buffer": 0, "byteOffset": 4, "byteLength": 16, "target": ARRAY_BUFFER})
        );
        assert_eq!(bin.len(), 20);
    }
}

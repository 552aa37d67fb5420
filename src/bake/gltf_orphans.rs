//! What a baked glTF copy's replacements leave unused, and only that: the texture, image,
//! sampler and accessor a baked texture or `COLOR_0` replaces, and their buffer views with
//! their bytes, once nothing in the file references them any more (a re-bake of a baked
//! copy replaces the earlier bake's textures; a user's own occlusion texture replaced by the
//! bake goes the same way). Anything the file references elsewhere stays, and so does what
//! the source file itself held unreferenced.
//!
//! Replaced textures, images and accessors are not removed but reused: the bake's new one
//! takes the replaced one's index (it was added last, so nothing is renumbered), which
//! keeps every reference an extension may hold to the others valid. Buffer views are
//! removed ([`drop_views`]) and renumbered at every `bufferView` member, and samplers at
//! the textures' `sampler`; the views' bytes leave the buffer with the padding after them
//! (a multiple of 4 bytes, so every later view keeps its alignment).

use serde_json::Value;

/// The number of members `key` with value `index` in `json`, outside `extras` (which hold
/// application data, not glTF references).
fn count_key(json: &Value, key: &str, index: usize) -> usize {
    match json {
        Value::Object(o) => o
            .iter()
            .filter(|(k, _)| *k != "extras")
            .map(|(k, v)| {
                usize::from(k == key && v.as_u64() == Some(index as u64)) + count_key(v, key, index)
            })
            .sum(),
        Value::Array(a) => a.iter().map(|v| count_key(v, key, index)).sum(),
        _ => 0,
    }
}

/// Every integer in `json` equal to `index` (outside `extras`).
fn count_numbers(json: &Value, index: usize) -> usize {
    match json {
        Value::Object(o) => o
            .iter()
            .filter(|(k, _)| *k != "extras")
            .map(|(_, v)| count_numbers(v, index))
            .sum(),
        Value::Array(a) => a.iter().map(|v| count_numbers(v, index)).sum(),
        v => usize::from(v.as_u64() == Some(index as u64)),
    }
}

/// The references to accessor `a`: the primitives' attributes, morph targets and indices,
/// the skins' inverse bind matrices and the animation samplers' input and output, and —
/// to be safe — any number equal to `a` in the extensions of a node, mesh or primitive
/// (instancing attributes, compressed meshes).
fn accessor_refs(json: &Value, a: usize) -> usize {
    let is = |v: &Value| usize::from(v.as_u64() == Some(a as u64));
    let values = |v: &Value| v.as_object().map_or(0, |o| o.values().map(is).sum());
    let items = |key: &str| json[key].as_array().map_or(&[][..], Vec::as_slice);
    let mut n = 0;
    for mesh in items("meshes") {
        n += count_numbers(&mesh["extensions"], a);
        for p in mesh["primitives"].as_array().into_iter().flatten() {
            n += values(&p["attributes"]) + is(&p["indices"]);
            n += p["targets"]
                .as_array()
                .map_or(0, |t| t.iter().map(values).sum());
            n += count_numbers(&p["extensions"], a);
        }
    }
    for node in items("nodes") {
        n += count_numbers(&node["extensions"], a);
    }
    for skin in items("skins") {
        n += is(&skin["inverseBindMatrices"]);
    }
    for animation in items("animations") {
        for s in animation["samplers"].as_array().into_iter().flatten() {
            n += is(&s["input"]) + is(&s["output"]);
        }
    }
    n
}

/// The buffer views accessor `accessor` reads (its own and its sparse parts').
fn accessor_views(accessor: &Value) -> Vec<usize> {
    [
        &accessor["bufferView"],
        &accessor["sparse"]["indices"]["bufferView"],
        &accessor["sparse"]["values"]["bufferView"],
    ]
    .into_iter()
    .filter_map(|v| v.as_u64().map(|v| v as usize))
    .collect()
}

/// What the replacements of one copy orphaned so far: buffer views and samplers that go
/// when nothing references them at the end ([`Orphans::drop`]).
#[derive(Debug, Default)]
pub struct Orphans {
    views: Vec<usize>,
    samplers: Vec<usize>,
}

impl Orphans {
    /// After the bake's texture was added as the last texture and made the reference at
    /// the JSON pointer `reference` (a texture info, such as a material's
    /// `/materials/0/occlusionTexture`), the texture `replaced` it referenced before: when
    /// nothing references that now, the new texture (and its image, when the replaced
    /// texture's image is unused too) takes its index.
    pub fn reuse_texture(&mut self, json: &mut Value, replaced: usize, reference: &str) {
        let textures = json["textures"].as_array().map_or(0, Vec::len);
        if textures == 0 || replaced >= textures - 1 || count_key(json, "index", replaced) != 0 {
            return;
        }
        let old = json["textures"][replaced].take();
        let mut texture = json["textures"]
            .as_array_mut()
            .and_then(Vec::pop)
            .expect("the new texture");
        if let Some(info) = json.pointer_mut(reference) {
            info["index"] = replaced.into();
        }
        if let Some(s) = old["sampler"].as_u64() {
            self.samplers.push(s as usize);
        }
        // The old texture's image, unless another texture (or one of its extensions) shows it.
        if let Some(image) = old["source"].as_u64().map(|i| i as usize) {
            json["textures"][replaced] = Value::Null;
            let images = json["images"].as_array().map_or(0, Vec::len);
            let unused = count_key(json, "source", image) == 0;
            if unused && image < images - 1 && texture["source"].as_u64() == Some(images as u64 - 1)
            {
                let old_image = json["images"][image].take();
                let new_image = json["images"]
                    .as_array_mut()
                    .and_then(Vec::pop)
                    .expect("the new image");
                json["images"][image] = new_image;
                texture["source"] = image.into();
                if let Some(v) = old_image["bufferView"].as_u64() {
                    self.views.push(v as usize);
                }
            }
        }
        json["textures"][replaced] = texture;
    }

    /// After the bake's colours were added as the last accessor and made a primitive's
    /// `COLOR_0` (`attributes`: the JSON pointer of its attributes), the accessor `replaced`
    /// it had before: when nothing references it now, the new accessor takes its index.
    pub fn reuse_accessor(&mut self, json: &mut Value, replaced: usize, attributes: &str) {
        let accessors = json["accessors"].as_array().map_or(0, Vec::len);
        if accessors == 0 || replaced >= accessors - 1 || accessor_refs(json, replaced) != 0 {
            return;
        }
        let accessor = json["accessors"]
            .as_array_mut()
            .and_then(Vec::pop)
            .expect("the new accessor");
        let old = std::mem::replace(&mut json["accessors"][replaced], accessor);
        self.views.extend(accessor_views(&old));
        if let Some(a) = json.pointer_mut(attributes) {
            a["COLOR_0"] = replaced.into();
        }
    }

    /// Removes the orphaned samplers and buffer views that nothing references (and the
    /// views' bytes from `bin`, with the padding after them), renumbering the references
    /// to the others.
    pub fn drop(mut self, json: &mut Value, bin: &mut Vec<u8>) {
        self.samplers.sort_unstable();
        self.samplers.dedup();
        let unused_samplers: Vec<usize> = self
            .samplers
            .into_iter()
            .filter(|&s| {
                json["textures"]
                    .as_array()
                    .is_none_or(|t| !t.iter().any(|t| t["sampler"].as_u64() == Some(s as u64)))
            })
            .collect();
        remove_items(json, "samplers", &unused_samplers);
        for t in items_mut(json, "textures") {
            if let Some(s) = t["sampler"].as_u64() {
                t["sampler"] = renumbered(s as usize, &unused_samplers).into();
            }
        }
        self.views.sort_unstable();
        self.views.dedup();
        let unused: Vec<usize> = self
            .views
            .into_iter()
            .filter(|&v| count_key(json, "bufferView", v) == 0)
            .collect();
        drop_views(json, bin, &unused);
    }
}

/// The items of the top-level array `key` (none when it is missing: nothing is added).
fn items_mut<'a>(json: &'a mut Value, key: &str) -> impl Iterator<Item = &'a mut Value> {
    json.get_mut(key)
        .and_then(Value::as_array_mut)
        .into_iter()
        .flatten()
}

/// `index` after removing the items `removed` (sorted) before it.
fn renumbered(index: usize, removed: &[usize]) -> usize {
    index - removed.iter().filter(|&&r| r < index).count()
}

/// Removes the items `removed` (sorted, unique) of the top-level array `key`.
fn remove_items(json: &mut Value, key: &str, removed: &[usize]) {
    if let Some(items) = json.get_mut(key).and_then(Value::as_array_mut) {
        for &r in removed.iter().rev() {
            if r < items.len() {
                items.remove(r);
            }
        }
    }
}

/// Renumbers every `bufferView` member of `json` (outside `extras`) past the `removed` views.
fn renumber_views(json: &mut Value, removed: &[usize]) {
    match json {
        Value::Object(o) => {
            for (k, v) in o.iter_mut().filter(|(k, _)| *k != "extras") {
                match v.as_u64() {
                    Some(i) if k == "bufferView" => *v = renumbered(i as usize, removed).into(),
                    _ => renumber_views(v, removed),
                }
            }
        }
        Value::Array(a) => a.iter_mut().for_each(|v| renumber_views(v, removed)),
        _ => {}
    }
}

/// A view's bytes in the buffer: `[offset, end)`.
fn view_range(view: &Value) -> (usize, usize) {
    let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
    (
        offset,
        offset + view["byteLength"].as_u64().unwrap_or(0) as usize,
    )
}

/// Removes the buffer views `removed` (sorted, unique; nothing references them) and their
/// bytes — those no other view covers, with the uncovered padding after them, a multiple
/// of 4 bytes — from `bin` (every view is in buffer 0, `bin`), moving the later views.
pub fn drop_views(json: &mut Value, bin: &mut Vec<u8>, removed: &[usize]) {
    if removed.is_empty() {
        return;
    }
    let views = json["bufferViews"].as_array().cloned().unwrap_or_default();
    let kept: Vec<(usize, usize)> = views
        .iter()
        .enumerate()
        .filter(|(i, _)| !removed.contains(i))
        .map(|(_, v)| view_range(v))
        .collect();
    let mut covered = vec![false; bin.len()];
    for &(start, end) in &kept {
        covered[start.min(bin.len())..end.min(bin.len())].fill(true);
    }
    let gone: Vec<(usize, usize)> = removed
        .iter()
        .filter_map(|&r| views.get(r).map(view_range))
        .collect();
    // The runs of bytes no kept view covers that hold a removed view's bytes.
    let mut cuts: Vec<(usize, usize)> = Vec::new();
    let mut b = 0;
    while b < bin.len() {
        if covered[b] {
            b += 1;
            continue;
        }
        let run = b;
        while b < bin.len() && !covered[b] {
            b += 1;
        }
        let len = if b == bin.len() {
            b - run
        } else {
            (b - run) / 4 * 4
        };
        if len > 0 && gone.iter().any(|&(s, e)| s < b && run < e) {
            cuts.push((run, len));
        }
    }
    cuts.sort_unstable();
    for &(start, len) in cuts.iter().rev() {
        bin.drain(start..start + len);
        for v in items_mut(json, "bufferViews") {
            let offset = v["byteOffset"].as_u64().unwrap_or(0) as usize;
            if offset >= start + len {
                v["byteOffset"] = (offset - len).into();
            }
        }
    }
    remove_items(json, "bufferViews", removed);
    renumber_views(json, removed);
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// Views 1 and 3 go with their bytes (and the padding after view 1); view 0 shares its
    /// bytes with view 2, which stays; references to views 2 and 4 are renumbered.
    #[test]
    fn dropped_views_take_their_bytes_and_later_views_move() {
        let mut json = json!({
            "bufferViews": [
                {"buffer": 0, "byteOffset": 0, "byteLength": 4},
                {"buffer": 0, "byteOffset": 4, "byteLength": 6},
                {"buffer": 0, "byteOffset": 0, "byteLength": 4},
                {"buffer": 0, "byteOffset": 12, "byteLength": 4},
                {"buffer": 0, "byteOffset": 16, "byteLength": 4},
            ],
            "accessors": [{"bufferView": 2}, {"bufferView": 4, "extras": {"bufferView": 4}}],
        });
        let mut bin: Vec<u8> = (0..20).collect();
        drop_views(&mut json, &mut bin, &[0, 1, 3]);
        assert_eq!(bin, [0, 1, 2, 3, 16, 17, 18, 19]);
        assert_eq!(
            json["bufferViews"],
            json!([
                {"buffer": 0, "byteOffset": 0, "byteLength": 4},
                {"buffer": 0, "byteOffset": 4, "byteLength": 4},
            ])
        );
        assert_eq!(
            json["accessors"],
            json!([{"bufferView": 0}, {"bufferView": 1, "extras": {"bufferView": 4}}])
        );
    }

    /// A replaced texture another material still shows stays; one nothing shows gives its
    /// index (and its image's) to the new one.
    #[test]
    fn a_replaced_texture_is_reused_only_when_unused() {
        let start = json!({
            "materials": [{"occlusionTexture": {"index": 2}}, {"occlusionTexture": {"index": 0}}],
            "textures": [{"source": 0, "sampler": 0}, {"source": 1}, {"source": 2}],
            "images": [{"bufferView": 0}, {"bufferView": 1}, {"bufferView": 2}],
            "samplers": [{}],
        });
        let mut json = start.clone();
        let mut orphans = Orphans::default();
        // Material 0 showed texture 0 (material 1 still does).
        json["materials"][0]["occlusionTexture"]["index"] = 2.into();
        orphans.reuse_texture(&mut json, 0, "/materials/0/occlusionTexture");
        assert_eq!(json, start);
        // Material 1 replaced texture 0 by texture 2: nothing shows 0 now.
        let mut json = start.clone();
        json["materials"][0]["occlusionTexture"]["index"] = 1.into();
        json["materials"][1]["occlusionTexture"]["index"] = 2.into();
        let mut orphans = Orphans::default();
        orphans.reuse_texture(&mut json, 0, "/materials/1/occlusionTexture");
        assert_eq!(json["materials"][1]["occlusionTexture"]["index"], 0);
        assert_eq!(json["textures"], json!([{"source": 0}, {"source": 1}]));
        assert_eq!(
            json["images"],
            json!([{"bufferView": 2}, {"bufferView": 1}])
        );
        let mut bin = vec![0u8; 12];
        json["bufferViews"] = json!([
            {"byteOffset": 0, "byteLength": 4},
            {"byteOffset": 4, "byteLength": 4},
            {"byteOffset": 8, "byteLength": 4},
        ]);
        orphans.drop(&mut json, &mut bin);
        assert_eq!(bin.len(), 8);
        assert_eq!(json["samplers"], json!([]));
        assert_eq!(
            json["images"],
            json!([{"bufferView": 1}, {"bufferView": 0}])
        );
    }
}

//! A baked glTF copy holds only what something references after the bake's replacements:
//! re-baking a baked copy replaces its textures instead of piling them up (three round
//! trips keep two images and the same size), and a per-vertex bake replacing `COLOR_0`
//! leaves no unused accessor, view or bytes.

use std::path::Path;

use serde_json::Value;

use crate::common::cli::{run_in, scratch_dir, stderr_of};
use crate::gltf_names::Glb;

/// The JSON chunk and the `BIN` chunk of a GLB.
fn chunks(glb: &[u8]) -> (Value, &[u8]) {
    let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json = serde_json::from_slice(&glb[20..20 + len]).unwrap();
    let bin = glb.get(20 + len + 8..).unwrap_or(&[]);
    (json, bin)
}

fn bake(dir: &Path, scene: &str, out: &str) -> Vec<u8> {
    let o = run_in(
        dir,
        &["bake", scene, "-o", out, "--write-gltf", "--seed", "3"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    std::fs::read(dir.join(out).join("plane.glb")).unwrap()
}

/// Every buffer view is referenced by an accessor or an image.
fn assert_views_used(json: &Value) {
    let views = json["bufferViews"].as_array().unwrap().len();
    let mut used = vec![false; views];
    for key in ["accessors", "images"] {
        for item in json[key].as_array().into_iter().flatten() {
            used[item["bufferView"].as_u64().unwrap() as usize] = true;
        }
    }
    assert!(used.iter().all(|u| *u), "unused views: {used:?} in {json}");
}

/// `bake plane.glb` → rt1, its copy → rt2, that → rt3: each copy holds exactly the two
/// baked images (the earlier bake's are replaced, not kept unreferenced), rt2 and rt3 have
/// the same size, and the embedded images are the PNG files of their bake, byte for byte.
#[test]
fn rebaking_a_baked_copy_replaces_its_textures() {
    let dir = scratch_dir("gltf_rebake_rounds");
    let mut g = Glb::new();
    let quad = g.quad(0.0, 0.25, true);
    let mesh = g.mesh("plane", vec![quad]);
    g.root(serde_json::json!({"name": "plane", "mesh": mesh}));
    g.write(&dir.join("plane.glb"));
    let mut sizes = Vec::new();
    for (scene, out) in [
        ("plane.glb", "rt1"),
        ("rt1/plane.glb", "rt2"),
        ("rt2/plane.glb", "rt3"),
    ] {
        let glb = bake(&dir, scene, out);
        let (json, bin) = chunks(&glb);
        assert_eq!(json["images"].as_array().unwrap().len(), 2, "{out}: {json}");
        assert_eq!(
            json["textures"].as_array().unwrap().len(),
            2,
            "{out}: {json}"
        );
        assert_views_used(&json);
        let material = &json["materials"][0];
        for (info, file) in [
            (&material["occlusionTexture"], "plane_ao.png"),
            (
                &material["extensions"]["MSFT_lightmap"]["lightmapTexture"],
                "plane_lightmap.png",
            ),
        ] {
            let texture = info["index"].as_u64().unwrap() as usize;
            let image = json["textures"][texture]["source"].as_u64().unwrap() as usize;
            let view = &json["bufferViews"]
                [json["images"][image]["bufferView"].as_u64().unwrap() as usize];
            let at = view["byteOffset"].as_u64().unwrap() as usize;
            let len = view["byteLength"].as_u64().unwrap() as usize;
            let png = std::fs::read(dir.join(out).join(file)).unwrap();
            assert!(bin[at..at + len] == png[..], "{out}: {file} differs");
        }
        sizes.push(glb.len());
    }
    assert_eq!(sizes[1], sizes[2], "{sizes:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A primitive with a VEC4 `COLOR_0` and no `TEXCOORD_1` bakes AO per vertex: the copy's
/// `COLOR_0` takes the old accessor's index, and the old colours' view and bytes are gone
/// (4 accessors as in the source; the buffer 64 bytes of RGBA shorter, 48 of RGB longer).
#[test]
fn a_replaced_color_0_leaves_no_unused_accessor() {
    let dir = scratch_dir("gltf_rebake_colors");
    let mut g = Glb::new();
    let mut quad = g.quad(0.0, 0.25, false);
    let colours = g.floats(&[[0.5f32, 0.5, 0.5, 1.0]; 4], "VEC4");
    quad["attributes"]["COLOR_0"] = colours.into();
    let mesh = g.mesh("plane", vec![quad]);
    g.root(serde_json::json!({"name": "plane", "mesh": mesh}));
    g.write(&dir.join("plane.glb"));
    let source = std::fs::read(dir.join("plane.glb")).unwrap();
    let (_, source_bin) = chunks(&source);
    let glb = bake(&dir, "plane.glb", "out");
    let (json, bin) = chunks(&glb);
    assert_eq!(json["accessors"].as_array().unwrap().len(), 4, "{json}");
    let attributes = &json["meshes"][0]["primitives"][0]["attributes"];
    assert_eq!(attributes["COLOR_0"], colours);
    assert_eq!(json["accessors"][colours]["type"], "VEC3");
    assert_views_used(&json);
    assert_eq!(json["bufferViews"].as_array().unwrap().len(), 4, "{json}");
    assert_eq!(bin.len(), source_bin.len() - 64 + 48);
    let _ = std::fs::remove_dir_all(&dir);
}

//! `bake scene.ron --write-gltf` of outputs written as EXR: core glTF images are PNG or
//! JPEG only, so the `.glb` embeds a 16-bit PNG of the same texels (the EXR files stay as
//! written) — the AO linear in the occlusion texture, an HDR lightmap divided by its largest
//! value, sRGB-encoded like PNG lightmaps, with that value as `lightmapFactor` — the same
//! bytes at any thread count and from merged bake parts. (Before, an EXR bake's `.glb` had
//! no texture at all.)

use std::path::Path;

use serde_json::Value;
use stagelight::image_io::png_codec::{decode_png, Samples};

use crate::common::cli::{dir_names, run_in, scratch_dir, stderr_of};

/// A 2 × 2 floor under a box and a bright point lamp (irradiance up to 20 W/m²), baked to
/// EXR (the default format): AO and an irradiance lightmap at the default `scale` of 1.
const SCENE: &str = r#"Scene(
    options: (seed: 3),
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
               placement: LookAt(eye: (0, -4, 4), target: (0, 0, 0), up: (0, 0, 1)))],
    lights: [(name: "lamp", kind: Point(position: (0.5, -0.5, 1)), intensity: 20.0)],
    materials: [(name: "w", shader: Lambert(albedo: (0.8, 0.8, 0.8)))],
    objects: [
        (name: "floor", mesh: Inline(
            vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
            polygons: [[0, 1, 2, 3]]), material: "w"),
        (name: "box", mesh: Inline(
            vertices: [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                       (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)],
            polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5],
                       [0, 4, 7, 3]]), material: "w"),
    ],
    instances: [(name: "f", of: "floor",
                 bake: (resolution: (16, 16), uvs: Unwrap, outputs: [
                     (kind: AmbientOcclusion(samples: 16)),
                     (kind: Lightmap(store: Irradiance))])),
                (name: "b", of: "box", transform: [Scale((0.3, 0.3, 0.3)), Translate((0, 0, 0.3))])],
    groups: [(name: "world", members: ["f", "b"])],
    render: (root: "world", camera: "cam"),
)
"#;

fn ok(dir: &Path, args: &[&str]) {
    let o = run_in(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

/// The JSON chunk and the `BIN` chunk of a GLB.
fn chunks(glb: &[u8]) -> (Value, &[u8]) {
    let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json = serde_json::from_slice(&glb[20..20 + len]).unwrap();
    (json, &glb[20 + len + 8..])
}

/// The 16-bit samples (3 per texel) of the PNG embedded for texture `texture`.
fn embedded_png(json: &Value, bin: &[u8], texture: &Value) -> (u32, u32, Vec<u16>) {
    let image = &json["images"][json["textures"][texture.as_u64().unwrap() as usize]["source"]
        .as_u64()
        .unwrap() as usize];
    assert_eq!(image["mimeType"], "image/png");
    let view = &json["bufferViews"][image["bufferView"].as_u64().unwrap() as usize];
    let offset = view["byteOffset"].as_u64().unwrap() as usize;
    let length = view["byteLength"].as_u64().unwrap() as usize;
    let png = decode_png(&bin[offset..offset + length]).unwrap();
    assert_eq!(png.channels, 3);
    let Samples::Sixteen(samples) = png.samples else {
        panic!("a 16-bit PNG");
    };
    (png.width, png.height, samples)
}

/// An EXR's R, G, B per texel, row 0 at the top.
fn read_exr(path: &Path) -> (usize, usize, Vec<[f32; 3]>) {
    use exr::prelude::*;
    let image = read_first_rgba_layer_from_file(
        path,
        |res, _| {
            (
                res.width(),
                res.height(),
                vec![[0.0; 3]; res.width() * res.height()],
            )
        },
        |(w, _, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * *w + pos.x()] = [r, g, b]
        },
    )
    .unwrap();
    image.layer_data.channel_data.pixels
}

/// The sRGB decoding (IEC 61966-2-1) of an encoded value in [0, 1].
fn srgb_decode(e: f64) -> f64 {
    if e <= 0.04045 {
        e / 12.92
    } else {
        ((e + 0.055) / 1.055).powf(2.4)
    }
}

/// The `.glb` of an EXR bake carries both textures: the AO in the occlusion texture, each
/// texel's R the EXR's AO within half a 16-bit step; the lightmap in `MSFT_lightmap`, its
/// `lightmapFactor` the EXR's largest value (above 1: the lightmap is HDR) and
/// `factor × sRGB-decoded texel` each EXR channel within the 16-bit sRGB step at the top of
/// the range (`dlinear/dencoded` ≤ 2.28). The EXR files are on disk as baked.
#[test]
fn an_exr_bake_embeds_png_copies_of_its_textures() {
    let dir = scratch_dir("gltf-export-exr");
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
    ok(&dir, &["bake", "scene.ron", "-o", "out", "--write-gltf"]);
    assert_eq!(
        dir_names(&dir.join("out")),
        ["f_ao.exr", "f_lightmap.exr", "scene.glb"]
    );
    let glb = std::fs::read(dir.join("out/scene.glb")).unwrap();
    gltf::Gltf::from_slice(&glb).expect("a valid glb");
    let (json, bin) = chunks(&glb);
    let material = &json["materials"][0];
    assert_eq!(material["name"], "f_baked");
    assert_eq!(json["images"].as_array().unwrap().len(), 2);

    let occlusion = &material["occlusionTexture"];
    assert_eq!(occlusion["texCoord"], 1);
    let (w, h, samples) = embedded_png(&json, bin, &occlusion["index"]);
    let (ew, eh, ao) = read_exr(&dir.join("out/f_ao.exr"));
    assert_eq!((w as usize, h as usize), (ew, eh));
    assert_eq!((w, h), (16, 16));
    let mut varied = (f32::INFINITY, f32::NEG_INFINITY);
    for (i, texel) in ao.iter().enumerate() {
        let written = f64::from(samples[3 * i]) / 65535.0;
        let want = f64::from(texel[0]);
        assert!(
            (written - want).abs() <= 0.5 / 65535.0 + 1e-7,
            "texel {i}: {written} against the EXR's {want}"
        );
        varied = (varied.0.min(texel[0]), varied.1.max(texel[0]));
    }
    assert!(varied.0 < 0.9 && varied.1 > 0.9, "{varied:?}");

    let lightmap = &material["extensions"]["MSFT_lightmap"];
    assert_eq!(lightmap["lightmapTexture"]["texCoord"], 1);
    let (_, _, samples) = embedded_png(&json, bin, &lightmap["lightmapTexture"]["index"]);
    let (_, _, irradiance) = read_exr(&dir.join("out/f_lightmap.exr"));
    let peak = irradiance.iter().flatten().fold(0.0f32, |a, &b| a.max(b));
    assert!(peak > 1.0, "an HDR lightmap: {peak}");
    let factor = f64::from(peak);
    assert_eq!(
        lightmap["lightmapFactor"],
        serde_json::json!([factor, factor, factor])
    );
    assert!(samples.contains(&65535));
    let step = factor * 2.28 * (0.5 / 65535.0 + 2e-7);
    for (i, texel) in irradiance.iter().enumerate() {
        for c in 0..3 {
            let written = srgb_decode(f64::from(samples[3 * i + c]) / 65535.0) * factor;
            let want = f64::from(texel[c]);
            assert!(
                (written - want).abs() <= step,
                "texel {i} channel {c}: {written} against the EXR's {want} (step {step})"
            );
        }
    }
    assert_eq!(json["extensionsUsed"], serde_json::json!(["MSFT_lightmap"]));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The embedded PNGs are made from the bake's texels, so the `.glb` is the same bytes at 1
/// and 2 threads and from two merged bake parts.
#[test]
fn an_exr_bakes_glb_is_the_same_at_any_thread_count_and_part_split() {
    let dir = scratch_dir("gltf-export-exr-parts");
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
    for (out, threads) in [("one", "1"), ("two", "2")] {
        ok(
            &dir,
            &[
                "bake",
                "scene.ron",
                "-o",
                out,
                "--write-gltf",
                "--threads",
                threads,
            ],
        );
    }
    for k in ["1/2", "2/2"] {
        ok(
            &dir,
            &[
                "bake",
                "scene.ron",
                "--part",
                k,
                "-o",
                "parts",
                "--threads",
                "1",
            ],
        );
    }
    ok(
        &dir,
        &[
            "merge",
            "parts/bake_part_1_of_2.exr",
            "parts/bake_part_2_of_2.exr",
            "-o",
            "merged",
            "--write-gltf",
        ],
    );
    let one = std::fs::read(dir.join("one/scene.glb")).unwrap();
    for other in ["two", "merged"] {
        assert!(
            std::fs::read(dir.join(other).join("scene.glb")).unwrap() == one,
            "{other}/scene.glb differs"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

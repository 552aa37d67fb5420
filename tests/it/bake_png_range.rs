//! Bake outputs and the range of a PNG: a PNG output whose texels lie outside [0, 1] is
//! clipped with a warning located at the request (how many texels, the largest value, and
//! what to write instead); `store: IrradianceOverPi` writes E / π; and the default lightmap
//! of a glTF file is E / π, about 1 under the white environment of a file without lights,
//! where its irradiance E = π clipped to white.

use std::path::Path;

use stagelight::sweep::runner::read_exr_rgb;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// A 2 × 2 quad (albedo 0.2) under a directional light of irradiance 4 straight down.
const SCENE: &str = r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
               placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (0, 0, -1)), intensity: 4)],
    materials: [(name: "dark", shader: Lambert(albedo: (0.2, 0.2, 0.2)))],
    objects: [(name: "quad", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
        uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]), material: "dark")],
    instances: [(name: "q", of: "quad", bake: (resolution: (8, 8), uvs: Mesh, outputs: [
        (kind: Lightmap(), format: Png8),
        (kind: Lightmap(store: Radiance), format: Png16, file: "radiance.png"),
        (kind: Lightmap(store: IrradianceOverPi), file: "over_pi.exr"),
        (kind: Positions, format: Png16)]))],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
)
"#;

/// The irradiance (4) in an 8-bit PNG and the positions (±0.875 at the texel centres) in a
/// 16-bit one are clipped: one warning each, at the request; the radiance 0.2 · 4 / π fits
/// and is not mentioned; E / π in the EXR is 4 / π.
#[test]
fn png_outputs_that_clip_their_values_warn_at_the_request() {
    let dir = scratch_dir("bake-png-range");
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
    let o = run_in(&dir, &["bake", "scene.ron", "-o", "out"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stderr = stderr_of(&o);
    let lightmap = "scene.ron:8:17: warning: bake request on instance \"q\": 64 of 64 texels of \"q_lightmap.png\" lie outside the 8-bit PNG's range [0, 1] and were clipped (largest value 4.000)\n  help: write it as EXR (`format: Exr`) to keep the full range, or store `Lightmap(store: IrradianceOverPi)` (E / π: 1 under a white sky of radiance 1)\n";
    let positions = "scene.ron:8:17: warning: bake request on instance \"q\": 48 of 64 texels of \"q_positions.png\" lie outside the 16-bit PNG's range [0, 1] and were clipped (values from -0.875 to 0.875)\n  help: write it as EXR (`format: Exr`) to keep the full range\n";
    assert!(stderr.contains(lightmap), "{stderr}");
    assert!(stderr.contains(positions), "{stderr}");
    assert_eq!(stderr.matches("warning:").count(), 2, "{stderr}");
    let (texels, ..) = read_exr_rgb(&dir.join("out/over_pi.exr")).unwrap();
    let expected = 4.0 / std::f32::consts::PI;
    assert!(
        texels.iter().all(|t| (t.x - expected).abs() < 1e-5),
        "E / π: {:?}",
        &texels[..2]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A glTF quad with `TEXCOORD_1` and no lights, lit by the white environment (radiance 1):
/// its default lightmap is E / π ≈ 1 stored at `scale: 0.5` — the PNG holds ≈ 0.5, so
/// neither the irradiance E = π (which clipped to 255 everywhere, silently) nor the noise
/// of E / π around 1 (which clipped about half the texels, with a warning) is clipped — and
/// the `--write-gltf` copy's `lightmapFactor` of 2 restores E / π.
#[test]
fn the_default_gltf_lightmap_under_the_white_environment_is_e_over_pi_at_half_scale() {
    let dir = scratch_dir("bake-png-range-gltf");
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/gltf/two_uv_sets.glb");
    std::fs::copy(&fixture, dir.join("two_uv_sets.glb")).unwrap();
    let o = run_in(
        &dir,
        &["bake", "two_uv_sets.glb", "-o", "out", "--write-gltf"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stderr = stderr_of(&o);
    assert!(!stderr.contains("warning"), "nothing clipped: {stderr}");
    let img = crate::common::png::read(&dir.join("out/quad_lightmap.png"));
    let n = (img.width * img.height) as usize;
    let linear = |c: f32| {
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    // The texels written (the rest of the texture, outside the quad's charts, is black).
    let written: Vec<f32> = (0..n)
        .map(|p| img.rgba(p)[0])
        .filter(|&v| v > 0.0)
        .map(linear)
        .collect();
    assert!(written.len() > 100, "{} texels written", written.len());
    let (lo, hi) = written
        .iter()
        .fold((f32::INFINITY, 0f32), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    let mean = written.iter().sum::<f32>() / written.len() as f32;
    // E / π = 1 halved, within the estimate's noise (a few per cent) and 8-bit rounding.
    assert!(lo > 0.45 && hi < 0.55, "texels from {lo} to {hi}");
    assert!((mean - 0.5).abs() < 0.01, "mean {mean}");
    // The copy undoes the scale.
    let bytes = std::fs::read(dir.join("out/two_uv_sets.glb")).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let factors: Vec<&serde_json::Value> = json["materials"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|m| m["extensions"]["MSFT_lightmap"].get("lightmapFactor"))
        .collect();
    assert!(!factors.is_empty());
    for f in factors {
        assert_eq!(f, &serde_json::json!([2.0, 2.0, 2.0]));
    }
    // The request the file's reader made is the one written as RON.
    let o = run_in(&dir, &["convert", "two_uv_sets.glb", "-o", "scene.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let ron = std::fs::read_to_string(dir.join("scene.ron")).unwrap();
    assert!(ron.contains("store: IrradianceOverPi"), "{ron}");
    assert!(ron.contains("scale: 0.5"), "{ron}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `scale` multiplies the stored lightmap exactly (0.25 is a power of two), a non-positive
/// scale is a located error, and a clipping lightmap's help names the scale that fits.
#[test]
fn a_lightmap_scale_multiplies_the_stored_value() {
    let dir = scratch_dir("bake-png-range-scale");
    let scene = SCENE.replace(
        r#"(kind: Lightmap(store: IrradianceOverPi), file: "over_pi.exr"),"#,
        r#"(kind: Lightmap(store: IrradianceOverPi), file: "over_pi.exr"),
        (kind: Lightmap(store: IrradianceOverPi, scale: 0.25), file: "quarter.exr"),
        (kind: Lightmap(scale: 0.2), format: Png8, file: "fifth.png"),"#,
    );
    std::fs::write(dir.join("scene.ron"), &scene).unwrap();
    let o = run_in(&dir, &["bake", "scene.ron", "-o", "out"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let (full, ..) = read_exr_rgb(&dir.join("out/over_pi.exr")).unwrap();
    let (quarter, ..) = read_exr_rgb(&dir.join("out/quarter.exr")).unwrap();
    assert_eq!(full.len(), quarter.len());
    assert!(full.iter().zip(&quarter).all(|(f, q)| *q == *f * 0.25));
    // E = 4 at scale 0.2 is 0.8: it fits, so the only lightmap warning is the unscaled one.
    let stderr = stderr_of(&o);
    assert!(!stderr.contains("texels of \"fifth.png\""), "{stderr}");
    assert_eq!(stderr.matches("warning:").count(), 2, "{stderr}");
    let bad = SCENE.replace(
        "(kind: Lightmap(), format: Png8),",
        "(kind: Lightmap(scale: 0), format: Png8),",
    );
    std::fs::write(dir.join("bad.ron"), &bad).unwrap();
    let o = run_in(&dir, &["bake", "bad.ron", "-o", "out2"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert!(
        stderr_of(&o)
            .contains("scale must be a positive number (it multiplies the stored value), found 0"),
        "{}",
        stderr_of(&o)
    );
    assert!(!dir.join("out2").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

//! Seamless and denoised bakes end to end (issue 15): `stagelight bake` stitches an unwrapped
//! torus's UV seams (the seam metric falls ≥ 10×, texels no seam reads are unchanged to the
//! bit), the texel-space denoiser keeps two charts packed side by side apart, and bad
//! `denoise` values are refused with their scene position.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::process::Command;

use stagelight::bake::seams::{find_seams, seam_difference};
use stagelight::bake::{corner_uvs, TexelImage};
use stagelight::components::{TriMesh, UvSource};
use stagelight::scene::load_scene_str;
use stagelight::sweep::runner::read_exr_rgb;

fn scratch(test: &str) -> PathBuf {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight-seams-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn torus_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/meshes/torus.obj")
}

/// The torus, generated UVs, AO at 16 rays per texel (noisy, so seams show).
fn torus_scene(bake_extra: &str) -> String {
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 35.0, resolution: (8, 8),
               placement: LookAt(eye: (0, 3.2, 6.5), target: (0, 0, 0), up: (0, 1, 0)))],
    materials: [(name: "m", shader: Lambert(albedo: (0.6, 0.6, 0.6)))],
    objects: [(name: "torus", mesh: Obj(file: "{}"), material: "m")],
    instances: [(name: "t", of: "torus", bake: (
        resolution: (256, 256), uvs: Unwrap, {bake_extra}
        outputs: [(kind: AmbientOcclusion(samples: 16))],
    ))],
    groups: [(name: "world", members: ["t"])],
    render: (root: "world", camera: "cam"),
)
"#,
        torus_path().display()
    )
}

/// Bakes `scene` into `dir`; returns the AO texture and the report's `seams` object.
fn bake(dir: &Path, scene: &str) -> (Vec<glam::Vec3>, serde_json::Value) {
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_stagelight"))
        .current_dir(dir)
        .args([
            "bake",
            "scene.ron",
            "-o",
            "out",
            "--stats-json",
            "stats.json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (texels, ..) = read_exr_rgb(&dir.join("out/t_ao.exr")).unwrap();
    let stats: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("stats.json")).unwrap()).unwrap();
    let seams = stats["bakes"][0]["seams"].clone();
    assert!(seams.is_object(), "no seam report in {stats}");
    (texels, seams)
}

#[test]
fn stitching_an_unwrapped_torus_closes_its_seams_and_leaves_other_texels_alone() {
    let dir = scratch("torus");
    let (plain, plain_report) = bake(&dir, &torus_scene("stitch_seams: false,"));
    let dir2 = scratch("torus-stitched");
    let (stitched, report) = bake(&dir2, &torus_scene(""));
    let f = |r: &serde_json::Value, k: &str| r[k].as_f64().unwrap();

    // The report: the metric falls by ≥ 10× (mean and max); unstitched, before = after.
    assert_eq!(report["stitched"], true);
    assert!(f(&report, "edges") > 20.0, "{report}");
    assert!(
        f(&report, "mean_after") * 10.0 <= f(&report, "mean_before"),
        "{report}"
    );
    assert!(
        f(&report, "max_after") * 10.0 <= f(&report, "max_before"),
        "{report}"
    );
    assert_eq!(plain_report["stitched"], false);
    assert_eq!(plain_report["mean_before"], report["mean_before"]);
    assert_eq!(plain_report["mean_after"], plain_report["mean_before"]);

    // The same seams, found independently from the mesh and its generated UVs, measured on
    // the written textures.
    let mesh = TriMesh {
        normals: None,
        uvs: None,
        ..stagelight::scene::parse_obj_bytes(&std::fs::read(torus_path()).unwrap()).unwrap()
    };
    let uvs = corner_uvs(&mesh, UvSource::Unwrap, 256, 2).unwrap();
    let seams = find_seams(&mesh.positions, &mesh.triangles, &uvs, 256, 256);
    assert_eq!(seams.edges as f64, f(&report, "edges"));
    let image = |texels: &Vec<glam::Vec3>| TexelImage {
        width: 256,
        height: 256,
        texels: texels.clone(),
        valid: texels.iter().map(|t| *t != glam::Vec3::ZERO).collect(),
    };
    let (before, after) = (
        seam_difference(&image(&plain), &seams),
        seam_difference(&image(&stitched), &seams),
    );
    assert!(before.mean > 0.01, "{before:?}");
    assert!(after.mean * 10.0 <= before.mean, "{before:?} → {after:?}");

    // Only texels under a seam sample's bilinear taps changed; they are few, the rest is
    // bit for bit the unstitched bake.
    let taps: HashSet<usize> = seams
        .pairs
        .iter()
        .flat_map(|p| {
            let img = image(&plain);
            let mut v: Vec<usize> = img.bilinear_taps(p.a).iter().map(|t| t.0).collect();
            v.extend(img.bilinear_taps(p.b).iter().map(|t| t.0));
            v
        })
        .collect();
    let changed: Vec<usize> = (0..plain.len())
        .filter(|&k| plain[k] != stitched[k])
        .collect();
    assert!(!changed.is_empty());
    for k in &changed {
        assert!(taps.contains(k), "texel {k} away from the seams changed");
    }
    let nonzero = plain.iter().filter(|t| **t != glam::Vec3::ZERO).count();
    assert!(
        changed.len() * 4 < nonzero,
        "{} of {nonzero}",
        changed.len()
    );
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&dir2);
}

/// Two quads far apart in space but packed side by side in UV space (u < ½ and u > ½): the
/// left one open to the sky (AO ≈ 1), the right one under a low roof (AO ≈ 0.1).
fn two_chart_scene(denoise: &str) -> String {
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 35.0, resolution: (8, 8),
               placement: LookAt(eye: (0, -6, 4), target: (2, 0, 0), up: (0, 0, 1)))],
    materials: [(name: "m", shader: Lambert(albedo: (0.6, 0.6, 0.6)), two_sided: true)],
    objects: [
        (name: "pair", mesh: Inline(
            vertices: [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
                       (4, 0, 0), (5, 0, 0), (5, 1, 0), (4, 1, 0)],
            uvs: [(0, 0), (0.5, 0), (0.5, 1), (0, 1),
                  (0.5, 0), (1, 0), (1, 1), (0.5, 1)],
            polygons: [[0, 1, 2, 3], [4, 5, 6, 7]]), material: "m"),
        (name: "roof", mesh: Inline(
            vertices: [(3.5, -0.5, 0.08), (5.5, -0.5, 0.08), (5.5, 1.5, 0.08), (3.5, 1.5, 0.08)],
            polygons: [[0, 3, 2, 1]]), material: "m"),
    ],
    instances: [
        (name: "p", of: "pair", bake: (
            resolution: (32, 16), uvs: Mesh, padding: 0,
            outputs: [(kind: AmbientOcclusion(samples: 16){denoise})],
        )),
        (name: "r", of: "roof"),
    ],
    groups: [(name: "world", members: ["p", "r"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

/// Bakes the two-chart scene and returns the AO texels (32 × 16).
fn bake_pair(dir: &Path, denoise: &str) -> Vec<f32> {
    std::fs::write(dir.join("scene.ron"), two_chart_scene(denoise)).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_stagelight"))
        .current_dir(dir)
        .args(["bake", "scene.ron", "-o", "out"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    read_exr_rgb(&dir.join("out/p_ao.exr"))
        .unwrap()
        .0
        .iter()
        .map(|t| t.x)
        .collect()
}

fn spread(values: impl Iterator<Item = f32>) -> f32 {
    let v: Vec<f32> = values.collect();
    let mean = v.iter().sum::<f32>() / v.len() as f32;
    (v.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / v.len() as f32).sqrt()
}

#[test]
fn the_denoiser_never_mixes_two_charts_packed_side_by_side() {
    let dir = scratch("charts");
    let noisy = bake_pair(&dir, "");
    // A wide colour width: only the chart border can keep the halves apart (both lie in the
    // plane z = 0 facing up, so positions and normals cannot).
    let denoised = bake_pair(&dir, ", denoise: (passes: 4, sigma_color: 1000.0)");
    let left = |k: &usize| k % 32 < 16;
    let min_left_noisy = (0..noisy.len())
        .filter(left)
        .map(|k| noisy[k])
        .fold(f32::INFINITY, f32::min);
    let max_right_noisy = (0..noisy.len())
        .filter(|k| !left(k))
        .map(|k| noisy[k])
        .fold(0.0, f32::max);
    assert!(
        min_left_noisy > 0.8 && max_right_noisy < 0.5,
        "the scene gives two very different charts: {min_left_noisy} vs {max_right_noisy}"
    );
    for (k, &value) in denoised.iter().enumerate() {
        if left(&k) {
            assert!(
                value >= min_left_noisy,
                "texel {k} of the open chart darkened to {value} (the roofed chart leaked in)"
            );
        } else {
            assert!(
                value <= max_right_noisy,
                "texel {k} of the roofed chart brightened to {value}"
            );
        }
    }
    // And it did denoise: the roofed chart's texels spread less.
    let right = |v: &Vec<f32>| spread((0..v.len()).filter(|k| !left(k)).map(|k| v[k]));
    assert!(
        right(&denoised) < 0.7 * right(&noisy),
        "{} → {}",
        right(&noisy),
        right(&denoised)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The diagnostics of a scene text, one string each.
fn diagnostics(text: &str) -> Vec<String> {
    match load_scene_str(text, Path::new("seams.ron")) {
        Ok(_) => panic!("loaded without errors"),
        Err(e) => e.0.iter().map(ToString::to_string).collect(),
    }
}

#[test]
fn bad_denoise_values_are_refused_where_they_stand() {
    let bad =
        |output: &str| two_chart_scene("").replace("(kind: AmbientOcclusion(samples: 16))", output);
    let cases = [
        (
            "(kind: AmbientOcclusion(samples: 16), denoise: (passes: 0))",
            "seams.ron:19:79: error: denoise passes must be 1 … 8, found 0\n  help: 3 passes (steps 1, 2 and 4 texels) is the default",
        ),
        (
            "(kind: AmbientOcclusion(samples: 16), denoise: (passes: 9))",
            "seams.ron:19:79: error: denoise passes must be 1 … 8, found 9\n  help: 3 passes (steps 1, 2 and 4 texels) is the default",
        ),
        (
            "(kind: AmbientOcclusion(samples: 16), denoise: (sigma_color: -1.0))",
            "seams.ron:19:84: error: sigma_color must be a positive finite number, found -1\n  help: 4.0 (the default) keeps edges larger than four standard deviations of the noise",
        ),
        ("(kind: Normals(), denoise: ())", "seams.ron:19:50: error: `denoise` filters noisy estimates: only AmbientOcclusion and Lightmap outputs have them, not normals\n  help: remove `denoise` from this output"),
        (
            "(kind: AmbientOcclusion(samples: 16), target: Vertices, denoise: ())",
            "seams.ron:19:88: error: `denoise` filters the texels of a texture; a per-vertex output (`target: Vertices`) has none\n  help: remove `denoise`, or bake a texture (leave `target` out)",
        ),
        (
            "(kind: AmbientOcclusion(samples: 16), denoise: (pases: 2))",
            "seams.ron:19:71: error: unknown field \"pases\" in Denoise\n  help: did you mean \"passes\"?",
        ),
    ];
    for (output, expected) in cases {
        assert_eq!(
            diagnostics(&bad(output)),
            vec![expected.to_string()],
            "{output}"
        );
    }
}

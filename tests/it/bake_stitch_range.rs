//! Seam stitching keeps values in their physical range and leaves matching seams alone: a
//! stitched texel lies within the baked values of the taps it mixes (AO ≤ 1, irradiance
//! ≥ 0), and a cube whose AO is 1 everywhere is written byte for byte as without stitching,
//! with 0 texels changed.

use std::path::Path;

use stagelight::sweep::runner::read_exr_rgb;

use crate::common::{run_in, scratch_dir, stderr_of};

/// The tester's unit cube with generated UVs (12 seam edges), on a floor or alone, baked at
/// 64 × 64 with `outputs`.
fn cube_scene(floor: bool, stitch: bool, outputs: &str) -> String {
    let (floor_instance, member) = if floor {
        (r#"(name: "f", of: "floor"),"#, r#", "f""#)
    } else {
        ("", "")
    };
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
        placement: LookAt(eye: (3, 3, 3), target: (0, 0, 0), up: (0, 1, 0)), outputs: [])],
    lights: [(name: "L", kind: Point(position: (0.3, 3, 0.2)), intensity: 10.0)],
    materials: [(name: "m", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [
        (name: "cube", mesh: Inline(vertices: [(-0.5,0,-0.5),(0.5,0,-0.5),(0.5,0,0.5),(-0.5,0,0.5),
                                             (-0.5,1,-0.5),(0.5,1,-0.5),(0.5,1,0.5),(-0.5,1,0.5)],
            polygons: [[0,1,2,3],[4,7,6,5],[0,4,5,1],[1,5,6,2],[2,6,7,3],[3,7,4,0]]), material: "m"),
        (name: "floor", mesh: Inline(vertices: [(-3,0,3),(3,0,3),(3,0,-3),(-3,0,-3)], polygons: [[0,1,2,3]]), material: "m"),
    ],
    instances: [
        (name: "c", of: "cube", bake: (resolution: (64, 64), uvs: Unwrap, stitch_seams: {stitch},
            outputs: [{outputs}])),
        {floor_instance}
    ],
    groups: [(name: "world", members: ["c"{member}])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

/// Bakes `text` in `dir` into `out`; returns stdout and stderr.
fn bake(dir: &Path, text: &str, out: &str) -> String {
    std::fs::write(dir.join("scene.ron"), text).unwrap();
    let o = run_in(dir, &["bake", "scene.ron", "-o", out, "--stats"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    format!("{}{}", String::from_utf8_lossy(&o.stdout), stderr_of(&o))
}

/// The cube on the floor: AO and an indirect lightmap differ across the seams and are
/// stitched, yet no AO texel exceeds 1 and no irradiance is negative (26–78 lightmap
/// texels were about −0.003 W/m², where the unstitched bake has none below 0).
#[test]
fn stitched_ao_stays_at_most_one_and_irradiance_at_least_zero() {
    let dir = scratch_dir("bake-stitch-range");
    let outputs =
        "(kind: AmbientOcclusion(samples: 64)), (kind: Lightmap(indirect: true, samples: 16))";
    let log = bake(&dir, &cube_scene(true, true, outputs), "out");
    assert!(log.contains("→ stitched"), "{log}");
    let (ao, ..) = read_exr_rgb(&dir.join("out/c_ao.exr")).unwrap();
    let (lightmap, ..) = read_exr_rgb(&dir.join("out/c_lightmap.exr")).unwrap();
    let ao_max = ao.iter().map(|t| t.max_element()).fold(f32::MIN, f32::max);
    let ao_min = ao.iter().map(|t| t.min_element()).fold(f32::MAX, f32::min);
    let lightmap_min = lightmap
        .iter()
        .map(|t| t.min_element())
        .fold(f32::MAX, f32::min);
    assert!(
        ao_max <= 1.0 && ao_min >= 0.0,
        "AO from {ao_min} to {ao_max}"
    );
    assert!(lightmap_min >= 0.0, "lightmap down to {lightmap_min}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A lone cube sees nothing but the sky: its AO is exactly 1 everywhere, the seams already
/// match, and stitching changes nothing — 0 texels changed, the same bytes as with
/// `stitch_seams: false` (it reported 11 texels changed, values 0.99999988 … 1.00000012).
#[test]
fn an_all_ones_ao_cube_is_not_changed_by_stitching() {
    let dir = scratch_dir("bake-stitch-ones");
    let outputs = "(kind: AmbientOcclusion(samples: 64))";
    let log = bake(&dir, &cube_scene(false, true, outputs), "on");
    let line = log
        .lines()
        .find(|l| l.starts_with("bake c:"))
        .unwrap_or_default();
    assert!(
        line.ends_with("12 seam edges: difference mean 0.0000 max 0.0000 → stitched mean 0.0000 max 0.0000 (0 texels changed)"),
        "{log}"
    );
    bake(&dir, &cube_scene(false, false, outputs), "off");
    let stitched = std::fs::read(dir.join("on/c_ao.exr")).unwrap();
    let unstitched = std::fs::read(dir.join("off/c_ao.exr")).unwrap();
    assert!(stitched == unstitched, "stitching changed the bytes");
    let (ao, ..) = read_exr_rgb(&dir.join("on/c_ao.exr")).unwrap();
    assert!(
        ao.iter()
            .all(|t| *t == glam::Vec3::ONE || *t == glam::Vec3::ZERO),
        "AO is exactly 1 on every written texel (0 outside the charts)"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

//! The camera-space passes (`CameraDepth`, `CameraNormal`, `CameraPosition`; RenderMan's
//! `z`, `N`, `P`): a plane facing the camera seen off-axis has camera-space depth `d` at every
//! pixel while `Depth` grows as `d/cos`, normal (0, 0, −1) and positions on the pixel rays at
//! `z = d`; RIB displays `P`, `z` and `N` write RenderMan's camera space (scaled by the camera
//! transformation, not the reader's mirrored world); the passes merge from farm parts (tiles
//! and samples splits) byte-identically, through `merge` and through the library's EXR writer,
//! which derives them itself from merged buffers; a file cannot hold `Depth` and
//! `CameraDepth`.

use std::collections::BTreeMap;
use std::path::Path;

use crate::common::cli::{bin, run, scratch, stderr};
use stagelight::scene::load_scene_str;

/// The f32 channels of an EXR file by name (row-major, top row first).
fn channels(path: &Path) -> BTreeMap<String, Vec<f32>> {
    let image = exr::prelude::read_all_flat_layers_from_file(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    image.layer_data[0]
        .channel_data
        .list
        .iter()
        .map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect()))
        .collect()
}

/// Runs `stagelight args…` in `dir` and insists that it succeeds.
fn ok(dir: &Path, args: &[&str]) {
    let o = run(bin().current_dir(dir).args(args));
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
}

/// `|a − b| ≤ 1e-5·|b|` (absolute 1e-5 near zero).
fn close(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-5 * b.abs().max(1.0)
}

const W: u32 = 8;
const H: u32 = 6;
/// Distance of the plane in front of the camera.
const D: f32 = 4.0;

/// Film coordinates of pixel `(x, y)`'s centre on the image plane at distance 1 (+x right,
/// +y up) for a vertical field of view of 60°.
fn film(x: u32, y: u32) -> (f32, f32) {
    let t = 30f32.to_radians().tan();
    let aspect = W as f32 / H as f32;
    let sx = (2.0 * (x as f32 + 0.5) / W as f32 - 1.0) * t * aspect;
    let sy = (1.0 - 2.0 * (y as f32 + 0.5) / H as f32) * t;
    (sx, sy)
}

/// A camera at (1, 2, 3) looking down world +x (+z up) at a plane 4 units away facing it,
/// larger than the view; outputs `outputs`.
fn plane_scene(outputs: &str) -> String {
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 60.0, resolution: ({W}, {H}),
        placement: LookAt(eye: (1, 2, 3), target: (5, 2, 3), up: (0, 0, 1)),
        outputs: [{outputs}])],
    lights: [(name: "l", kind: Point(position: (1, 2, 3)), intensity: 1.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "wall", mesh: Inline(vertices: [(5, -20, -20), (5, -20, 20), (5, 20, 20), (5, 20, -20)],
        polygons: [[0, 1, 2, 3]]), material: "grey")],
    instances: [(name: "w", of: "wall")],
    groups: [(name: "world", members: ["w"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

#[test]
fn a_plane_facing_the_camera_off_axis_has_camera_depth_d_normal_minus_z_and_ray_positions() {
    let dir = scratch("camera-passes-plane");
    let scene = plane_scene(
        r#"(file: "world.exr", passes: [Depth, Normal]),
           (file: "camera.exr", passes: [CameraDepth, CameraNormal, CameraPosition])"#,
    );
    std::fs::write(dir.join("plane.ron"), scene).unwrap();
    ok(&dir, &["render", "plane.ron"]);
    let world = channels(&dir.join("world.exr"));
    let camera = channels(&dir.join("camera.exr"));
    let names: Vec<&String> = camera.keys().collect();
    assert_eq!(
        names,
        ["N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "Z"],
        "the camera file's channels"
    );
    let mut largest_ratio = 0.0f32;
    for y in 0..H {
        for x in 0..W {
            let i = (y * W + x) as usize;
            let (sx, sy) = film(x, y);
            let at = format!("pixel ({x}, {y})");
            // Camera-space depth: d everywhere; the distance along the ray: d / cos.
            assert!(close(camera["Z"][i], D), "{at}: z {}", camera["Z"][i]);
            let along = D * (sx * sx + sy * sy + 1.0).sqrt();
            assert!(
                close(world["Z"][i], along),
                "{at}: depth {} vs {along}",
                world["Z"][i]
            );
            largest_ratio = largest_ratio.max(world["Z"][i] / camera["Z"][i]);
            // World normal −x (toward the eye); camera space (0, 0, −1).
            let n = |c: &BTreeMap<String, Vec<f32>>| [c["N.X"][i], c["N.Y"][i], c["N.Z"][i]];
            assert_eq!(n(&world), [-1.0, 0.0, 0.0], "{at}: world normal");
            let cn = n(&camera);
            assert!(
                close(cn[0], 0.0) && close(cn[1], 0.0) && close(cn[2], -1.0),
                "{at}: camera normal {cn:?}"
            );
            // The pixel's ray direction scaled to z = d.
            let p = [camera["P.X"][i], camera["P.Y"][i], camera["P.Z"][i]];
            let want = [sx * D, sy * D, D];
            assert!(
                (0..3).all(|k| close(p[k], want[k])),
                "{at}: P {p:?} vs {want:?}"
            );
        }
    }
    // The corners are far off the axis: the two depths differ there by cos ≈ 0.77.
    assert!(largest_ratio > 1.25, "{largest_ratio}");
}

#[test]
fn uncovered_pixels_have_infinite_camera_depth_and_zero_normal_and_position() {
    let dir = scratch("camera-passes-miss");
    // Looking away from the wall: nothing is hit.
    let scene =
        plane_scene(r#"(file: "c.exr", passes: [CameraDepth, CameraNormal, CameraPosition])"#)
            .replace("target: (5, 2, 3)", "target: (-5, 2, 3)");
    std::fs::write(dir.join("away.ron"), scene).unwrap();
    ok(&dir, &["render", "away.ron"]);
    let c = channels(&dir.join("c.exr"));
    assert!(c["Z"].iter().all(|&z| z == f32::INFINITY));
    for name in ["N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z"] {
        assert!(c[name].iter().all(|&v| v == 0.0), "{name}");
    }
}

/// RIB's `P`, `z` and `N` displays: RenderMan's camera space (+z forward, left-handed) in
/// camera-space units. The camera transformation scales by 2 and turns; the world block
/// undoes the turn, so the polygon's object space is camera space at half scale: at object
/// z = 4 it lies at camera z = 8.
#[test]
fn rib_p_z_and_n_displays_write_renderman_camera_space() {
    let dir = scratch("camera-passes-rib");
    let rib = "Format 8 6 1\n\
               Projection \"perspective\" \"fov\" [60]\n\
               Display \"x.exr\" \"file\" \"P\"\n\
               Display \"+z.tif\" \"file\" \"z\"\n\
               Display \"+n.exr\" \"file\" \"N\"\n\
               Scale 2 2 2\n\
               Rotate 30 0 1 0\n\
               Translate 0.5 -1 0.25\n\
               WorldBegin\n\
               Translate -0.5 1 -0.25\n\
               Rotate -30 0 1 0\n\
               Polygon \"P\" [-10 -10 4  -10 10 4  10 10 4  10 -10 4]\n\
               WorldEnd\n";
    std::fs::write(dir.join("p.rib"), rib).unwrap();
    let o = run(bin().current_dir(&dir).args(["render", "p.rib"]));
    assert!(o.status.success(), "{}", stderr(&o));
    // No warning that the values differ from RenderMan's, nor that P is not written.
    let err = stderr(&o);
    assert!(
        !err.contains("RenderMan's camera-space") && !err.contains("not written"),
        "{err}"
    );
    let p = channels(&dir.join("x.exr"));
    let z = channels(&dir.join("z.exr"));
    let n = channels(&dir.join("n.exr"));
    assert_eq!(p.keys().collect::<Vec<_>>(), ["P.X", "P.Y", "P.Z"]);
    assert_eq!(z.keys().collect::<Vec<_>>(), ["Z"]);
    assert_eq!(n.keys().collect::<Vec<_>>(), ["N.X", "N.Y", "N.Z"]);
    for y in 0..H {
        for x in 0..W {
            let i = (y * W + x) as usize;
            // fov 60° spans the shorter side (the height), as `film` assumes.
            let (sx, sy) = film(x, y);
            let want = [8.0 * sx, 8.0 * sy, 8.0];
            let got = [p["P.X"][i], p["P.Y"][i], p["P.Z"][i]];
            assert!(
                (0..3).all(|k| close(got[k], want[k])),
                "pixel ({x}, {y}): P {got:?} vs {want:?}"
            );
            assert!(close(z["Z"][i], 8.0), "pixel ({x}, {y}): z {}", z["Z"][i]);
            let normal = [n["N.X"][i], n["N.Y"][i], n["N.Z"][i]];
            assert!(
                close(normal[0], 0.0) && close(normal[1], 0.0) && close(normal[2], -1.0),
                "pixel ({x}, {y}): N {normal:?}"
            );
        }
    }
}

/// Farm parts carry the depth and normal the camera-space passes are derived from: `merge`
/// writes the single render's bytes, tiles and samples splits.
#[test]
fn camera_space_passes_merge_from_parts_byte_identically() {
    let dir = scratch("camera-passes-farm");
    let text = r#"Scene(
    options: (samples: 4),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (12, 8),
        placement: LookAt(eye: (0.5, -3, 3), target: (0, 0, 0)),
        outputs: [(file: "c.exr", passes: [Beauty, CameraDepth, CameraNormal, CameraPosition])])],
    lights: [(name: "sun", kind: Point(position: (1, -1, 3)), intensity: 4.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.4, 0.3)))],
    objects: [(name: "ball", mesh: Sphere(radius: 1), material: "grey")],
    instances: [(name: "b", of: "ball")],
    groups: [(name: "world", members: ["b"])],
    render: (root: "world", camera: "cam"),
)
"#;
    std::fs::write(dir.join("c.ron"), text).unwrap();
    ok(&dir, &["render", "c.ron", "-o", "single.exr"]);
    let single = std::fs::read(dir.join("single.exr")).unwrap();
    let c = channels(&dir.join("single.exr"));
    assert!(c["Z"].iter().any(|z| z.is_finite()) && c["Z"].iter().any(|z| z.is_infinite()));
    for (split, count) in [("tiles", 3), ("samples", 2)] {
        let mut names = Vec::new();
        for k in 1..=count {
            let part = format!("{k}/{count}");
            let name = format!("{split}_{k}.exr");
            ok(
                &dir,
                &[
                    "render", "c.ron", "--part", &part, "--split", split, "-o", &name,
                ],
            );
            names.push(name);
        }
        let merged = format!("merged_{split}.exr");
        let mut args = vec!["merge"];
        args.extend(names.iter().map(String::as_str));
        args.extend(["-o", merged.as_str()]);
        ok(&dir, &args);
        assert!(
            std::fs::read(dir.join(&merged)).unwrap() == single,
            "{split}: the merged file differs from the single render"
        );
    }
}

/// The merged frame buffers of parts, straight from `farm::merge` (they carry only the
/// centre-sample depth and normal, and never went through `write_output`), written by the
/// library's EXR writer with the render camera: the camera-space passes are derived there,
/// so the file is the single `render`'s bytes for both splits.
#[test]
fn the_exr_writer_derives_camera_space_passes_of_merged_buffers_itself() {
    use stagelight::camera_space::CameraSpace;
    use stagelight::components::Pass;
    use stagelight::farm::merge::{merge, LoadedPart};
    use stagelight::farm::part_file::{decode, encode};
    use stagelight::farm::{part_file, Part, PartRun, Split};
    use stagelight::frame::Frame;

    let dir = scratch("camera-passes-writer");
    let text = plane_scene(
        r#"(file: "c.exr", passes: [Beauty, CameraDepth, CameraNormal, CameraPosition])"#,
    )
    .replace("Scene(\n", "Scene(\n    options: (samples: 2),\n");
    std::fs::write(dir.join("p.ron"), &text).unwrap();
    ok(&dir, &["render", "p.ron"]);
    let single = std::fs::read(dir.join("c.exr")).unwrap();
    let passes = [
        Pass::Beauty,
        Pass::CameraDepth,
        Pass::CameraNormal,
        Pass::CameraPosition,
    ];
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    for (split, count) in [(Split::Samples, 2), (Split::Tiles, 3)] {
        let mut camera = None;
        let parts: Vec<LoadedPart> = (1..=count)
            .map(|index| {
                let mut scene = load_scene_str(&text, &dir.join("p.ron")).unwrap();
                let mut frame = Frame::new(scene.settings.clone());
                let run = PartRun {
                    part: Part {
                        index,
                        count,
                        split,
                    },
                    scene: "p.ron".into(),
                    scene_hash: 1,
                };
                frame.inputs.part = Some(run.clone());
                stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame).unwrap();
                camera = CameraSpace::of_render_camera(&scene.world, Default::default());
                // A tiles part past the image's one tile writes the empty part file.
                let fb = (frame.outputs.image.take())
                    .or_else(|| stagelight::systems::shade::idle_part_image(&scene.world, &frame))
                    .unwrap();
                let file = part_file(&run, &frame.inputs.settings, &fb).unwrap();
                LoadedPart {
                    path: format!("part_{index}.exr").into(),
                    file: decode(&encode(&file).unwrap()).unwrap(),
                }
            })
            .collect();
        let merged = merge(&parts).unwrap();
        let bytes = stagelight::exr_output::encode_exr(&merged, &camera.unwrap(), &passes).unwrap();
        assert!(
            bytes == single,
            "{split}: the written file differs from render's"
        );
    }
}

#[test]
fn a_file_cannot_hold_two_passes_of_one_channel_nor_a_png_a_camera_pass() {
    let errors = |outputs: &str| match load_scene_str(&plane_scene(outputs), Path::new("t.ron")) {
        Ok(_) => "ok".to_string(),
        Err(e) => e.to_string(),
    };
    assert_eq!(
        errors(r#"(file: "a.exr", passes: [Depth, CameraDepth])"#),
        "t.ron:4:51: error: the Depth and CameraDepth passes both write the EXR channel Z: one file cannot hold both\n  help: write the CameraDepth pass to another .exr output"
    );
    assert_eq!(
        errors(r#"(file: "a.exr", passes: [CameraNormal, Normal])"#),
        "t.ron:4:58: error: the CameraNormal and Normal passes both write the EXR channels N.X N.Y N.Z: one file cannot hold both\n  help: write the Normal pass to another .exr output"
    );
    assert_eq!(
        errors(r#"(file: "a.png", passes: [CameraPosition])"#),
        "t.ron:4:44: error: a PNG output cannot hold the CameraPosition pass\n  help: write the CameraPosition pass to an .exr output"
    );
    assert_eq!(
        errors(r#"(file: "a.exr", passes: [Depth, CameraNormal, CameraPosition])"#),
        "ok"
    );
}

#[test]
fn space_scale_scales_camera_depth_and_must_be_positive() {
    let dir = scratch("camera-passes-scale");
    let scene = plane_scene(r#"(file: "c.exr", passes: [CameraDepth])"#)
        .replace("up: (0, 0, 1)),", "up: (0, 0, 1)), space_scale: 2.5,");
    std::fs::write(dir.join("s.ron"), &scene).unwrap();
    ok(&dir, &["render", "s.ron"]);
    let c = channels(&dir.join("c.exr"));
    assert!(c["Z"].iter().all(|&z| close(z, 2.5 * D)), "{:?}", c["Z"]);
    let e = load_scene_str(&scene.replace("2.5", "0.0"), Path::new("t.ron"))
        .err()
        .expect("refused")
        .to_string();
    assert_eq!(
        e,
        "t.ron:3:91: error: space_scale must be positive (the camera-space length of one world unit), found 0"
    );
}

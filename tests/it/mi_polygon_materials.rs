//! Issue 13: per-polygon materials — an inline mesh whose polygons name their own materials
//! (RON `materials: [...]`, `.mi` `p "material" …`) renders each polygon in its material,
//! stays one object (one object id), keeps its polygons' materials under an instance
//! override (which reaches only polygons without one, as in mental ray), converts to RON
//! that renders the same bytes and converts again to the same text; malformed lists give
//! exact located messages.

use std::path::{Path, PathBuf};

use glam::Vec3;
use stagelight::components::{Camera, RenderCamera};
use stagelight::framebuffer::FrameBuffers;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::import::to_ron::to_ron;
use stagelight::scene::{load_scene, load_scene_str, LoadedScene};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_polygons/two_materials.mi")
}

const RED: Vec3 = Vec3::new(0.8, 0.1, 0.1);
const GREEN: Vec3 = Vec3::new(0.1, 0.7, 0.2);
const BLUE: Vec3 = Vec3::new(0.1, 0.2, 0.9);

/// Renders the whole image at 1 sample per pixel (no output files).
fn render(mut scene: LoadedScene) -> (u32, u32, FrameBuffers) {
    let size = scene
        .world
        .query_mut::<(&Camera, &RenderCamera)>()
        .into_iter()
        .map(|(c, _)| (c.width, c.height))
        .next()
        .expect("a render camera");
    let mut settings = scene.settings.clone();
    settings.spp = 1;
    settings.adaptive = None;
    let frame = crate::common::render(&mut scene.world, settings);
    (size.0, size.1, frame.outputs.image.expect("an image"))
}

/// Checks every pixel wholly inside one half of the plane z = −1 against mental ray's
/// `mib_illum_lambert` under a `mib_light_point` at the eye without attenuation:
/// `diffuse · (−z / d)`, with `left`'s diffuse for x < 0 and `right`'s for x > 0, within
/// 1 % per channel. Returns the object ids seen on each side.
fn check_halves(scene: LoadedScene, left: Vec3, right: Vec3) -> (Vec<u32>, Vec<u32>) {
    let (w, h, image) = render(scene);
    // focal 12, aperture 32, aspect 4/3: the image plane spans ±16/12 by ±1 at distance 1.
    let (tan_x, tan_y) = (16.0 / 12.0, 1.0);
    let pixel = 2.0 * tan_x / f64::from(w);
    let mut ids = (Vec::new(), Vec::new());
    let mut checked = [0u32; 2];
    for j in 1..h - 1 {
        for i in 0..w {
            let x = ((f64::from(i) + 0.5) / f64::from(w) * 2.0 - 1.0) * tan_x;
            let y = (1.0 - (f64::from(j) + 0.5) / f64::from(h) * 2.0) * tan_y;
            if x.abs() > 1.0 - pixel || x.abs() < pixel {
                continue;
            }
            let cos = 1.0 / (x * x + y * y + 1.0).sqrt();
            let (side, diffuse) = if x < 0.0 { (0, left) } else { (1, right) };
            let k = (j * w + i) as usize;
            let got = image.beauty[k];
            for c in 0..3 {
                let want = f64::from(diffuse[c]) * cos;
                let g = f64::from(got[c]);
                assert!(
                    (g - want).abs() <= 0.01 * want,
                    "pixel ({i}, {j}) channel {c}: {g} vs {want}"
                );
            }
            checked[side] += 1;
            let list = if side == 0 { &mut ids.0 } else { &mut ids.1 };
            if !list.contains(&image.object_id[k]) {
                list.push(image.object_id[k]);
            }
        }
    }
    assert!(checked.iter().all(|&n| n > w * h / 5), "{checked:?}");
    ids
}

#[test]
fn mi_polygons_render_in_their_own_materials_as_one_object() {
    let scene = load_scene(&fixture()).unwrap();
    let (left, right) = check_halves(scene, GREEN, RED);
    assert_eq!(left.len(), 1, "{left:?}");
    assert_eq!(left, right, "one object: one object id on both halves");
    assert_ne!(left[0], 0);
}

#[test]
fn an_instance_material_reaches_only_polygons_without_their_own() {
    let text = std::fs::read_to_string(fixture())
        .unwrap()
        .replace("p \"green\" 3 5 4 2", "p 3 5 4 2")
        .replace("p \"red\" 0 3 2 1\n", "")
        .replace("v 5\n", "v 5\np 3 5 4 2\np \"red\" 0 3 2 1\n")
        .replace(
            "instance \"Plane_inst\" \"Plane\"\n",
            "instance \"Plane_inst\" \"Plane\"\nmaterial \"blue\"\n",
        );
    // The first polygon has no material of its own (the next two lines keep mental ray's
    // "previous polygon's material" rule out of play): it takes the instance's "blue".
    assert!(
        text.contains("v 5\np 3 5 4 2\np \"red\" 0 3 2 1\n"),
        "{text}"
    );
    let path = fixture().with_file_name("override.mi");
    let read = read_mi(&path, text.as_bytes()).unwrap();
    let ron = to_ron(&read.desc).unwrap();
    let scene = load_scene_str(&ron, &path.with_extension("ron")).unwrap();
    check_halves(scene, BLUE, RED);
}

#[test]
fn inline_materials_in_ron_render_each_polygon_in_its_material() {
    let ron = r#"Scene(
    cameras: [(name: "cam", fov_y: 90, resolution: (128, 96),
               placement: LookAt(eye: (0, 0, 0), target: (0, 0, -1), up: (0, 1, 0)))],
    lights: [(name: "lamp", kind: Point(position: (0, 0, 0)), inverse_square: false)],
    materials: [
        (name: "red", shader: Local(color: (0.8, 0.1, 0.1), ka: 0, kd: 1, specular: (0, 0, 0))),
        (name: "green", shader: Local(color: (0.1, 0.7, 0.2), ka: 0, kd: 1, specular: (0, 0, 0))),
        (name: "blue", shader: Local(color: (0.1, 0.2, 0.9), ka: 0, kd: 1, specular: (0, 0, 0))),
    ],
    objects: [(name: "plane", material: "blue", mesh: Inline(
        vertices: [(1, 1, -1), (1, -1, -1), (0, -1, -1), (0, 1, -1), (-1, -1, -1), (-1, 1, -1)],
        polygons: [[0, 3, 2, 1], [3, 5, 4, 2]],
        materials: ["red", ""],
    ))],
    instances: [(name: "plane", of: "plane")],
    groups: [(name: "root", members: ["plane"])],
    render: (root: "root", camera: "cam"),
)"#;
    let path = Path::new("polygons.ron");
    let scene = load_scene_str(ron, path).unwrap_or_else(|e| panic!("{e}"));
    check_halves(scene, BLUE, RED);
    let green = ron.replace(r#"["red", ""]"#, r#"["red", "green"]"#);
    let scene = load_scene_str(&green, path).unwrap();
    let (left, right) = check_halves(scene, GREEN, RED);
    assert_eq!(left, right, "one object: one object id on both halves");
}

#[test]
fn cli_convert_round_trips_polygon_materials() {
    let exe = env!("CARGO_BIN_EXE_stagelight");
    let tmp =
        crate::common::scratch_root().join(format!("stagelight_mi_polys_{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let run = |args: &[&Path]| {
        let out = std::process::Command::new(exe).args(args).output().unwrap();
        assert!(
            out.status.success(),
            "{args:?}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    let p = |s: &str| tmp.join(s);
    let mi = fixture();
    run(&[Path::new("convert"), &mi, Path::new("-o"), &p("a.ron")]);
    run(&[
        Path::new("convert"),
        &p("a.ron"),
        Path::new("-o"),
        &p("b.ron"),
    ]);
    let a = std::fs::read_to_string(p("a.ron")).unwrap();
    assert!(a.contains("materials: ["), "{a}");
    assert_eq!(a, std::fs::read_to_string(p("b.ron")).unwrap());
    for (scene, png) in [(mi.clone(), p("mi.png")), (p("a.ron"), p("ron.png"))] {
        run(&[
            Path::new("render"),
            &scene,
            Path::new("--spp"),
            Path::new("1"),
            Path::new("-o"),
            &png,
        ]);
    }
    let (a, b) = (
        std::fs::read(p("mi.png")).unwrap(),
        std::fs::read(p("ron.png")).unwrap(),
    );
    assert!(a.len() > 100);
    assert!(a == b, "the PNGs differ");
    let _ = std::fs::remove_dir_all(&tmp);
}

/// An inline mesh with `materials` written as `list` and displacement `displacement`.
fn bad_scene(list: &str, displacement: &str) -> String {
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (8, 8),
               placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0), up: (0, 1, 0)))],
    materials: [(name: "red", shader: Lambert(albedo: (1, 0, 0)))],
    objects: [(name: "quad", mesh: Inline(
        vertices: [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)],
        polygons: [[0, 1, 2], [0, 2, 3]],
        materials: {list},
    ){displacement})],
    instances: [(name: "quad", of: "quad")],
    groups: [(name: "root", members: ["quad"])],
    render: (root: "root", camera: "cam"),
)"#
    )
}

#[test]
fn malformed_polygon_materials_have_exact_located_messages() {
    let cases = [
        (
            bad_scene(r#"["red"]"#, ""),
            "polygons.ron:8:20: error: materials has 1 entries but polygons has 2: give one \
             material per polygon\n  help: write \"\" for a polygon that takes the object's \
             material",
        ),
        (
            bad_scene(r#"["rde", "rde"]"#, ""),
            "polygons.ron:8:21: error: unknown material \"rde\"\n  help: did you mean \"red\"?",
        ),
        (
            bad_scene(
                r#"["red", ""]"#,
                ", displacement: (shader: Constant(0.1), bound: 0.1)",
            ),
            "polygons.ron:8:20: error: per-polygon materials cannot be combined with true \
             displacement\n  help: give the displaced polygons an object of their own, or use \
             mode: Bump",
        ),
    ];
    for (text, want) in cases {
        let err = load_scene_str(&text, Path::new("polygons.ron"))
            .err()
            .unwrap_or_else(|| panic!("accepted:\n{text}"));
        assert_eq!(err.to_string().trim_end(), want, "\n{text}");
    }
}

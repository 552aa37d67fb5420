//! Issue 13: feature switches (`options.disable`, mental ray `lens off`, …, CLI
//! `--disable`): a switched-off kind of shader changes the image exactly as if the scene had
//! none, and the stage report says the work was skipped because it was disabled.

use std::path::Path;

use glam::Vec3;
use stagelight::report::StageReport;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene_str;

use crate::common::cli::{bin, run, scratch, stderr};

/// A floor (a `Grid` geometry shader), a displaced inline quad and a contour shader, seen
/// through `lens`; `options` go inside `options: (…)`.
fn scene(options: &str, lens: &str, displacement: &str, grid: bool) -> String {
    let grid_object = if grid {
        r#"(name: "floor", mesh: Grid(size_x: 6, size_y: 6), material: "grey"),"#
    } else {
        ""
    };
    let grid_instance = if grid {
        r#"(name: "floor_1", of: "floor", transform: [Translate((0, 0, -0.5))]),"#
    } else {
        ""
    };
    format!(
        r#"Scene(
    options: (samples: 1{options}),
    cameras: [(name: "cam", fov_y: 50, resolution: (24, 24),
        placement: LookAt(eye: (0, -3, 3), target: (0, 0, 0), up: (0, 0, 1)),
        {lens}
        outputs: [(file: "switches.png", passes: [Beauty, Contours])])],
    lights: [(name: "lamp", kind: Point(position: (1, -1, 3)), intensity: 20)],
    materials: [
        (name: "grey", shader: Lambert(albedo: (0.6, 0.6, 0.6))),
        (name: "red", shader: Lambert(albedo: (0.8, 0.2, 0.1)), contour: Simple(color: (0, 0, 0, 1), width: 1)),
    ],
    objects: [
        {grid_object}
        (name: "quad", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
            polygons: [[0, 1, 2, 3]]), material: "red"{displacement}),
    ],
    instances: [{grid_instance} (name: "quad_1", of: "quad")],
    groups: [(name: "world", members: [{members}])],
    render: (root: "world", camera: "cam"),
)"#,
        members = if grid {
            r#""floor_1", "quad_1""#
        } else {
            r#""quad_1""#
        }
    )
}

const LENS: &str = "lens: [Fisheye(fov: 150)],";
const DISPLACED: &str = ", displacement: (shader: Sine(amplitude: 0.2, factor: 2), bound: 0.2), \
                         approximation: Parametric(u: 8, v: 8)";

/// The beauty image and the stage report of a render (no files written).
fn render(text: &str) -> (Vec<Vec3>, Vec<StageReport>) {
    let mut scene =
        load_scene_str(text, Path::new("switches.ron")).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("an image").beauty;
    (image, frame.report.stages)
}

fn reason<'a>(report: &'a [StageReport], stage: &str) -> (bool, &'a str) {
    let r = report
        .iter()
        .find(|r| r.stage == stage)
        .expect("stage reported");
    (r.ran, r.reason.as_str())
}

fn bits(img: &[Vec3]) -> Vec<[u32; 3]> {
    img.iter().map(|c| c.to_array().map(f32::to_bits)).collect()
}

#[test]
fn lens_off_renders_the_pinhole_image() {
    let (pinhole, _) = render(&scene("", "", "", true));
    let (fisheye, _) = render(&scene("", LENS, "", true));
    assert_ne!(bits(&pinhole), bits(&fisheye));
    let (off, report) = render(&scene(", disable: [Lens]", LENS, "", true));
    assert_eq!(bits(&off), bits(&pinhole));
    let (ran, why) = reason(&report, "shade");
    assert!(ran && why.contains("lens shaders disabled"), "{why}");
}

#[test]
fn displacement_off_renders_the_undisplaced_mesh() {
    let (flat, _) = render(&scene("", "", "", false));
    let (displaced, report) = render(&scene("", "", DISPLACED, false));
    assert!(reason(&report, "tessellate").0);
    assert_ne!(bits(&flat), bits(&displaced));
    let (off, report) = render(&scene(", disable: [Displacement]", "", DISPLACED, false));
    assert_eq!(bits(&off), bits(&flat));
    assert_eq!(
        reason(&report, "tessellate"),
        (
            false,
            "displacement disabled (1 displacement shader(s) left out)"
        )
    );
}

#[test]
fn geometry_and_output_off_skip_their_stages() {
    let (without_floor, _) = render(&scene("", "", "", false));
    let (on, report) = render(&scene("", "", "", true));
    assert!(reason(&report, "expand_geometry").0 && reason(&report, "draw_contours").0);
    assert_ne!(bits(&on), bits(&without_floor));
    let (off, report) = render(&scene(", disable: [Geometry, Output]", "", "", true));
    assert_eq!(bits(&off), bits(&without_floor));
    assert_eq!(
        reason(&report, "expand_geometry"),
        (
            false,
            "geometry shaders disabled (1 geometry shader(s), 0 scatter(s) left empty)"
        )
    );
    assert_eq!(
        reason(&report, "draw_contours"),
        (
            false,
            "output shaders disabled (1 material(s) with a contour shader)"
        )
    );
}

/// With geometry shaders off, a `Sphere` is never expanded: `tessellate` says so (not "no
/// parametric surfaces"), and `build_accel` no longer waits for generated triangles.
#[test]
fn geometry_off_gives_the_true_reasons_downstream() {
    let sphere = |options: &str| {
        scene(options, "", "", true).replace("Grid(size_x: 6, size_y: 6)", "Sphere(radius: 0.5)")
    };
    let (_, report) = render(&sphere(""));
    assert!(reason(&report, "tessellate").0);
    let (_, report) = render(&sphere(", disable: [Geometry]"));
    assert_eq!(
        reason(&report, "tessellate"),
        (
            false,
            "geometry shaders disabled (1 shape(s) not expanded into surfaces)"
        )
    );
    let (ran, why) = reason(&report, "build_accel");
    assert!(ran && !why.contains("more to be generated"), "{why}");
    // A displaced sphere left unexpanded has nothing to displace either: `tessellate` does
    // not run with 0 triangles (its true displacement counted the unexpanded shape's).
    let displaced = |options: &str| {
        scene(options, "", "", false)
            .replace(
                "Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],\n            polygons: [[0, 1, 2, 3]])",
                "Sphere(radius: 0.5)",
            )
            .replace(
                r#"material: "red")"#,
                r#"material: "red", displacement: (shader: Sine(amplitude: 0.1, factor: 8)))"#,
            )
    };
    assert!(displaced("").contains("Sphere(radius: 0.5), material: \"red\", displacement"));
    let (_, report) = render(&displaced(""));
    assert!(reason(&report, "tessellate").0);
    let (_, report) = render(&displaced(", disable: [Geometry]"));
    assert_eq!(
        reason(&report, "tessellate"),
        (
            false,
            "geometry shaders disabled (1 shape(s) not expanded into surfaces)"
        )
    );
}

#[test]
fn mi_switches_and_trace_off_map_onto_the_options() {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_controls/caustic_filter.mi"),
    )
    .unwrap()
    .replace(
        "caustic on\ncaustic filter tent\n",
        "lens off\ndisplace off\nvolume off\nvolume on\noutput off\ntrace off\ntrace depth 3 3 6\n",
    );
    let read = read_mi(Path::new("switches.mi"), text.as_bytes()).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let o = read.desc.options.unwrap();
    use stagelight::scene::desc::FeatureDesc;
    assert_eq!(
        o.disable,
        [
            FeatureDesc::Lens,
            FeatureDesc::Displacement,
            FeatureDesc::Output
        ]
    );
    assert_eq!((o.reflection_depth, o.refraction_depth), (0, 0));
}

#[test]
fn cli_disable_adds_to_the_options_and_reports_the_skip() {
    let dir = scratch("feature_switches_cli");
    std::fs::write(dir.join("s.ron"), scene("", LENS, DISPLACED, true)).unwrap();
    let out = run(bin().current_dir(&dir).args([
        "render",
        "s.ron",
        "--stats",
        "--disable",
        "displacement,lens",
        "-o",
        "a.png",
    ]));
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout).to_string() + &stderr(&out);
    assert!(text.contains("displacement disabled"), "{text}");
    assert!(text.contains("lens shaders disabled"), "{text}");
    let bad = run(bin()
        .current_dir(&dir)
        .args(["render", "s.ron", "--disable", "fog"]));
    assert!(!bad.status.success());
    assert!(
        stderr(&bad).contains("unknown feature \"fog\" (expected one of lens, volume, geometry, displacement, output)"),
        "{}",
        stderr(&bad)
    );
}

#[test]
fn the_samples_diagnostic_shows_where_adaptive_sampling_refined() {
    let adaptive = ", samples: (min: 4, max: 16, contrast: (0.05, 0.05, 0.05))";
    let run = |options: &str| {
        let text = scene(options, "", "", true).replace("samples: 1, ", "");
        let mut scene = load_scene_str(&text, Path::new("d.ron")).unwrap_or_else(|e| panic!("{e}"));
        let frame = crate::common::render(&mut scene.world, scene.settings.clone());
        (frame.outputs.image.unwrap(), frame.report.stages)
    };
    let (shaded, _) = run(adaptive);
    let (view, report) = run(&format!("{adaptive}, diagnostic: Samples"));
    assert_eq!(view.samples, shaded.samples, "the same sampling");
    for (v, n) in view.beauty.iter().zip(&view.samples) {
        assert_eq!(*v, Vec3::splat(*n as f32 / 16.0));
    }
    let refined = view.samples.iter().filter(|&&n| n > 4).count();
    assert!(refined > 0 && refined < view.samples.len(), "{refined}");
    let (ran, why) = reason(&report, "shade");
    assert!(ran && why.contains("diagnostic samples"), "{why}");
}

/// `shade`'s reason names the lens and volume shaders it leaves out only where the scene has
/// some, as `tessellate` names switched-off displacement only where there is some.
#[test]
fn shade_names_disabled_lens_and_volume_shaders_only_when_the_scene_has_them() {
    let plain = ", disable: [Lens, Volume]";
    let (_, report) = render(&scene(plain, "", "", false));
    assert_eq!(reason(&report, "shade"), (true, "render camera 24×24"));
    let (_, report) = render(&scene(plain, LENS, "", false));
    assert_eq!(
        reason(&report, "shade"),
        (true, "render camera 24×24, lens shaders disabled")
    );
    let fog = "atmosphere: Fog(sigma_a: (0.1, 0.1, 0.1), sigma_s: (0.2, 0.2, 0.2), g: 0),";
    let (_, report) = render(&scene(plain, fog, "", false));
    assert_eq!(
        reason(&report, "shade"),
        (true, "render camera 24×24, volume shaders disabled")
    );
}

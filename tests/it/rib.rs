//! The RenderMan RIB reader end to end: the seed's RIB scenes read, convert to RON and render
//! without NaN; malformed RIB files give exact located messages.

use std::path::{Path, PathBuf};

use stagelight::components::{Camera, RenderCamera};
use stagelight::scene::import::rib::read_rib;
use stagelight::scene::import::to_ron::to_ron;
use stagelight::scene::{load_scene, load_scene_str};

fn dir(sub: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(sub)
}

fn files(sub: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir(sub))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "rib"))
        .collect();
    v.sort();
    v
}

/// Renders a loaded scene at most 40 pixels wide, 2 samples per pixel, without writing.
fn render_small(mut scene: stagelight::scene::LoadedScene) -> Vec<glam::Vec3> {
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        let scale = (40.0 / camera.width.max(camera.height) as f32).min(1.0);
        camera.width = ((camera.width as f32 * scale).round() as u32).max(1);
        camera.height = ((camera.height as f32 * scale).round() as u32).max(1);
    }
    let mut settings = scene.settings.clone();
    settings.spp = settings.spp.min(2);
    let frame = crate::common::render(&mut scene.world, settings);
    frame.outputs.image.expect("an image").beauty
}

#[test]
fn seed_ribs_render_without_nan_and_their_ron_renders_the_same() {
    let ribs = files("assets/seeds/rib");
    assert!(ribs.len() >= 10, "{ribs:?}");
    for path in ribs {
        let name = path.display().to_string();
        let scene = load_scene(&path).unwrap_or_else(|e| panic!("{name}:\n{e}"));
        let beauty = render_small(scene);
        assert!(
            beauty
                .iter()
                .all(|c| c.is_finite() && c.min_element() >= 0.0),
            "{name}: NaN or negative"
        );
        assert!(
            beauty.iter().any(|c| c.max_element() > 0.0),
            "{name}: black"
        );
        // `stagelight convert`'s RON loads into the same description: the same pixels.
        let bytes = std::fs::read(&path).unwrap();
        let text = to_ron(&read_rib(&path, &bytes).unwrap().desc).unwrap();
        let again = load_scene_str(&text, &path.with_extension("ron"))
            .unwrap_or_else(|e| panic!("{name}:\n{e}\n{text}"));
        let same = render_small(again);
        assert!(
            beauty
                .iter()
                .zip(&same)
                .all(|(a, b)| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)),
            "{name}: the converted RON renders differently"
        );
    }
}

#[test]
fn cli_convert_writes_ron_that_renders_byte_identical() {
    crate::common::convert_renders_the_same_png(
        "rib_convert",
        &dir("assets/seeds/rib/shadertest.rib"),
    );
}

/// `(fixture, every message it produces)`.
const MALFORMED: &[(&str, &str)] = &[
    (
        "attribute_end_without_begin",
        "tests/fixtures/rib/attribute_end_without_begin.rib:2:1: error: AttributeEnd without AttributeBegin",
    ),
    (
        "bad_paraboloid",
        "tests/fixtures/rib/bad_paraboloid.rib:2:1: error: Paraboloid needs rmax > 0, 0 ≤ zmin < zmax and thetamax > 0, found 1 2 1 360",
    ),
    (
        "bad_pixel_filter",
        "tests/fixtures/rib/bad_pixel_filter.rib:2:24: error: PixelFilter width must be above 0 and at most 128 pixels, found 0\n  help: a width of 2 to 4 pixels is usual (`PixelFilter \"gaussian\" 2 2`)",
    ),
    (
        "bad_number",
        "tests/fixtures/rib/bad_number.rib:2:13: error: invalid number \"1.2.3\"",
    ),
    (
        "declare_type",
        "tests/fixtures/rib/declare_type.rib:1:16: error: unknown type \"flaot\": expected float, integer, point, vector, normal, color, hpoint, matrix or string",
    ),
    (
        "display_mode",
        "tests/fixtures/rib/display_mode.rib:1:26: error: display mode \"Ci\" is not supported\n  help: expected one of \"rgb\", \"rgba\", \"rgbz\", \"rgbaz\", \"a\", \"az\", \"z\", \"N\" or \"P\"",
    ),
    (
        "geometry_before_world",
        "tests/fixtures/rib/geometry_before_world.rib:1:1: error: Sphere before WorldBegin\n  help: geometry and lights go between WorldBegin and WorldEnd",
    ),
    (
        "mismatched_blocks",
        "tests/fixtures/rib/mismatched_blocks.rib:4:1: error: AttributeEnd closes a block opened by TransformBegin at 3:1",
    ),
    (
        "missing_archive",
        "tests/fixtures/rib/missing_archive.rib:2:13: error: cannot read archive \"tests/fixtures/rib/missing.rib\": file not found",
    ),
    (
        "missing_argument",
        "tests/fixtures/rib/missing_argument.rib:2:1: error: Sphere needs thetamax (a number)",
    ),
    (
        "mixed_array",
        "tests/fixtures/rib/mixed_array.rib:2:7: error: an array mixes numbers and strings",
    ),
    (
        "negative_radius",
        "tests/fixtures/rib/negative_radius.rib:2:8: error: object \"sphere_1\" (sphere): parameter `radius` = -1 is out of range (expected > 0)",
    ),
    (
        "no_world",
        "tests/fixtures/rib/no_world.rib:1:1: error: the file has no WorldBegin: no scene to render\n  help: geometry and lights go between WorldBegin and WorldEnd",
    ),
    (
        "parameter_count",
        "tests/fixtures/rib/parameter_count.rib:2:35: error: parameter \"specularcolor\" of Surface takes a multiple of 3 numbers, found 2",
    ),
    (
        "patch_point_count",
        "tests/fixtures/rib/patch_point_count.rib:2:22: error: Patch needs nu × nv = 4 points, found 3",
    ),
    (
        "screen_window_order",
        "tests/fixtures/rib/screen_window_order.rib:1:1: error: ScreenWindow needs left < right and bottom < top, found 1 -1 -1 1",
    ),
    (
        "too_many_arguments",
        "tests/fixtures/rib/too_many_arguments.rib:2:17: error: too many arguments for Translate",
    ),
    (
        "two_errors",
        "tests/fixtures/rib/two_errors.rib:2:1: error: Translate needs dz (a number)\ntests/fixtures/rib/two_errors.rib:3:17: error: unknown parameter \"Ks\" of surface \"matte\"\n  help: did you mean \"Ka\"?",
    ),
    (
        "unclosed_array",
        "tests/fixtures/rib/unclosed_array.rib:2:7: error: unclosed '[' before request \"Sphere\"",
    ),
    (
        "unclosed_attribute",
        "tests/fixtures/rib/unclosed_attribute.rib:4:1: error: WorldEnd closes a block opened by AttributeBegin at 2:1",
    ),
    (
        "undeclared_parameter",
        "tests/fixtures/rib/undeclared_parameter.rib:2:19: error: undeclared parameter \"near\"\n  help: declare it first (Declare \"near\" \"float\") or write its type inline (\"float near\")",
    ),
    (
        "unexpected_character",
        "tests/fixtures/rib/unexpected_character.rib:2:15: error: unexpected character '@'",
    ),
    (
        "unknown_parameter",
        "tests/fixtures/rib/unknown_parameter.rib:2:19: error: unknown parameter \"Kz\" of surface \"plastic\"\n  help: did you mean \"Ka\"?",
    ),
    (
        "unknown_request",
        "tests/fixtures/rib/unknown_request.rib:2:1: error: unknown request \"Sphre\"\n  help: did you mean \"Sphere\"?",
    ),
    (
        "unsupported_basis",
        "tests/fixtures/rib/unsupported_basis.rib:1:7: error: the \"hermite\" basis is not supported: expected \"bezier\", \"b-spline\" or \"catmull-rom\"",
    ),
    (
        "unterminated_string",
        "tests/fixtures/rib/unterminated_string.rib:1:28: error: unterminated string (a string ends on its line)",
    ),
    (
        "spot_cone_angle",
        "tests/fixtures/rib/spot_cone_angle.rib:2:39: error: coneangle of \"spotlight\" must be above 0 and at most π/2 radians (90°), found -1\n  help: light-shader angles are in radians: 0.5236 is 30°",
    ),
    (
        "singular_camera",
        "tests/fixtures/rib/singular_camera.rib:1:1: error: the camera transformation is singular after this Scale: it cannot place a camera\n  help: the transformation current at WorldBegin is camera-from-world and must be invertible (no scale by 0)",
    ),
    (
        "empty_polygon",
        "tests/fixtures/rib/empty_polygon.rib:2:13: error: Polygon needs at least 3 vertices, found 0",
    ),
    (
        "motion_count",
        "tests/fixtures/rib/motion_count.rib:2:1: warning: motion blur is not rendered: each motion block uses its first time sample\n\
         tests/fixtures/rib/motion_count.rib:5:1: error: the motion block opened at 2:1 gives 3 times but holds 2 requests\n  help: write one request per time, all of the same kind",
    ),
    (
        "unknown_object",
        "tests/fixtures/rib/unknown_object.rib:5:16: error: unknown object handle \"bal\"\n  help: did you mean \"ball\"?",
    ),
    (
        "displacement_parameters",
        "tests/fixtures/rib/displacement_parameters.rib:2:28: error: unknown axis \"q\" of \"sine\"\n  help: expected \"s\", \"t\" or \"st\"\ntests/fixtures/rib/displacement_parameters.rib:3:33: error: parameter \"amplitude\" of displacement \"sine\" takes one float\ntests/fixtures/rib/displacement_parameters.rib:4:21: error: unknown parameter \"Km\" of displacement \"sine\"\n  help: expected \"amplitude\", \"factor\" or \"axis\"",
    ),
    (
        "later_frame_syntax",
        // The warning is the clue: the error is in a frame that is never rendered.
        "tests/fixtures/rib/later_frame_syntax.rib:7:1: warning: ignored this frame and every later one: only the first frame is rendered\n\
         tests/fixtures/rib/later_frame_syntax.rib:9:15: error: invalid number \"1.2.3\"",
    ),
    (
        "wrong_kind",
        "tests/fixtures/rib/wrong_kind.rib:2:13: error: expected a number for dy of Translate, found a string",
    ),
];

#[test]
fn malformed_ribs_give_exact_located_messages() {
    let fixtures = files("tests/fixtures/rib");
    assert!(fixtures.len() >= 15);
    assert_eq!(
        fixtures.len(),
        MALFORMED.len(),
        "one expectation per fixture"
    );
    for path in fixtures {
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        let shown = Path::new("tests/fixtures/rib").join(path.file_name().unwrap());
        let Some((_, expected)) = MALFORMED.iter().find(|(n, _)| *n == stem) else {
            panic!("no expectation for {stem}");
        };
        let got = match load_scene(&shown) {
            Ok(_) => "ok".to_string(),
            Err(e) => e.to_string(),
        };
        assert_eq!(got, *expected, "{stem}");
    }
}

#[test]
fn fuzz_corpus_reads_or_reports_located_errors() {
    for path in files("fuzz/corpus/rib") {
        let bytes = std::fs::read(&path).unwrap();
        match read_rib(Path::new("fuzz.rib"), &bytes) {
            Ok(scene) => {
                let text = to_ron(&scene.desc).unwrap();
                // Loading may fail validation, but never panics.
                let _ = load_scene_str(&text, Path::new("fuzz.ron"));
            }
            Err(errors) => {
                assert!(!errors.is_empty(), "{}", path.display());
                for e in &errors {
                    let p = e.problem.pos;
                    assert!(p.line >= 1 && p.column >= 1, "{}: {e}", path.display());
                }
            }
        }
    }
}

/// The tester's `dup3.rib`: an unnamed sphere and one named `sphere_1`, in either order.
fn named_sphere_scene(named_first: bool) -> String {
    let unnamed = "Sphere 0.2 -0.2 0.2 360\n";
    let named = "AttributeBegin\nAttribute \"identifier\" \"name\" [\"sphere_1\"]\nTranslate -1 0 0\nSphere 0.5 -0.5 0.5 360\nAttributeEnd\n";
    let (a, b) = if named_first {
        (named, unnamed)
    } else {
        (unnamed, named)
    };
    format!("Display \"d.png\" \"file\" \"rgb\"\nFormat 16 16 1\nTranslate 0 0 3\nWorldBegin\nLightSource \"pointlight\" 1 \"intensity\" [10] \"from\" [0 0 -3]\n{a}{b}WorldEnd\n")
}

#[test]
fn generated_names_skip_a_name_the_file_gives_in_either_order() {
    for (named_first, expected) in [
        (false, ["sphere_2", "sphere_1"]),
        (true, ["sphere_1", "sphere_2"]),
    ] {
        let text = named_sphere_scene(named_first);
        let path = Path::new("dup3.rib");
        let read = read_rib(path, text.as_bytes()).unwrap();
        let names: Vec<&str> = read.desc.objects.iter().map(|o| o.name.as_str()).collect();
        assert_eq!(names, expected, "named first: {named_first}");
        if let Err(e) = load_scene_str(&text, path) {
            panic!("named first: {named_first}: {e}");
        }
    }
}

//! Malformed scenes: every fixture in `tests/fixtures/scenes/bad/` with the exact text the
//! user sees, plus a robustness check that no input makes the loader panic.

use std::path::Path;

use stagelight::scene::{load_scene, load_scene_str, SceneErrors};

const GOOD: &str = "tests/fixtures/scenes/good/main.ron";

/// Loads a bad fixture (path relative to the package root, as a user would type it) and
/// returns its errors.
fn errors(name: &str) -> SceneErrors {
    let path = format!("tests/fixtures/scenes/bad/{name}");
    match load_scene(Path::new(&path)) {
        Ok(_) => panic!("{name} loaded without errors"),
        Err(e) => e,
    }
}

/// Asserts the full report of `name`, one string per diagnostic.
fn check(name: &str, expected: &[&str]) {
    let errors = errors(name);
    let got: Vec<String> = errors.0.iter().map(ToString::to_string).collect();
    assert_eq!(got, expected, "\n--- {name} reported:\n{errors}\n");
}

/// A missing comma between two fields, reported where it belongs: just after the first
/// field's value (it was reported at the start of the next field).
#[test]
fn syntax() {
    check(
        "syntax.ron",
        &[concat!(
            "tests/fixtures/scenes/bad/syntax.ron:2:30: error: expected comma\n",
            "  help: add ',' here",
        )],
    );
}

/// A misspelt field, with a suggestion.
#[test]
fn unknown_field() {
    check(
        "unknown_field.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/unknown_field.ron:3:61: error: unknown field \"two_side\" in Material\n",
                "  help: did you mean \"two_sided\"?",
            ),
        ],
    );
}

/// An unknown field with no close match lists what is expected.
#[test]
fn unknown_field_no_match() {
    check(
        "unknown_field_no_match.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/unknown_field_no_match.ron:2:59: error: unknown field \"radius\" in Point\n",
                "  help: expected \"position\"",
            ),
        ],
    );
}

/// A misspelt enum variant, with a suggestion.
#[test]
fn unknown_variant() {
    check(
        "unknown_variant.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/unknown_variant.ron:3:33: error: unknown variant \"Lambrt\" of Shader\n",
                "  help: did you mean \"Lambert\"?",
            ),
        ],
    );
}

/// A required field left out: reported at the opening of its struct.
#[test]
fn missing_field() {
    check(
        "missing_field.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/missing_field.ron:3:9: error: missing field \"fov_y\" in Camera\n",
                "  help: add `fov_y: …`; docs/scene-format.md lists the fields and their defaults",
            ),
        ],
    );
}

/// A string where a list is expected.
#[test]
fn wrong_type() {
    check(
        "wrong_type.ron",
        &["tests/fixtures/scenes/bad/wrong_type.ron:2:39: error: expected opening `[`\n  help: write a list `[…]` here"],
    );
}

/// A material name that is not defined, with a did-you-mean.
#[test]
fn dangling_material() {
    check(
        "dangling_material.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/dangling_material.ron:4:54: error: unknown material \"chrom\"\n",
                "  help: did you mean \"chrome\"?",
            ),
        ],
    );
}

/// Dangling names of each kind: `of`, group members, render camera.
#[test]
fn dangling_of() {
    check(
        "dangling_of.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/dangling_of.ron:3:34: error: unknown object or group \"bunyn\"\n",
                "  help: did you mean \"bunny\"?",
            ),
            concat!(
                "tests/fixtures/scenes/bad/dangling_of.ron:4:46: error: unknown instance \"b2\"\n",
                "  help: did you mean \"b1\"?",
            ),
            concat!(
                "tests/fixtures/scenes/bad/dangling_of.ron:6:37: error: unknown camera \"cma\"\n",
                "  help: did you mean \"cam\"?",
            ),
        ],
    );
}

/// A name defined twice points at the first definition.
#[test]
fn duplicate_name() {
    check(
        "duplicate_name.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/duplicate_name.ron:5:16: error: duplicate material name \"white\"\n",
                "  help: first defined at tests/fixtures/scenes/bad/duplicate_name.ron:3:16",
            ),
        ],
    );
}

/// Two groups containing each other through instances.
#[test]
fn dag_cycle() {
    check(
        "dag_cycle.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/dag_cycle.ron:3:30: error: instance cycle: a -> b_in_a -> b -> a_in_b -> a\n",
                "  help: a group may not contain itself, directly or through instances",
            ),
        ],
    );
}

/// Includes that come back to a file on the include chain.
#[test]
fn include_cycle() {
    check(
        "include_cycle.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/lib/cycle_b.ron:3:15: error: include cycle: tests/fixtures/scenes/bad/lib/cycle_a.ron -> tests/fixtures/scenes/bad/lib/cycle_b.ron -> tests/fixtures/scenes/bad/lib/cycle_a.ron\n",
                "  help: a file may not include itself, directly or through other files",
            ),
        ],
    );
}

/// An OBJ file that does not exist, with its resolved path.
#[test]
fn missing_obj() {
    check(
        "missing_obj.ron",
        &[
            "tests/fixtures/scenes/bad/missing_obj.ron:2:47: error: cannot read OBJ file \"tests/fixtures/scenes/bad/meshes/bunny.obj\": file not found\n  help: \"meshes/bunny.obj\" is read relative to tests/fixtures/scenes/bad/missing_obj.ron, the file that names it",
        ],
    );
}

/// An include that does not exist, with its resolved path.
#[test]
fn missing_include() {
    check(
        "missing_include.ron",
        &[
            "tests/fixtures/scenes/bad/missing_include.ron:2:36: error: cannot read include file \"tests/fixtures/scenes/bad/lib/nothing_here.ron\": file not found\n  help: \"lib/nothing_here.ron\" is read relative to tests/fixtures/scenes/bad/missing_include.ron, the file that names it",
        ],
    );
}

/// A transform matrix without an inverse, located at its transform entry.
#[test]
fn singular_matrix() {
    check(
        "singular_matrix.ron",
        &[
            "tests/fixtures/scenes/bad/singular_matrix.ron:6:13: error: transform matrix is singular (determinant 0): not invertible\n  help: the matrix flattens space onto a plane, a line or a point (a scale of 0, or two axes mapped to the same direction): every axis must keep a non-zero length and a direction of its own",
        ],
    );
}

/// A scale with a zero component.
#[test]
fn zero_scale() {
    check(
        "zero_scale.ron",
        &[
            "tests/fixtures/scenes/bad/zero_scale.ron:3:91: error: scale (1, 0, 1) has a zero component: the transform is not invertible\n  help: every factor must be non-zero: 1 keeps an axis as it is, and a thin object takes a small factor such as 0.001 (a negative factor mirrors)",
        ],
    );
}

/// Scales every value of which fits f32 but whose composition does not: a determinant that
/// underflows (its inverse is needed), a product beyond f32's range.
#[test]
fn tiny_and_huge_scales() {
    check(
        "tiny_and_huge_scales.ron",
        &[
            "tests/fixtures/scenes/bad/tiny_and_huge_scales.ron:3:54: error: the transform of \"world/tiny\" composed along its path scales space so little that its determinant (1.000e-60) underflows f32, and the renderer needs its inverse\n  help: scale the mesh itself (or the scene's units) so each instance scales by more than about 1e-12",
            "tests/fixtures/scenes/bad/tiny_and_huge_scales.ron:4:46: error: the transform of \"world/huge\" composed along its path does not fit in f32 (a value beyond ±3.4e38)\n  help: scale the scene's units down, or the mesh itself instead of its instance",
        ],
    );
}

/// NaN and inf literals where colours are expected.
#[test]
fn nan_colour() {
    check(
        "nan_colour.ron",
        &[
            "tests/fixtures/scenes/bad/nan_colour.ron:2:59: error: albedo must be a finite number, found NaN",
            "tests/fixtures/scenes/bad/nan_colour.ron:2:82: error: emission must be a finite number, found inf",
        ],
    );
}

/// A field of view outside (0, 180) degrees.
#[test]
fn fov_range() {
    check(
        "fov_range.ron",
        &[
            "tests/fixtures/scenes/bad/fov_range.ron:3:36: error: fov_y must be between 0 and 180 degrees (exclusive), found 180\n  help: fov_y is the full vertical angle of the view in degrees, such as 40 (a normal lens) or 90 (a wide one); a view of 180° or more needs a fisheye lens, `lens: [Fisheye(fov: 180)]`",
        ],
    );
}

/// An image with zero rows.
#[test]
fn resolution_zero() {
    check(
        "resolution_zero.ron",
        &[
            "tests/fixtures/scenes/bad/resolution_zero.ron:3:58: error: resolution height must be at least 1, found 0\n  help: the image is width × height pixels, each at least 1: `resolution: (640, 480)`",
        ],
    );
}

/// A Depth pass in a PNG output and an unknown output extension.
#[test]
fn png_depth() {
    check(
        "png_depth.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/png_depth.ron:6:54: error: a PNG output cannot hold the Depth pass\n",
                "  help: write the Depth pass to an .exr output",
            ),
            concat!(
                "tests/fixtures/scenes/bad/png_depth.ron:6:70: error: unknown output extension \".tiff\" in \"out.tiff\"\n",
                "  help: use .png, .exr, .svg or .eps, or give `format: Png`, `Exr`, `Svg` or `Eps`",
            ),
        ],
    );
}

/// A scene without a render entry.
#[test]
fn no_render() {
    check(
        "no_render.ron",
        &[concat!(
            "tests/fixtures/scenes/bad/no_render.ron:2:1: error: the scene has no render entry\n",
            "  help: add `render: (root: \"<group>\", camera: \"<camera>\")`",
        )],
    );
}

/// Many problems in one file: all reported, ordered by position.
#[test]
fn several() {
    check(
        "several.ron",
        &[
            "tests/fixtures/scenes/bad/several.ron:2:24: error: samples must be at least 1, found 0",
            "tests/fixtures/scenes/bad/several.ron:4:59: error: albedo must not be negative, found -0.1\n  help: albedo takes 0 or more: write 0.1 if only the sign is wrong",
            "tests/fixtures/scenes/bad/several.ron:6:91: error: cone_angle must be in (0, 90] degrees, found 95\n  help: cone_angle is the angle in degrees from the spot's axis to the edge of its cone (90 lights a half space, a cone 180° across); a light that shines every way is a point light",
            "tests/fixtures/scenes/bad/several.ron:6:105: error: penumbra must be in [0, cone_angle] = [0, 95] degrees, found 100",
            "tests/fixtures/scenes/bad/several.ron:6:122: error: intensity must not be negative, found -1\n  help: intensity takes 0 or more: write 1 if only the sign is wrong",
            "tests/fixtures/scenes/bad/several.ron:7:109: error: vertex index 3 is out of range: the mesh has 3 vertices, 0 to 2",
            "tests/fixtures/scenes/bad/several.ron:7:113: error: a polygon needs at least 3 vertex indices, found 2",
            concat!(
                "tests/fixtures/scenes/bad/several.ron:8:52: error: unknown material \"glod\"\n",
                "  help: did you mean \"gold\"?",
            ),
            "tests/fixtures/scenes/bad/several.ron:10:36: error: fov_y must be between 0 and 180 degrees (exclusive), found 0\n  help: fov_y is the full vertical angle of the view in degrees, such as 40 (a normal lens) or 90 (a wide one)",
            "tests/fixtures/scenes/bad/several.ron:10:101: error: target must differ from eye\n  help: the camera at eye looks toward target: make target the point to look at, such as the middle of the scene",
        ],
    );
}

/// A semantic error inside an included file names that file.
#[test]
fn error_in_include() {
    check(
        "error_in_include.ron",
        &[
            "tests/fixtures/scenes/bad/lib/broken_materials.ron:4:71: error: emission must not be negative, found -1\n  help: emission takes 0 or more: write 1 if only the sign is wrong",
        ],
    );
}

/// A syntax error inside an included file names that file.
#[test]
fn syntax_in_include() {
    check(
        "syntax_in_include.ron",
        &[
            "tests/fixtures/scenes/bad/lib/syntax.ron:2:66: error: expected a tuple of size 3 but found 2 elements\n  help: write exactly 3 values in `(…)`",
        ],
    );
}

/// A malformed OBJ file is reported at its own line.
#[test]
fn obj_parse() {
    check(
        "obj_parse.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/meshes/broken.obj:4:5: error: invalid OBJ file \"tests/fixtures/scenes/bad/meshes/broken.obj\": \"l\" is not a number\n",
                "  help: loaded for object \"broken\" at tests/fixtures/scenes/bad/obj_parse.ron:2:48",
            ),
        ],
    );
}

/// An index past the vertex list and a polygon with two indices.
#[test]
fn polygon_index() {
    check(
        "polygon_index.ron",
        &[
            "tests/fixtures/scenes/bad/polygon_index.ron:6:34: error: vertex index 4 is out of range: the mesh has 4 vertices, 0 to 3",
            "tests/fixtures/scenes/bad/polygon_index.ron:6:38: error: a polygon needs at least 3 vertex indices, found 2",
        ],
    );
}

/// A second render entry (in an include) points at the first.
#[test]
fn render_twice() {
    check(
        "render_twice.ron",
        &[concat!(
            "tests/fixtures/scenes/bad/lib/render.ron:2:13: error: render entry is given twice\n",
            "  help: first defined at tests/fixtures/scenes/bad/render_twice.ron:5:13",
        )],
    );
}

/// A camera matrix with scale is not rigid.
#[test]
fn camera_matrix() {
    check(
        "camera_matrix.ron",
        &[
            "tests/fixtures/scenes/bad/camera_matrix.ron:3:78: error: a camera matrix must be rigid: orthonormal rotation with determinant 1, no scale, shear or mirroring\n  help: the 3×3 part must be a rotation (columns of length 1 at right angles, determinant 1): scale the objects instead, or place the camera with `LookAt(eye: …, target: …, up: …)`",
        ],
    );
}
/// The errors of one file come in position order, and the count is exact.
#[test]
fn several_errors_are_all_reported_in_order() {
    let errors = errors("several.ron");
    assert_eq!(errors.0.len(), 10);
    let positions: Vec<(usize, usize)> = errors.0.iter().map(|d| (d.line, d.column)).collect();
    let mut sorted = positions.clone();
    sorted.sort();
    assert_eq!(positions, sorted);
}

/// Errors in several files are ordered by file (load order), then position.
#[test]
fn errors_are_ordered_by_file_then_position() {
    let text = r#"Scene(
        include: ["lib/broken_materials.ron"],
        groups: [(name: "world", members: ["nobody"])],
        cameras: [(name: "cam", fov_y: 400, resolution: (4, 4), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
        render: (root: "world", camera: "cam"),
    )"#;
    let errors = load_scene_str(text, Path::new("tests/fixtures/scenes/bad/inline.ron"))
        .err()
        .expect("errors");
    let got: Vec<String> = errors
        .0
        .iter()
        .map(|d| format!("{}:{}:{}", d.file.display(), d.line, d.column))
        .collect();
    assert_eq!(
        got,
        [
            "tests/fixtures/scenes/bad/inline.ron:3:44",
            "tests/fixtures/scenes/bad/inline.ron:4:40",
            "tests/fixtures/scenes/bad/lib/broken_materials.ron:4:71",
        ]
    );
}

/// A tiny deterministic generator for the robustness test (no dependency needed).
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Truncated prefixes and random byte mutations of a valid scene load or fail, never panic.
#[test]
fn no_input_makes_the_loader_panic() {
    let text = std::fs::read_to_string(GOOD).unwrap();
    let path = Path::new(GOOD);
    assert!(load_scene_str(&text, path).is_ok());
    let mut cut: Vec<usize> = (0..text.len()).step_by(3).collect();
    cut.push(text.len() - 1);
    for end in cut {
        if text.is_char_boundary(end) {
            let _ = load_scene_str(&text[..end], path);
        }
    }
    let alphabet = b"()[]{},:\"'/*#.-+0123456789eE_ \nrbNaNinfxyz";
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    for _ in 0..1500 {
        let mut bytes = text.clone().into_bytes();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(bytes.len());
            match rng.below(3) {
                0 => bytes[at] = alphabet[rng.below(alphabet.len())],
                1 => {
                    bytes.remove(at);
                }
                _ => bytes.insert(at, alphabet[rng.below(alphabet.len())]),
            }
        }
        if let Ok(mutated) = String::from_utf8(bytes) {
            let _ = load_scene_str(&mutated, path);
        }
    }
}

/// Non-finite numbers, a zero rotation axis and a non-affine matrix in transform lists.
#[test]
fn transform_values() {
    check(
        "transform_values.ron",
        &[
            "tests/fixtures/scenes/bad/transform_values.ron:4:56: error: translation must be a finite number, found -inf",
            "tests/fixtures/scenes/bad/transform_values.ron:4:83: error: rotation axis must not be zero\n  help: the axis is the direction to turn about: `axis: (0, 1, 0)` turns about y, `(1, 0, 0)` about x",
            "tests/fixtures/scenes/bad/transform_values.ron:5:95: error: the last row of a transform matrix must be (0, 0, 0, 1), found (0, 0, 1, 1)\n  help: the rows are written in order with the translation in the last column, `((a, b, c, tx), (d, e, f, ty), (g, h, i, tz), (0, 0, 0, 1))`: a matrix written column by column (translation in the last row) must be transposed",
        ],
    );
}

/// A number that is finite in f64 but not in f32 would become infinite when loaded.
#[test]
fn number_beyond_f32() {
    let text = r#"Scene(lights: [(name: "l", kind: Point(position: (1e300, 0, 0)))])"#;
    let errors = load_scene_str(text, Path::new("big.ron"))
        .err()
        .expect("errors");
    assert_eq!(errors.0.len(), 2, "{errors}");
    assert_eq!(
        errors.0[1].to_string(),
        "big.ron:1:51: error: position 1e300 is beyond the f32 range"
    );
}

/// Shader graphs: a phenomenon cycle, an unknown interface parameter, an unknown shader
/// parameter, a misspelt node and node field, a colour bound to a number, a missing image.
#[test]
fn shader_graph() {
    check(
        "shader_graph.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/shader_graph.ron:3:56: error: phenomenon \"wood\" uses itself: wood → bark → wood\n",
                "  help: a phenomenon cannot call itself, directly or through others",
            ),
            concat!(
                "tests/fixtures/scenes/bad/shader_graph.ron:4:32: error: phenomenon \"bark\" uses itself: bark → wood → bark\n",
                "  help: a phenomenon cannot call itself, directly or through others",
            ),
            concat!(
                "tests/fixtures/scenes/bad/shader_graph.ron:4:56: error: phenomenon \"wood\" has no parameter \"grian\"\n",
                "  help: did you mean \"grain\"?",
            ),
            concat!(
                "tests/fixtures/scenes/bad/shader_graph.ron:7:73: error: shader Lambert has no parameter \"albdo\"\n",
                "  help: did you mean \"albedo\"?",
            ),
            concat!(
                "tests/fixtures/scenes/bad/shader_graph.ron:7:73: error: unknown node \"Chekcer\"\n",
                "  help: did you mean \"Checker\"?",
            ),
            concat!(
                "tests/fixtures/scenes/bad/shader_graph.ron:8:60: error: parameter \"roughness\" is a number, but this gives a colour\n",
                "  help: take one channel with Channel(…, 0) or use Luminance(…)",
            ),
            concat!(
                "tests/fixtures/scenes/bad/shader_graph.ron:9:62: error: unknown field \"scael\" in Checker\n",
                "  help: did you mean \"scale\"?",
            ),
            concat!(
                "tests/fixtures/scenes/bad/shader_graph.ron:10:66: error: cannot read image file \"tests/fixtures/scenes/bad/missing.png\": file not found\n",
                "  help: image textures are PNG files, or EXR files with R, G and B, Y or a single channel, relative to the scene file",
            ),
        ],
    );
}

/// Lens shaders, volume shaders and adaptive samples are checked with located errors.
#[test]
fn lens_volume_and_adaptive_samples() {
    let f = "tests/fixtures/scenes/bad/lens_volume.ron";
    check(
        "lens_volume.ron",
        &[
            &format!("{f}:2:38: error: max must be at least min (8), found 4"),
            &format!(
                "{f}:5:16: error: a ThinLens needs exactly one of `radius` and `fstop`\n  help: e.g. `ThinLens(radius: 0.05, focus_distance: 4.0)`"
            ),
            &format!(
                "{f}:5:70: error: a projection lens (Fisheye, Spherical, Shift) must be the first lens\n  help: a projection replaces the pinhole, so it must come first in `lens`"
            ),
            &format!("{f}:5:124: error: focus_distance must be positive, found 0"),
            &format!("{f}:6:40: error: sigma_s must not be negative, found -0.2\n  help: sigma_s takes 0 or more: write 0.2 if only the sign is wrong"),
            &format!("{f}:6:55: error: g must be between -1 and 1 (exclusive), found 1"),
            &format!("{f}:7:99: error: sigma_a 1e39 is beyond the f32 range"),
        ],
    );
}

/// Photon map knobs out of range: every one reported at its value.
#[test]
fn photon_options() {
    check(
        "photon_options.ron",
        &[
            "tests/fixtures/scenes/bad/photon_options.ron:2:35: error: photons must be at least 1, found 0",
            "tests/fixtures/scenes/bad/photon_options.ron:2:46: error: gather must be at least 2 (the estimate divides by k − 1), found 1",
            "tests/fixtures/scenes/bad/photon_options.ron:2:80: error: radius must not be negative, found -1\n  help: radius takes 0 or more: write 1 if only the sign is wrong",
            "tests/fixtures/scenes/bad/photon_options.ron:2:98: error: final_gather must be at least 1, found 0",
        ],
    );
}

/// `ron` says only "integer is out of bounds"; the message names the number as written, the
/// field and the range it takes.
#[test]
fn out_of_range_integers_name_the_number_the_field_and_the_range() {
    let dir =
        crate::common::scratch_root().join(format!("stagelight-int-range-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (text, expected) in [
        (
            "Scene(\n  objects: [(name: \"g\", mesh: Grid(nx: 99999999999, ny: 2))],\n)\n",
            "int.ron:2:40: error: integer 99999999999 is out of range for `nx`\n  help: `nx` takes a whole number from 0 to 4294967295",
        ),
        (
            "Scene(\n  options: (seed: -3),\n)\n",
            "int.ron:2:20: error: integer -3 is out of range for `seed`\n  help: `seed` takes a whole number from 0 to 18446744073709551615",
        ),
    ] {
        let path = dir.join("int.ron");
        std::fs::write(&path, text).unwrap();
        let errors = stagelight::scene::load_scene(&path).err().expect("refused");
        let got = errors.0[0].to_string();
        assert_eq!(got, format!("{}/{expected}", dir.display()));
    }
}

/// A decimal where a whole number belongs: `ron` read `1` and said "expected comma" at the
/// `.`; the message names the number from its first digit and the range the field takes
/// (the least value the loader accepts, 1 for `resolution`, not 0). Adaptive `samples`
/// names itself in an unknown field's message (it said "in Options").
#[test]
fn decimals_for_whole_numbers_and_adaptive_samples_fields_are_named() {
    for (text, expected) in [
        (
            "Scene(\n  options: (seed: 1.5),\n)\n",
            "d.ron:2:19: error: expected a whole number, found 1.5\n  help: `seed` takes a whole number from 0 to 18446744073709551615",
        ),
        (
            "Scene(\n  cameras: [(name: \"c\", resolution: (32.5, 24))],\n)\n",
            "d.ron:2:38: error: expected a whole number, found 32.5\n  help: `resolution` takes a whole number from 1 to 4294967295",
        ),
        (
            "Scene(\n  cameras: [(name: \"c\", resolution: (-32, 24))],\n)\n",
            "d.ron:2:39: error: integer -32 is out of range for `resolution`\n  help: `resolution` takes a whole number from 1 to 4294967295",
        ),
        (
            "Scene(\n  options: (samples: (zzz: 1)),\n)\n",
            "d.ron:2:23: error: unknown field \"zzz\" in adaptive samples\n  help: expected \"min\", \"max\" or \"contrast\"",
        ),
    ] {
        let err = load_scene_str(text, Path::new("d.ron"))
            .err()
            .expect("refused");
        assert_eq!(err.0[0].to_string(), expected, "{text}");
    }
}

/// A key given twice in a `bind` map is an error at the repeated key, as a struct field
/// given twice is (the last value silently won before). The same holds for `Graph(…, {…})`
/// arguments and phenomenon `params`.
#[test]
fn duplicate_bind_key() {
    check(
        "duplicate_bind_key.ron",
        &[concat!(
            "tests/fixtures/scenes/bad/duplicate_bind_key.ron:3:38: error: key \"albedo\" is given twice in this map\n",
            "  help: keep one entry for each key",
        )],
    );
    let graph = r#"Scene(phenomena: [(name: "p", params: {"k": 1, "k": 2}, output: (1, 1, 1))])"#;
    let call = r#"Scene(phenomena: [(name: "p", params: {"k": 1}, output: Param("k"))],
        materials: [(name: "m", shader: Lambert(albedo: (1, 1, 1)),
            bind: {"albedo": Graph("p", {"k": 0.5, "k": 0.25})})])"#;
    for text in [graph, call] {
        let err = load_scene_str(text, Path::new("g.ron"))
            .err()
            .expect("refused");
        assert!(
            err.to_string()
                .contains("key \"k\" is given twice in this map"),
            "{err}"
        );
    }
}

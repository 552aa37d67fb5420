//! `.mi` value errors are located at the value: a bad camera `resolution`, light `spread`,
//! contour contrast value, contour width, photon option (`caustic accuracy`, `finalgather
//! accuracy`, `photonmap file`), object vertex or instance `transform` points at its own
//! `line:column` (not at the element's instance or block), and one bad value is one error (no cascade through the
//! rest of its parameter list, none after the lexer's own error).

use std::path::{Path, PathBuf};

use stagelight::scene::load_scene;

fn fixture() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_contours/square.mi");
    std::fs::read_to_string(path).unwrap()
}

fn dir(name: &str) -> PathBuf {
    let dir = crate::common::scratch_root().join(format!(
        "stagelight_mi_values_{name}_{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// What loading `text` as `bad.mi` in `dir` says (paths relative to `dir`).
fn messages(dir: &Path, text: &str) -> String {
    let path = dir.join("bad.mi");
    std::fs::write(&path, text).unwrap();
    let got = match load_scene(&path) {
        Ok(_) => "ok".to_string(),
        Err(e) => e.to_string(),
    };
    got.replace(&format!("{}/", dir.display()), "")
        .trim_end()
        .to_string()
}

fn replaced(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

#[test]
fn value_errors_point_at_the_value() {
    let text = fixture();
    let dir = dir("at");
    let cases = [
        (
            replaced(&text, "resolution 128 96", "resolution 0 96"),
            "bad.mi:29:12: error: resolution width must be at least 1, found 0\n  help: the image is width × height pixels, each at least 1: `resolution 640 480`",
        ),
        (
            replaced(&text, "resolution 128 96", "resolution 128 0"),
            "bad.mi:29:16: error: resolution height must be at least 1, found 0\n  help: the image is width × height pixels, each at least 1: `resolution 640 480`",
        ),
        (
            replaced(&text, "focal 12.0", "focal 0"),
            "bad.mi:26:7: error: camera \"Camera\" needs focal > 0 and aperture > 0, found 0 and 32",
        ),
        (
            replaced(
                &text,
                "origin 0.0 0.0 0.0\n",
                "origin 0.0 0.0 0.0\ndirection 0 0 1\nspread 2.0\n",
            ),
            "bad.mi:56:8: error: light \"Lamp_inst\": spread must be the cosine of the cone, in [0, 1), found 2",
        ),
        (
            replaced(&text, "\"ndelta\" 20.0,", "\"ndelta\" -5,"),
            "bad.mi:15:10: error: ndelta must be in (0, 180] degrees, found -5",
        ),
        (
            replaced(&text, "\"width\" 1.0", "\"width\" -1.0"),
            "bad.mi:76:9: error: contour width must be positive, found -1\n  help: widths are in percent of the smaller image dimension, e.g. `\"width\" 0.5`; to draw no contours, leave out the material's `contour` shader",
        ),
        (
            replaced(&text, "\"color\" 1.0 0.0 0.0 1.0,", "\"color\" 1.0 0.0 0.0 5.0,"),
            "bad.mi:75:9: error: color must be in [0, 1], found 5",
        ),
    ];
    for (bad, want) in cases {
        assert_eq!(messages(&dir, &bad), want);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn one_bad_contour_value_is_one_error() {
    let text = fixture();
    let dir = dir("one");
    let cases = [
        (
            replaced(&text, "\"ndelta\" 20.0,", "\"ndelta\" abc,"),
            "bad.mi:15:10: error: expected a value for parameter \"ndelta\", found \"abc\"",
        ),
        (
            replaced(&text, "\"ndelta\" 20.0,", "\"ndelta\" 20.0.5,"),
            "bad.mi:15:10: error: invalid number \"20.0.5\"",
        ),
        (
            replaced(&text, "\"width\" 1.0", "\"width\" 1.0.0"),
            "bad.mi:76:9: error: invalid number \"1.0.0\"",
        ),
        (
            replaced(&text, "\"width\" 1.0", "\"width\" big"),
            "bad.mi:76:9: error: expected a value for parameter \"width\", found \"big\"",
        ),
        (
            replaced(
                &text,
                "\"color\" 1.0 0.0 0.0 1.0,",
                "\"color\" 1.0 0.0 0.0 1.0",
            ),
            "bad.mi:76:1: error: expected ',' or ')' after parameter, found a string",
        ),
    ];
    for (bad, want) in cases {
        assert_eq!(messages(&dir, &bad), want);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A quad lit by a point light; `options`, `object` and `instance` go into those blocks.
fn small(options: &str, object: &str, instance: &str) -> String {
    format!(
        "options \"opt\"
object space
{options}
end options
camera \"cam\" resolution 8 6 focal 1 aperture 1 end camera
light \"lamp\" \"mib_light_point\" (\"color\" 1 1 1) origin 0 0 0 end light
material \"mtl\" \"mib_illum_lambert\" (\"diffuse\" 0.8 0.8 0.8, \"lights\" [\"lamp_inst\"]) end material
object \"quad\" group
{object}1 -1 -1  -1 -1 -1  -1 1 -1
v 0 v 1 v 2 v 3
p \"mtl\" 0 3 2 1
end group end object
instance \"cam_inst\" \"cam\" end instance
instance \"lamp_inst\" \"lamp\" end instance
instance \"quad_inst\" \"quad\" {instance} end instance
instgroup \"root\" \"cam_inst\" \"lamp_inst\" \"quad_inst\" end instgroup
render \"root\" \"cam_inst\" \"opt\"
"
    )
}

#[test]
fn photon_object_and_instance_values_point_at_the_value() {
    let dir = dir("photon_object_instance");
    let ok_vertex = "1 1 -1  ";
    let identity = "transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1";
    let cases = [
        (
            small("caustic on\ncaustic accuracy 0", ok_vertex, identity),
            "bad.mi:4:18: error: caustic accuracy must be at least 2 photons per estimate, found 0",
        ),
        (
            small("globillum on\nfinalgather accuracy 0", ok_vertex, identity),
            "bad.mi:4:22: error: finalgather accuracy must be at least 1 ray, found 0",
        ),
        (
            small("caustic on\nphotonmap file \"\"", ok_vertex, identity),
            "bad.mi:4:16: error: photon_map file is empty: name the file the photon maps are kept in, e.g. \"scene.pmap\"",
        ),
        (
            small("", "1 1e39 -1  ", identity),
            "bad.mi:9:3: error: vertex 1e39 is beyond the f32 range",
        ),
        (
            small("", ok_vertex, "transform 0 0 0 0  0 0 0 0  0 0 0 0  0 0 0 1"),
            "bad.mi:15:39: error: the transform of instance \"quad_inst\" is singular",
        ),
        (
            small("", ok_vertex, "transform 1e300 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1"),
            "bad.mi:15:39: error: transform matrix is singular",
        ),
    ];
    for (bad, want) in cases {
        let got = messages(&dir, &bad);
        let first = got.lines().next().unwrap();
        // The determinant's digits left out of the last message.
        match want.strip_suffix("is singular") {
            Some(prefix) if want.contains("transform matrix") => {
                assert!(first.starts_with(prefix), "{got}")
            }
            _ => assert_eq!(first, want),
        }
        assert_eq!(
            got.lines().filter(|l| l.contains("error:")).count(),
            1,
            "{got}"
        );
    }
}

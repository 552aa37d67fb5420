//! `.mi` value errors are located at the value: a bad camera `resolution`, light `spread`,
//! contour contrast value or contour width points at its own `line:column` (not at the
//! element's instance or block), and one bad value is one error (no cascade through the
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
            "bad.mi:29:12: error: resolution width must be at least 1, found 0",
        ),
        (
            replaced(&text, "resolution 128 96", "resolution 128 0"),
            "bad.mi:29:16: error: resolution height must be at least 1, found 0",
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
            "bad.mi:15:10: error: normal_angle must be in (0, 180] degrees, found -5",
        ),
        (
            replaced(&text, "\"width\" 1.0", "\"width\" -1.0"),
            "bad.mi:76:9: error: contour width must be positive, found -1\n  help: widths are in percent of the smaller image dimension, e.g. `width: 0.5`; to draw no contours, leave out `contour`",
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

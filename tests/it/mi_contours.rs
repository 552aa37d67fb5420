//! Issue 13: mental ray contours in `.mi` — `contour store`/`contour contrast` in the
//! options, a material's `contour_shader_simple`, and the camera's `output "contour" "eps"
//! "file"` — draw the contour file from the CLI with its lines on the silhouette; malformed
//! contour statements give exact located messages.

use std::path::{Path, PathBuf};

use stagelight::scene::desc::{ContourDesc, ContoursDesc};
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene;

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_contours/square.mi")
}

/// Every `x y m` / `x y l` point of an EPS document (PostScript y up).
fn eps_points(eps: &str) -> Vec<(f32, f32)> {
    let words: Vec<&str> = eps.split_whitespace().collect();
    words
        .windows(3)
        .filter(|w| w[2] == "m" || w[2] == "l")
        .filter_map(|w| Some((w[0].parse().ok()?, w[1].parse().ok()?)))
        .collect()
}

#[test]
fn the_contour_statements_map_onto_the_contour_stage() {
    let bytes = std::fs::read(fixture()).unwrap();
    let read = read_mi(&fixture(), &bytes).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let contours = read.desc.options.unwrap().contours.expect("contours on");
    let mut want = ContoursDesc::default();
    want.contrast.normal_angle = 20.0;
    assert_eq!(contours, want);
    assert_eq!(
        read.desc.materials[0].contour,
        Some(ContourDesc::Simple {
            color: (1.0, 0.0, 0.0, 1.0),
            width: 1.0
        })
    );
}

#[test]
fn cli_render_writes_the_eps_with_lines_at_the_silhouette() {
    let tmp = crate::common::scratch_root()
        .join(format!("stagelight_mi_contours_{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let scene = tmp.join("square.mi");
    std::fs::copy(fixture(), &scene).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stagelight"))
        .current_dir(&tmp)
        .args(["render", "square.mi", "--spp", "1"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let eps = std::fs::read_to_string(tmp.join("square.eps")).expect("the contour file");
    assert!(eps.starts_with("%!PS-Adobe-3.0 EPSF-3.0\n"), "{eps}");
    assert!(eps.contains("%%BoundingBox: 0 0 128 96\n"), "{eps}");
    assert!(eps.contains("1.0000 0.0000 0.0000 setrgbcolor"), "{eps}");
    // The square ±0.5 at distance 1 (focal 12, aperture 32: tan 4/3 across, 1 up) spans
    // x 40…88 and y 24…72 pixels; the outline lies within the line's half-width (0.48 px,
    // 1 % of 96) plus 0.25 px of that boundary, and reaches every side.
    let points = eps_points(&eps);
    assert!(points.len() >= 8, "{eps}");
    let mut sides = [false; 4];
    for &(x, y) in &points {
        let d = [
            (x - 40.0).abs(),
            (x - 88.0).abs(),
            (y - 24.0).abs(),
            (y - 72.0).abs(),
        ];
        let inside = (39.0..=89.0).contains(&x) && (23.0..=73.0).contains(&y);
        let near = d.iter().copied().fold(f32::INFINITY, f32::min);
        assert!(
            inside && near <= 0.75,
            "({x}, {y}) is {near} px off the silhouette"
        );
        for (k, s) in sides.iter_mut().enumerate() {
            *s |= d[k] <= 0.75;
        }
    }
    assert_eq!(sides, [true; 4], "every side has a line");
    let _ = std::fs::remove_dir_all(&tmp);
}

#[test]
fn malformed_contour_statements_give_exact_located_messages() {
    let text = std::fs::read_to_string(fixture()).unwrap();
    let dir = crate::common::scratch_root()
        .join(format!("stagelight_mi_contour_bad_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        (
            text.replace("contour_shader_simple", "contour_shader_simpel"),
            "bad.mi:74:9: error: unknown contour shader \"contour_shader_simpel\"\n  help: did you mean \"contour_shader_simple\"?",
        ),
        (
            text.replace("contour store", "contour stroe"),
            "bad.mi:13:9: error: expected \"store\" or \"contrast\" after \"contour\", found \"stroe\"\n  help: did you mean \"store\"?",
        ),
        (
            text.replace("\"contour\" \"eps\"", "\"contour\" \"pdf\""),
            "bad.mi:25:18: error: contour output format \"pdf\" is not supported\n  help: write \"ps\" or \"eps\" (Encapsulated PostScript)",
        ),
    ];
    for (bad, want) in cases {
        let path = dir.join("bad.mi");
        std::fs::write(&path, &bad).unwrap();
        let got = match load_scene(&path) {
            Ok(_) => "ok".to_string(),
            Err(e) => e.to_string(),
        };
        let prefix = format!("{}/", dir.display());
        assert_eq!(got.replace(&prefix, "").trim_end(), want);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `max_level` outside 1 … 9 is read as the nearest level followed, with a warning at the
/// value (it was clamped silently).
#[test]
fn a_max_level_outside_the_levels_followed_warns() {
    let text = std::fs::read_to_string(fixture()).unwrap();
    for (written, ray_depth) in [("20", 8), ("0", 0)] {
        let bad = text.replace("\"max_level\" 1\n", &format!("\"max_level\" {written}\n"));
        let read = read_mi(Path::new("c.mi"), bad.as_bytes()).unwrap();
        let warnings: Vec<String> = read.warnings.iter().map(|w| w.to_string()).collect();
        let used = if written == "20" { 9 } else { 1 };
        assert_eq!(
            warnings,
            [format!("c.mi:18:13: warning: \"max_level\" {written} is read as {used}: contours follow 1 to 9 levels (the first hit and up to 8 mirror, refraction or transparency levels behind it; RON `ray_depth` 0 to 8)")]
        );
        assert_eq!(
            read.desc.options.unwrap().contours.unwrap().ray_depth,
            ray_depth
        );
    }
}

/// `-o lines.svg` on a `.mi` scene without contour shaders says what to add in `.mi`
/// statements (the options' store and contrast functions, a material's contour shader),
/// not in RON.
#[test]
fn dash_o_svg_without_contour_shaders_helps_in_mi_terms() {
    let mut plain = std::fs::read_to_string(fixture()).unwrap();
    for first in [
        "\ncontour store",
        "\ncontour contrast",
        "\ncontour \"contour_shader_simple\"",
    ] {
        let start = plain.find(first).unwrap() + 1;
        let end = start + plain[start..].find(")\n").unwrap() + 2;
        plain.replace_range(start..end, "");
    }
    let plain = plain.replace("output \"contour\" \"eps\" \"square.eps\"\n", "");
    let dir = crate::common::cli::scratch_dir("mi-contours-dash-o");
    std::fs::write(dir.join("plain.mi"), plain).unwrap();
    let o = crate::common::cli::run_in(&dir, &["render", "plain.mi", "-o", "lines.svg"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        crate::common::cli::stderr_of(&o).trim_end(),
        "error: -o lines.svg writes contour lines, but no material of the scene has a contour shader\n  help: add `contour store \"contour_store_function\" ()` and `contour contrast \"contour_contrast_function_levels\" ()` to the options and `contour \"contour_shader_simple\" (\"color\" 0 0 0 1, \"width\" 0.5)` to a material, or write a .png or .exr"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

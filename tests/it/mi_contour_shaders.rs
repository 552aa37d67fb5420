//! Issue 13: the rest of mental ray's contour shaders in `.mi` — `contour_shader_silhouette`
//! draws the outline but not a crease inside the object, `contour_shader_widthfromcolor`
//! draws thick lines around a dark material and thin ones around a bright one,
//! `contour_shader_framefade` takes its width and colour from the camera's frame, and
//! `contour_shader_layerthinner` becomes the layer-thinning shader.

use std::path::{Path, PathBuf};

use stagelight::contour::ContourImage;
use stagelight::scene::desc::ContourDesc;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene;

fn fixture() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_contours/square.mi");
    std::fs::read_to_string(path).unwrap()
}

const SIMPLE: &str =
    "contour \"contour_shader_simple\" (\n\"color\" 1.0 0.0 0.0 1.0,\n\"width\" 1.0\n)";

/// The square folded along x = 0 towards the camera (a 53° crease), one material.
const FOLDED: &str = "group
0.5 0.5 0.0
0.5 -0.5 0.0
-0.5 -0.5 0.0
-0.5 0.5 0.0
0.0 0.5 0.25
0.0 -0.5 0.25
v 0
v 1
v 2
v 3
v 4
v 5
p \"grey\" 4 3 2 5
p \"grey\" 0 4 5 1
end group";

const SQUARE_GROUP: &str = "group
0.5 0.5 0.0
0.5 -0.5 0.0
-0.5 -0.5 0.0
-0.5 0.5 0.0
v 0
v 1
v 2
v 3
p \"grey\" 0 3 2 1
end group";

fn write(text: &str, name: &str) -> PathBuf {
    let dir = crate::common::scratch_root().join(format!(
        "stagelight_mi_cshaders_{}_{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.mi");
    std::fs::write(&path, text).unwrap();
    path
}

/// The contour lines of the `.mi` scene `text` (every stage but `write_output`).
fn contours(text: &str, name: &str) -> ContourImage {
    let path = write(text, name);
    let mut scene = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    let _ = std::fs::remove_dir_all(path.parent().unwrap());
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    frame.outputs.contours.expect("contour lines")
}

/// Line points within 3 px of the crease (x = 64) and 12 px of the middle row.
fn on_crease(image: &ContourImage) -> usize {
    image
        .lines
        .iter()
        .flat_map(|l| &l.points)
        .filter(|p| (p.pos.x - 64.0).abs() < 3.0 && (p.pos.y - 48.0).abs() < 12.0)
        .count()
}

/// Line points within 3 px of the square's left side (x = 40) and 12 px of the middle row.
fn on_left_side(image: &ContourImage) -> usize {
    image
        .lines
        .iter()
        .flat_map(|l| &l.points)
        .filter(|p| (p.pos.x - 40.0).abs() < 3.0 && (p.pos.y - 48.0).abs() < 12.0)
        .count()
}

#[test]
fn silhouette_draws_the_outline_but_not_the_crease() {
    let folded = fixture().replace(SQUARE_GROUP, FOLDED);
    let simple = contours(&folded, "simple");
    assert!(
        on_crease(&simple) >= 10,
        "the simple shader draws the crease"
    );
    let silhouette = folded.replace("contour_shader_simple", "contour_shader_silhouette");
    let read = read_mi(Path::new("s.mi"), silhouette.as_bytes()).unwrap();
    assert_eq!(
        read.desc.materials[0].contour,
        Some(ContourDesc::Silhouette {
            color: (1.0, 0.0, 0.0, 1.0),
            width: 1.0
        })
    );
    let image = contours(&silhouette, "silhouette");
    assert_eq!(on_crease(&image), 0, "no line on the crease");
    assert!(on_left_side(&image) >= 10, "the outline is drawn");
    assert_eq!(on_left_side(&image), on_left_side(&simple));
}

#[test]
fn widthfromcolor_draws_thick_lines_on_dark_and_thin_on_bright_materials() {
    // Two squares of 0.8 × 0.8 at x ∈ [−0.9, −0.1] (dark) and [0.1, 0.9] (bright).
    let text = fixture()
        .replace(
            SIMPLE,
            "contour \"contour_shader_widthfromcolor\" (\"color\" 0 0 0 1, \"min_width\" 0.5, \"max_width\" 3.0)",
        )
        .replace(
            "end material\n",
            "end material\nmaterial \"bright\"\nopaque\n\"mib_illum_lambert\" (\"diffuse\" 0.9 0.9 0.9, \"lights\" [ \"Lamp_inst\" ])\ncontour \"contour_shader_widthfromcolor\" (\"color\" 0 0 0 1, \"min_width\" 0.5, \"max_width\" 3.0)\nend material\n",
        )
        .replace("\"diffuse\" 0.5 0.5 0.5", "\"diffuse\" 0.1 0.1 0.1")
        .replace(
            SQUARE_GROUP,
            "group
-0.1 0.4 0.0
-0.1 -0.4 0.0
-0.9 -0.4 0.0
-0.9 0.4 0.0
0.9 0.4 0.0
0.9 -0.4 0.0
0.1 -0.4 0.0
0.1 0.4 0.0
v 0
v 1
v 2
v 3
v 4
v 5
v 6
v 7
p \"grey\" 0 3 2 1
p \"bright\" 4 7 6 5
end group",
        );
    let image = contours(&text, "widthfromcolor");
    let widths = |name: &str| -> Vec<f32> {
        let k = image
            .material_names
            .iter()
            .position(|n| n == name)
            .expect(name);
        image
            .lines
            .iter()
            .filter(|l| l.material == k as u32 + 1)
            .flat_map(|l| l.points.iter().map(|p| p.width))
            .collect()
    };
    let (dark, bright) = (widths("grey"), widths("bright"));
    assert!(
        dark.len() > 50 && bright.len() > 50,
        "{} {}",
        dark.len(),
        bright.len()
    );
    // width = (max − (max − min)·L) % of 96 px, L the shaded luminance: diffuse × cos θ with
    // cos θ in [0.7, 1] over the squares.
    let px = |percent: f32| percent * 0.96;
    for w in &dark {
        assert!(
            (px(3.0 - 2.5 * 0.1) - 0.01..=px(3.0 - 2.5 * 0.07) + 0.01).contains(w),
            "dark: {w}"
        );
    }
    for w in &bright {
        assert!(
            (px(3.0 - 2.5 * 0.9) - 0.01..=px(3.0 - 2.5 * 0.63) + 0.01).contains(w),
            "bright: {w}"
        );
    }
}

#[test]
fn framefade_takes_width_and_colour_from_the_camera_frame() {
    let fade = "contour \"contour_shader_framefade\" (\"frame1\" 1, \"frame2\" 11, \"color1\" 1 0 0 1, \"color2\" 0 0 1 1, \"width1\" 0.5, \"width2\" 2.5)";
    for (frame, t) in [(1, 0.0), (6, 0.5), (11, 1.0), (20, 1.0), (0, 0.0)] {
        let text = fixture()
            .replace(SIMPLE, fade)
            .replace("frame 1\n", &format!("frame {frame}\n"));
        let read = read_mi(Path::new("f.mi"), text.as_bytes()).unwrap();
        let width = 0.5 + 2.0 * t;
        assert_eq!(
            read.desc.materials[0].contour,
            Some(ContourDesc::Simple {
                color: (1.0 - t, 0.0, t, 1.0),
                width
            }),
            "frame {frame}"
        );
        if frame == 1 || frame == 11 {
            let image = contours(&text, &format!("frame{frame}"));
            let points: Vec<f32> = image
                .lines
                .iter()
                .flat_map(|l| l.points.iter().map(|p| p.width))
                .collect();
            assert!(points.len() > 50);
            let want = width as f32 * 0.96;
            assert!(
                points.iter().all(|w| (w - want).abs() < 1e-4),
                "frame {frame}: every line {want} px wide"
            );
        }
    }
}

#[test]
fn layerthinner_becomes_the_layer_thinning_shader() {
    let text = fixture().replace(
        SIMPLE,
        "contour \"contour_shader_layerthinner\" (\"color\" 0 0 1 1, \"width\" 2.0, \"factor\" 0.25)",
    );
    let read = read_mi(Path::new("l.mi"), text.as_bytes()).unwrap();
    assert_eq!(
        read.desc.materials[0].contour,
        Some(ContourDesc::Layered {
            color: (0.0, 0.0, 1.0, 1.0),
            width: 2.0,
            thinning: 0.25
        })
    );
    // What the camera sees directly is behind no layer: the full width, 2 % of 96 px.
    let image = contours(&text, "layerthinner");
    assert!(image
        .lines
        .iter()
        .flat_map(|l| &l.points)
        .all(|p| (p.width - 1.92).abs() < 1e-4));
}

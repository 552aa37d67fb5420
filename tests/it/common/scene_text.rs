//! Rendering scenes written as RON text (loaded through the real scene loader).

use std::path::Path;

use glam::Vec3;
use stagelight::frame::Frame;
use stagelight::framebuffer::FrameBuffers;
use stagelight::settings::RenderSettings;

/// Loads `text` as a scene and renders it (every stage but `write_output`), with `tweak`
/// applied to the scene's settings. Returns the frame buffers and the shade stage's
/// reported work items.
pub fn render_text(text: &str, tweak: impl FnOnce(&mut RenderSettings)) -> (FrameBuffers, u64) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.ron");
    let mut scene = stagelight::scene::load_scene_str(text, &path)
        .unwrap_or_else(|e| panic!("scene does not load:\n{e}"));
    let mut settings = scene.settings.clone();
    tweak(&mut settings);
    let mut frame = Frame::new(settings);
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame).expect("render");
    let items = frame
        .report
        .stages
        .iter()
        .find(|s| s.stage == "shade")
        .map_or(0, |s| s.items);
    (frame.outputs.image.expect("image"), items)
}

/// A camera-facing square of half-size `h` centred at `c` (its normal points at the origin),
/// as an inline mesh object named `name` with material `material`.
pub fn facing_quad(name: &str, material: &str, c: Vec3, h: f32) -> String {
    let n = -c.normalize();
    let (t, b) = n.any_orthonormal_pair();
    // Counter-clockwise seen from the origin (front face toward the camera).
    let p = [
        c - t * h - b * h,
        c + t * h - b * h,
        c + t * h + b * h,
        c - t * h + b * h,
    ];
    let ccw = (p[1] - p[0]).cross(p[2] - p[0]).dot(n) > 0.0;
    let order = if ccw { [0, 1, 2, 3] } else { [0, 3, 2, 1] };
    let v: Vec<String> = order
        .iter()
        .map(|&i| format!("({}, {}, {})", p[i].x, p[i].y, p[i].z))
        .collect();
    format!(
        "(name: \"{name}\", mesh: Inline(vertices: [{}], polygons: [[0, 1, 2, 3]]), material: \"{material}\"),",
        v.join(", ")
    )
}

/// Whether every buffer value is finite (depth may be infinite).
pub fn all_finite(fb: &FrameBuffers) -> bool {
    fb.beauty.iter().all(|c| c.is_finite()) && fb.alpha.iter().all(|a| a.is_finite())
}

/// Reads an EXR written by a bake: width and linear RGB texels, row 0 at the top.
pub fn read_exr_texels(path: &Path) -> (usize, Vec<Vec3>) {
    use exr::prelude::*;
    let image = read_first_rgba_layer_from_file(
        path,
        |res, _| (res.width(), vec![Vec3::ZERO; res.width() * res.height()]),
        |(w, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * *w + pos.x()] = Vec3::new(r, g, b)
        },
    )
    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    image.layer_data.channel_data.pixels
}

//! EXR displacement images: float heights as stored, so a linear ramp displaces a grid into
//! the tilted plane of its slope (negative heights too); the same heights as a 16-bit PNG
//! give the same surface within the PNG's quantisation; a truncated EXR, or one without a
//! channel to read, is a located error.

use std::path::Path;
use std::sync::Arc;

use stagelight::components::{Name, TriMesh};
use stagelight::frame::Frame;
use stagelight::image_io::png_codec::{encode_png, PngLayout};
use stagelight::scene::load_scene;
use stagelight::schedule::run_stages;
use stagelight::settings::RenderSettings;
use stagelight::systems::STAGES;

use crate::common::{run_in, scratch_dir, stderr_of};

/// Texels of the height maps: 8 across, 2 rows; texel x holds (x + ½)/8, so that with
/// `scale: 2, offset: -1` the height at u is 2u − 1 between the first and last texel centres.
const W: usize = 8;

fn ramp(x: usize) -> f32 {
    (x as f32 + 0.5) / W as f32
}

fn write_exr(path: &Path, channels: &[&str]) {
    use exr::prelude::*;
    let values: Vec<f32> = (0..2 * W).map(|i| ramp(i % W)).collect();
    let list: Vec<AnyChannel<FlatSamples>> = channels
        .iter()
        .map(|name| AnyChannel::new(*name, FlatSamples::F32(values.clone())))
        .collect();
    Image::from_channels((W, 2), AnyChannels::sort(list.into()))
        .write()
        .to_file(path)
        .unwrap();
}

/// The same ramp as a 16-bit PNG (R = G = B, so its luma is the sample).
fn write_png(path: &Path) {
    let mut data = Vec::new();
    for i in 0..2 * W {
        let code = (ramp(i % W) * 65535.0).round() as u16;
        for _ in 0..3 {
            data.extend_from_slice(&code.to_be_bytes());
        }
    }
    std::fs::write(
        path,
        encode_png(&data, W as u32, 2, PngLayout::Rgb16).unwrap(),
    )
    .unwrap();
}

/// A 2×2 grid (x, y ∈ [−1, 1], u = (x + 1)/2) of 8×8 quads displaced by the image `file`.
fn scene(file: &str) -> String {
    format!(
        "Scene(\n  objects: [(name: \"g\", mesh: Grid(size_x: 2, size_y: 2, nx: 8, ny: 8),\n    displacement: (shader: Image(file: \"{file}\", scale: 2, offset: -1), mode: True))],\n  instances: [(name: \"i\", of: \"g\")],\n  groups: [(name: \"world\", members: [\"i\"])],\n  cameras: [(name: \"cam\", fov_y: 60, resolution: (8, 8), placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0), up: (0, 0, 1)), outputs: [(file: \"out.png\")])],\n  render: (root: \"world\", camera: \"cam\"),\n)\n"
    )
}

/// The displaced grid's vertex positions (object space), after the geometry stages.
fn displaced(dir: &Path, file: &str) -> Vec<glam::Vec3> {
    let path = dir.join(format!("{file}.ron"));
    std::fs::write(&path, scene(file)).unwrap();
    let mut world = load_scene(&path).unwrap_or_else(|e| panic!("{e}")).world;
    let stages: Vec<_> = STAGES
        .iter()
        .copied()
        .filter(|s| s.name == "expand_geometry" || s.name == "tessellate")
        .collect();
    run_stages(
        &stages,
        &mut world,
        &mut Frame::new(RenderSettings::default()),
    )
    .unwrap();
    let g = world
        .query::<(hecs::Entity, &Name)>()
        .iter()
        .find(|(_, n)| n.0 == "g")
        .map(|(e, _)| e)
        .unwrap();
    let mesh = Arc::clone(&*world.get::<&Arc<TriMesh>>(g).unwrap());
    mesh.positions.clone()
}

#[test]
fn an_exr_ramp_tilts_a_grid_by_its_slope_as_the_png_does() {
    let dir = scratch_dir("displacement-exr");
    write_exr(&dir.join("h.exr"), &["Y"]);
    write_exr(&dir.join("rgb.exr"), &["R", "G", "B"]);
    write_png(&dir.join("h.png"));
    let exr = displaced(&dir, "h.exr");
    let mut inside = 0;
    for p in &exr {
        // Between the first and last texel centres (u ∈ [1/16, 15/16]) the height is
        // 2u − 1 = x: the plane z = x, negative heights included.
        if p.x.abs() <= 0.875 + 1e-6 {
            assert!((p.z - p.x).abs() < 1e-5, "{p}");
            inside += 1;
        }
    }
    assert!(inside >= 7 * 9, "{inside} vertices checked");
    // Grey R = G = B reads as its luminance: the same surface (the Rec. 709 weights sum
    // to 1 within f32 rounding).
    let rgb = displaced(&dir, "rgb.exr");
    assert_eq!(rgb.len(), exr.len());
    for (a, b) in rgb.iter().zip(&exr) {
        assert!((*a - *b).abs().max_element() < 1e-6, "{a} vs {b}");
    }
    // The 16-bit PNG of the same ramp: the same vertices, heights within its quantisation
    // (half a code, times the scale of 2).
    let png = displaced(&dir, "h.png");
    assert_eq!(png.len(), exr.len());
    for (a, b) in png.iter().zip(&exr) {
        assert_eq!((a.x, a.y), (b.x, b.y));
        assert!(
            (a.z - b.z).abs() <= 2.0 * 0.5 / 65535.0 + 1e-6,
            "{a} vs {b}"
        );
    }
    // And it renders.
    let o = run_in(&dir, &["render", "h.exr.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
}

const HELP: &str = "  help: displacement images are PNG files (read as grey 0…1) or EXR files (heights as stored: Y, a single channel, or the luminance of R, G and B), relative to the scene file";

/// A truncated EXR, and one with no channel a displacement image reads, are errors at the
/// image's `file`.
#[test]
fn a_bad_exr_displacement_image_is_a_located_error() {
    let dir = scratch_dir("displacement-exr-bad");
    write_exr(&dir.join("full.exr"), &["Y"]);
    let bytes = std::fs::read(dir.join("full.exr")).unwrap();
    std::fs::write(dir.join("cut.exr"), &bytes[..bytes.len() - 40]).unwrap();
    write_exr(&dir.join("uv.exr"), &["U", "V"]);
    for (file, reason) in [
        ("cut.exr", "not a readable OpenEXR image (invalid: reference to missing bytes)"),
        ("uv.exr", "no layer has the channels a displacement image reads (R, G and B; or Y; or a single channel, each with an optional A): the file has the channels U, V"),
    ] {
        std::fs::write(dir.join("scene.ron"), scene(file)).unwrap();
        let o = run_in(&dir, &["check", "scene.ron"]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
        assert_eq!(
            stderr_of(&o),
            format!(
                "scene.ron:3:40: error: cannot read image file \"{file}\": {reason}\n{HELP}\n1 error in scene.ron\n"
            ),
            "{file}"
        );
    }
}

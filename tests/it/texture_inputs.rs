//! Image texture inputs: a texture is counted against the run's memory budget from its
//! header before it is decoded, and once decoded in the run-wide estimate; an EXR texture with only a `Y` (or one) channel reads as grey,
//! one with no channels a texture reads is a located error naming them; a PNG palette index
//! past the palette is a located error; and a `.png` `-o` that drops passes of the output it
//! replaces says so.

use std::path::Path;

use crate::common::{run_in, run_limited, scratch_dir, stderr_of};
use stagelight::image_io::png_codec::{encode_png, PngLayout};

/// A scene whose quad (filling the 8×8 view) has one material per file in `files`, each
/// binding `Image(file: …)` to a `Constant` colour; the render camera writes `outputs`.
fn scene(files: &[&str], outputs: &str) -> String {
    let materials: Vec<String> = files
        .iter()
        .enumerate()
        .map(|(k, f)| {
            format!(
                "        (name: \"m{k}\", shader: Constant(color: (1, 1, 1)), bind: {{\"color\": Image(file: \"{f}\")}}),\n"
            )
        })
        .collect();
    let objects: Vec<String> = (0..files.len())
        .map(|k| format!("        (name: \"q{k}\", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]), material: \"m{k}\"),\n"))
        .collect();
    let instances: Vec<String> = (0..files.len())
        .map(|k| format!("(name: \"i{k}\", of: \"q{k}\")"))
        .collect();
    let members: Vec<String> = (0..files.len()).map(|k| format!("\"i{k}\"")).collect();
    format!(
        "Scene(\n    options: (samples: 1),\n    materials: [\n{}    ],\n    objects: [\n{}    ],\n    instances: [{}],\n    groups: [(name: \"world\", members: [{}])],\n    cameras: [(name: \"cam\", fov_y: 90, resolution: (8, 8),\n        placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)), outputs: [{outputs}])],\n    render: (root: \"world\", camera: \"cam\"),\n)\n",
        materials.concat(),
        objects.concat(),
        instances.join(", "),
        members.join(", ")
    )
}

/// `line:column` of the quoted `file` in `text`.
fn position(text: &str, file: &str) -> String {
    let quoted = format!("\"{file}\"");
    let (n, line) = text
        .lines()
        .enumerate()
        .find(|(_, l)| l.contains(&quoted))
        .unwrap();
    format!("{}:{}", n + 1, line.find(&quoted).unwrap() + 1)
}

fn grey_png(dir: &Path, name: &str, side: u32) {
    let data = vec![128u8; (side * side) as usize];
    let png = encode_png(&data, side, side, PngLayout::Grey8).unwrap();
    std::fs::write(dir.join(name), png).unwrap();
}

const BUDGET_HELP: &str =
    "  help: use a smaller image (or fewer), or raise the budget with --memory-limit BYTES";

/// A 1024² grey PNG decodes to 1 MiB of samples and 12 MiB of texels: under an 8 MiB budget
/// it is refused at its `file`, from its header (under `ulimit -v`, at `check` and `render`).
#[test]
fn a_texture_past_the_memory_budget_is_refused_before_decoding() {
    let dir = scratch_dir("texture-budget");
    grey_png(&dir, "big.png", 1024);
    let text = scene(&["big.png"], "(file: \"out.png\")");
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    for args in [
        &["check", "scene.ron", "--memory-limit", "8M"][..],
        &["render", "scene.ron", "--memory-limit", "8M"],
    ] {
        let expected = format!(
            "scene.ron:{}: error: image \"big.png\": the texels of a 1024×1024 image need about 13.0 MiB, more than the memory budget of 8.0 MiB (--memory-limit)\n{BUDGET_HELP}\n1 error in scene.ron{}\n",
            position(&text, "big.png"),
            crate::common::refused_tail(args[0])
        );
        let o = run_limited(&dir, args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr_of(&o));
        assert_eq!(stderr_of(&o), expected, "{args:?}");
    }
    assert!(!dir.join("out.png").exists());
    // Within the budget it renders.
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "14M"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
}

/// Two 640² textures of about 5.1 MiB each fit an 8 MiB budget alone, not together: the
/// second is refused, naming the total.
#[test]
fn textures_are_counted_together() {
    let dir = scratch_dir("texture-budget-total");
    grey_png(&dir, "a.png", 640);
    grey_png(&dir, "b.png", 640);
    let text = scene(&["a.png", "b.png"], "");
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "8M"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        format!(
            "scene.ron:{}: error: image \"b.png\": the texels of a 640×640 image need about 5.1 MiB, and the scene's image textures together about 10.2 MiB, more than the memory budget of 8.0 MiB (--memory-limit)\n{BUDGET_HELP}\n1 error in scene.ron\n",
            position(&text, "b.png")
        )
    );
}

/// The run-wide estimate counts decoded textures with the camera, geometry, photons and
/// bakes: a 1024×512 grey PNG (6 MiB of texels; 6.5 MiB with its samples while it is read)
/// and an 80×80 camera (1.6 MiB of frame buffers) each fit a 7 MiB budget, together they do
/// not, and the run is refused before rendering, naming the largest element (the image, at
/// its `file`) and the total.
#[test]
fn decoded_textures_count_in_the_run_wide_estimate() {
    let dir = scratch_dir("texture-budget-run");
    let data = vec![128u8; 1024 * 512];
    let png = encode_png(&data, 1024, 512, PngLayout::Grey8).unwrap();
    std::fs::write(dir.join("wide.png"), png).unwrap();
    let text = scene(&["wide.png"], "(file: \"out.png\")")
        .replace("resolution: (8, 8)", "resolution: (80, 80)");
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    for args in [
        &["check", "scene.ron", "--memory-limit", "7M"][..],
        &["render", "scene.ron", "--memory-limit", "7M"],
    ] {
        let expected = format!(
            "scene.ron:{}: error: image \"wide.png\": the texels of a 1024×512 image need about 6.0 MiB, and the whole run about 7.6 MiB, more than the memory budget of 7.0 MiB (--memory-limit)\n{BUDGET_HELP}\n1 error in scene.ron{}\n",
            position(&text, "wide.png"),
            crate::common::refused_tail(args[0])
        );
        let o = run_limited(&dir, args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr_of(&o));
        assert_eq!(stderr_of(&o), expected, "{args:?}");
    }
    assert!(!dir.join("out.png").exists());
    // With room for both it renders.
    let o = run_in(&dir, &["render", "scene.ron", "--memory-limit", "8M"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert!(dir.join("out.png").exists());
}

/// Writes an EXR of 2×2 pixels with `channels` (name, four values top-down).
fn exr(path: &Path, channels: &[(&str, [f32; 4])]) {
    use exr::prelude::*;
    let list: Vec<AnyChannel<FlatSamples>> = channels
        .iter()
        .map(|(name, v)| AnyChannel::new(*name, FlatSamples::F32(v.to_vec())))
        .collect();
    Image::from_channels((2, 2), AnyChannels::sort(list.into()))
        .write()
        .to_file(path)
        .unwrap();
}

/// A `Y` channel, or a layer's one channel, is read as grey (rows bottom-up); an `A` beside
/// it is the alpha.
#[test]
fn single_channel_exr_textures_read_as_grey() {
    use glam::Vec3;
    use stagelight::shading::texture::image::{load, Wrap};
    let dir = scratch_dir("texture-exr-grey");
    let grey = |v: [f32; 4]| -> Vec<Vec3> { v.map(Vec3::splat).to_vec() };
    exr(&dir.join("y.exr"), &[("Y", [0.1, 0.2, 0.3, 0.4])]);
    let t = load(&dir.join("y.exr"), None, Wrap::Clamp).unwrap();
    assert_eq!(t.texels, grey([0.3, 0.4, 0.1, 0.2]));
    assert!(t.alpha.is_empty());
    exr(
        &dir.join("ya.exr"),
        &[("Y", [0.1, 0.2, 0.3, 0.4]), ("A", [1.0, 0.5, 0.25, 0.0])],
    );
    let t = load(&dir.join("ya.exr"), None, Wrap::Clamp).unwrap();
    assert_eq!(t.texels, grey([0.3, 0.4, 0.1, 0.2]));
    assert_eq!(t.alpha, vec![0.25, 0.0, 1.0, 0.5]);
    exr(
        &dir.join("rough.exr"),
        &[("roughness", [0.5, 0.5, 0.5, 2.0])],
    );
    let t = load(&dir.join("rough.exr"), None, Wrap::Clamp).unwrap();
    assert_eq!(t.texels, grey([0.5, 2.0, 0.5, 0.5]));
}

/// A file with two channels that are neither R, G, B nor Y is a located error naming them.
#[test]
fn an_exr_texture_without_usable_channels_names_its_channels() {
    let dir = scratch_dir("texture-exr-channels");
    exr(&dir.join("uv.exr"), &[("U", [0.0; 4]), ("V", [0.0; 4])]);
    let text = scene(&["uv.exr"], "");
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        format!(
            "scene.ron:{}: error: cannot read image file \"uv.exr\": no layer has the channels an image texture reads (R, G and B; or Y; or a single channel, each with an optional A): the file has the channels U, V\n  help: image textures are PNG files, or EXR files with R, G and B, Y or a single channel, relative to the scene file\n1 error in scene.ron\n",
            position(&text, "uv.exr")
        )
    );
}

/// An index past a 2-entry palette is a located error, not a black texel.
#[test]
fn a_palette_index_past_the_palette_is_a_located_error() {
    let dir = scratch_dir("texture-palette");
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, 2, 1);
    encoder.set_color(png::ColorType::Indexed);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_palette(vec![0, 0, 0, 255, 255, 255]);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(&[1, 5]).unwrap();
    writer.finish().unwrap();
    std::fs::write(dir.join("p.png"), bytes).unwrap();
    let text = scene(&["p.png"], "");
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        format!(
            "scene.ron:{}: error: cannot read image file \"p.png\": pixel (1, 0) has palette index 5, but the PLTE chunk holds 2 entries (indices 0 to 1)\n  help: image textures are PNG files, or EXR files with R, G and B, Y or a single channel, relative to the scene file\n1 error in scene.ron\n",
            position(&text, "p.png")
        )
    );
}

/// `-o o.png` replacing an EXR output of four passes warns that three are dropped; a PNG
/// output, or an EXR `-o`, says nothing.
#[test]
fn a_png_o_that_drops_passes_warns() {
    let dir = scratch_dir("png-o-passes");
    grey_png(&dir, "t.png", 2);
    let text = scene(
        &["t.png"],
        "(file: \"out.exr\", passes: [Beauty, Depth, Normal, Specular])",
    );
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    let o = run_in(&dir, &["render", "scene.ron", "-o", "o.png"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        "warning: -o o.png replaces the camera's output \"out.exr\" and drops its passes Depth, Normal, Specular: a PNG holds only Beauty, Alpha and Contours\n  help: give -o an .exr file to keep every pass\nwrote o.png\n"
    );
    assert!(dir.join("o.png").exists());
    let o = run_in(&dir, &["render", "scene.ron", "-o", "o.exr"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert_eq!(stderr_of(&o), "wrote o.exr\n");
}

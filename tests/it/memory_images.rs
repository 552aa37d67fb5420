//! Environment maps and displacement images in the run's memory budget: each is refused from
//! its header when its reading alone would not fit (located at its `file`, worded as an
//! image texture's refusal), counted once read in the run-wide estimate with what it really
//! holds (a scene environment's texels and sampling tables, a material environment's texels,
//! a displacement image's heights: the estimate equals the allocations), and a scene that
//! fits renders as it did without a budget.

use std::path::Path;

use hecs::Entity;
use stagelight::budget::{human, Budget};
use stagelight::components::{DecodedImage, Displacement, Environment, Name, ScalarNode};
use stagelight::image_io::png_codec::{encode_png, PngLayout};
use stagelight::scene::{load_scene_within, read_lat_long};
use stagelight::shading::lights::environment::footprint;
use stagelight::shading::EnvLight;

use crate::common::{refused_tail, run_in, run_limited, scratch_dir, stderr_of};

const HELP: &str =
    "  help: use a smaller image (or fewer), or raise the budget with --memory-limit BYTES";

/// An 8×8 view of a grey quad; `extra` adds top-level fields or replaces the material or
/// the quad (see the callers).
fn scene(environment: &str, material: &str, object: &str) -> String {
    format!(
        "Scene(\n    options: (samples: 1),\n{environment}    materials: [{material}],\n    objects: [{object}],\n    instances: [(name: \"i\", of: \"q\")],\n    groups: [(name: \"world\", members: [\"i\"])],\n    cameras: [(name: \"cam\", fov_y: 90, resolution: (8, 8),\n        placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)), outputs: [(file: \"out.png\")])],\n    render: (root: \"world\", camera: \"cam\"),\n)\n"
    )
}

const GREY: &str = "(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5)))";
const QUAD: &str = "(name: \"q\", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]), material: \"m\")";
const SKY: &str = "    environment: (shader: LatLong(file: \"sky.exr\")),\n";

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

/// Writes a `width × height` EXR with `channels`, each filled by `f(x, y)` (rows top-down).
fn exr(
    path: &Path,
    width: usize,
    height: usize,
    channels: &[&str],
    f: impl Fn(usize, usize) -> f32,
) {
    use exr::prelude::*;
    let values: Vec<f32> = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| f(x, y))
        .collect();
    let list: Vec<AnyChannel<FlatSamples>> = channels
        .iter()
        .map(|name| AnyChannel::new(*name, FlatSamples::F32(values.clone())))
        .collect();
    Image::from_channels((width, height), AnyChannels::sort(list.into()))
        .write()
        .to_file(path)
        .unwrap();
}

fn sky(dir: &Path) {
    exr(&dir.join("sky.exr"), 256, 128, &["R", "G", "B"], |x, y| {
        0.2 + (x + y) as f32 / 512.0
    });
}

/// Runs `check` and `render` under `limit` and asserts the one refusal `message` (without
/// its `file:line:col: error: ` start) at `at`, and that nothing is rendered.
fn refused(dir: &Path, text: &str, at: &str, limit: &str, message: &str) {
    std::fs::write(dir.join("scene.ron"), text).unwrap();
    for command in ["check", "render"] {
        let o = run_limited(dir, &[command, "scene.ron", "--memory-limit", limit]);
        assert_eq!(o.status.code(), Some(1), "{command}: {}", stderr_of(&o));
        assert_eq!(
            stderr_of(&o),
            format!(
                "scene.ron:{at}: error: {message}\n{HELP}\n1 error in scene.ron{}\n",
                refused_tail(command)
            ),
            "{command}"
        );
    }
    assert!(!dir.join("out.png").exists());
}

/// The scene environment's 256×128 map holds 384 KiB of texels, 264.5 KiB of sampling
/// tables and, while they are built, 130 KiB of weights: 778.5 KiB at its peak, refused from
/// its header under a 512 KiB budget.
#[test]
fn an_environment_map_past_the_budget_is_refused_at_its_file() {
    let dir = scratch_dir("memory-environment");
    sky(&dir);
    let text = scene(SKY, GREY, QUAD);
    refused(
        &dir,
        &text,
        &position(&text, "sky.exr"),
        "512K",
        "image \"sky.exr\": the texels and sampling tables of a 256×128 environment map need about 778.5 KiB, more than the memory budget of 512.0 KiB (--memory-limit)",
    );
}

/// A material's own environment map is looked up, never sampled: only its 384 KiB of texels.
#[test]
fn a_material_environment_map_counts_its_texels() {
    let dir = scratch_dir("memory-material-environment");
    sky(&dir);
    let material = "(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5)), environment: (shader: LatLong(file: \"sky.exr\")))";
    let text = scene("", material, QUAD);
    refused(
        &dir,
        &text,
        &position(&text, "sky.exr"),
        "256K",
        "image \"sky.exr\": the texels of a 256×128 environment map need about 384.0 KiB, more than the memory budget of 256.0 KiB (--memory-limit)",
    );
}

/// The map fits the budget alone, not with the camera and the quad: the run is refused
/// before rendering, naming the map at its `file` and the whole run.
#[test]
fn an_environment_map_counts_in_the_run_wide_estimate() {
    let dir = scratch_dir("memory-environment-run");
    sky(&dir);
    let text = scene(SKY, GREY, QUAD);
    // 797 196 B of the map + 16 KiB of frame buffers + 2 triangles of 384 B.
    refused(
        &dir,
        &text,
        &position(&text, "sky.exr"),
        "790K",
        "image \"sky.exr\": the texels and sampling tables of a 256×128 environment map need about 778.5 KiB, and the whole run about 795.3 KiB, more than the memory budget of 790.0 KiB (--memory-limit)",
    );
    // With room for all, it renders, as it does without a budget.
    let o = run_in(&dir, &["render", "scene.ron", "--memory-limit", "800K"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let within = std::fs::read(dir.join("out.png")).unwrap();
    std::fs::remove_file(dir.join("out.png")).unwrap();
    let o = run_in(&dir, &["render", "scene.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert_eq!(within, std::fs::read(dir.join("out.png")).unwrap());
}

/// A displaced grid whose image's reading (the file, its decoded samples and a 4-byte height
/// per texel) would not fit: refused at the image's `file`, for PNG and EXR images.
#[test]
fn a_displacement_image_past_the_budget_is_refused_at_its_file() {
    let dir = scratch_dir("memory-displacement");
    let png = encode_png(&vec![128u8; 512 * 512], 512, 512, PngLayout::Grey8).unwrap();
    std::fs::write(dir.join("h.png"), &png).unwrap();
    exr(&dir.join("h.exr"), 256, 256, &["Y"], |x, _| {
        x as f32 / 256.0
    });
    let exr_len = std::fs::metadata(dir.join("h.exr")).unwrap().len();
    for (file, size, bytes, limit) in [
        ("h.png", 512, png.len() as u64 + (512 * 512) * 5, "1M"),
        ("h.exr", 256, exr_len + 256 * 256 * 4, "200K"),
    ] {
        let object = format!("(name: \"q\", mesh: Grid(nx: 2, ny: 2), material: \"m\", displacement: (shader: Image(file: \"{file}\"), mode: True))");
        let text = scene("", GREY, &object);
        refused(
            &dir,
            &text,
            &position(&text, file),
            limit,
            &format!(
                "image \"{file}\": the heights of a {size}×{size} displacement image need about {}, more than the memory budget of {} (--memory-limit)",
                human(bytes),
                if limit == "1M" { "1.0 MiB" } else { "200.0 KiB" }
            ),
        );
    }
}

fn named(world: &hecs::World, name: &str) -> Vec<Entity> {
    world
        .query::<(Entity, &Name)>()
        .iter()
        .filter(|(_, n)| n.0 == name)
        .map(|(e, _)| e)
        .collect()
}

/// The run-wide estimate of a decoded image is what its reading allocated: the map's texels
/// (by capacity) + the tables the built light holds + the weights of building them; a
/// displacement image's heights (by capacity).
#[test]
fn the_estimates_are_the_allocations() {
    let dir = scratch_dir("memory-images-allocations");
    sky(&dir);
    exr(&dir.join("h.exr"), 24, 10, &["height"], |x, y| {
        (x * y) as f32
    });
    let object = "(name: \"q\", mesh: Grid(nx: 2, ny: 2), material: \"m\", displacement: (shader: Image(file: \"h.exr\"), mode: True))";
    std::fs::write(dir.join("scene.ron"), scene(SKY, GREY, object)).unwrap();
    let loaded = load_scene_within(&dir.join("scene.ron"), &Budget::unlimited()).unwrap();
    let world = &loaded.world;
    let image = |name: &str| {
        let e = named(world, name);
        assert_eq!(e.len(), 1, "{name}");
        *world.get::<&DecodedImage>(e[0]).unwrap()
    };
    let map = read_lat_long(&dir.join("sky.exr")).unwrap();
    let environment = world
        .query::<&Environment>()
        .iter()
        .next()
        .cloned()
        .unwrap();
    let light = EnvLight::new(&environment);
    assert_eq!(
        image("sky.exr").bytes,
        (map.texels.capacity() * std::mem::size_of::<glam::Vec3>()) as u64
            + light.table_bytes()
            + footprint::building_bytes(256, 128)
    );
    assert_eq!(image("sky.exr").bytes, 797_196);
    let q = named(world, "q")[0];
    let displacement = world.get::<&Displacement>(q).unwrap();
    let ScalarNode::Image(heights) = &displacement.shader else {
        panic!("{:?}", displacement.shader)
    };
    assert_eq!(
        image("h.exr").bytes,
        (heights.texels.capacity() * std::mem::size_of::<f32>()) as u64
    );
    assert_eq!((image("h.exr").width, image("h.exr").height), (24, 10));
}

//! PLY vertex colours: `red green blue` (with or without `alpha`) read from integer
//! (display values, sRGB-decoded) or floating-point (linear) properties and used through
//! the `VertexColor` node — here as a Lambert albedo, rendered in closed form — and a
//! colour property written as a list is a located error.

use std::path::Path;

use glam::Vec3;

const DIR: &str = "tests/fixtures/meshes";

/// A 16² render of `file` (two unit quads side by side in z = 0, x ∈ [−1, 0] and [0, 1])
/// with `Lambert` whose albedo is the vertex colour, lit straight on by a directional
/// light of irradiance π (so the radiance equals the albedo); returns the left and right
/// quads' pixel values.
fn render_halves(file: &str) -> (Vec3, Vec3) {
    let mut scene = stagelight::scene::load_scene_str(&scene(file), &Path::new(DIR).join("s.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.located_warnings, Vec::<String>::new());
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("image");
    let w = image.width as usize;
    (image.beauty[8 * w + 3], image.beauty[8 * w + 12])
}

fn scene(file: &str) -> String {
    format!(
        r#"(
    options: (samples: 4),
    cameras: [(name: "cam", fov_y: 30, resolution: (16, 16),
               placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (0, 0, -1)), intensity: 3.14159265358979)],
    materials: [(name: "m", shader: Lambert(albedo: (1, 1, 1)), bind: {{"albedo": VertexColor}})],
    objects: [(name: "quads", material: "m", mesh: Ply(file: "{file}"))],
    instances: [(name: "q", of: "quads")],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

fn close(got: Vec3, want: Vec3) {
    assert!((got - want).abs().max_element() < 1e-4, "{got} vs {want}");
}

/// `uchar` colours (255, 0, 0) and (0, 0, 128) show as linear (1, 0, 0) and
/// (0, 0, srgb⁻¹(128/255)); the `alpha` property is read past.
#[test]
fn a_two_colour_ply_renders_its_colours() {
    let (left, right) = render_halves("two_colours.ply");
    let blue = stagelight::shading::texture::colour::srgb_to_linear(128.0 / 255.0);
    close(left, Vec3::X);
    close(right, Vec3::new(0.0, 0.0, blue));
}

/// Floating-point colours are linear as written.
#[test]
fn float_colours_are_linear() {
    let (left, right) = render_halves("two_colours_float.ply");
    close(left, Vec3::new(0.25, 0.5, 0.75));
    close(right, Vec3::new(0.5, 0.125, 0.0));
}

/// A colour property that is a list is an error at its header line.
#[test]
fn a_colour_list_is_a_located_error() {
    let text = scene("colour_list.ply");
    let errors = match stagelight::scene::load_scene_str(&text, &Path::new(DIR).join("s.ron")) {
        Ok(_) => panic!("loaded"),
        Err(e) => e.to_string(),
    };
    assert_eq!(
        errors,
        format!("{DIR}/colour_list.ply:7:1: error: invalid PLY file \"{DIR}/colour_list.ply\": vertex property \"red\" is a list: it must be a number\n  help: loaded for object \"quads\" at {DIR}/s.ron:7:62")
    );
}

//! glTF vertex attributes on files written by the third-party writer `pygltflib`
//! (`scripts/make_gltf_fixtures.py`): `COLOR_0` (float, normalised u8 and u16; linear)
//! read exactly and multiplying the base colour, `TANGENT` giving normal maps their frame
//! (its sign flipping the tilt, a turned tangent turning it), and malformed accessors
//! refused with the glTF element.

use std::path::Path;

use glam::Vec3;
use stagelight::scene::LoadedScene;

const DIR: &str = "tests/fixtures/gltf";

/// Runs every stage but `write_output`; returns (width, beauty).
fn render(mut scene: LoadedScene) -> (usize, Vec<Vec3>) {
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("image");
    (image.width as usize, image.beauty)
}

fn load_ron(text: &str) -> LoadedScene {
    let scene = stagelight::scene::load_scene_str(text, &Path::new(DIR).join("s.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.located_warnings, Vec::<String>::new());
    scene
}

/// The colours of `colours.glb`'s quads (left to right) as the specification decodes them:
/// float as written, integers divided by the type's maximum, no sRGB decoding.
fn colours() -> [Vec3; 4] {
    [
        Vec3::new(0.25, 0.5, 1.0),
        Vec3::new(1.0, 64.0 / 255.0, 0.0),
        Vec3::new(0.0, 32768.0 / 65535.0, 1.0),
        Vec3::ONE,
    ]
}

/// Each quad of `colours.glb` as a `Gltf(…)` mesh with a Lambert material whose albedo is
/// `VertexColor`, lit straight on by a directional light of irradiance π: the radiance is
/// the vertex colour.
#[test]
fn color_0_is_read_linear_in_every_encoding() {
    for (mesh, want) in ["float3", "u8", "u16", "plain"].into_iter().zip(colours()) {
        let text = format!(
            r#"(
    options: (samples: 1),
    cameras: [(name: "cam", fov_y: 10, resolution: (4, 4),
               placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (0, 0, -1)), intensity: 3.14159265358979)],
    materials: [(name: "m", shader: Lambert(albedo: (1, 1, 1)), bind: {{"albedo": VertexColor}})],
    objects: [(name: "quad", material: "m", mesh: Gltf(file: "colours.glb", mesh: "{mesh}"))],
    instances: [(name: "q", of: "quad", transform: [Translate((0, 0, 0))])],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
)"#
        );
        // Centre each quad in the view.
        let x = -1.65
            + 1.1
                * ["float3", "u8", "u16", "plain"]
                    .iter()
                    .position(|m| *m == mesh)
                    .unwrap() as f64;
        let text = text.replace(
            "Translate((0, 0, 0))",
            &format!("Translate(({}, 0, 0))", -x),
        );
        let (w, beauty) = render(load_ron(&text));
        for y in 0..w {
            for x in 0..w {
                let got = beauty[y * w + x];
                assert!(
                    (got - want).abs().max_element() < 1e-5,
                    "{mesh} ({x}, {y}): {got} vs {want}"
                );
            }
        }
    }
}

/// `colours.glb` as the scene: four polished metal quads (metallic 1, roughness 0, base
/// colour factor (0.8, 0.6, 0.5)) facing the camera in the white default environment reflect
/// F0 = the base colour at normal incidence; COLOR_0 multiplies it, the quad without COLOR_0
/// keeps the factor.
#[test]
fn color_0_multiplies_the_base_colour() {
    let scene = stagelight::scene::load_scene(&Path::new(DIR).join("colours.glb"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.located_warnings, Vec::<String>::new());
    let (w, beauty) = render(scene);
    let h = beauty.len() / w;
    let half_w = 5.0 * (0.25f32).tan() * w as f32 / h as f32;
    let factor = Vec3::new(0.8, 0.6, 0.5);
    let plain = beauty[(h / 2) * w + ((1.65 / half_w + 1.0) / 2.0 * w as f32) as usize];
    for (k, colour) in colours().into_iter().enumerate() {
        let x = -1.65 + 1.1 * k as f32;
        let got = beauty[(h / 2) * w + ((x / half_w + 1.0) / 2.0 * w as f32) as usize];
        let want = factor * colour;
        assert!(
            (got - want).abs().max_element() < 1e-3,
            "quad {k}: {got} vs {want}"
        );
        // Against the quad without colours: exactly the colour's ratio.
        let ratio = got / plain;
        for c in 0..3 {
            if colour[c] > 0.0 {
                assert!(
                    (ratio[c] - colour[c]).abs() < 1e-4 * colour[c],
                    "quad {k}: {ratio} vs {colour}"
                );
            }
        }
    }
}

/// `tangents.glb`'s quads under a Lambert material with their normal texture (uniform
/// (128, 192, 255): "green up" along the bitangent, scale 1.5), lit by a directional light
/// of irradiance π from 30° toward +y. Each quad shows `ρ·(n'·l)·S` with `n'` the texel's
/// normal in the frame its TANGENT gives: (+x, +y) for w = +1, (+x, −y) for w = −1, and
/// (+y, −x) for the turned tangent. Generated tangents would give all three the first.
#[test]
fn tangents_give_the_normal_map_its_frame() {
    let mut objects = String::new();
    let mut instances = String::new();
    for mesh in ["plus", "minus", "turned"] {
        objects += &format!(
            r#"(name: "{mesh}", material: "m", mesh: Gltf(file: "tangents.glb", mesh: "{mesh}")),"#
        );
        instances += &format!(r#"(name: "{mesh}_1", of: "{mesh}"),"#);
    }
    let text = format!(
        r#"(
    options: (samples: 4),
    cameras: [(name: "cam", fov_y: 30, resolution: (96, 32),
               placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (0, -0.5, -0.8660254037844386)),
              intensity: 3.14159265358979)],
    materials: [(name: "m", shader: Lambert(albedo: (0.8, 0.8, 0.8)),
                 bump: (normal_map: Image(file: "tangents.glb#images[0]", wrap: Clamp,
                                          color_space: Linear), scale: 1.5))],
    objects: [{objects}],
    instances: [{instances}],
    groups: [(name: "world", members: ["plus_1", "minus_1", "turned_1"])],
    render: (root: "world", camera: "cam"),
)"#
    );
    let (w, beauty) = render(load_ron(&text));
    let l = Vec3::new(0.0, 0.5, 0.8660254);
    let texel = Vec3::new(128.0, 192.0, 255.0) / 255.0 * 2.0 - Vec3::ONE;
    let local = Vec3::new(texel.x * 1.5, texel.y * 1.5, texel.z).normalize();
    let half_w = 3.0 * (15f32).to_radians().tan() * 3.0;
    let frames = [(Vec3::X, Vec3::Y), (Vec3::X, -Vec3::Y), (Vec3::Y, -Vec3::X)];
    let mut seen = Vec::new();
    for (k, (t, b)) in frames.into_iter().enumerate() {
        let n = t * local.x + b * local.y + Vec3::Z * local.z;
        let s = stagelight::shading::texture::bump::shadowing(Vec3::Z, n, l);
        let want = 0.8 * n.dot(l) * s;
        let x = -1.1 + 1.1 * k as f32;
        let got = beauty[16 * w + ((x / half_w + 1.0) / 2.0 * w as f32) as usize].x;
        assert!(
            (got - want).abs() < 1e-3 * want,
            "quad {k}: {got} vs {want}"
        );
        seen.push(got);
    }
    // Tilted toward the light, away from it, and across it.
    assert!(
        seen[0] > 1.1 * seen[2] && seen[2] > 1.1 * seen[1],
        "{seen:?}"
    );
}

fn load_errors(file: &str) -> Vec<String> {
    match stagelight::scene::load_scene(&Path::new(DIR).join(file)) {
        Ok(_) => panic!("{file} loaded"),
        Err(e) => e.0.iter().map(|d| d.to_string()).collect(),
    }
}

/// A TANGENT without the ±1 handedness and integer colours that are not normalised are
/// refused with the accessor.
#[test]
fn malformed_tangents_and_colours_are_located_errors() {
    let error = |f: &str, object: &str, message: &str| {
        [format!(
            "{DIR}/{f}:1:1: error: invalid glTF file \"{DIR}/{f}\": {message}\n  help: loaded for object \"{object}\" at {DIR}/{f}:1:1"
        )]
    };
    assert_eq!(
        load_errors("bad_tangent.glb"),
        error(
            "bad_tangent.glb",
            "tilted_mesh",
            "accessors[4]: TANGENT element 0 is (1, 0, 0, 0.5): expected a non-zero direction and w = 1 or -1 (the bitangent's sign)"
        )
    );
    assert_eq!(
        load_errors("bad_colour.glb"),
        error(
            "bad_colour.glb",
            "raw_mesh",
            "accessors[4]: COLOR_0: U8 components must be normalized (\"normalized\": true) to be colours in [0, 1]"
        )
    );
}

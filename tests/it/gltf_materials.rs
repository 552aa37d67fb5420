//! glTF material textures end to end, on files written by the third-party writer
//! `pygltflib` (`scripts/make_gltf_fixtures.py`): the normal texture as a tangent-space
//! normal map (its closed form under a tilted directional light), the emissive texture with
//! `emissiveFactor` and `KHR_materials_emissive_strength` (each texel's radiance at its
//! pixel), and `alphaMode: MASK` (the card lets the wall and the light through exactly
//! where alpha < `alphaCutoff`, and its shadow has the hole), and image files that cannot be
//! read located at their `uri` (`.gltf`) or named by index and name (`.glb`, also an
//! embedded image that does not decode).

use std::path::Path;

use glam::Vec3;
use stagelight::scene::desc::{InputDesc, NodeDesc, ShaderDesc};
use stagelight::scene::LoadedScene;

const DIR: &str = "tests/fixtures/gltf";

/// Runs every stage but `write_output`; returns (width, beauty).
fn render(mut scene: LoadedScene) -> (usize, Vec<Vec3>) {
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("image");
    (image.width as usize, image.beauty)
}

fn load(file: &str) -> LoadedScene {
    let scene = stagelight::scene::load_scene(&Path::new(DIR).join(file))
        .unwrap_or_else(|e| panic!("{file}: {e}"));
    assert_eq!(scene.located_warnings, Vec::<String>::new(), "{file}");
    scene
}

/// The pixel of a square `res`² image that sees the point (x, y, z) through a camera at
/// (0, 0, `eye`) looking down −Z with the vertical field of view `yfov` (radians).
fn pixel(res: usize, beauty: &[Vec3], eye: f32, yfov: f32, p: Vec3) -> Vec3 {
    let half = (eye - p.z) * (yfov / 2.0).tan();
    let px = ((p.x / half + 1.0) / 2.0 * res as f32) as usize;
    let py = ((1.0 - p.y / half) / 2.0 * res as f32) as usize;
    beauty[py * res + px]
}

fn srgb(code: u8) -> f32 {
    stagelight::shading::texture::colour::srgb_to_linear(code as f32 / 255.0)
}

fn desc(file: &str) -> stagelight::scene::desc::SceneDesc {
    let path = Path::new(DIR).join(file);
    stagelight::scene::import::gltf_scene::read(&path, &std::fs::read(&path).unwrap())
        .unwrap_or_else(|e| panic!("{e:?}"))
        .desc
}

/// The reader maps `normalTexture` (with its `scale`) onto a normal map of the embedded
/// image, read linear.
#[test]
fn the_normal_texture_becomes_a_normal_map() {
    let d = desc("normal_map.glb");
    let bump = d.materials[0].bump.as_ref().expect("a bump");
    assert!(bump.height.is_none());
    assert_eq!(bump.scale, 1.5);
    let Some(InputDesc::Node(n)) = &bump.normal_map else {
        panic!("a normal map node");
    };
    let NodeDesc::Image {
        file, color_space, ..
    } = &**n
    else {
        panic!("an image: {n:?}");
    };
    assert_eq!(file, "normal_map.glb#images[0]");
    assert_eq!(
        *color_space,
        Some(stagelight::scene::nodes_desc::EncodingDesc::Linear)
    );
}

/// The normal map of `normal_map.glb` on its own mesh, with a Lambert material, lit by a
/// directional light of irradiance π from 30° toward +y: each half shows `ρ·(n'·l)·S` where `n'` is the
/// texel's normal `(2c − 1)·(1.5, 1.5, 1)` in the frame (+x, +y, +z) — +y being the
/// image's top ("green up") — and `S` the bump shadowing term. The two halves tilt by the
/// same angle, along u and toward the image's top, and differ as the closed form says.
#[test]
fn a_normal_map_tilts_lambert_shading_as_its_closed_form_says() {
    let text = r#"(
    options: (samples: 4),
    cameras: [(name: "cam", fov_y: 30, resolution: (32, 32),
               placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (0, -0.5, -0.8660254037844386)),
              intensity: 3.14159265358979)],
    materials: [(name: "m", shader: Lambert(albedo: (0.8, 0.8, 0.8)),
                 bump: (normal_map: Image(file: "normal_map.glb#images[0]", wrap: Clamp,
                                          color_space: Linear), scale: 1.5))],
    objects: [(name: "quad", material: "m", mesh: Gltf(file: "normal_map.glb"))],
    instances: [(name: "q", of: "quad")],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
)"#;
    let scene = stagelight::scene::load_scene_str(text, &Path::new(DIR).join("n.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    let (w, beauty) = render(scene);
    let l = Vec3::new(0.0, 0.5, 0.8660254);
    let expected = |c: [u8; 3]| {
        let t = Vec3::from(c.map(|x| x as f32 / 255.0)) * 2.0 - Vec3::ONE;
        let n = Vec3::new(t.x * 1.5, t.y * 1.5, t.z).normalize();
        let s = stagelight::shading::texture::bump::shadowing(Vec3::Z, n, l);
        0.8 * n.dot(l) * s
    };
    let (left, right) = (expected([192, 128, 255]), expected([128, 192, 255]));
    // Columns 8 and 24 see u ≈ 0.31 and 0.71: inside each half's texels.
    let (got_left, got_right) = (beauty[16 * w + 8].x, beauty[16 * w + 24].x);
    assert!(
        (got_left - left).abs() < 1e-3 * left,
        "{got_left} vs {left}"
    );
    assert!(
        (got_right - right).abs() < 1e-3 * right,
        "{got_right} vs {right}"
    );
    // Tilted toward the light ("green up" in glTF's convention) is brighter than tilted
    // across it; an unmapped quad would show 0.8·cos 30°.
    assert!(right > 1.1 * left && right > 0.8 * 0.8660254 && left < 0.8 * 0.8660254);
}

/// Each quadrant of the emissive texture shows at its pixels as
/// `emissiveFactor × emissiveStrength × texel` (W/(sr·m²)), the texel decoded from sRGB.
#[test]
fn an_emissive_texel_shows_at_its_pixel_with_its_strength() {
    let d = desc("emissive.glb");
    assert_eq!(d.materials[0].emission, (0.75, 0.75, 0.75));
    assert!(d.materials[0].bind.contains_key("emission"));
    assert!(
        d.environment.is_none(),
        "an emitting material lights the scene"
    );
    let (w, beauty) = render(load("emissive.glb"));
    let at = |x: f32, y: f32| pixel(w, &beauty, 3.0, 0.8, Vec3::new(x, y, 0.0));
    let grey = 0.75 * srgb(128);
    for (x, y, want) in [
        (-0.5, 0.5, Vec3::new(0.75, 0.0, 0.0)),
        (0.5, 0.5, Vec3::new(0.0, 0.75, 0.0)),
        (-0.5, -0.5, Vec3::new(0.0, 0.0, 0.75)),
        (0.5, -0.5, Vec3::splat(grey)),
    ] {
        let got = at(x, y);
        assert!(
            (got - want).abs().max_element() < 1e-4,
            "({x}, {y}): {got} vs {want}"
        );
    }
}

/// `mask.glb`: a black card whose left half has alpha 0 (`MASK`, cutoff ½) in front of a
/// grey wall one unit behind it, lit by a directional light travelling along
/// (−1, 0, −1)/√2, so the card's shadow falls one unit to the left of it on the wall.
/// Camera rays pass the cut half and see the lit wall; the opaque half is black; the
/// shadow of the opaque half is dark and the shadow of the cut half is missing — the
/// boundaries where the card's alpha crosses the cutoff (its centre line, x = 0).
#[test]
fn a_mask_cut_out_lets_camera_and_shadow_rays_through() {
    let d = desc("mask.glb");
    let card = d.materials.iter().find(|m| m.name == "card").unwrap();
    assert!(matches!(card.shader, ShaderDesc::Opacity { .. }));
    assert!(card.bind.contains_key("opacity"));
    let (w, beauty) = render(load("mask.glb"));
    let at = |x: f32, z: f32| pixel(w, &beauty, 4.0, 0.9, Vec3::new(x, 0.0, z)).x;
    let lit = at(1.0, -1.0);
    assert!(lit > 0.05, "the wall is lit: {lit}");
    let near = |v: f32, what: &str| {
        assert!((v - lit).abs() < 0.03 * lit, "{what}: {v} vs lit {lit}");
    };
    // Through the cut half (card x < 0) the wall shows, lit; the opaque half is black.
    near(at(-0.25, 0.0), "through the cut half");
    near(at(-0.02, 0.0), "just left of the cut edge");
    assert!(
        at(0.02, 0.0) < 0.1 * lit,
        "just right of the edge: the card"
    );
    assert!(at(0.25, 0.0) < 0.1 * lit, "the opaque half");
    // On the wall: the opaque half's shadow spans x ∈ [−1, −0.5]; the cut half's would
    // span [−1.5, −1] and is lit.
    assert!(
        at(-0.8, -1.0) < 0.1 * lit,
        "in the shadow of the opaque half"
    );
    assert!(
        at(-0.97, -1.0) < 0.1 * lit,
        "just inside the shadow's cut edge"
    );
    near(at(-1.03, -1.0), "just outside the shadow's cut edge");
    near(at(-1.3, -1.0), "where the cut half's shadow would be");
}

fn load_error(text: &str) -> String {
    match stagelight::scene::load_scene_str(text, Path::new("scene.ron")) {
        Ok(_) => panic!("expected errors"),
        Err(e) => e.to_string(),
    }
}

fn quad_with(material: &str) -> String {
    format!(
        r#"(
    cameras: [(name: "cam", fov_y: 30, resolution: (8, 8), placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)))],
    materials: [{material}],
    objects: [(name: "quad", material: "m",
               mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0)], polygons: [[0, 1, 2]]))],
    instances: [(name: "q", of: "quad")],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// A bump is a height map, a normal map or an object-space normal: two, or none, is a
/// located error, and so is a `scale` on an object-space normal.
#[test]
fn a_bump_needs_exactly_one_of_height_normal_map_and_object_normal() {
    let help = "\n  help: give one: `height: <scalar node>` for a height map, `normal_map: <colour node>` for a tangent-space normal map, or `object_normal: <colour node>` for an object-space normal";
    let both = quad_with(
        r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)), bump: (height: 0.1, normal_map: (0.5, 0.5, 1)))"#,
    );
    assert_eq!(
        load_error(&both),
        format!("scene.ron:3:71: error: a bump has both a `height` and a `normal_map`{help}")
    );
    let two = quad_with(
        r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)), bump: (normal_map: (0.5, 0.5, 1), object_normal: (0, 0, 1)))"#,
    );
    assert_eq!(
        load_error(&two),
        format!(
            "scene.ron:3:71: error: a bump has both a `normal_map` and an `object_normal`{help}"
        )
    );
    let neither = quad_with(r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)), bump: (scale: 2))"#);
    assert_eq!(
        load_error(&neither),
        format!("scene.ron:3:71: error: a bump needs a `height`, a `normal_map` or an `object_normal`{help}")
    );
    let scaled = quad_with(
        r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)), bump: (object_normal: (0, 0, 1), scale: 2))"#,
    );
    assert_eq!(
        load_error(&scaled),
        "scene.ron:3:105: error: a bump's `scale` does not apply to an `object_normal`, found 2\n  help: leave `scale` out: the object-space normal is used as given"
    );
}

/// An `Alpha` node of a file that cannot be read is an error at its `file`, as for `Image`.
#[test]
fn an_alpha_node_of_a_missing_file_is_located() {
    let text = quad_with(
        r#"(name: "m", shader: Opacity(opacity: (1, 1, 1), input: Lambert(albedo: (1, 1, 1))), bind: {"opacity": Alpha(file: "nowhere.png")})"#,
    );
    assert_eq!(
        load_error(&text),
        "scene.ron:3:131: error: cannot read image file \"nowhere.png\": file not found\n  help: image textures are PNG files, or EXR files with R, G and B, Y or a single channel, relative to the scene file"
    );
}

/// A glTF normal texture whose image file does not exist is an error naming the file.
#[test]
fn a_missing_gltf_texture_is_an_error() {
    let errors = match stagelight::scene::load_scene(&Path::new(DIR).join("missing_texture.gltf")) {
        Ok(_) => panic!("loaded"),
        Err(e) => e.to_string(),
    };
    let help = "  help: expected a PNG file at the image's uri, relative to the glTF file: put the file there, correct the uri, or embed the image (a bufferView or a base64 data: URI)";
    // A `.gltf` has lines: the error stands at the image's `uri`.
    assert_eq!(
        errors,
        format!("{DIR}/missing_texture.gltf:84:14: error: materials[0]: normal texture images[0]: cannot read image file \"{DIR}/nowhere.png\": file not found\n{help}")
    );
    // A `.glb` has none: the message names the image by index and name.
    let errors = match stagelight::scene::load_scene(&Path::new(DIR).join("missing_texture.glb")) {
        Ok(_) => panic!("loaded"),
        Err(e) => e.to_string(),
    };
    assert_eq!(
        errors,
        format!("{DIR}/missing_texture.glb:1:1: error: materials[0]: base colour texture images[0] (\"bricks\"): cannot read image file \"{DIR}/nowhere.png\": file not found\n{help}")
    );
}

/// An image file that is there but is not an image is reported at its `uri` in a `.gltf`
/// (by the shared image loader, through the reader's positions).
#[test]
fn an_image_that_does_not_decode_is_located_at_its_uri() {
    let dir = crate::common::cli::scratch_dir("gltf_bad_image");
    let text = std::fs::read_to_string(Path::new(DIR).join("missing_texture.gltf")).unwrap();
    std::fs::write(dir.join("model.gltf"), text).unwrap();
    std::fs::write(dir.join("nowhere.png"), "not a picture").unwrap();
    let errors = match stagelight::scene::load_scene(&dir.join("model.gltf")) {
        Ok(_) => panic!("loaded"),
        Err(e) => e.to_string(),
    };
    let at = format!(
        "{}:84:14: error: cannot read image file",
        dir.join("model.gltf").display()
    );
    assert!(errors.starts_with(&at), "{errors}");
}

/// `blend.glb`: a card that reflects nothing (black polished metal) with texture alpha
/// a = 64/255 (`BLEND`) in front of the white environment of radiance 1: rays pass it with
/// probability 1 − a, so the card's pixels average 1 − a (within 4σ of the binomial noise
/// over 200² pixels × 4 samples).
#[test]
fn a_blended_card_lets_through_one_minus_its_texture_alpha() {
    let d = desc("blend.glb");
    assert!(d.materials[0].bind.contains_key("opacity"));
    let (w, beauty) = render(load("blend.glb"));
    let (cx, cy) = (w / 2, w / 2);
    let mut sum = 0.0f64;
    let mut n = 0usize;
    for y in cy - 100..cy + 100 {
        for x in cx - 100..cx + 100 {
            sum += beauty[y * w + x].x as f64;
            n += 1;
        }
    }
    let mean = sum / n as f64;
    let a = 64.0 / 255.0;
    let sigma = (a * (1.0 - a) / (4.0 * n as f64)).sqrt();
    assert!(
        (mean - (1.0 - a)).abs() < 4.0 * sigma,
        "mean {mean} vs {} (σ {sigma})",
        1.0 - a
    );
}

/// An image embedded in a `.glb` that does not decode is named by index and name.
#[test]
fn an_embedded_image_that_does_not_decode_is_named() {
    let errors = match stagelight::scene::load_scene(&Path::new(DIR).join("bad_image.glb")) {
        Ok(_) => panic!("loaded"),
        Err(e) => e.to_string(),
    };
    assert_eq!(errors, format!("{DIR}/bad_image.glb:1:1: error: cannot read images[0] (\"garbage\") of glTF file \"{DIR}/bad_image.glb\": not a PNG file (it does not start with the PNG signature)\n  help: glTF images are read as PNG: export the image as PNG"));
}

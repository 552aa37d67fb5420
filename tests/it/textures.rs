//! Shader graphs end to end: texture nodes bound to material parameters, phenomena, image
//! textures, bump mapping and the bent-normal hard cases H11/H12, each checked against
//! analytic values at low resolution.

use std::path::{Path, PathBuf};

use glam::Vec3;
use stagelight::scene::load_scene_str;

/// Renders `text` as if it were `dir/scene.ron`; returns (width, beauty).
fn render_in(dir: &Path, text: &str) -> (usize, Vec<Vec3>) {
    let mut scene = load_scene_str(text, &dir.join("scene.ron")).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("image");
    (image.width as usize, image.beauty)
}

fn render(text: &str) -> (usize, Vec<Vec3>) {
    render_in(Path::new(env!("CARGO_MANIFEST_DIR")), text)
}

fn load_errors(text: &str) -> String {
    match load_scene_str(text, Path::new("scene.ron")) {
        Ok(_) => panic!("expected errors"),
        Err(e) => e.to_string(),
    }
}

/// A unit-uv quad spanning [−1, 1]² in z = 0 (uv (0, 0) at (−1, −1)), seen from z = 3 with
/// a 30° field of view (the image shows x, y ∈ [−0.80, 0.80]), lit straight on by a
/// directional light of irradiance π (so a Lambert albedo ρ shows as radiance ρ).
fn quad_scene(materials: &str, extra: &str, res: u32, spp: u32) -> String {
    format!(
        r#"(
    options: (samples: {spp}),
    cameras: [(name: "cam", fov_y: 30, resolution: ({res}, {res}),
               placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (0, 0, -1)), intensity: 3.14159265358979)],
    materials: [{materials}],
    objects: [(name: "quad", material: "m",
               mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
                            polygons: [[0, 1, 2, 3]],
                            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)]))],
    instances: [(name: "q", of: "quad")],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
    {extra}
)"#
    )
}

/// uv of the centre of pixel (px, py) of a `res`² render of [`quad_scene`], and the
/// half-size of the pixel in uv.
fn pixel_uv(px: usize, py: usize, res: usize) -> (f32, f32, f32) {
    let half = 3.0 * (15f32).to_radians().tan();
    let x = ((px as f32 + 0.5) / res as f32 * 2.0 - 1.0) * half;
    let y = (1.0 - (py as f32 + 0.5) / res as f32 * 2.0) * half;
    (
        (x + 1.0) / 2.0,
        (y + 1.0) / 2.0,
        half / res as f32 / 2.0 * 1.01,
    )
}

#[test]
fn checker_plane_matches_the_checker_colours_times_lighting() {
    let m = r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)),
               bind: {"albedo": Checker(scale: 5, a: (0.9, 0.5, 0.1), b: 0.2)})"#;
    let res = 40;
    let (w, img) = render(&quad_scene(m, "", res, 4));
    let (a, b) = (Vec3::new(0.9, 0.5, 0.1), Vec3::splat(0.2));
    let mut counts = [0, 0];
    for (i, c) in img.iter().enumerate() {
        let (u, v, h) = pixel_uv(i % w, i / w, res as usize);
        let cell = |u: f32, v: f32| ((u * 5.0).floor() + (v * 5.0).floor()) as i32;
        if cell(u - h, v - h) != cell(u + h, v + h)
            || (u * 5.0 - h * 5.0).floor() != (u * 5.0 + h * 5.0).floor()
        {
            continue; // the pixel straddles a cell edge
        }
        let even = cell(u, v).rem_euclid(2) == 0;
        let want = if even { a } else { b };
        counts[even as usize] += 1;
        assert!(
            (*c - want).abs().max_element() < 1e-4,
            "pixel {i}: {c} vs {want}"
        );
    }
    assert!(counts[0] > 300 && counts[1] > 300, "{counts:?}");
}

#[test]
fn phenomenon_used_twice_renders_each_parameter_set() {
    let phen = r#"phenomena: [(name: "painted", params: {"base": (0.5, 0.5, 0.5), "k": 1.0},
                              output: Mul(Param("base"), Param("k")))],"#;
    let mats = r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)),
                   bind: {"albedo": Graph("painted", {"base": (0.8, 0.2, 0.4)})}),
                  (name: "n", shader: Lambert(albedo: (1, 1, 1)),
                   bind: {"albedo": Graph("painted", {"k": 0.5})})"#;
    // Two quads: the left half uses "m", the right half "n".
    let text = quad_scene(mats, phen, 16, 1)
        .replace(
            r#"instances: [(name: "q", of: "quad")]"#,
            r#"instances: [(name: "q", of: "quad", transform: [Scale((0.5, 1, 1)), Translate((-0.5, 0, 0))]),
                           (name: "r", of: "quad", material: "n", transform: [Scale((0.5, 1, 1)), Translate((0.5, 0, 0))])]"#,
        )
        .replace(r#"members: ["q"]"#, r#"members: ["q", "r"]"#);
    let (w, img) = render(&text);
    let left = img[8 * w + 2];
    let right = img[8 * w + w - 3];
    assert!(
        (left - Vec3::new(0.8, 0.2, 0.4)).abs().max_element() < 1e-4,
        "{left}"
    );
    assert!(
        (right - Vec3::splat(0.25)).abs().max_element() < 1e-4,
        "{right}"
    );
}

/// A 2×2 RGB PNG, top row red/green, bottom row blue/white (8-bit sRGB codes given).
fn write_png(path: &Path, codes: [[u8; 3]; 4]) {
    crate::common::png::write_rgb(path, 2, 2, &codes);
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight-textures-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn srgb(code: u8) -> f32 {
    let x = code as f32 / 255.0;
    if x <= 0.04045 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

#[test]
fn image_texture_is_decoded_upright_and_sampled_bilinearly() {
    let dir = temp_dir("png");
    let codes = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [188, 188, 188]];
    write_png(&dir.join("tex.png"), codes);
    // Constant shader: the pixel is the texture value itself.
    let m = r#"(name: "m", shader: Constant(color: (0, 0, 0)),
               bind: {"color": Image(file: "tex.png", wrap: Clamp)})"#;
    let res = 64;
    let (w, img) = render_in(&dir, &quad_scene(m, "", res, 1));
    // The file's top-left texel (red) shows at the top left of the quad, where uv is
    // (0.25, 0.75); the image shows uv ∈ [0.1, 0.9]², so that is pixel ≈ (12, 12).
    let at = |u: f32, v: f32| {
        let px = ((u * 2.0 - 1.0) / (3.0 * 15f32.to_radians().tan()) + 1.0) / 2.0 * res as f32;
        let py = (1.0 - (v * 2.0 - 1.0) / (3.0 * 15f32.to_radians().tan())) / 2.0 * res as f32;
        img[py as usize * w + px as usize]
    };
    let texel = |k: usize| Vec3::new(srgb(codes[k][0]), srgb(codes[k][1]), srgb(codes[k][2]));
    // Pixels near texel centres (footprint ~0.0067 uv, bilinear slope ≤ 2 per uv unit).
    for (u, v, k) in [
        (0.25, 0.75, 0),
        (0.75, 0.75, 1),
        (0.25, 0.25, 2),
        (0.75, 0.25, 3),
    ] {
        let c = at(u, v);
        assert!(
            (c - texel(k)).abs().max_element() < 0.06,
            "({u}, {v}): {c} vs {}",
            texel(k)
        );
    }
    // 188 decodes to ≈ 0.503 (not 0.737): the sRGB curve was applied.
    assert!((at(0.75, 0.25).x - 0.5029).abs() < 0.06);
    // Half-way between the top texels: the bilinear mean of red and green.
    let mid = at(0.5, 0.75);
    assert!(
        (mid - Vec3::new(0.5, 0.5, 0.0)).abs().max_element() < 0.03,
        "{mid}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `wrap: PerAxis(u: Mirror, v: Clamp)`: u ∈ [0, 2] shows the image beside its mirror
/// image (the same pixels as a twice-as-wide image of both, clamped, on u ∈ [0, 1]) and
/// v ∈ [−½, 1½] extends the edge rows; repeating u instead changes the picture.
#[test]
fn a_per_axis_wrap_mirrors_one_axis_and_clamps_the_other() {
    let dir = temp_dir("per_axis_wrap");
    let texels: Vec<[u8; 3]> = (0..16u8)
        .map(|k| [k * 16, 255 - k * 13, ((k as u32 * 97) % 251) as u8])
        .collect();
    crate::common::png::write_rgb(&dir.join("tex.png"), 4, 4, &texels);
    let beside: Vec<[u8; 3]> = texels
        .chunks(4)
        .flat_map(|row| row.iter().chain(row.iter().rev()).copied())
        .collect();
    crate::common::png::write_rgb(&dir.join("beside.png"), 8, 4, &beside);
    let image = |file: &str, su: u32, wrap: &str| {
        let m = format!(
            r#"(name: "m", shader: Constant(color: (0, 0, 0)),
               bind: {{"color": Image(file: "{file}", uv: Sub(Mul(Uv, ({su}, 2, 0)), (0, 0.5, 0)),
                                     wrap: {wrap})}})"#
        );
        render_in(&dir, &quad_scene(&m, "", 24, 1)).1
    };
    let mirrored = image("tex.png", 2, "PerAxis(u: Mirror, v: Clamp)");
    let want = image("beside.png", 1, "Clamp");
    let repeated = image("tex.png", 2, "PerAxis(u: Repeat, v: Clamp)");
    let largest = |a: &[Vec3], b: &[Vec3]| {
        a.iter()
            .zip(b)
            .map(|(a, b)| (*a - *b).abs().max_element())
            .fold(0.0f32, f32::max)
    };
    assert!(
        largest(&mirrored, &want) < 1e-6,
        "{}",
        largest(&mirrored, &want)
    );
    assert!(largest(&repeated, &want) > 0.05);
    std::fs::remove_dir_all(&dir).ok();
}

/// A wrap mode that is not one, or a field `PerAxis` does not have, is a located error
/// naming what is expected.
#[test]
fn bad_wrap_modes_are_located_errors() {
    let wrap = |w: &str| {
        let m = format!(
            r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)),
               bind: {{"albedo": Image(file: "tex.png", wrap: {w})}})"#
        );
        load_errors(&quad_scene(&m, "", 8, 1))
    };
    assert_eq!(
        wrap("Mirorr"),
        "scene.ron:7:62: error: unknown variant \"Mirorr\" of Wrap\n  help: did you mean \"Mirror\"?"
    );
    assert_eq!(
        wrap("PerAxis(u: Mirror, v: Wrap)"),
        "scene.ron:7:84: error: unknown variant \"Wrap\" of AxisWrap\n  help: expected \"Repeat\", \"Clamp\" or \"Mirror\""
    );
    assert_eq!(
        wrap("PerAxis(u: PerAxis)"),
        "scene.ron:7:73: error: unknown variant \"PerAxis\" of AxisWrap\n  help: expected \"Repeat\", \"Clamp\" or \"Mirror\""
    );
    assert_eq!(
        wrap("PerAxis(u: Mirror, w: Clamp)"),
        "scene.ron:7:81: error: unknown field \"w\" in PerAxis\n  help: did you mean \"u\"?"
    );
}

#[test]
fn exr_textures_are_linear_and_png_can_be_declared_linear() {
    use stagelight::shading::texture::image::{load, Encoding, Wrap};
    let dir = temp_dir("exr");
    let path = dir.join("t.exr");
    exr::prelude::write_rgb_file(&path, 2, 1, |x, _y| {
        if x == 0 {
            (0.25f32, 2.0f32, 0.5f32)
        } else {
            (1.0, 0.0, 0.125)
        }
    })
    .unwrap();
    let t = load(&path, None, Wrap::Clamp).unwrap();
    assert_eq!((t.width, t.height), (2, 1));
    assert_eq!(
        t.texels,
        vec![Vec3::new(0.25, 2.0, 0.5), Vec3::new(1.0, 0.0, 0.125)]
    );
    let png = dir.join("t.png");
    write_png(&png, [[188, 0, 255], [0, 0, 0], [0, 0, 0], [0, 0, 0]]);
    let lin = load(&png, Some(Encoding::Linear), Wrap::Repeat).unwrap();
    // Top-left of the file is the last row (v = 1 at the top).
    assert!(
        (lin.texels[2] - Vec3::new(188.0 / 255.0, 0.0, 1.0))
            .abs()
            .max_element()
            < 1e-6
    );
    let s = load(&png, None, Wrap::Repeat).unwrap();
    assert!((s.texels[2].x - srgb(188)).abs() < 1e-6);
    assert!(load(&dir.join("missing.png"), None, Wrap::Repeat).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn graph_errors_are_located_with_suggestions() {
    let m = r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)),
               bind: {"albdo": Checker(scale: 4),
                      "albedo": Chekcer(scale: 4)})"#;
    let e = load_errors(&quad_scene(m, "", 8, 1));
    assert!(
        e.contains("scene.ron:7:32: error: shader Lambert has no parameter \"albdo\""),
        "{e}"
    );
    assert!(e.contains("did you mean \"albedo\"?"), "{e}");
    assert!(
        e.contains("scene.ron:8:33: error: unknown node \"Chekcer\""),
        "{e}"
    );
    assert!(e.contains("did you mean \"Checker\"?"), "{e}");

    // A field typo inside a known node: ron's own message at the field.
    let m =
        r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)), bind: {"albedo": Checker(scael: 4)})"#;
    let e = load_errors(&quad_scene(m, "", 8, 1));
    assert!(e.contains("unknown field \"scael\""), "{e}");
    assert!(e.contains("did you mean \"scale\"?"), "{e}");

    // A colour where a number is expected.
    let m = r#"(name: "m", shader: Plastic(), bind: {"roughness": Checker(a: (1, 1, 1))})"#;
    let e = load_errors(&quad_scene(m, "", 8, 1));
    assert!(
        e.contains("parameter \"roughness\" is a number, but this gives a colour"),
        "{e}"
    );
    let m = r#"(name: "m", shader: Lambert(albedo: (1,1,1)), bump: (height: Uv))"#;
    let e = load_errors(&quad_scene(m, "", 8, 1));
    assert!(
        e.contains("bump height must be a number, but this gives a colour"),
        "{e}"
    );

    // Phenomena: unknown name, unknown parameter, wrong argument type, cycles.
    let phen = r#"phenomena: [
        (name: "a", params: {"k": 1.0}, output: Graph("b", {})),
        (name: "b", output: Graph("a", {"k": 2})),
        (name: "ok", params: {"grain": 1.0}, output: Mul(Param("grain"), Param("grian"))),
        (name: "fine", params: {"grain": 1.0}, output: Param("grain")),
    ],"#;
    let m = r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)),
               bind: {"albedo": Graph("marbel", {})}),
               (name: "n", shader: Metal(),
               bind: {"roughness": Graph("fine", {"grian": 2, "grain": (1, 1, 1)})})"#;
    let e = load_errors(&quad_scene(m, phen, 8, 1));
    assert!(e.contains("unknown phenomenon \"marbel\""), "{e}");
    assert!(e.contains("phenomenon \"a\" uses itself: a → b → a"), "{e}");
    assert!(e.contains("phenomenon \"b\" uses itself: b → a → b"), "{e}");
    assert!(
        e.contains("phenomenon \"ok\" has no parameter \"grian\""),
        "{e}"
    );
    assert!(
        e.contains("phenomenon \"fine\" has no parameter \"grian\""),
        "{e}"
    );
    assert!(
        e.contains("parameter \"grain\" of \"fine\" is a number, but this gives a colour"),
        "{e}"
    );
    assert!(e.contains("did you mean \"grain\"?"), "{e}");

    // A phenomenon defined twice.
    let phen = r#"phenomena: [(name: "p", output: Uv), (name: "p", output: Normal)],"#;
    let m = r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)))"#;
    let e = load_errors(&quad_scene(m, phen, 8, 1));
    assert!(e.contains("phenomenon \"p\" is defined twice"), "{e}");
    assert!(e.contains("first defined at scene.ron:"), "{e}");

    // Param outside a phenomenon.
    let m = r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)), bind: {"albedo": Param("x")})"#;
    let e = load_errors(&quad_scene(m, "", 8, 1));
    assert!(
        e.contains("Param(\"x\") is only allowed inside a phenomenon"),
        "{e}"
    );

    // Missing image file.
    let m = r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)), bind: {"albedo": Image(file: "nope.png")})"#;
    let e = load_errors(&quad_scene(m, "", 8, 1));
    assert!(e.contains("cannot read image file"), "{e}");
    assert!(e.contains("nope.png"), "{e}");

    // Hostile numbers are rejected.
    let m =
        r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)), bind: {"albedo": Checker(scale: NaN)})"#;
    let e = load_errors(&quad_scene(m, "", 8, 1));
    assert!(e.contains("must be a finite number"), "{e}");
    let m =
        r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)), bind: {"albedo": Fbm(octaves: 40)})"#;
    let e = load_errors(&quad_scene(m, "", 8, 1));
    assert!(e.contains("octaves must be in 1…12, found 40"), "{e}");
}

#[test]
fn nodes_with_all_defaults_may_be_written_bare() {
    let m = r#"(name: "m", shader: Lambert(albedo: (1, 1, 1)),
               bind: {"albedo": Mix(a: Checker(), b: Turbulence(), t: Smoothstep(edge0: 0, edge1: 1, x: Fbm()))})"#;
    let (_, img) = render(&quad_scene(m, "", 8, 1));
    assert!(img.iter().all(|c| c.is_finite()));
}

/// Hostile numbers in node parameters (scales, radii, noise settings, colours, bump scale,
/// phenomenon arguments) are rejected at their value or render finite, non-negative pixels.
#[test]
fn hostile_node_parameters_are_rejected_or_render_finite_pixels() {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRng, TestRunner};
    const ORDINARY: [&str; 10] = ["4", "0.4", "0.1", "3", "2", "0.5", "0.8", "1", "0.05", "2"];
    let template = r#"(name: "m", shader: Plastic(roughness: 0.2),
        bind: {"color": Mix(a: Checker(scale: {}, a: (0.9, 0.9, 0.9)),
                            b: Disk(uv: Repeat(scale: 3), radius: {}, fuzz: {}),
                            t: Add(0.5, Fbm(frequency: {}, lacunarity: {}, gain: {}))),
               "roughness": Graph("g", {"k": {}})},
        bump: (height: Mul(Turbulence(frequency: {}), {}), scale: {}))"#;
    let phen = r#"phenomena: [(name: "g", params: {"k": 0.3}, output: Mul(Param("k"), Noise(frequency: 2)))],"#;
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 64,
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::deterministic_rng(proptest::test_runner::RngAlgorithm::ChaCha),
    );
    let hostile = prop::sample::select(vec![
        "NaN", "inf", "-inf", "0", "-0.0", "-1", "1e39", "-1e39", "1e-45", "1e30", "-1e-30",
    ]);
    let strategy = (
        prop::collection::vec((any::<bool>(), hostile), 10),
        0usize..10,
    );
    runner
        .run(&strategy, |(picks, forced)| {
            let mut m = template.to_string();
            for (k, &(bad, v)) in picks.iter().enumerate() {
                let v = if bad || k == forced { v } else { ORDINARY[k] };
                m = m.replacen("{}", v, 1);
            }
            let text = quad_scene(&m, phen, 6, 1);
            match load_scene_str(&text, Path::new("scene.ron")) {
                Err(errors) => {
                    for d in &errors.0 {
                        prop_assert!(d.line >= 1 && d.column >= 1, "unlocated: {d}");
                        prop_assert!(
                            d.message.contains("finite") || d.message.contains("f32"),
                            "{d}"
                        );
                    }
                }
                Ok(_) => {
                    let (_, img) = render(&text);
                    prop_assert!(
                        img.iter().all(|c| c.is_finite() && c.min_element() >= 0.0),
                        "non-finite pixel for\n{m}"
                    );
                }
            }
            Ok(())
        })
        .unwrap();
}

/// `stagelight bake` of `Albedo` evaluates the material's nodes: an 8 × 8 bake of a floor
/// whose albedo is a 2 × 2 checker holds exactly the checker colours per texel.
#[test]
fn baked_albedo_evaluates_texture_nodes() {
    use stagelight::shading::texture::image::{load, Wrap};
    let dir = temp_dir("bake");
    let text = r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
               placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (0.3, 0.2, -1)), intensity: 2.0)],
    materials: [(name: "m", shader: Lambert(albedo: (0.5, 0.5, 0.5)),
                 bind: {"albedo": Checker(scale: 2, a: (0.9, 0.1, 0.1), b: (0.1, 0.1, 0.9))})],
    objects: [(name: "floor", material: "m", mesh: Inline(
        vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
        uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]))],
    instances: [(name: "floor_1", of: "floor",
                 bake: (resolution: (8, 8), padding: 0, outputs: [(kind: Albedo)]))],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)"#;
    std::fs::write(dir.join("scene.ron"), text).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stagelight"))
        .arg("bake")
        .arg(dir.join("scene.ron"))
        .arg("-o")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let t = load(&dir.join("floor_1_albedo.exr"), None, Wrap::Clamp).unwrap();
    assert_eq!((t.width, t.height), (8, 8));
    for y in 0..8 {
        for x in 0..8 {
            // Row 0 of the loaded texture is v = 0.
            let (u, v) = ((x as f32 + 0.5) / 8.0, (y as f32 + 0.5) / 8.0);
            let even = ((u * 2.0).floor() + (v * 2.0).floor()) as i32 % 2 == 0;
            let want = if even {
                Vec3::new(0.9, 0.1, 0.1)
            } else {
                Vec3::new(0.1, 0.1, 0.9)
            };
            let got = t.texels[y * 8 + x];
            assert!(
                (got - want).abs().max_element() < 1e-5,
                "texel ({x}, {y}): {got}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A bump map with a linear height `h = u` on the quad (∂P/∂u = 2x) tilts every shading
/// normal to normalize(−1, 0, 2): under light straight down, Lambert 0.8 shows
/// 0.8 · cos(26.57°) = 0.8 · 2/√5 in every pixel (the bump shadowing term is 1 for light
/// along the geometric normal).
#[test]
fn linear_bump_tilts_the_normal_as_predicted() {
    for height in ["Channel(Uv, 0)", "Mul(Channel(Uv, 1), -1)"] {
        let m = format!(
            r#"(name: "m", shader: Lambert(albedo: (0.8, 0.8, 0.8)),
                bump: (height: {height}, scale: 1))"#
        );
        let (_, img) = render(&quad_scene(&m, "", 8, 1));
        let want = 0.8 * 2.0 / 5f32.sqrt();
        for c in &img {
            assert!((c.x - want).abs() < 1e-3, "{height}: {c} vs {want}");
        }
    }
}

/// `assets/scenes/textures.ron` (every node family, a phenomenon, an image, a bump map)
/// renders the same bits with 1 and 3 threads.
#[test]
fn textured_images_do_not_depend_on_the_thread_count() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/textures.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text.replace("resolution: (240, 160)", "resolution: (48, 32)");
    let render = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render_in(path.parent().unwrap(), &text).1)
    };
    let bits = |img: Vec<Vec3>| -> Vec<u32> {
        img.iter()
            .flat_map(|c| c.to_array().map(f32::to_bits))
            .collect()
    };
    let one = bits(render(1));
    assert!(one.iter().any(|&b| b != 0));
    assert_eq!(one, bits(render(3)));
}

//! The mental ray `.mi` reader end to end: the seed's §3.2.2 plane scene against mental
//! ray's base-shader formulas, light lists, the seed scenes (render, convert to RON that
//! renders the same), malformed files with exact located messages, the fuzz corpus.

use std::path::{Path, PathBuf};

use stagelight::components::{Camera, LightPhotons, RenderCamera};
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::import::to_ron::to_ron;
use stagelight::scene::{load_scene, load_scene_str, LoadedScene};

fn dir(sub: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(sub)
}

fn files(sub: &str, ext: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir(sub))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == ext))
        .collect();
    v.sort();
    v
}

/// Renders without writing: `max_width` pixels wide at most, `spp` samples, no adaptivity.
fn render(mut scene: LoadedScene, max_width: u32, spp: u32) -> (u32, u32, Vec<glam::Vec3>) {
    let mut size = (0, 0);
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        let scale = (max_width as f32 / camera.width as f32).min(1.0);
        camera.width = ((camera.width as f32 * scale).round() as u32).max(1);
        camera.height = ((camera.height as f32 * scale).round() as u32).max(1);
        size = (camera.width, camera.height);
    }
    // The seed's caustic light asks for 5 000 000 photons: a few thousand show the same.
    for photons in scene.world.query_mut::<&mut LightPhotons>() {
        for n in [&mut photons.caustic_photons, &mut photons.globillum_photons] {
            *n = n.map(|n| n.min(4000));
        }
    }
    let mut settings = scene.settings.clone();
    // caustics.mi names a photon map file: keep the maps in memory here.
    settings.photon_map = None;
    settings.spp = spp;
    settings.adaptive = None;
    let frame = crate::common::render(&mut scene.world, settings);
    (
        size.0,
        size.1,
        frame.outputs.image.expect("an image").beauty,
    )
}

fn plane_text() -> String {
    std::fs::read_to_string(dir("assets/seeds/mi/plane.mi")).unwrap()
}

/// Compares every pixel wholly inside the plane with `expected(x, y, z)` at the point
/// `(x, y, z)` the pixel centre sees on the plane z = −1 (f64), within 1 %.
fn check_plane(scene: LoadedScene, width: u32, expected: impl Fn(f64, f64, f64) -> f64) {
    let (w, h, beauty) = render(scene, width, 1);
    // focal 12, aperture 32, aspect 4/3: the image plane spans ±16/12 by ±1 at distance 1.
    let (tan_x, tan_y) = (16.0 / 12.0, 1.0);
    let mut checked = 0;
    for j in 1..h - 1 {
        for i in 0..w {
            let x = ((f64::from(i) + 0.5) / f64::from(w) * 2.0 - 1.0) * tan_x;
            let y = (1.0 - (f64::from(j) + 0.5) / f64::from(h) * 2.0) * tan_y;
            let pixel = 2.0 * tan_x / f64::from(w);
            if x.abs() > 1.0 - pixel {
                continue;
            }
            let want = expected(x, y, -1.0);
            let got = f64::from(beauty[(j * w + i) as usize].x);
            assert!(
                (got - want).abs() <= 0.01 * want,
                "pixel ({i}, {j}): {got} vs mental ray's {want}"
            );
            checked += 1;
        }
    }
    assert!(checked as u32 > w * h / 2, "{checked}");
}

#[test]
fn plane_scene_as_printed_matches_mental_rays_lambert_and_point_light() {
    let path = dir("assets/seeds/mi/plane.mi");
    let scene = load_scene(&path).unwrap();
    let (w, h, _) = {
        let cam = scene
            .world
            .query::<(&Camera, &RenderCamera)>()
            .iter()
            .next()
            .map(|(c, _)| (c.width, c.height, 0))
            .unwrap();
        cam
    };
    assert_eq!((w, h), (508, 380), "the printed resolution");
    // mib_illum_lambert: diffuse · Cl · max(0, N·L), no 1/π; mib_light_point with atten
    // false: Cl = colour at every distance. N = +z, the light at the eye.
    check_plane(scene, 508, |x, y, z| {
        let d = (x * x + y * y + z * z).sqrt();
        0.8 * (-z / d)
    });
}

#[test]
fn point_light_atten_ramps_linearly_and_ambience_adds() {
    let text = plane_text()
        .replace("\"atten\" false", "\"atten\" true")
        .replace("\"start\" 0,", "\"start\" 0.5,")
        .replace("\"stop\" 1\n", "\"stop\" 2.5\n")
        .replace("\"ambient\" 0.0 0.0 0.0", "\"ambient\" 0.1 0.2 0.3")
        .replace("\"ambience\" 0.0 0.0 0.0", "\"ambience\" 0.5 1 1");
    let scene = load_scene_str(&text, &dir("assets/seeds/mi/plane_atten.mi")).unwrap();
    // Every visible point is between 1 and √3 from the light: inside the ramp.
    check_plane(scene, 508, |x, y, z| {
        let d = (x * x + y * y + z * z).sqrt();
        let ramp = ((2.5 - d) / (2.5 - 0.5)).clamp(0.0, 1.0);
        0.05 + 0.8 * (-z / d) * ramp
    });
}

/// The plane scene with `shader` (a whole call) in place of its `mib_illum_lambert`.
fn plane_with(shader: &str) -> String {
    let text = plane_text();
    let at = text.find("\"mib_illum_lambert\" (").unwrap();
    let end = at + text[at..].find("\n)").unwrap() + 2;
    format!("{}{shader}{}", &text[..at], &text[end..])
}

/// `mib_illum_blinn`/`mib_illum_cooktorr` keep mental ray's semantics: the diffuse term is
/// `mib_illum_lambert`'s (no 1/π), the highlight Cook and Torrance's specular term per light,
/// `F·D·G / (π N·V)`. Light and eye at the origin: `H = V = L`, so `N·H = N·V = 1/d`, `F` is
/// the normal-incidence `((n−1)/(n+1))²`, `G = min(1, 2 (N·V)²)`.
#[test]
fn blinn_and_cooktorr_diffuse_is_lamberts_and_their_highlight_cook_torrances() {
    let lights = "\"mode\" 1,\n\"lights\" [ \"Lamp_inst\" ]";
    for name in ["mib_illum_blinn", "mib_illum_cooktorr"] {
        let text = plane_with(&format!(
            "\"{name}\" (\n\"diffuse\" 0.8 0.8 0.8,\n\"specular\" 0 0 0,\n{lights}\n)"
        ));
        let scene = load_scene_str(&text, &dir(&format!("assets/seeds/mi/{name}.mi"))).unwrap();
        check_plane(scene, 508, |x, y, z| {
            0.8 * (-z / (x * x + y * y + z * z).sqrt())
        });
    }
    let highlight = |m: f64, n: f64| {
        move |x: f64, y: f64, z: f64| {
            let c = -z / (x * x + y * y + z * z).sqrt();
            let tan2 = (1.0 - c * c) / (c * c);
            let d = (-tan2 / (m * m)).exp() / (m * m * c.powi(4));
            let g = (2.0 * c * c).min(1.0);
            let f = ((n - 1.0) / (n + 1.0)).powi(2);
            f * d * g / (std::f64::consts::PI * c)
        }
    };
    let text = plane_with(&format!(
        "\"mib_illum_blinn\" (\n\"specular\" 1 1 1,\n\"roughness\" 1,\n\"ior\" 3,\n{lights}\n)"
    ));
    let scene = load_scene_str(&text, &dir("assets/seeds/mi/blinn.mi")).unwrap();
    check_plane(scene, 508, highlight(1.0, 3.0));
    let text = plane_with(&format!(
        "\"mib_illum_cooktorr\" (\n\"specular\" 1 1 1,\n\"roughness\" 1,\n\"ior\" 3 1.5 2,\n{lights}\n)"
    ));
    let scene = load_scene_str(&text, &dir("assets/seeds/mi/cooktorr.mi")).unwrap();
    check_plane(scene, 508, highlight(1.0, 3.0));
}

/// The plane scene with a second point light `B` at `(0.6, 0.4, 0)`; the material lists
/// only `lights`.
fn two_lights(lights: &str, with_b: bool) -> String {
    let b = "light \"B\" \"mib_light_point\" (\"color\" 0.7 0.3 0.2) origin 0 0 0 end light\n\
             instance \"B_inst\" \"B\" transform 1 0 0 0 0 1 0 0 0 0 1 0 -0.6 -0.4 0 1 end instance\n";
    let mut text = plane_text().replace("\"lights\" [ \"Lamp_inst\" ]", lights);
    if with_b {
        text = text
            .replace("material \"mtl\"", &format!("{b}material \"mtl\""))
            .replace(
                "\"Lamp_inst\"\n\"Plane_inst\"",
                "\"Lamp_inst\"\n\"B_inst\"\n\"Plane_inst\"",
            );
    }
    text
}

#[test]
fn a_material_listing_one_light_ignores_the_other_pixel_exact() {
    let at = dir("assets/seeds/mi/lists.mi");
    let listed = load_scene_str(&two_lights("\"lights\" [ \"Lamp_inst\" ]", true), &at).unwrap();
    let alone = load_scene_str(&two_lights("\"lights\" [ \"Lamp_inst\" ]", false), &at).unwrap();
    let all = load_scene_str(&two_lights("\"mode\" 0", true), &at).unwrap();
    let exclusive = load_scene_str(
        &two_lights("\"mode\" 2, \"lights\" [ \"B_inst\" ]", true),
        &at,
    )
    .unwrap();
    let (_, _, a) = render(listed, 48, 1);
    let (_, _, b) = render(alone, 48, 1);
    let (_, _, c) = render(all, 48, 1);
    let (_, _, d) = render(exclusive, 48, 1);
    let bits = |v: &[glam::Vec3]| -> Vec<[u32; 3]> {
        v.iter().map(|c| c.to_array().map(f32::to_bits)).collect()
    };
    assert_eq!(
        bits(&a),
        bits(&b),
        "light B reaches a material that lists only Lamp_inst"
    );
    assert_eq!(bits(&d), bits(&b), "mode 2 (exclusive) leaves B out");
    // Without a list both lights light the plane: brighter where B reaches.
    let brighter = c.iter().zip(&a).filter(|(c, a)| c.x > a.x + 1e-3).count();
    assert!(brighter > c.len() / 2, "{brighter}");
}

/// A RIB scene with two point lights; the sphere switches light 2 off when `off`, and light 2
/// is not written at all when `!with_2`.
fn illuminate_rib(off: bool, with_2: bool) -> String {
    let second = if with_2 {
        "LightSource \"pointlight\" 2 \"from\" [2 1 -1] \"intensity\" 3 \"lightcolor\" [1 0.5 0.2]\n"
    } else {
        ""
    };
    let illuminate = if off && with_2 {
        "Illuminate 2 0\n"
    } else {
        ""
    };
    format!(
        "Format 24 18 1\nProjection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nWorldBegin\n\
         LightSource \"pointlight\" 1 \"from\" [-2 2 -3] \"intensity\" 8\n{second}\
         AttributeBegin\n{illuminate}Surface \"matte\"\nSphere 1 -1 1 360\nAttributeEnd\n\
         AttributeBegin\nSurface \"matte\"\nTranslate 0 0 2\nPatch \"bilinear\" \"P\" [-4 -4 0 4 -4 0 -4 4 0 4 4 0]\nAttributeEnd\nWorldEnd\n"
    )
}

#[test]
fn rib_illuminate_off_is_a_light_list() {
    let at = dir("assets/seeds/rib/illuminate.rib");
    let load = |text: String| load_scene_str(&text, &at).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let (w, _, off) = render(load(illuminate_rib(true, true)), 24, 1);
    let (_, _, without) = render(load(illuminate_rib(false, false)), 24, 1);
    let (_, _, on) = render(load(illuminate_rib(false, true)), 24, 1);
    // The sphere covers the middle of the image: there light 2 is off, exactly as if it
    // were not in the scene; the patch behind still sees it.
    let mid = (9 * w + 12) as usize;
    assert_eq!(
        off[mid].to_array().map(f32::to_bits),
        without[mid].to_array().map(f32::to_bits)
    );
    assert!(on[mid].x > off[mid].x + 1e-4, "{} vs {}", on[mid], off[mid]);
    let brighter_behind = off
        .iter()
        .zip(&without)
        .filter(|(a, b)| a.x > b.x + 1e-4)
        .count();
    assert!(brighter_behind > 0, "the patch no longer sees light 2");
}

#[test]
fn seed_mi_scenes_render_without_nan_and_their_ron_renders_the_same() {
    let scenes = files("assets/seeds/mi", "mi");
    assert!(scenes.len() >= 4, "{scenes:?}");
    for path in scenes {
        let name = path.display().to_string();
        let scene = load_scene(&path).unwrap_or_else(|e| panic!("{name}:\n{e}"));
        let (_, _, beauty) = render(scene, 32, 1);
        assert!(
            beauty
                .iter()
                .all(|c| c.is_finite() && c.min_element() >= 0.0),
            "{name}: NaN or negative"
        );
        assert!(
            beauty.iter().any(|c| c.max_element() > 0.0),
            "{name}: black"
        );
        let bytes = std::fs::read(&path).unwrap();
        let text = to_ron(&read_mi(&path, &bytes).unwrap().desc).unwrap();
        let again = load_scene_str(&text, &path.with_extension("ron"))
            .unwrap_or_else(|e| panic!("{name}:\n{e}\n{text}"));
        let (_, _, same) = render(again, 32, 1);
        assert!(
            beauty
                .iter()
                .zip(&same)
                .all(|(a, b)| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)),
            "{name}: the converted RON renders differently"
        );
    }
}

/// `stairs.mi` is `stairs.rib` written for mental ray: the same view (the RIB's `fov 30`
/// spans the vertical side; the `.mi` aperture is the film width; the same camera placement)
/// and the same spot cone and penumbra (`spread` = cos coneangle, `cone` = cos(coneangle −
/// conedeltaangle)).
#[test]
fn stairs_mi_frames_and_lights_like_stairs_rib() {
    use stagelight::components::{Emitter, LightShape};
    let view = |scene: &LoadedScene| {
        let (c, _) = scene
            .world
            .query::<(&Camera, &RenderCamera)>()
            .iter()
            .next()
            .map(|(c, r)| (c.clone(), *r))
            .unwrap();
        (c.fov_y, c.aspect, c.world_from_camera)
    };
    let spot = |scene: &LoadedScene| {
        scene
            .world
            .query::<&Emitter>()
            .iter()
            .find_map(|e| match &e.shape {
                LightShape::Spot {
                    position,
                    direction,
                    cone_angle,
                    penumbra,
                    ..
                } => Some((*position, *direction, *cone_angle, *penumbra)),
                _ => None,
            })
            .expect("a spot light")
    };
    let mi = load_scene(&dir("assets/seeds/mi/stairs.mi")).unwrap();
    let rib = load_scene(&dir("assets/seeds/rib/stairs.rib")).unwrap();
    // stairs.mi writes the RIB's points as they are; the RIB reader mirrors the RIB world
    // through z = 0 (docs/rib.md). The scene is symmetric in x, so the two worlds are one
    // half turn about y apart: compare the RIB's turned by it.
    let turn = glam::Affine3A::from_rotation_y(std::f32::consts::PI);
    let (a, mut b) = (view(&mi), view(&rib));
    b.2 = turn * b.2;
    assert!((a.0 - b.0).abs() < 1e-5, "fov_y {} vs {}", a.0, b.0);
    assert!((a.0 - 30f32.to_radians()).abs() < 1e-5, "{}", a.0);
    assert!((a.1 - b.1).abs() < 1e-5);
    let eye = |m: glam::Affine3A| m.transform_point3(glam::Vec3::ZERO);
    let ahead = |m: glam::Affine3A| m.transform_vector3(-glam::Vec3::Z).normalize();
    assert!(
        eye(a.2).distance(eye(b.2)) < 1e-4,
        "{} vs {}",
        eye(a.2),
        eye(b.2)
    );
    assert!(ahead(a.2).distance(ahead(b.2)) < 1e-4);
    let (p, mut q) = (spot(&mi), spot(&rib));
    q.0 = turn.transform_point3(q.0);
    q.1 = turn.transform_vector3(q.1);
    assert!(p.0.distance(q.0) < 1e-4, "{} vs {}", p.0, q.0);
    assert!(p.1.distance(q.1) < 1e-4, "{} vs {}", p.1, q.1);
    assert!(
        (p.2 - 0.35).abs() < 1e-5 && (q.2 - 0.35).abs() < 1e-5,
        "{} {}",
        p.2,
        q.2
    );
    assert!((p.3 - q.3).abs() < 1e-5, "penumbra {} vs {}", p.3, q.3);
    assert!((p.3 - 5f32.to_radians()).abs() < 1e-5, "{}", p.3);
}

#[test]
fn cli_convert_writes_ron_that_renders_byte_identical() {
    crate::common::convert_renders_the_same_png("mi_convert", &dir("assets/seeds/mi/plane.mi"));
}

/// `(fixture, every message it produces)`.
const MALFORMED: &[(&str, &str)] = &[
    (
        "bad_number",
        "tests/fixtures/mi/bad_number.mi:5:14: error: invalid number \"6.0.1\"",
    ),
    (
        "bad_spread",
        "tests/fixtures/mi/bad_spread.mi:10:85: error: light \"lamp_inst\": spread must be the cosine of the cone, in [0, 1), found 1.5",
    ),
    (
        "duplicate_name",
        "tests/fixtures/mi/duplicate_name.mi:14:8: error: \"quad\" is defined twice\n  help: the first is at tests/fixtures/mi/duplicate_name.mi:13:10",
    ),
    (
        "include_cycle",
        "tests/fixtures/mi/include_cycle.mi:1:10: error: \"tests/fixtures/mi/include_cycle.mi\" includes itself",
    ),
    (
        "missing_include",
        "tests/fixtures/mi/missing_include.mi:1:10: error: cannot read include \"tests/fixtures/mi/missing.mi\": file not found",
    ),
    (
        "native_light_shader",
        "tests/fixtures/mi/native_light_shader.mi:10:14: error: unknown light shader \"myLight\"\n  help: the tutorial's \"myLight\" is built in once its library is linked: link \"myLight.so\"",
    ),
    (
        "no_render",
        "tests/fixtures/mi/no_render.mi:1:1: error: the file has no render statement: nothing to render\n  help: end the scene with render \"root_instgroup\" \"camera_instance\" \"options\"",
    ),
    (
        "output_type",
        "tests/fixtures/mi/output_type.mi:6:8: error: output type \"rgbz\" is not supported\n  help: expected \"rgb\", \"rgba\", \"z\", \"n\", \"tag\" or \"contour\", or a file format (\"png\", \"exr\", \"rgb\", \"tif\", …)",
    ),
    (
        "short_polygon",
        "tests/fixtures/mi/short_polygon.mi:16:1: error: a polygon needs at least 3 vertices, found 2",
    ),
    (
        "singular_transform",
        "tests/fixtures/mi/singular_transform.mi:19:11: error: the transform of instance \"quad_inst\" is singular",
    ),
    (
        "two_errors",
        "tests/fixtures/mi/two_errors.mi:5:14: error: unexpected character '@'\ntests/fixtures/mi/two_errors.mi:12:37: error: unknown parameter \"difuse\" of shader \"mib_illum_lambert\"\n  help: did you mean \"diffuse\"?",
    ),
    (
        "unclosed_options",
        "tests/fixtures/mi/unclosed_options.mi:1:1: error: \"options\" block is not closed (expected \"end options\")",
    ),
    (
        "unknown_element",
        "tests/fixtures/mi/unknown_element.mi:18:22: error: unknown element \"qaud\"\n  help: did you mean \"quad\"?",
    ),
    (
        "unknown_light_in_list",
        "tests/fixtures/mi/unknown_light_in_list.mi:12:69: error: unknown light instance \"lmap_inst\"\n  help: did you mean \"lamp_inst\"?",
    ),
    (
        "unknown_material",
        "tests/fixtures/mi/unknown_material.mi:16:1: error: unknown material \"mlt\"\n  help: did you mean \"mtl\"?",
    ),
    (
        "unknown_option",
        "tests/fixtures/mi/unknown_option.mi:3:7: error: unknown option \"dpth\"",
    ),
    (
        "unknown_parameter",
        "tests/fixtures/mi/unknown_parameter.mi:12:37: error: unknown parameter \"difuse\" of shader \"mib_illum_lambert\"\n  help: did you mean \"diffuse\"?",
    ),
    (
        "unknown_render_camera",
        "tests/fixtures/mi/unknown_render_camera.mi:20:15: error: unknown camera instance \"camera_inst\"\n  help: did you mean \"cam_inst\"?",
    ),
    (
        "unknown_shader",
        "tests/fixtures/mi/unknown_shader.mi:12:16: error: unknown material shader \"mib_illum_lambret\"\n  help: did you mean \"mib_illum_lambert\"?",
    ),
    (
        "unknown_statement",
        "tests/fixtures/mi/unknown_statement.mi:1:1: error: unknown statement \"optoins\"\n  help: did you mean \"options\"?",
    ),
    (
        "unterminated_string",
        "tests/fixtures/mi/unterminated_string.mi:1:9: error: unterminated string (a string ends on its line)",
    ),
    (
        "vector_out_of_range",
        "tests/fixtures/mi/vector_out_of_range.mi:15:15: error: vector index 9 is out of range (the group has 4 vectors)",
    ),
    (
        "vertex_out_of_range",
        "tests/fixtures/mi/vertex_out_of_range.mi:16:15: error: vertex index 4 is out of range (the group has 4 vertices so far)",
    ),
    (
        "wrong_parameter_kind",
        "tests/fixtures/mi/wrong_parameter_kind.mi:12:47: error: parameter \"diffuse\" of \"mib_illum_lambert\" takes a color (3 numbers), found a string",
    ),
];

#[test]
fn malformed_mi_files_give_exact_located_messages() {
    let fixtures = files("tests/fixtures/mi", "mi");
    assert!(fixtures.len() >= 15);
    assert_eq!(
        fixtures.len(),
        MALFORMED.len(),
        "one expectation per fixture"
    );
    for path in fixtures {
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        let shown = Path::new("tests/fixtures/mi").join(path.file_name().unwrap());
        let Some((_, expected)) = MALFORMED.iter().find(|(n, _)| *n == stem) else {
            panic!("no expectation for {stem}");
        };
        let got = match load_scene(&shown) {
            Ok(_) => "ok".to_string(),
            Err(e) => e.to_string(),
        };
        assert_eq!(got, *expected, "{stem}");
    }
}

#[test]
fn fuzz_corpus_reads_or_reports_located_errors() {
    for path in files("fuzz/corpus/mi", "mi") {
        let bytes = std::fs::read(&path).unwrap();
        match read_mi(Path::new("fuzz.mi"), &bytes) {
            Ok(scene) => {
                let text = to_ron(&scene.desc).unwrap();
                let _ = load_scene_str(&text, Path::new("fuzz.ron"));
            }
            Err(errors) => {
                assert!(!errors.is_empty(), "{}", path.display());
                for e in &errors {
                    let p = e.problem.pos;
                    assert!(p.line >= 1 && p.column >= 1, "{}: {e}", path.display());
                }
            }
        }
    }
}

/// The seed's photon statements map onto the photon controls: light `energy` and `caustic
/// photons`, object and instance `caustic`/`globillum` modes (`on` = 3); a mode outside 0–3
/// is a located error.
#[test]
fn photon_statements_map_onto_lights_objects_and_instances() {
    let path = dir("assets/seeds/mi/caustics.mi");
    let bytes = std::fs::read(&path).unwrap();
    let desc = read_mi(&path, &bytes).unwrap().desc;
    let light = &desc.lights[0];
    assert_eq!(light.energy, Some((1000.0, 1000.0, 1000.0)));
    assert_eq!(light.caustic_photons, Some(5_000_000));
    assert_eq!(light.globillum_photons, None);
    let flagged: Vec<(&str, Option<u8>)> = desc
        .objects
        .iter()
        .map(|o| (o.name.as_str(), o.caustic))
        .filter(|(_, c)| c.is_some())
        .collect();
    assert!(
        !flagged.is_empty(),
        "the seed flags its objects: {flagged:?}"
    );

    let text = "object \"o\"\n  caustic 5\n  globillum on\n  group\n    0 0 0  1 0 0  0 1 0\n    v 0 v 1 v 2\n    p 0 1 2\n  end group\nend object\n";
    let e = read_mi(Path::new("flags.mi"), text.as_bytes())
        .err()
        .unwrap();
    assert!(
        e.iter().any(|p| p
            .to_string()
            .contains("caustic must be 0, 1, 2 or 3, found 5")),
        "{e:?}"
    );
}

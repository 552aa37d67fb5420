//! AIR's caustics in RIB scenes (seed 001, section 4.4): the caustic light, the photon and
//! gather counts and the primitives' caustic attributes drive the photon pass — the seed's
//! `aircaustics.rib` stores caustic photons, a mirror's caustic carries `specularcolor` times
//! the light it reflects, and without the caustic light the attributes do nothing and say so.

use std::path::{Path, PathBuf};

use stagelight::scene::load_scene;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

fn asset(sub: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(sub)
}

/// `render --spp 1 --stats --stats-json` on `scene` in `dir`; the stderr and the
/// `trace_photons` entry of the report.
fn photon_stage(dir: &Path, scene: &Path) -> (String, serde_json::Value) {
    let scene = scene.display().to_string();
    let o = run_in(
        dir,
        &[
            "render",
            &scene,
            "-o",
            "out.png",
            "--spp",
            "1",
            "--stats",
            "--stats-json",
            "stats.json",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("stats.json")).unwrap()).unwrap();
    let stage = v["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["stage"] == "trace_photons")
        .expect("trace_photons in the report")
        .clone();
    (stderr_of(&o), stage)
}

#[test]
fn aircaustics_rib_stores_caustic_photons_and_maps_the_air_attributes() {
    let dir = scratch_dir("rib-aircaustics");
    let (stderr, s) = photon_stage(&dir, &asset("assets/seeds/rib/aircaustics.rib"));
    assert_eq!(s["ran"], true, "{s}");
    assert_eq!(s["reason"], "caustics (100000 photons)");
    assert!(s["items"].as_u64().unwrap() > 1000, "{s}");
    // The caustic attributes are mapped; only maxpixeldist is reported as ignored.
    for name in [
        "specularcolor",
        "refractioncolor",
        "refractionindex",
        "ngather",
    ] {
        assert!(
            !stderr.contains(&format!("\"caustic\" \"{name}\"")),
            "{stderr}"
        );
    }
    assert!(!stderr.contains("\"visibility\" \"indirect\""), "{stderr}");
    assert!(
        stderr.contains(
            "aircaustics.rib:40:21: warning: ignored Attribute \"caustic\" \"maxpixeldist\": \
             stagelight bounds a caustic estimate by its photon count (ngather), not by a \
             distance in pixels"
        ),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A distant light (intensity 1, 45° down along +x) over a 2 × 2 mirror at y = 0 and a matte
/// wall at x = 3 facing it, seen head-on over the middle of the mirror's reflection; the
/// mirror's caustic `specularcolor` is `s`.
fn mirror_and_wall(s: f64) -> String {
    format!(
        "Format 8 8 1\nPixelSamples 1 1\nProjection \"perspective\" \"fov\" 19\n\
         Rotate -90 0 1 0\nTranslate 0 -3 0\nWorldBegin\nLightSource \"caustic\" 1\n\
         Attribute \"light\" \"integer nphotons\" [ 100000 ]\n\
         LightSource \"distantlight\" 2 \"from\" [0 0 0] \"to\" [1 -1 0] \"intensity\" 1\n\
         AttributeBegin\nAttribute \"caustic\" \"integer ngather\" [ 50 ]\nSurface \"matte\"\n\
         Polygon \"P\" [ 3 0 -3 3 0 3 3 6 3 3 6 -3 ]\nAttributeEnd\n\
         AttributeBegin\nAttribute \"caustic\" \"color specularcolor\" [ {s} {s} {s} ]\n\
         Surface \"matte\" \"Kd\" 0\nPolygon \"P\" [ -1 0 -1 1 0 -1 1 0 1 -1 0 1 ]\n\
         AttributeEnd\nWorldEnd\n"
    )
}

/// The mean red radiance of the rendered image and the caustic photons stored.
fn render_rib(dir: &Path, name: &str, text: &str) -> (f32, u64) {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let mut scene = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.settings.clone();
    let frame = crate::common::render(&mut scene.world, settings);
    let stored = frame
        .outputs
        .photons
        .as_ref()
        .and_then(|m| m.caustics.as_ref())
        .map_or(0, |c| c.stored());
    let beauty = frame.outputs.image.expect("an image").beauty;
    let mean = beauty.iter().map(|c| c.x).sum::<f32>() / beauty.len() as f32;
    (mean, stored)
}

#[test]
fn a_mirror_caustic_adds_specularcolor_times_the_light_the_mirror_reflects() {
    let dir = scratch_dir("rib-caustic-mirror");
    // The wall's direct light: `matte` is Cs·Kd·Σ Cl·N·L = 1 · cos 45° (no 1/π).
    let direct = std::f32::consts::FRAC_1_SQRT_2;
    let (without, stored) = render_rib(&dir, "black.rib", &mirror_and_wall(0.0));
    assert_eq!(stored, 0);
    assert!((without - direct).abs() < 1e-5, "{without}");
    // A mirror of 0.5 reflects the parallel beam onto the wall: the caustic irradiance there
    // is 0.5 × the light's irradiance across the beam × cos 45°, added by AIR's caustic light
    // to the diffuse sum like any light's.
    let (with, stored) = render_rib(&dir, "mirror.rib", &mirror_and_wall(0.5));
    assert!(stored > 10_000, "{stored}");
    let caustic = with - without;
    let expected = 0.5 * direct;
    assert!(
        (caustic / expected - 1.0).abs() < 0.07,
        "caustic {caustic}, expected {expected}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn caustic_attributes_without_the_caustic_light_do_nothing_and_say_so() {
    let dir = scratch_dir("rib-caustic-no-light");
    let text = mirror_and_wall(0.5).replace("LightSource \"caustic\" 1\n", "");
    std::fs::write(dir.join("t.rib"), text).unwrap();
    let (stderr, s) = photon_stage(&dir, Path::new("t.rib"));
    assert_eq!(s["ran"], false, "{s}");
    assert_eq!(s["reason"], "caustics and global illumination are off");
    let help =
        "  help: AIR renders caustics with its caustic light: add `LightSource \"caustic\" 1`";
    for (at, class, name) in [
        ("7:19", "light", "nphotons"),
        ("10:21", "caustic", "ngather"),
        ("15:21", "caustic", "specularcolor"),
    ] {
        let line = format!(
            "t.rib:{at}: warning: ignored Attribute \"{class}\" \"{name}\": no LightSource \
             \"caustic\" switches caustics on\n{help}"
        );
        assert!(stderr.contains(&line), "{line}\n{stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_ron_photon_shader_out_of_range_is_a_located_error() {
    let text = crate::common::cli::small_scene(&crate::common::cli::quad_object("q"), "", "", "")
        .replace(
            "shader: Lambert(albedo: (0.5, 0.5, 0.5)))",
            "shader: Lambert(albedo: (0.5, 0.5, 0.5)), \
             photon: Some(Caustic(specular: (0.4, 1.5, 0.4), ior: 0)))",
        );
    let err = stagelight::scene::load_scene_str(&text, Path::new("bad.ron"))
        .err()
        .expect("an error")
        .to_string();
    assert_eq!(
        err.trim_end(),
        "bad.ron:2:111: error: photon specular colour must be at most 1, found 1.5\n  \
         help: it is the fraction of each photon's power that goes on\n\
         bad.ron:2:127: error: photon refraction index must be above 0, found 0"
    );
}

/// A lit ball over a floor whose material's photon shader is `photon`, the ball's instance
/// with `flags`, at 16×12.
fn ball_over_floor(photon: &str, flags: &str, two_sided: bool) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, caustics: (photons: 20000, gather: 50)),
    cameras: [(name: "cam", fov_y: 50, resolution: (16, 12),
        placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0), up: (0, 0, 1)), outputs: [(file: "o.png")])],
    lights: [(name: "l", kind: Point(position: (0, 0, 3)), intensity: 20)],
    materials: [
        (name: "floor", shader: Lambert(albedo: (0.8, 0.8, 0.8))),
        (name: "ball", shader: Lambert(albedo: (0.5, 0.5, 0.5)), two_sided: {two_sided},
         photon: Some(Caustic({photon}))),
    ],
    objects: [
        (name: "floor", mesh: Grid(size_x: 6, size_y: 6), material: "floor"),
        (name: "ball", mesh: Sphere(radius: 0.6), material: "ball", approximation: Parametric(u: 32, v: 16)),
    ],
    instances: [(name: "f", of: "floor"), (name: "b", of: "ball"{flags}, transform: [Translate((0, 0, 1.2))])],
    groups: [(name: "world", members: ["f", "b"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// A photon shader alone makes a caster: `trace_photons` runs for a Lambert ball whose
/// photon shader reflects (it skipped: "nothing casts them"), and stores photons.
#[test]
fn a_photon_shader_alone_casts_caustics() {
    let dir = scratch_dir("photon-shader-casts");
    let mirror = "specular: (1, 1, 1), refraction: (0, 0, 0), ior: 1";
    std::fs::write(dir.join("a.ron"), ball_over_floor(mirror, "", false)).unwrap();
    let (_, stage) = photon_stage(&dir, Path::new("a.ron"));
    assert_eq!(stage["ran"], true, "{stage}");
    assert!(stage["items"].as_u64().unwrap() > 1000, "{stage}");
}

/// Photons refracted into a closed one-sided object leave it through its back faces, as
/// from a two-sided one: the same photons are stored (they died inside before).
#[test]
fn a_refracting_photon_shader_passes_photons_out_of_a_one_sided_object() {
    let dir = scratch_dir("photon-shader-one-sided");
    let glass = "specular: (0, 0, 0), refraction: (1, 1, 1), ior: 1.5";
    let flags = ", caustic: Some(1)";
    let stored = |two_sided: bool| {
        std::fs::write(dir.join("b.ron"), ball_over_floor(glass, flags, two_sided)).unwrap();
        let (_, stage) = photon_stage(&dir, Path::new("b.ron"));
        stage["items"].as_u64().unwrap()
    };
    let (one, two) = (stored(false), stored(true));
    assert!(two > 1000, "{two}");
    assert_eq!(one, two);
}

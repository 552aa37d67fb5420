//! Malformed area lights, light options and environments: each fixture in
//! `tests/fixtures/scenes/bad/` with the exact text the user sees.

use std::path::Path;

use stagelight::scene::{load_scene, load_scene_str};

fn check(name: &str, expected: &[&str]) {
    let path = format!("tests/fixtures/scenes/bad/{name}");
    let errors = match load_scene(Path::new(&path)) {
        Ok(_) => panic!("{name} loaded without errors"),
        Err(e) => e,
    };
    let got: Vec<String> = errors.0.iter().map(ToString::to_string).collect();
    assert_eq!(got, expected, "\n--- {name} reported:\n{errors}\n");
}

/// Zero and negative radii, NaN, a zero normal, a zero-length cylinder, `visible` on a point
/// light, reversed, negative and infinite attenuation ranges, attenuation on a directional
/// light: every error at its value, all reported together.
#[test]
fn area_lights() {
    check(
        "area_lights.ron",
        &[
            "tests/fixtures/scenes/bad/area_lights.ron:3:59: error: normal must not be zero",
            "tests/fixtures/scenes/bad/area_lights.ron:3:78: error: radius must be positive, found 0\n  help: the radius is the light's size in scene units, above 0 (such as 0.5); a light with no size is a point light",
            "tests/fixtures/scenes/bad/area_lights.ron:4:46: error: center must be a finite number, found NaN",
            "tests/fixtures/scenes/bad/area_lights.ron:4:63: error: radius must be positive, found -1\n  help: the radius is the light's size in scene units, above 0 (such as 0.5); a light with no size is a point light",
            "tests/fixtures/scenes/bad/area_lights.ron:5:59: error: end must differ from start",
            concat!(
                "tests/fixtures/scenes/bad/area_lights.ron:6:64: error: only area lights can be visible (a point, spot, directional or ambient light has no surface)\n",
                "  help: remove `visible`, or use a Rect, Disc, Sphere or Cylinder light",
            ),
            concat!(
                "tests/fixtures/scenes/bad/area_lights.ron:6:87: error: attenuation end must be greater than start (2), found 1\n",
                "  help: light falls off linearly from full at `start` to none at `end`",
            ),
            concat!(
                "tests/fixtures/scenes/bad/area_lights.ron:7:78: error: a directional light has no distance to attenuate over\n",
                "  help: remove `attenuation`, or use a point, spot or area light",
            ),
            "tests/fixtures/scenes/bad/area_lights.ron:8:76: error: samples must be at least 1, found 0",
            "tests/fixtures/scenes/bad/area_lights.ron:8:93: error: attenuation start must not be negative, found -1",
            "tests/fixtures/scenes/bad/area_lights.ron:8:97: error: attenuation end must be a finite number, found inf",
        ],
    );
}

/// A missing EXR file, a NaN rotation, a negative intensity and zero samples.
#[test]
fn environment_missing() {
    check(
        "environment_missing.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/environment_missing.ron:2:41: error: cannot use EXR file \"tests/fixtures/scenes/bad/textures/nowhere.exr\": file not found\n",
                "  help: a lat-long environment is an RGB(A) OpenEXR image; the path is relative to this scene file",
            ),
            "tests/fixtures/scenes/bad/environment_missing.ron:2:75: error: rotation must be a finite number, found NaN",
            "tests/fixtures/scenes/bad/environment_missing.ron:2:92: error: intensity must not be negative, found -2\n  help: intensity takes 0 or more: write 2 if only the sign is wrong",
            "tests/fixtures/scenes/bad/environment_missing.ron:2:105: error: samples must be at least 1, found 0",
        ],
    );
}

/// A file that is not an EXR image.
#[test]
fn environment_bad_exr() {
    check(
        "environment_bad_exr.ron",
        &[
            concat!(
                "tests/fixtures/scenes/bad/environment_bad_exr.ron:2:41: error: cannot use EXR file \"tests/fixtures/scenes/bad/not_an.exr\": not a readable OpenEXR RGB image (invalid: file identifier missing)\n",
                "  help: a lat-long environment is an RGB(A) OpenEXR image; the path is relative to this scene file",
            ),
        ],
    );
}

/// Two files may not both define the environment.
#[test]
fn environment_twice() {
    let dir = crate::common::scratch_root().join("stagelight_env_twice");
    std::fs::create_dir_all(&dir).unwrap();
    let lib = dir.join("lib.ron");
    std::fs::write(
        &lib,
        "Scene(environment: (shader: Constant(color: (1, 1, 1))))",
    )
    .unwrap();
    let text = r#"Scene(
    include: ["lib.ron"],
    environment: (shader: Constant(color: (0, 0, 1))),
    groups: [(name: "world")],
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
    render: (root: "world", camera: "cam"),
)"#;
    let errors = load_scene_str(text, &dir.join("main.ron"))
        .err()
        .expect("errors");
    let got: Vec<String> = errors.0.iter().map(ToString::to_string).collect();
    assert_eq!(got.len(), 1, "{errors}");
    assert!(got[0].contains("environment is given twice"), "{errors}");
    assert!(got[0].contains("help: first defined at"), "{errors}");
}

/// Radiant values beyond 1e20 (a light's colour × intensity whose factors are each in the f32
/// range, an emission, an environment's colour × intensity) are errors at their value: they
/// overflowed in sampling and their light was dropped without a word.
#[test]
fn radiant_values_beyond_1e20_are_errors() {
    let text = r#"Scene(
    environment: (shader: Constant(color: (1e19, 1, 1)), intensity: 20),
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
    lights: [
        (name: "sun", kind: Point(position: (0, 0, 2)), color: (3e38, 1, 1), intensity: 10),
        (name: "ok", kind: Point(position: (0, 0, 2)), color: (1, 1, 1), intensity: 1e20),
    ],
    materials: [(name: "hot", shader: Lambert(albedo: (0.5, 0.5, 0.5)), emission: (0, 2e20, 0))],
    objects: [(name: "o", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]), material: "hot")],
    instances: [(name: "i", of: "o")],
    groups: [(name: "world", members: ["i"])],
    render: (root: "world", camera: "cam"),
)"#;
    let errors = load_scene_str(text, Path::new("bright.ron"))
        .err()
        .expect("errors");
    let got: Vec<String> = errors.0.iter().map(ToString::to_string).collect();
    let help = "  help: radiant values above 1e20 overflow f32 arithmetic in sampling; scale the scene's light down (the camera's imager exposure can scale the image back)";
    assert_eq!(
        got,
        [
            format!("bright.ron:2:69: error: color × intensity 2e20 is brighter than stagelight carries (at most 1e20)\n{help}"),
            format!("bright.ron:5:89: error: color × intensity 3e39 is brighter than stagelight carries (at most 1e20)\n{help}"),
            format!("bright.ron:8:83: error: emission 2e20 is brighter than stagelight carries (at most 1e20)\n{help}"),
        ],
        "\n{errors}"
    );
}

/// An ambient light has no samples to take and emits no photons: `samples` said "delta
/// light", and photon counts and `energy` passed without a word.
#[test]
fn ambient_lights_refuse_samples_and_photons() {
    let text = r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
    lights: [
        (name: "a", kind: Ambient, samples: 8),
        (name: "b", kind: Ambient, caustic_photons: 1000, globillum_photons: 10, energy: (1, 1, 1)),
        (name: "c", kind: Ambient, samples: 1, caustic_photons: 0, energy: (0, 0, 0)),
    ],
    groups: [(name: "world")],
    render: (root: "world", camera: "cam"),
)"#;
    let errors = load_scene_str(text, Path::new("amb.ron"))
        .err()
        .expect("errors");
    let got: Vec<String> = errors.0.iter().map(ToString::to_string).collect();
    let photons = |field: &str| {
        format!("an ambient light emits no photons\n  help: remove `{field}`; photons leave point, spot, directional and area lights")
    };
    assert_eq!(
        got,
        [
            "amb.ron:4:45: error: samples must be 1 for an ambient light, found 8\n  help: only area lights take several samples; remove `samples`".to_string(),
            format!("amb.ron:5:53: error: {}", photons("caustic_photons")),
            format!("amb.ron:5:78: error: {}", photons("globillum_photons")),
            format!("amb.ron:5:90: error: {}", photons("energy")),
        ],
        "\n{errors}"
    );
}

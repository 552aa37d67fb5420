//! Issue 13: a light's shadow `factor` (mental ray `mib_light_point`/`_spot`/`_infinite`
//! `"factor"`, RON `shadow_factor`): that fraction of the light passes occluders — what
//! reaches a shadowed point is `factor + (1 − factor)·T` of it. On the shadow-shader scene
//! (a sun straight down, an opaque black square hanging over a grey floor), factor 0.25
//! leaves exactly a quarter of the light under the square in both integrators and in an
//! irradiance bake, factor 1 removes the shadow; the `.mi` parameter maps onto it and
//! round-trips through `convert`; out-of-range factors are exact located errors.

use std::path::Path;

use glam::Vec3;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene_str;

use crate::common::cli::{run_in, scratch, stderr_of};
use crate::common::read_exr_texels;
use crate::mi_shadow_shaders::{assert_shadow, mi_scene, render, scene};

const SUN: &str = "intensity: 1.0)]";
const OCCLUDER: &str = r#"(name: "occ", shader: Lambert(albedo: (0, 0, 0)))"#;

fn with_factor(text: &str, factor: &str) -> String {
    text.replace(SUN, &format!("intensity: 1.0, shadow_factor: {factor})]"))
}

#[test]
fn a_quarter_of_the_light_passes_the_occluder_in_both_integrators() {
    for integrator in ["Direct", "Path"] {
        let lit = render(&scene(OCCLUDER, integrator, false));
        let shadowed = scene(OCCLUDER, integrator, true);
        assert_shadow(&lit, &render(&shadowed), Vec3::ZERO, integrator);
        let quarter = render(&with_factor(&shadowed, "0.25"));
        assert_shadow(&lit, &quarter, Vec3::splat(0.25), integrator);
        let none = render(&with_factor(&shadowed, "1"));
        assert_shadow(&lit, &none, Vec3::ONE, integrator);
    }
}

/// Factor 1 lets all the light through: no shadow ray is traced (the image is the one of a
/// light with `shadows: false`, and its `shade` stage counts as many occlusion rays).
#[test]
fn a_factor_of_one_traces_no_shadow_rays() {
    let shadowed = scene(OCCLUDER, "Direct", true);
    let run = |text: &str| {
        let mut scene =
            load_scene_str(text, Path::new("shadow.ron")).unwrap_or_else(|e| panic!("{e}"));
        let settings = scene.settings.clone();
        crate::common::render(&mut scene.world, settings)
    };
    let none = run(&with_factor(&shadowed, "1"));
    let off = run(&shadowed.replace(SUN, "intensity: 1.0, shadows: false)]"));
    let traced = run(&with_factor(&shadowed, "0.999"));
    let occlusion = |f: &stagelight::frame::Frame| f.report.stage("shade").unwrap().rays_occlusion;
    assert_eq!(occlusion(&none), 0);
    assert_eq!(occlusion(&off), 0);
    assert!(occlusion(&traced) > 0);
    let beauty = |f: &stagelight::frame::Frame| f.outputs.image.as_ref().unwrap().beauty.clone();
    assert_eq!(beauty(&none), beauty(&off));
}

#[test]
fn an_irradiance_bake_keeps_the_factor() {
    let dir = scratch("light-shadow-factor-bake");
    let text = with_factor(&scene(OCCLUDER, "Direct", true), "0.25")
        .replace(
            "polygons: [[0, 1, 2, 3]]), material: \"grey\")",
            "polygons: [[0, 1, 2, 3]], uvs: [(0, 0), (1, 0), (1, 1), (0, 1)]), material: \"grey\")",
        )
        .replace(
            r#"(name: "floor_1", of: "floor")"#,
            r#"(name: "floor_1", of: "floor", bake: (resolution: (48, 48), uvs: Mesh,
                outputs: [(kind: Lightmap(store: Irradiance), file: "e.exr")]))"#,
        );
    std::fs::write(dir.join("scene.ron"), text).unwrap();
    let o = run_in(&dir, &["bake", "scene.ron", "-o", "out"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let (w, e) = read_exr_texels(&dir.join("out").join("e.exr"));
    let mut inside = 0;
    for (k, texel) in e.iter().enumerate() {
        // Texel centres in world units (x, y ∈ [−3, 3], texels 0.125 wide).
        let x = ((k % w) as f64 + 0.5) / 48.0 * 6.0 - 3.0;
        let y = ((k / w) as f64 + 0.5) / 48.0 * 6.0 - 3.0;
        if x.abs().max(y.abs()) < 0.5 - 0.125 {
            assert!((texel.x - 0.25).abs() < 1e-6, "texel {k}: {texel}");
            inside += 1;
        }
    }
    assert!(inside >= 36, "{inside}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn mi_light_factor_maps_onto_shadow_factor_and_round_trips() {
    let point = r#""mib_light_point" ("color" 1.0 1.0 1.0, "atten" false, "shadow" on)"#;
    let text = mi_scene("").replace(
        point,
        r#""mib_light_point" ("color" 1.0 1.0 1.0, "atten" false, "shadow" on, "factor" 0.25)"#,
    );
    let read = read_mi(Path::new("f.mi"), text.as_bytes()).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    assert_eq!(read.desc.lights[0].shadow_factor, 0.25);
    // Shadows off: the factor has nothing to lighten.
    let off = text.replace(r#""shadow" on, "factor""#, r#""shadow" off, "factor""#);
    let read_off = read_mi(Path::new("f.mi"), off.as_bytes()).unwrap();
    assert_eq!(read_off.desc.lights[0].shadow_factor, 0.0);

    let dir = scratch("light-shadow-factor-mi");
    std::fs::write(dir.join("f.mi"), &text).unwrap();
    let o = run_in(&dir, &["convert", "f.mi", "-o", "f.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let ron = std::fs::read_to_string(dir.join("f.ron")).unwrap();
    assert!(ron.contains("shadow_factor: 0.25"), "{ron}");
    let reloaded = load_scene_str(&ron, &dir.join("f.ron")).unwrap_or_else(|e| panic!("{e}"));
    drop(reloaded);

    let bad = text.replace(r#""factor" 0.25"#, r#""factor" 1.5"#);
    let errors = read_mi(Path::new("f.mi"), bad.as_bytes()).unwrap_err();
    let line = bad
        .lines()
        .position(|l| l.contains("\"factor\" 1.5"))
        .unwrap()
        + 1;
    let column = bad
        .lines()
        .nth(line - 1)
        .unwrap()
        .find("\"factor\"")
        .unwrap()
        + 1;
    assert_eq!(
        errors[0].to_string(),
        format!(
            "f.mi:{line}:{column}: error: shadow \"factor\" must be between 0 and 1, found 1.5\n  help: 0 gives full shadows, 1 none"
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_ron_factor_outside_zero_to_one_is_a_located_error() {
    let dir = scratch("light-shadow-factor-ron");
    for (factor, message) in [
        ("1.5", "shadow_factor must be at most 1, found 1.5"),
        ("-0.5", "shadow_factor must not be negative, found -0.5"),
    ] {
        std::fs::write(
            dir.join("s.ron"),
            with_factor(&scene(OCCLUDER, "Direct", true), factor),
        )
        .unwrap();
        let o = run_in(&dir, &["check", "s.ron"]);
        assert!(!o.status.success());
        let err = stderr_of(&o);
        assert!(err.contains(message), "{err}");
        assert!(err.contains("s.ron:"), "{err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

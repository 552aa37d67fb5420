//! Issue 13: per-material environments (RON `environment:` on a material, `.mi` material
//! `environment` shaders). Under a blue scene environment, a mirror whose material has a red
//! environment shows red wherever its reflected ray leaves the scene, while a mirror without
//! one shows blue — in the Direct integrator and the path tracer, pixel-exact. `.mi` →
//! `convert` → RON round-trips; bad values are exact located errors.

use std::path::Path;

use glam::{DVec3, Vec3};
use stagelight::scene::desc::EnvironmentShaderDesc;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::{load_scene, load_scene_str};

use crate::common::cli::{run_in, scratch, stderr_of};
use crate::common::{mi_preamble, BASE, PHYSICS};

const RED: Vec3 = Vec3::new(1.0, 0.0, 0.0);
const BLUE: Vec3 = Vec3::new(0.0, 0.0, 1.0);

/// Two finely tessellated mirror spheres of radius 0.5 at x = ∓1.2 seen from z = 5
/// (160 × 80 pixels, fov 40°) under a blue environment; the left one's material is `left`.
fn scene(left: &str, integrator: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 4, integrator: {integrator}, max_depth: 4),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (160, 80),
        placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "out.exr")])],
    environment: (shader: Constant(color: (0, 0, 1))),
    materials: [
        {left},
        (name: "plain", shader: Mirror(color: (1, 1, 1))),
    ],
    objects: [
        (name: "a", mesh: Sphere(radius: 0.5), material: "left",
         approximation: Parametric(u: 96, v: 48)),
        (name: "b", mesh: Sphere(radius: 0.5), material: "plain",
         approximation: Parametric(u: 96, v: 48)),
    ],
    instances: [
        (name: "a_1", of: "a", transform: [Translate((-1.2, 0, 0))]),
        (name: "b_1", of: "b", transform: [Translate((1.2, 0, 0))]),
    ],
    groups: [(name: "world", members: ["a_1", "b_1"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

const RED_MIRROR: &str = r#"(name: "left", shader: Mirror(color: (1, 1, 1)),
        environment: Some((shader: Constant(color: (1, 0, 0)))))"#;

fn render(text: &str) -> Vec<Vec3> {
    let mut scene = load_scene_str(text, Path::new("env.ron")).unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.settings.clone();
    crate::common::render(&mut scene.world, settings)
        .outputs
        .image
        .expect("an image")
        .beauty
}

/// Distance along the ray `o + t·d` (unit `d`) to the sphere, if it is hit `margin` inside
/// its silhouette; `Err(())` when the ray passes within `margin` of the silhouette.
fn hit(o: DVec3, d: DVec3, centre: DVec3, r: f64, margin: f64) -> Result<Option<f64>, ()> {
    let oc = o - centre;
    let b = oc.dot(d);
    let closest = (oc - b * d).length();
    if (closest - r).abs() < margin {
        return Err(());
    }
    if closest > r || b > 0.0 {
        return Ok(None);
    }
    Ok(Some(-b - (r * r - closest * closest).sqrt()))
}

/// What the camera ray through image-plane point `(x, y)` (at distance 1) must bring back:
/// the left sphere's escaping reflections `left`, the right one's blue, the background
/// blue; `Err(())` near a silhouette or where a reflection comes near the other sphere.
fn verdict(x: f64, y: f64, left: Vec3) -> Result<Vec3, ()> {
    let eye = DVec3::new(0.0, 0.0, 5.0);
    let (a, b) = (DVec3::new(-1.2, 0.0, 0.0), DVec3::new(1.2, 0.0, 0.0));
    let d = DVec3::new(x, y, -1.0).normalize();
    match (hit(eye, d, a, 0.5, 0.03)?, hit(eye, d, b, 0.5, 0.03)?) {
        (None, None) => Ok(BLUE),
        (Some(s), _) | (_, Some(s)) => {
            let p = eye + s * d;
            let (own, other, colour) = if (p - a).length() < 0.6 {
                (a, b, left)
            } else {
                (b, a, BLUE)
            };
            let n = (p - own).normalize();
            let r = d - 2.0 * d.dot(n) * n;
            match hit(p, r, other, 0.5, 0.1)? {
                None => Ok(colour),
                Some(_) => Err(()),
            }
        }
    }
}

/// What each pixel must show, or `None` where its centre and corners disagree (silhouettes,
/// reflections of the other sphere): the samples of a pixel fall anywhere inside it.
fn expected(left: Vec3) -> Vec<Option<Vec3>> {
    let t = 20f64.to_radians().tan();
    let mut out = Vec::new();
    for j in 0..80 {
        for i in 0..160 {
            let at = |u: f64, v: f64| {
                let x = ((i as f64 + u) / 160.0 * 2.0 - 1.0) * t * 2.0;
                let y = (1.0 - (j as f64 + v) / 80.0 * 2.0) * t;
                verdict(x, y, left)
            };
            let centre = at(0.5, 0.5);
            let corners = [at(0.0, 0.0), at(1.0, 0.0), at(0.0, 1.0), at(1.0, 1.0)];
            out.push(match centre {
                Ok(c) if corners.iter().all(|k| *k == Ok(c)) => Some(c),
                _ => None,
            });
        }
    }
    out
}

fn assert_pixels(got: &[Vec3], want: &[Option<Vec3>], what: &str) -> usize {
    let mut checked = 0;
    for (k, (g, w)) in got.iter().zip(want).enumerate() {
        if let Some(w) = w {
            assert!(
                (*g - *w).abs().max_element() < 1e-5,
                "{what}: pixel ({}, {}) is {g}, expected {w}",
                k % 160,
                k / 160
            );
            checked += 1;
        }
    }
    checked
}

#[test]
fn a_mirror_with_a_red_environment_reflects_red_where_its_rays_leave_the_scene() {
    let want = expected(RED);
    let reds = want.iter().filter(|w| **w == Some(RED)).count();
    assert!(reds > 250, "{reds} red pixels to check");
    for integrator in ["Direct", "Path"] {
        let got = render(&scene(RED_MIRROR, integrator));
        let checked = assert_pixels(&got, &want, integrator);
        assert!(checked > 10000, "{integrator}: {checked} pixels");
    }
    // Without its own environment the left mirror reflects the scene's blue.
    let plain = render(&scene(
        r#"(name: "left", shader: Mirror(color: (1, 1, 1)))"#,
        "Direct",
    ));
    assert_pixels(&plain, &expected(BLUE), "no material environment");
}

#[test]
fn a_material_environment_scales_and_goes_black_past_the_trace_depth() {
    // Intensity scales the colour; with no reflection budget left the mirror's ray sees its
    // material's `depth_exceeded`.
    let half = RED_MIRROR.replace("(1, 0, 0))", "(1, 0, 0)), intensity: 0.5");
    assert_pixels(
        &render(&scene(&half, "Direct")),
        &expected(0.5 * RED),
        "intensity",
    );
    let budget =
        |m: &str| scene(m, "Direct").replace("max_depth: 4)", "max_depth: 4, reflection_depth: 0)");
    assert_pixels(
        &render(&budget(RED_MIRROR)),
        &expected(RED),
        "past the depth",
    );
    let black = RED_MIRROR.replace("(1, 0, 0))", "(1, 0, 0)), depth_exceeded: Black");
    assert_pixels(
        &render(&budget(&black)),
        &expected(Vec3::ZERO),
        "black past the depth",
    );
}

/// A `.mi` scene: a camera at the origin looking down −z (160 × 120, the image plane spans
/// ±4/3 by ±1 at distance 1) with a blue environment; two `dgs_material` mirrors at
/// z = −2, x ∈ [−1.5, −0.3] (`left`, whose statements follow its shader) and
/// x ∈ [0.3, 1.5], y ∈ [−0.5, 0.5], facing the camera.
fn mi_scene(left: &str) -> String {
    let preamble = mi_preamble(
        &format!("{BASE}{PHYSICS}"),
        "environment \"mib_opacity\" (\"input\" 0 0 1, \"opacity\" 1 1 1)\n",
    );
    format!(
        r#"{preamble}material "left"
"dgs_material" ("specular" 1 1 1)
{left}
end material
material "right"
"dgs_material" ("specular" 1 1 1)
end material
object "Mirrors"
group
-1.5 -0.5 -2
-0.3 -0.5 -2
-0.3 0.5 -2
-1.5 0.5 -2
0.3 -0.5 -2
1.5 -0.5 -2
1.5 0.5 -2
0.3 0.5 -2
v 0
v 1
v 2
v 3
v 4
v 5
v 6
v 7
p "left" 0 1 2 3
p "right" 4 5 6 7
end group
end object
instance "Mirrors_inst" "Mirrors"
end instance
instgroup "rootgrp"
"Camera_inst" "Mirrors_inst"
end instgroup
render "rootgrp" "Camera_inst" "opt"
"#
    )
}

const MI_RED: &str = r#"environment "mib_opacity" ("input" 1 0 0, "opacity" 1 1 1)"#;

#[test]
fn a_mi_material_environment_is_what_its_mirror_reflects() {
    let read = read_mi(Path::new("e.mi"), mi_scene(MI_RED).as_bytes()).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let left = read
        .desc
        .materials
        .iter()
        .find(|m| m.name == "left")
        .unwrap();
    let env = left.environment.as_ref().expect("a material environment");
    assert!(
        matches!(env.shader, EnvironmentShaderDesc::Constant { color } if color == (1.0, 0.0, 0.0)),
        "{env:?}"
    );
    let right = read
        .desc
        .materials
        .iter()
        .find(|m| m.name == "right")
        .unwrap();
    assert!(right.environment.is_none());

    let dir = scratch("mi6-env-mi");
    std::fs::write(dir.join("env.mi"), mi_scene(MI_RED)).unwrap();
    let run = |args: &[&str]| {
        let o = run_in(&dir, args);
        assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
    };
    run(&["convert", "env.mi", "-o", "env.ron"]);
    run(&["convert", "env.ron", "-o", "again.ron"]);
    let ron = std::fs::read_to_string(dir.join("env.ron")).unwrap();
    assert!(
        ron.contains(
            "environment: MaterialEnvironment(\n                shader: Constant(\n                    color: (1.0, 0.0, 0.0),"
        ),
        "{ron}"
    );
    assert_eq!(ron, std::fs::read_to_string(dir.join("again.ron")).unwrap());
    run(&["render", "env.mi", "--spp", "1", "-o", "mi.exr"]);
    run(&["render", "env.ron", "--spp", "1", "-o", "ron.exr"]);
    assert_eq!(
        std::fs::read(dir.join("mi.exr")).unwrap(),
        std::fs::read(dir.join("ron.exr")).unwrap(),
        "the RON renders the same bytes"
    );
    let mut scene = load_scene(&dir.join("env.mi")).unwrap();
    let mut settings = scene.settings.clone();
    settings.spp = 1;
    settings.adaptive = None;
    let got = crate::common::render(&mut scene.world, settings)
        .outputs
        .image
        .unwrap()
        .beauty;
    let (mut red, mut blue) = (0, 0);
    for j in 0..120 {
        for i in 0..160 {
            let x = 2.0 * ((i as f64 + 0.5) / 160.0 * 2.0 - 1.0) * 4.0 / 3.0;
            let y = 2.0 * (1.0 - (j as f64 + 0.5) / 120.0 * 2.0);
            let g = got[j * 160 + i];
            let inside_y = y.abs() < 0.48;
            if inside_y && (-1.48..-0.32).contains(&x) {
                assert_eq!(g, RED, "({i}, {j}) on the left mirror");
                red += 1;
            } else if inside_y && (0.32..1.48).contains(&x)
                || y.abs() > 0.52
                || x.abs() > 1.52
                || x.abs() < 0.28
            {
                assert_eq!(g, BLUE, "({i}, {j}) on the right mirror or the background");
                blue += 1;
            }
        }
    }
    assert!(red > 900 && blue > 5000, "{red} / {blue}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_material_environments_give_exact_located_messages() {
    let dir = scratch("mi6-env-bad");
    let mut failures = Vec::new();
    let mut check = |name: &str, text: &str, want: String| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let got = match load_scene(&path) {
            Ok(_) => "ok".to_string(),
            Err(e) => e.to_string(),
        };
        let got = got
            .replace(&format!("{}/", dir.display()), "")
            .trim_end()
            .to_string();
        if got != want {
            failures.push(format!("got:  {got}\nwant: {want}"));
        }
    };
    let mi = mi_scene(r#"environment "mib_lookup_spherical" ("tex" "sky")"#);
    let at = mi
        .lines()
        .position(|l| l.contains("mib_lookup_spherical"))
        .unwrap()
        + 1;
    check(
        "bad.mi",
        &mi,
        format!("bad.mi:{at}:13: error: environment shader \"mib_lookup_spherical\" is not mapped\n  help: a mib_opacity with a constant input (directly or as a phenomenon's root) maps onto a constant environment"),
    );
    let ron = |m: &str| scene(m, "Direct");
    let at = ron(RED_MIRROR)
        .lines()
        .position(|l| l.contains("environment: Some"))
        .unwrap()
        + 1;
    check(
        "bad.ron",
        &ron(&RED_MIRROR.replace("(1, 0, 0))", "(1, 0, 0)), intensity: -1")),
        format!("bad.ron:{at}:75: error: intensity must not be negative, found -1\n  help: intensity takes 0 or more: write 1 if only the sign is wrong"),
    );
    check(
        "bad.ron",
        &ron(&RED_MIRROR.replace("Constant(color: (1, 0, 0))", "LatLong(file: \"missing.exr\")")),
        format!("bad.ron:{at}:50: error: cannot use EXR file \"missing.exr\": file not found\n  help: a lat-long environment is an RGB(A) OpenEXR image; the path is relative to this scene file"),
    );
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

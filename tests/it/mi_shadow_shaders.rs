//! Issue 13: material shadow shaders independent of the surface shader (RON `shadow:`,
//! `.mi` `shadow "mib_shadow_transparency" (…)`). A sun straight down lights a grey floor;
//! an occluding square (invisible to the camera, so only its shadow shows) hangs above it.
//! A 50 % grey shadow transparency on an opaque material lets exactly half the light
//! through (Direct and path tracer renders, and a lightmap bake); an opaque shadow shader
//! on a half-transparent sheet blocks; a tinted one on glass tints. `.mi` → `convert` →
//! RON round-trips; bad parameters are exact located errors.

use std::path::Path;

use glam::Vec3;
use stagelight::scene::desc::ShadowDesc;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::{load_scene, load_scene_str};

use crate::common::cli::{run_in, scratch, stderr_of};
use crate::common::{mi_point_lamp, mi_preamble, read_exr_texels, BASE};

/// 40 × 40 pixels looking straight down at the floor from z = 4 (fov 40°); the occluder
/// (`material` `occ`, hidden from the camera) is the square |x|, |y| ≤ 0.5 at z = 1.
pub(crate) fn scene(occ_material: &str, integrator: &str, with_occluder: bool) -> String {
    let members = if with_occluder {
        r#""floor_1", "occ_1""#
    } else {
        r#""floor_1""#
    };
    format!(
        r#"Scene(
    options: (samples: 2, integrator: {integrator}, max_depth: 3),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (40, 40),
        placement: LookAt(eye: (0, 0, 4), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "out.exr")])],
    lights: [(name: "sun", kind: Directional(direction: (0, 0, -1)), intensity: 1.0)],
    materials: [
        (name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5))),
        {occ_material},
    ],
    objects: [
        (name: "floor", mesh: Inline(
            vertices: [(-3, -3, 0), (3, -3, 0), (3, 3, 0), (-3, 3, 0)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
        (name: "occ", mesh: Inline(
            vertices: [(-0.5, -0.5, 1), (0.5, -0.5, 1), (0.5, 0.5, 1), (-0.5, 0.5, 1)],
            polygons: [[0, 1, 2, 3]]), material: "occ", visible: false),
    ],
    instances: [(name: "floor_1", of: "floor"), (name: "occ_1", of: "occ")],
    groups: [(name: "world", members: [{members}])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

pub(crate) fn render(text: &str) -> Vec<Vec3> {
    let mut scene = load_scene_str(text, Path::new("shadow.ron")).unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.settings.clone();
    let frame = crate::common::render(&mut scene.world, settings);
    frame.outputs.image.expect("an image").beauty
}

/// Where the camera ray of pixel `(i, j)` meets the floor.
fn floor_point(i: usize, j: usize) -> (f64, f64) {
    let t = 20f64.to_radians().tan();
    let x = ((i as f64 + 0.5) / 40.0 * 2.0 - 1.0) * t;
    let y = (1.0 - (j as f64 + 0.5) / 40.0 * 2.0) * t;
    (4.0 * x, 4.0 * y)
}

/// Checks every pixel: inside the shadow (0.05 from its edge) it is `lit · through`, outside
/// it equals `lit`. Returns how many shadow pixels were checked.
pub(crate) fn assert_shadow(lit: &[Vec3], got: &[Vec3], through: Vec3, what: &str) -> usize {
    let mut inside = 0;
    for j in 0..40 {
        for i in 0..40 {
            let (x, y) = floor_point(i, j);
            let (l, g) = (lit[j * 40 + i], got[j * 40 + i]);
            let d = x.abs().max(y.abs());
            if d < 0.45 {
                let want = l * through;
                assert!(
                    (g - want).abs().max_element() <= 1e-6 * l.max_element(),
                    "{what}: pixel ({i}, {j}) in the shadow is {g}, expected {want}"
                );
                inside += 1;
            } else if d > 0.55 {
                assert_eq!(g, l, "{what}: pixel ({i}, {j}) outside the shadow");
            }
        }
    }
    assert!(inside > 100, "{what}: {inside} shadow pixels");
    inside
}

#[test]
fn a_grey_shadow_transparency_lets_half_the_light_through_in_both_integrators() {
    let occ = r#"(name: "occ", shader: Lambert(albedo: (0, 0, 0)),
        shadow: Some(Transparency(color: (0.5, 0.5, 0.5))))"#;
    for integrator in ["Direct", "Path"] {
        let lit = render(&scene(occ, integrator, false));
        // The closed form: albedo / π · E on the lit floor.
        let centre = lit[20 * 40 + 20];
        assert!(
            (centre.x - 0.5 / std::f32::consts::PI).abs() < 1e-5,
            "{integrator}: lit floor {centre}"
        );
        let half = render(&scene(occ, integrator, true));
        assert_shadow(&lit, &half, Vec3::splat(0.5), integrator);
        // Without the shadow shader the opaque material blocks.
        let blocked = render(&scene(
            &occ.replace("Some(Transparency(color: (0.5, 0.5, 0.5)))", "None"),
            integrator,
            true,
        ));
        assert_shadow(&lit, &blocked, Vec3::ZERO, integrator);
    }
}

#[test]
fn shadow_shaders_override_transparent_sheets_and_glass() {
    let lit = render(&scene(
        r#"(name: "occ", shader: Lambert(albedo: (0, 0, 0)))"#,
        "Direct",
        false,
    ));
    let sheet = r#"(name: "occ", shader: Opacity(opacity: (0.5, 0.5, 0.5),
        input: Lambert(albedo: (0.5, 0.5, 0.5))){}, two_sided: true)"#;
    // The surface shader alone: the sheet lets 1 − opacity through.
    let own = render(&scene(&sheet.replace("{}", ""), "Direct", true));
    assert_shadow(&lit, &own, Vec3::splat(0.5), "sheet");
    let opaque = render(&scene(
        &sheet.replace("{}", ", shadow: Some(Opaque)"),
        "Direct",
        true,
    ));
    assert_shadow(
        &lit,
        &opaque,
        Vec3::ZERO,
        "sheet with an opaque shadow shader",
    );
    let glass = |shadow: &str| {
        format!(r#"(name: "occ", shader: Dielectric(ior: 1.5), shadow: Some({shadow}))"#)
    };
    let tint = Vec3::new(0.25, 0.5, 1.0);
    let tinted = render(&scene(
        &glass("Transparency(color: (0.25, 0.5, 1.0))"),
        "Direct",
        true,
    ));
    assert_shadow(&lit, &tinted, tint, "glass with a tinted shadow shader");
    let black = render(&scene(&glass("Opaque"), "Direct", true));
    assert_shadow(
        &lit,
        &black,
        Vec3::ZERO,
        "glass with an opaque shadow shader",
    );
}

#[test]
fn a_bake_under_a_grey_shadow_transparency_stores_half_the_irradiance() {
    let dir = scratch("mi6-shadow-bake");
    let bake = |shadow: &str, out: &str| {
        let occ = format!(r#"(name: "occ", shader: Lambert(albedo: (0, 0, 0)), shadow: {shadow})"#);
        let text = scene(&occ, "Direct", true)
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
        let o = run_in(&dir, &["bake", "scene.ron", "-o", out]);
        assert!(o.status.success(), "{}", stderr_of(&o));
        read_exr_texels(&dir.join(out).join("e.exr"))
    };
    for (shadow, through) in [
        ("Some(Transparency(color: (0.5, 0.5, 0.5)))", 0.5),
        ("None", 0.0),
    ] {
        let (w, e) = bake(shadow, if through > 0.0 { "half" } else { "none" });
        assert_eq!(w, 48);
        let (mut inside, mut outside) = (0, 0);
        for (k, texel) in e.iter().enumerate() {
            // Texel centres in world units (the floor's UVs span x, y ∈ [−3, 3]; the shadow
            // is symmetric, so the direction of v does not matter); texels are 0.125 wide.
            let x = ((k % w) as f64 + 0.5) / 48.0 * 6.0 - 3.0;
            let y = ((k / w) as f64 + 0.5) / 48.0 * 6.0 - 3.0;
            let d = x.abs().max(y.abs());
            if d < 0.5 - 0.125 {
                assert!(
                    (texel.x - through).abs() < 1e-6 && texel.x == texel.z,
                    "{shadow}: texel {k} under the occluder holds {texel}, expected {through}"
                );
                inside += 1;
            } else if d > 0.5 + 0.125 {
                assert!(
                    (texel.x - 1.0).abs() < 1e-6,
                    "{shadow}: lit texel {k} holds {texel}"
                );
                outside += 1;
            }
        }
        assert!(inside >= 36 && outside > 2000, "{inside} / {outside}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A `.mi` version: a camera at the origin looking down −z (160 × 120), a point light at the
/// eye, a grey floor at z = −2 and an occluder hidden from the camera at z = −1 over
/// x, y ∈ [−0.3, 0.3] in material `occ`, whose statements follow its shader.
pub(crate) fn mi_scene(shadow: &str) -> String {
    let preamble = mi_preamble(BASE, "");
    let lamp = mi_point_lamp("\"color\" 1.0 1.0 1.0, \"atten\" false, \"shadow\" on");
    format!(
        r#"{preamble}{lamp}material "grey"
opaque
"mib_illum_lambert" ("diffuse" 0.5 0.5 0.5, "lights" [ "Lamp_inst" ])
end material
material "occ"
opaque
"mib_illum_lambert" ("diffuse" 0 0 0)
{shadow}
end material
object "Floor"
group
-3 -3 -2
3 -3 -2
3 3 -2
-3 3 -2
v 0
v 1
v 2
v 3
p "grey" 0 1 2 3
end group
end object
instance "Floor_inst" "Floor"
end instance
object "Occ"
visible off
group
-0.3 -0.3 -1
0.3 -0.3 -1
0.3 0.3 -1
-0.3 0.3 -1
v 0
v 1
v 2
v 3
p "occ" 0 1 2 3
end group
end object
instance "Occ_inst" "Occ"
end instance
instgroup "rootgrp"
"Camera_inst" "Lamp_inst" "Floor_inst" "Occ_inst"
end instgroup
render "rootgrp" "Camera_inst" "opt"
"#
    )
}

#[test]
fn mib_shadow_transparency_maps_onto_the_shadow_transmittance() {
    let cases = [
        (r#""color" 1 1 1 1, "transp" 0.5 0.5 0.5"#, (0.5, 0.5, 0.5)),
        (r#""color" 1 0.5 0.25, "transp" 1"#, (1.0, 0.5, 0.25)),
        // Alpha 0.5: half passes untouched, half through colour · transp.
        (
            r#""color" 0.2 0.4 0.6 0.5, "transp" 1 1 0.5"#,
            (0.6, 0.7, 0.65),
        ),
    ];
    for (params, want) in cases {
        let text = mi_scene(&format!("shadow \"mib_shadow_transparency\" ({params})"));
        let read = read_mi(Path::new("s.mi"), text.as_bytes()).unwrap();
        assert!(read.warnings.is_empty(), "{params}: {:?}", read.warnings);
        let occ = read
            .desc
            .materials
            .iter()
            .find(|m| m.name == "occ")
            .unwrap();
        let Some(ShadowDesc::Transparency { color }) = occ.shadow.clone() else {
            panic!("{params}: {:?}", occ.shadow);
        };
        for (g, w) in [(color.0, want.0), (color.1, want.1), (color.2, want.2)] {
            assert!((g - w).abs() < 1e-12, "{params}: {color:?} vs {want:?}");
        }
    }
    let opaque = mi_scene(r#"shadow "mib_shadow_transparency" ("color" 1 1 1 1, "transp" 0)"#);
    let read = read_mi(Path::new("s.mi"), opaque.as_bytes()).unwrap();
    let occ = read
        .desc
        .materials
        .iter()
        .find(|m| m.name == "occ")
        .unwrap();
    assert_eq!(occ.shadow, Some(ShadowDesc::Opaque));
}

#[test]
fn a_mi_shadow_shader_halves_the_light_and_round_trips_through_convert() {
    let dir = scratch("mi6-shadow-mi");
    let half =
        mi_scene(r#"shadow "mib_shadow_transparency" ("color" 1 1 1 1, "transp" 0.5 0.5 0.5)"#);
    std::fs::write(dir.join("half.mi"), &half).unwrap();
    let run = |args: &[&str]| {
        let o = run_in(&dir, args);
        assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
    };
    run(&["convert", "half.mi", "-o", "half.ron"]);
    run(&["convert", "half.ron", "-o", "again.ron"]);
    let ron = std::fs::read_to_string(dir.join("half.ron")).unwrap();
    assert!(
        ron.contains("shadow: Transparency(\n                color: (0.5, 0.5, 0.5),"),
        "{ron}"
    );
    assert_eq!(ron, std::fs::read_to_string(dir.join("again.ron")).unwrap());
    run(&["render", "half.mi", "--spp", "1", "-o", "mi.exr"]);
    run(&["render", "half.ron", "--spp", "1", "-o", "ron.exr"]);
    assert_eq!(
        std::fs::read(dir.join("mi.exr")).unwrap(),
        std::fs::read(dir.join("ron.exr")).unwrap(),
        "the RON renders the same bytes"
    );
    // Pixel closed form: the floor behind the occluder gets half of the lamp's light.
    let lit = load_scene(&{
        let p = dir.join("lit.mi");
        std::fs::write(
            &p,
            mi_scene("").replace("\"Floor_inst\" \"Occ_inst\"", "\"Floor_inst\""),
        )
        .unwrap();
        p
    })
    .unwrap();
    let shadowed = load_scene(&dir.join("half.mi")).unwrap();
    let image = |mut s: stagelight::scene::LoadedScene| {
        let mut settings = s.settings.clone();
        settings.spp = 1;
        settings.adaptive = None;
        crate::common::render(&mut s.world, settings)
            .outputs
            .image
            .unwrap()
            .beauty
    };
    let (a, b) = (image(lit), image(shadowed));
    let mut inside = 0;
    for j in 0..120 {
        for i in 0..160 {
            let x = ((i as f64 + 0.5) / 160.0 * 2.0 - 1.0) * 4.0 / 3.0;
            let y = 1.0 - (j as f64 + 0.5) / 120.0 * 2.0;
            // The floor point seen at (x, y)·2 is shadowed where the light ray crosses
            // z = −1 inside the occluder: |x|, |y| < 0.3 at unit distance.
            let d = x.abs().max(y.abs());
            let (l, s) = (a[j * 160 + i], b[j * 160 + i]);
            if d < 0.28 {
                assert!(
                    (s - 0.5 * l).abs().max_element() <= 1e-6 * l.max_element(),
                    "({i}, {j}): {s} vs {l}"
                );
                inside += 1;
            } else if d > 0.32 {
                assert_eq!(s, l, "({i}, {j}) outside the shadow");
            }
        }
    }
    assert!(inside > 500, "{inside}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_shadow_shaders_give_exact_located_messages() {
    let line =
        |text: &str, needle: &str| text.lines().position(|l| l.contains(needle)).expect(needle) + 1;
    let shader = |params: &str| mi_scene(&format!("shadow \"mib_shadow_transparency\" ({params})"));
    let s = line(&shader(""), "shadow \"mib");
    let cases = [
        (
            shader(r#""color" 1 1 1 1, "transp" "x""#),
            format!("bad.mi:{s}:61: error: parameter \"transp\" of \"mib_shadow_transparency\" takes a colour (r g b or r g b a), found a string"),
        ),
        (
            shader(r#""color" 1 1, "transp" 1"#),
            format!("bad.mi:{s}:43: error: parameter \"color\" of \"mib_shadow_transparency\" takes a colour (r g b or r g b a), found 2 numbers"),
        ),
        (
            shader(r#""color" 1 1 1, "transp" 1, "mode" 4"#),
            format!("bad.mi:{s}:69: error: \"mode\" of \"mib_shadow_transparency\" must be 0, 1, 2 or 3, found 4\n  help: 0: every light, 1: the listed lights, 2: all but the listed, 3: no light list"),
        ),
        (
            shader(r#""color" 2 1 1, "transp" 1"#),
            format!("bad.mi:{s}:50: error: \"mib_shadow_transparency\" would let 2 of the light through ((1 − alpha) + alpha · color · transp must lie in [0, 1])\n  help: colour, alpha and transp are each between 0 and 1"),
        ),
        (
            shader(r#""colour" 1 1 1"#),
            format!("bad.mi:{s}:35: error: unknown parameter \"colour\" of shader \"mib_shadow_transparency\"\n  help: did you mean \"color\"?"),
        ),
    ];
    let dir = scratch("mi6-shadow-bad");
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
    for (bad, want) in cases {
        check("bad.mi", &bad, want);
    }
    // RON: a transparency above 1, and a negative one.
    let ron = |color: &str| {
        scene(
            &format!(
                r#"(name: "occ", shader: Lambert(albedo: (0, 0, 0)), shadow: Some(Transparency(color: {color})))"#
            ),
            "Direct",
            true,
        )
    };
    let at = line(&ron("(1, 1, 1)"), "Transparency");
    check(
        "bad.ron",
        &ron("(0.5, 1.5, 0.5)"),
        format!("bad.ron:{at}:98: error: shadow transparency must be at most 1, found 1.5\n  help: a shadow shader can only dim light: 0 blocks, 1 lets all through"),
    );
    check(
        "bad.ron",
        &ron("(-0.5, 0.5, 0.5)"),
        format!("bad.ron:{at}:93: error: shadow transparency must not be negative, found -0.5\n  help: shadow transparency takes 0 or more: write 0.5 if only the sign is wrong"),
    );
    // A shader that is not built in warns and keeps the surface shader's shadows.
    let native = mi_scene(r#"shadow "my_shadow" ("k" 1)"#);
    let read = read_mi(Path::new("n.mi"), native.as_bytes()).unwrap();
    let warnings: Vec<String> = read
        .warnings
        .iter()
        .map(|w| {
            format!(
                "{}:{}: {}",
                w.problem.pos.line, w.problem.pos.column, w.problem.message
            )
        })
        .collect();
    let want = vec![format!("{s}:8: shadow shader \"my_shadow\" is not mapped: shadows follow the material shader (mib_opacity lets 1 − opacity through, every other shader blocks)")];
    if warnings != want {
        failures.push(format!("got:  {warnings:?}\nwant: {want:?}"));
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

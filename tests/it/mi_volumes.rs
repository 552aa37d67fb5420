//! Issue 13: `volume "parti_volume" (…)` in `.mi` materials and cameras becomes fog (a
//! material's `interior`, the camera's `atmosphere`; `mode 1` bounds it below `height`,
//! `nonuniform` varies its density): a transparent box filled with an absorbing
//! `parti_volume` dims the floor seen through it by exactly `e^(−extinction · path)` for the
//! camera ray and again for the shadow ray. `mib_volume` on the camera becomes a `Fade`
//! atmosphere; in a material it warns. Wrong parameters are exact located errors, and
//! `convert` round-trips every mapping (the RON renders the same bytes).

use std::path::Path;

use crate::common::{mi_point_lamp, mi_preamble, BASE, PHYSICS};
use stagelight::framebuffer::FrameBuffers;
use stagelight::scene::desc::{FalloffDesc, VolumeDesc};
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene;

/// A camera at the origin looking down −z (the image plane spans ±4/3 by ±1 at distance 1,
/// 160 × 120), a point light at the eye, a grey floor at z = −2 and, when `volume` is
/// given, a transparent box (`mib_opacity` 0) over x, y ∈ [−0.3, 0.3], z ∈ [−1.2, −0.8]
/// whose material has that volume statement.
fn scene(volume: &str) -> String {
    let preamble = mi_preamble(&format!("{BASE}{PHYSICS}"), "");
    let lamp = mi_point_lamp("\"color\" 1.0 1.0 1.0, \"atten\" false, \"shadow\" on");
    format!(
        r#"{preamble}{lamp}material "grey"
opaque
"mib_illum_lambert" ("diffuse" 0.5 0.5 0.5, "lights" [ "Lamp_inst" ])
end material
material "fog"
"mib_opacity" ("opacity" 0 0 0, "input" 0 0 0)
{volume}
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
object "Box"
group
-0.3 -0.3 -0.8
0.3 -0.3 -0.8
0.3 0.3 -0.8
-0.3 0.3 -0.8
-0.3 -0.3 -1.2
0.3 -0.3 -1.2
0.3 0.3 -1.2
-0.3 0.3 -1.2
v 0
v 1
v 2
v 3
v 4
v 5
v 6
v 7
p "fog" 0 1 2 3
p "fog" 4 7 6 5
p "fog" 0 3 7 4
p "fog" 1 5 6 2
p "fog" 0 4 5 1
p "fog" 3 2 6 7
end group
end object
instance "Box_inst" "Box"
end instance
instgroup "rootgrp"
"Camera_inst" "Lamp_inst" "Floor_inst" "Box_inst"
end instgroup
render "rootgrp" "Camera_inst" "opt"
"#
    )
}

fn render(text: &str, name: &str) -> FrameBuffers {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight_mi_vol_{}_{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.mi");
    std::fs::write(&path, text).unwrap();
    let mut scene = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    let _ = std::fs::remove_dir_all(&dir);
    let mut settings = scene.settings.clone();
    settings.spp = 1;
    settings.adaptive = None;
    let frame = crate::common::render(&mut scene.world, settings);
    frame.outputs.image.expect("an image")
}

#[test]
fn an_absorbing_parti_volume_dims_what_is_seen_through_it_by_beer_lambert() {
    let k = 1.5;
    let fog = format!("volume \"parti_volume\" (\"scatter\" 0 0 0, \"extinction\" {k})");
    let clear = render(&scene(""), "clear");
    let dimmed = render(&scene(&fog), "fog");
    let mut checked = 0;
    for j in 0..120 {
        for i in 0..160 {
            let x = ((f64::from(i) + 0.5) / 160.0 * 2.0 - 1.0) * 4.0 / 3.0;
            let y = 1.0 - (f64::from(j) + 0.5) / 120.0 * 2.0;
            let k_px = (j * 160 + i) as usize;
            let (a, b) = (clear.beauty[k_px], dimmed.beauty[k_px]);
            if x.abs() < 0.2 && y.abs() < 0.2 {
                // Camera ray and shadow ray each cross 0.4 / cos θ of the medium.
                let path = 0.4 * (1.0 + x * x + y * y).sqrt();
                let want = (-2.0 * k * path).exp();
                let got = f64::from(b.x) / f64::from(a.x);
                assert!(
                    (got - want).abs() < 0.01 * want,
                    "pixel ({i}, {j}): ratio {got} vs e^(−2·k·{path:.3}) = {want}"
                );
                checked += 1;
            } else if x.abs() > 0.5 || y.abs() > 0.5 {
                assert_eq!(a, b, "pixel ({i}, {j}) away from the box is unchanged");
            }
        }
    }
    assert!(checked > 400, "{checked} pixels through the box");
}

#[test]
fn parti_volume_maps_onto_fog_in_materials_and_cameras() {
    let text = scene(
        "volume \"parti_volume\" (\"scatter\" 0.2 0.3 0.4, \"extinction\" 0.5, \"r\" 1, \"g1\" 0.3, \"min_step_len\" 0.01)",
    )
    .replace(
        "resolution 160 120\n",
        "resolution 160 120\nvolume \"parti_volume\" (\"scatter\" 0.1 0.1 0.1, \"extinction\" 0.1)\n",
    );
    let read = read_mi(Path::new("v.mi"), text.as_bytes()).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let fog = read
        .desc
        .materials
        .iter()
        .find(|m| m.name == "fog")
        .unwrap();
    let want = VolumeDesc::Fog {
        sigma_a: (0.5 - 0.2, 0.5 - 0.3, 0.5 - 0.4),
        sigma_s: (0.2, 0.3, 0.4),
        g: 0.3,
        height: None,
        nonuniform: 0.0,
        noise_scale: 1.0,
    };
    assert_eq!(format!("{:?}", fog.interior), format!("{:?}", Some(want)));
    let atmosphere = VolumeDesc::Fog {
        sigma_a: (0.0, 0.0, 0.0),
        sigma_s: (0.1, 0.1, 0.1),
        g: 0.0,
        height: None,
        nonuniform: 0.0,
        noise_scale: 1.0,
    };
    assert_eq!(
        format!("{:?}", read.desc.cameras[0].atmosphere),
        format!("{:?}", Some(atmosphere))
    );
}

#[test]
fn unmapped_volume_shaders_warn_and_bad_parameters_are_located_errors() {
    let text = scene("volume \"mib_volume\" (\"color\" 1 1 1, \"max\" 2)");
    let read = read_mi(Path::new("w.mi"), text.as_bytes()).unwrap();
    let line = text.lines().position(|l| l.contains("mib_volume")).unwrap() + 1;
    let warnings: Vec<String> = read
        .warnings
        .iter()
        .map(|w| {
            format!(
                "{}:{}: {} / {:?}",
                w.problem.pos.line, w.problem.pos.column, w.problem.message, w.problem.help
            )
        })
        .collect();
    assert_eq!(
        warnings,
        [format!("{line}:8: volume shader \"mib_volume\" in a material is not mapped (a fade is a camera atmosphere only): the material's interior stays empty / Some(\"give the camera the mib_volume, or the material a parti_volume\")")]
    );
    let bad = scene("volume \"parti_volume\" (\"extintion\" 1)");
    let err = read_mi(Path::new("bad.mi"), bad.as_bytes()).unwrap_err();
    let got: Vec<String> = err
        .iter()
        .map(|e| {
            format!(
                "{}:{}: {} / {:?}",
                e.problem.pos.line, e.problem.pos.column, e.problem.message, e.problem.help
            )
        })
        .collect();
    assert_eq!(
        got,
        [format!("{line}:24: unknown parameter \"extintion\" of shader \"parti_volume\" / Some(\"did you mean \\\"extinction\\\"?\")")]
    );
}

/// The scene with `camera` statements added to the camera block.
fn with_camera_volume(material_volume: &str, camera: &str) -> String {
    scene(material_volume).replace(
        "resolution 160 120\n",
        &format!("resolution 160 120\n{camera}\n"),
    )
}

#[test]
fn parti_volume_mode_1_and_nonuniform_map_onto_the_fog_bounds() {
    let text = with_camera_volume(
        "volume \"parti_volume\" (\"scatter\" 0.2 0.2 0.2, \"extinction\" 0.5, \"nonuniform\" 0.7, \"height\" 3)",
        "volume \"parti_volume\" (\"scatter\" 0.1 0.1 0.1, \"extinction\" 0.1, \"mode\" 1, \"height\" -0.25)",
    );
    let read = read_mi(Path::new("v.mi"), text.as_bytes()).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let fog = read
        .desc
        .materials
        .iter()
        .find(|m| m.name == "fog")
        .unwrap();
    // Mode 0: the height is read but the medium fills the whole volume.
    let want = VolumeDesc::Fog {
        sigma_a: (0.3, 0.3, 0.3),
        sigma_s: (0.2, 0.2, 0.2),
        g: 0.0,
        height: None,
        nonuniform: 0.7,
        noise_scale: 1.0,
    };
    assert_eq!(fog.interior, Some(want));
    let want = VolumeDesc::Fog {
        sigma_a: (0.0, 0.0, 0.0),
        sigma_s: (0.1, 0.1, 0.1),
        g: 0.0,
        height: Some(-0.25),
        nonuniform: 0.0,
        noise_scale: 1.0,
    };
    assert_eq!(read.desc.cameras[0].atmosphere, Some(want));
}

#[test]
fn mib_volume_on_the_camera_maps_onto_a_fade() {
    let text = with_camera_volume(
        "",
        "volume \"mib_volume\" (\"color\" 0.2 0.4 0.6 0.5, \"max\" 3.5, \"lightrays\" on)",
    );
    let read = read_mi(Path::new("f.mi"), text.as_bytes()).unwrap();
    let line = text.lines().position(|l| l.contains("mib_volume")).unwrap() + 1;
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
    assert_eq!(
        warnings,
        [format!(
            "{line}:58: mib_volume: \"lightrays\" is not mapped: light (shadow) rays are not faded"
        )]
    );
    assert_eq!(
        read.desc.cameras[0].atmosphere,
        Some(VolumeDesc::Fade {
            color: (0.2, 0.4, 0.6),
            opacity: 0.5,
            max: 3.5,
            falloff: FalloffDesc::Linear,
        })
    );
    // Without alpha the fog is fully opaque at `max`.
    let text = with_camera_volume("", "volume \"mib_volume\" (\"color\" 1 1 1, \"max\" 2)");
    let read = read_mi(Path::new("f.mi"), text.as_bytes()).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    assert_eq!(
        read.desc.cameras[0].atmosphere,
        Some(VolumeDesc::Fade {
            color: (1.0, 1.0, 1.0),
            opacity: 1.0,
            max: 2.0,
            falloff: FalloffDesc::Linear,
        })
    );
}

#[test]
fn bad_volume_parameters_give_exact_located_errors() {
    let cases = [
        (
            with_camera_volume("volume \"parti_volume\" (\"extinction\" 1, \"mode\" 2)", ""),
            "parti_volume",
            "error: parti_volume: \"mode\" must be 0 (fog everywhere) or 1 (fog below \"height\"), found 2",
            47,
        ),
        (
            with_camera_volume("volume \"parti_volume\" (\"extinction\" 1, \"nonuniform\" 1.5)", ""),
            "parti_volume",
            "error: parti_volume: \"nonuniform\" must be between 0 and 1, found 1.5",
            53,
        ),
        (
            with_camera_volume("", "volume \"mib_volume\" (\"color\" 1 1 1 2, \"max\" 1)"),
            "mib_volume",
            "error: mib_volume: the alpha of \"color\" must be between 0 and 1, found 2",
            30,
        ),
        (
            with_camera_volume("", "volume \"mib_volume\" (\"color\" 1 1 1, \"max\" -1)"),
            "mib_volume",
            "error: mib_volume: \"max\" must not be negative, found -1",
            43,
        ),
        (
            with_camera_volume("", "volume \"mib_volume\" (\"colour\" 1 1 1, \"max\" 1)"),
            "mib_volume",
            "error: unknown parameter \"colour\" of shader \"mib_volume\"\n  help: did you mean \"color\"?",
            22,
        ),
    ];
    for (text, needle, message, column) in cases {
        let line = text.lines().position(|l| l.contains(needle)).unwrap() + 1;
        let err = read_mi(Path::new("bad.mi"), text.as_bytes()).unwrap_err();
        let got: Vec<String> = err.iter().map(ToString::to_string).collect();
        assert_eq!(got, [format!("bad.mi:{line}:{column}: {message}")]);
    }
}

#[test]
fn cli_convert_round_trips_height_noise_and_fade_volumes() {
    let fog = with_camera_volume(
        "volume \"parti_volume\" (\"scatter\" 0.3 0.3 0.3, \"extinction\" 0.9, \"nonuniform\" 0.6)",
        "volume \"parti_volume\" (\"scatter\" 0.05 0.05 0.05, \"extinction\" 0.2, \"mode\" 1, \"height\" -0.2)",
    );
    let fade = with_camera_volume(
        "",
        "volume \"mib_volume\" (\"color\" 0.3 0.5 0.7 0.8, \"max\" 4)",
    );
    for (name, text, needle) in [("fog", fog, "height: -0.2,"), ("fade", fade, "Fade(")] {
        let dir = crate::common::scratch_root().join(format!(
            "stagelight_mi_vol_cli_{}_{name}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("v.mi"), &text).unwrap();
        let run = |args: &[&str]| {
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_stagelight"))
                .current_dir(&dir)
                .args(args)
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{args:?}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        };
        run(&["convert", "v.mi", "-o", "v.ron"]);
        run(&["convert", "v.ron", "-o", "again.ron"]);
        let first = std::fs::read_to_string(dir.join("v.ron")).unwrap();
        assert!(first.contains(needle), "{first}");
        assert_eq!(
            first,
            std::fs::read_to_string(dir.join("again.ron")).unwrap()
        );
        run(&["render", "v.mi", "--spp", "2"]);
        let from_mi = std::fs::read(dir.join("out.png")).unwrap();
        run(&["render", "v.ron", "--spp", "2"]);
        assert!(
            from_mi == std::fs::read(dir.join("out.png")).unwrap(),
            "{name}: the RON renders the same bytes"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}

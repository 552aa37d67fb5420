//! Issue 13: the tutorial's displacement library in `.mi` (seed 001 §4.4: `link
//! "myDisplacement.so"`, `displace "myDisplacement" ("factor" f)` = `0.01 · sin(u · f · π)`
//! along the normal) displaces the objects drawn in the material, diced as the group's
//! `approximate` says: the depth of every pixel of a displaced plane follows the closed
//! form; a wrong parameter is a located error.

use std::path::Path;

use crate::common::{mi_point_lamp, mi_preamble, BASE};
use stagelight::framebuffer::FrameBuffers;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene;

/// A plane of side 1 at z = −1 facing the camera (u = x + 0.5 from its `t` vectors), in a
/// material with `displace` (when given), seen by a camera at the origin (image plane
/// ±4/3 by ±1 at distance 1, 160 × 120).
fn scene(displace: &str) -> String {
    let preamble = mi_preamble(&format!("{BASE}link \"myDisplacement.so\"\n"), "");
    let lamp = mi_point_lamp("\"color\" 1.0 1.0 1.0, \"atten\" false");
    format!(
        r#"{preamble}{lamp}material "grey"
opaque
"mib_illum_lambert" ("diffuse" 0.5 0.5 0.5, "lights" [ "Lamp_inst" ])
{displace}
end material
object "Plane"
group
-0.5 -0.5 -1
0.5 -0.5 -1
0.5 0.5 -1
-0.5 0.5 -1
0 0 0
1 0 0
1 1 0
0 1 0
v 0 t 4
v 1 t 5
v 2 t 6
v 3 t 7
p "grey" 0 1 2 3
approximate parametric 16 16
end group
end object
instance "Plane_inst" "Plane"
end instance
instgroup "rootgrp"
"Camera_inst" "Lamp_inst" "Plane_inst"
end instgroup
render "rootgrp" "Camera_inst" "opt"
"#
    )
}

fn render(text: &str, name: &str) -> FrameBuffers {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight_mi_disp_{}_{name}", std::process::id()));
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
fn my_displacement_moves_the_plane_by_its_sine() {
    let factor = 2.0;
    let image = render(
        &scene(&format!(
            "displace \"myDisplacement\" (\"factor\" {factor})"
        )),
        "sine",
    );
    let (mut checked, mut moved) = (0, 0);
    for j in 0..120u32 {
        for i in 0..160u32 {
            let x = ((f64::from(i) + 0.5) / 160.0 * 2.0 - 1.0) * 4.0 / 3.0;
            let y = 1.0 - (f64::from(j) + 0.5) / 120.0 * 2.0;
            if x.abs() > 0.45 || y.abs() > 0.45 {
                continue;
            }
            // The hit is at t·(x, y, −1) with z = −1 + δ(u), u = x·t + 0.5, t = 1 − δ.
            let mut delta = 0.0;
            for _ in 0..50 {
                let u = x * (1.0 - delta) + 0.5;
                delta = 0.01 * (u * factor * std::f64::consts::PI).sin();
            }
            let want = (1.0 - delta) * (1.0 + x * x + y * y).sqrt();
            let got = f64::from(image.depth[(j * 160 + i) as usize]);
            assert!(
                (got - want).abs() < 0.0015,
                "pixel ({i}, {j}): depth {got} vs {want} (δ = {delta})"
            );
            let flat = (1.0 + x * x + y * y).sqrt();
            if (got - flat).abs() > 0.005 {
                moved += 1;
            }
            checked += 1;
        }
    }
    assert!(checked > 2500, "{checked}");
    assert!(
        moved > checked / 3,
        "{moved} of {checked} pixels moved by more than 0.005"
    );
}

#[test]
fn my_displacement_maps_onto_the_sine_displacement() {
    let text = scene("displace \"myDisplacement\" (\"factor\" 60)");
    let read = read_mi(Path::new("d.mi"), text.as_bytes()).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let d = read.desc.objects[0]
        .displacement
        .as_ref()
        .expect("displaced");
    assert_eq!(
        format!("{:?}", d.shader),
        "Sine { amplitude: 0.01, factor: 60.0, axis: U }"
    );
    // Without the library the shader is native code: a warning, no displacement.
    let unlinked = text.replace("link \"myDisplacement.so\"\n", "");
    let read = read_mi(Path::new("d.mi"), unlinked.as_bytes()).unwrap();
    assert!(read.desc.objects[0].displacement.is_none());
    assert_eq!(
        read.warnings[0].problem.message,
        "displace shader \"myDisplacement\" is not mapped: objects with this material render undisplaced"
    );
    let bad = text.replace("\"factor\" 60", "\"factr\" 60");
    let line = bad.lines().position(|l| l.contains("factr")).unwrap() + 1;
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
        [format!("{line}:28: unknown parameter \"factr\" of shader \"myDisplacement\" / Some(\"its one parameter is \\\"factor\\\"\")")]
    );
}

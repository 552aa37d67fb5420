//! The tutorial's native shaders (seed 001 prints their C source) are built in once their
//! library is linked: the seed's own scene text renders, every pixel checked against the
//! formula of the printed C source — `myLight` (§3.2.2, the colour everywhere),
//! `mySurface` (§3.2.2: ambient + the Phong loop over the first listed light, once per
//! entry), `myDefaultSurface` (§4.1: `Ka + Kd·|N·D|` with no lights), `myEnvironment`
//! (§4.3: its colour for rays that leave the scene). Without the `link` they stay
//! located errors that say how to link them.

use std::path::{Path, PathBuf};

use stagelight::components::{Camera, RenderCamera};
use stagelight::scene::{load_scene_str, LoadedScene};

fn seed_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/seeds/mi")
}

/// The seed's §3.2.2 test.mi (`assets/seeds/mi/plane.mi`) with the tutorial's edits: its
/// light library linked and `"myLight" ("color" 1.0 1.0 1.0)` as the lamp's shader.
fn test_mi() -> String {
    let text = std::fs::read_to_string(seed_dir().join("plane.mi")).unwrap();
    let light = text
        .find("\"mib_light_point\" (")
        .expect("the printed light shader");
    let end = light + text[light..].find(')').unwrap() + 1;
    let text = format!(
        "{}\"myLight\" (\n\"color\" 1.0 1.0 1.0\n){}",
        &text[..light],
        &text[end..]
    );
    text.replacen(
        "$include <physics.mi>\n",
        "$include <physics.mi>\nlink \"myLight.so\"\n$include <myLight.mi>\n",
        1,
    )
}

/// `text` with the material's shader call replaced by `shader` (the whole call).
fn with_material(text: &str, shader: &str) -> String {
    let at = text.find("\"mib_illum_lambert\" (").unwrap();
    let end = at + text[at..].find("\n)").unwrap() + 2;
    format!("{}{shader}{}", &text[..at], &text[end..])
}

/// Renders `text` (read as if it were `assets/seeds/mi/<name>.mi`) 128 pixels wide, one
/// sample per pixel.
fn render(text: &str, name: &str) -> (u32, u32, Vec<glam::Vec3>) {
    let mut scene: LoadedScene = load_scene_str(text, &seed_dir().join(format!("{name}.mi")))
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    let mut size = (0, 0);
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        camera.height = (camera.height * 128 / camera.width).max(1);
        camera.width = 128;
        size = (camera.width, camera.height);
    }
    let mut settings = scene.settings.clone();
    settings.spp = 1;
    settings.adaptive = None;
    let frame = crate::common::render(&mut scene.world, settings);
    (
        size.0,
        size.1,
        frame.outputs.image.expect("an image").beauty,
    )
}

/// Checks every pixel whose centre sees the plane z = −1 (|x|, |y| < 1, a pixel's margin
/// kept) against `want(x, y)` per channel, within 1 % (+ 0.002 for values near 0); the
/// others against `outside` when given; a pixel may take any value the formula takes within
/// a pixel of its centre (its sample's place in the filter footprint). The camera is the seed's: focal 12, aperture 32,
/// aspect 4/3 — the image plane spans ±4/3 by ±1 at distance 1.
fn check(
    (w, h, beauty): &(u32, u32, Vec<glam::Vec3>),
    want: impl Fn(f64, f64) -> [f64; 3],
    outside: Option<[f64; 3]>,
) {
    let (tan_x, tan_y) = (4.0 / 3.0, 1.0);
    let pixel = 2.0 * tan_x / f64::from(*w);
    let (mut on, mut off) = (0, 0);
    for j in 0..*h {
        for i in 0..*w {
            let x = ((f64::from(i) + 0.5) / f64::from(*w) * 2.0 - 1.0) * tan_x;
            let y = (1.0 - (f64::from(j) + 0.5) / f64::from(*h) * 2.0) * tan_y;
            let got = beauty[(j * w + i) as usize].to_array().map(f64::from);
            let inside = x.abs() < 1.0 - pixel && y.abs() < 1.0 - pixel;
            let expected = if inside {
                on += 1;
                want(x, y)
            } else if x.abs() > 1.0 + pixel || y.abs() > 1.0 + pixel {
                match outside {
                    Some(c) => {
                        off += 1;
                        c
                    }
                    None => continue,
                }
            } else {
                continue;
            };
            // The pixel's sample may lie anywhere in its filter footprint: the value must
            // lie within the formula's range over ±1 pixel (steep highlights), ±1 %.
            let (mut lo, mut hi) = (expected, expected);
            if inside {
                for a in -4..=4 {
                    for b in -4..=4 {
                        let v = want(
                            x + f64::from(a) * pixel / 4.0,
                            y + f64::from(b) * pixel / 4.0,
                        );
                        for k in 0..3 {
                            lo[k] = lo[k].min(v[k]);
                            hi[k] = hi[k].max(v[k]);
                        }
                    }
                }
            }
            for k in 0..3 {
                assert!(
                    got[k] >= lo[k] - 0.01 * lo[k].abs() - 0.002
                        && got[k] <= hi[k] + 0.01 * hi[k].abs() + 0.002,
                    "pixel ({i}, {j}) channel {k}: {} vs the C source's {} ({} … {})",
                    got[k],
                    expected[k],
                    lo[k],
                    hi[k]
                );
            }
        }
    }
    assert!(on > (w * h / 3) as usize, "{on}");
    assert!(outside.is_none() || off > 0);
}

/// `1/d`: `N·L` (= `|N·D|`) at the plane point `(x, y, −1)` seen and lit from the origin.
fn cos_at(x: f64, y: f64) -> f64 {
    1.0 / (x * x + y * y + 1.0).sqrt()
}

#[test]
fn my_light_in_the_seeds_test_mi_is_its_colour_at_every_distance() {
    // mib_illum_lambert (diffuse 0.8) under myLight: 0.8 · Cl · N·L, Cl = colour.
    let image = render(&test_mi(), "my_light");
    check(&image, |x, y| [0.8 * cos_at(x, y); 3], None);
    // A coloured myLight scales each channel.
    let text = test_mi().replace("\"color\" 1.0 1.0 1.0\n)", "\"color\" 0.5 0.25 1.0\n)");
    let image = render(&text, "my_light_colour");
    check(
        &image,
        |x, y| {
            let c = 0.8 * cos_at(x, y);
            [0.5 * c, 0.25 * c, c]
        },
        None,
    );
}

/// The tutorial's mySurface call (§3.2.2) with `lights`.
fn my_surface(lights: &str) -> String {
    format!(
        "\"mySurface\" (\n\"ambient\" 1.0 0.0 0.0,\n\"diffuse\" 0.0 1.0 0.0,\n\
         \"specular\" 0.0 0.0 1.0,\n\"spec_exp\" 40,\n\"mode\" 1,\n\"lights\" [{lights}]\n)"
    )
}

fn my_surface_scene(lights: &str, second_light: &str) -> String {
    let text = with_material(&test_mi(), &my_surface(lights)).replacen(
        "$include <myLight.mi>\n",
        "$include <myLight.mi>\nlink \"mySurface.so\"\n$include <mySurface.mi>\n",
        1,
    );
    text.replace(
        "instgroup \"rootgrp\"",
        &format!("{second_light}instgroup \"rootgrp\""),
    )
}

#[test]
fn my_surface_is_ambient_plus_phong_of_the_first_listed_light_once_per_entry() {
    // ambient + Cl·(diffuse·N·L + specular·max(0, R·L)^40): light and eye at the origin,
    // so R·L = 2(N·L)² − 1.
    let want = |n: f64| {
        move |x: f64, y: f64| {
            let c = cos_at(x, y);
            let phong = (2.0 * c * c - 1.0).max(0.0).powi(40);
            [1.0, n * c, n * phong]
        }
    };
    let image = render(&my_surface_scene("\"Lamp_inst\"", ""), "my_surface");
    check(&image, want(1.0), None);
    // The printed loop never advances its light pointer: a second entry samples the first
    // light again (a red light B elsewhere adds nothing).
    let b = "light \"B\" \"myLight\" (\"color\" 1 0 0) origin 0.5 0.5 0 end light\n\
             instance \"B_inst\" \"B\" end instance\n";
    let text = my_surface_scene("\"Lamp_inst\", \"B_inst\"", b)
        .replace("\"Plane_inst\"\n", "\"Plane_inst\"\n\"B_inst\"\n");
    let image = render(&text, "my_surface_two");
    check(&image, want(2.0), None);
}

#[test]
fn my_default_surface_is_ka_plus_kd_abs_cos_with_no_lights() {
    // §4.1: no lights, "myDefaultSurface" ("Ka" 0.2, "Kd" 0.8) = Ka + Kd·|N·D| per channel.
    let text = with_material(
        &test_mi(),
        "\"myDefaultSurface\" (\n\"Ka\" 0.2,\n\"Kd\" 0.8\n)",
    )
    .replacen(
        "$include <myLight.mi>\n",
        "link \"myDefaultSurface.so\"\n$include <myDefaultSurface.mi>\n",
        1,
    )
    .replace("\"Lamp_inst\"\n\"Plane_inst\"", "\"Plane_inst\"");
    let image = render(&text, "my_default_surface");
    check(&image, |x, y| [0.2 + 0.8 * cos_at(x, y); 3], Some([0.0; 3]));
    // Parameters left out are the C struct's zero: black.
    let text = text.replace("\"Ka\" 0.2,\n\"Kd\" 0.8", "\"Kd\" 0.8");
    check(
        &render(&text, "my_default_surface_kd"),
        |x, y| [0.8 * cos_at(x, y); 3],
        None,
    );
}

#[test]
fn my_environment_is_its_colour_for_rays_that_leave_the_scene() {
    // §4.3: environment "myEnvironment" ("color" 9.0 9.0 10.0) on the camera; camera rays
    // that miss the plane see it, the plane keeps its lambert shading.
    let text = test_mi()
        .replacen(
            "$include <myLight.mi>\n",
            "$include <myLight.mi>\nlink \"myEnvironment.so\"\n$include <myEnvironment.mi>\n",
            1,
        )
        .replace(
            "resolution 508 380\n",
            "resolution 508 380\nenvironment \"myEnvironment\" (\"color\" 9.0 9.0 10.0)\n",
        );
    let image = render(&text, "my_environment");
    check(
        &image,
        |x, y| [0.8 * cos_at(x, y); 3],
        Some([9.0, 9.0, 10.0]),
    );
}

fn error_of(text: &str) -> String {
    match load_scene_str(text, Path::new("test.mi")) {
        Ok(_) => panic!("loads:\n{text}"),
        // The errors alone (the file's warnings come with them: `e.1`).
        Err(e) => {
            e.0.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("\n")
        }
    }
}

#[test]
fn tutorial_shaders_without_their_link_are_located_errors_that_say_so() {
    let text = test_mi().replace("link \"myLight.so\"\n$include <myLight.mi>\n", "");
    let err = error_of(&text);
    let line = 1 + text[..text.find("\"myLight\" (").unwrap()]
        .matches('\n')
        .count();
    assert_eq!(
        err,
        format!(
            "test.mi:{line}:1: error: unknown light shader \"myLight\"\n  help: the tutorial's \
             \"myLight\" is built in once its library is linked: link \"myLight.so\""
        )
    );
    let text = test_mi().replace("\"color\" 1.0 1.0 1.0\n)", "\"colour\" 1.0 1.0 1.0\n)");
    let err = error_of(&text);
    let line = 1 + text[..text.find("\"colour\"").unwrap()]
        .matches('\n')
        .count();
    assert_eq!(
        err,
        format!(
            "test.mi:{line}:1: error: unknown parameter \"colour\" of shader \"myLight\"\n  \
             help: did you mean \"color\"?"
        )
    );
}

/// A misspelt `link` of a tutorial library names the one meant and lists what is built in.
#[test]
fn a_misspelt_tutorial_library_link_suggests_the_library() {
    let text = "link \"myLigth.so\"\n";
    let read = stagelight::scene::import::mi::read_mi(Path::new("l.mi"), text.as_bytes());
    let warnings = match read {
        Ok(r) => r.warnings,
        Err(problems) => problems,
    };
    let w = warnings
        .iter()
        .find(|w| w.problem.message.contains("cannot be linked"))
        .expect("a link warning");
    assert_eq!(
        w.problem.help.as_deref(),
        Some(
            "did you mean \"myLight.so\"? built in: the base, physics and contour libraries and \
             the tutorial's myLight.so, mySurface.so, myDefaultSurface.so, myEnvironment.so, \
             myDisplacement.so"
        )
    );
}

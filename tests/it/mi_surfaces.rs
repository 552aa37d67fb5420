//! Issue 13: free-form `surface` objects in `.mi` (`basis` declarations, `surface`
//! statements, `approximate surface`) become NURBS surfaces: a bilinear Bézier square
//! renders the pixels of the same square written as a polygon, a flat bicubic Bézier patch
//! with bulging sides covers its closed-form area, a rational quadratic B-spline quarter
//! disc covers πr²/4 with its rim on the circle (the weights matter: without them it covers
//! 6 % more), several surfaces of one object become a group placed by the object's
//! instance, `convert` round-trips, and malformed surfaces give exact located messages.

use std::f64::consts::PI;
use std::path::Path;

use crate::common::{mi_point_lamp, mi_preamble, BASE};
use stagelight::components::{Camera, RenderCamera};
use stagelight::framebuffer::FrameBuffers;
use stagelight::scene::desc::{ApproximationDesc, MeshDesc, SpaceDesc};
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::{load_scene, LoadedScene};

/// Options, a camera at the origin looking down −z (focal 12, aperture 32, aspect 4/3,
/// 160 × 120: the image plane spans ±4/3 by ±1 at distance 1), a point light at the eye and
/// a grey `mib_illum_lambert`.
fn header() -> String {
    let preamble = mi_preamble(BASE, "");
    let lamp = mi_point_lamp("\"color\" 1.0 1.0 1.0, \"atten\" false");
    format!(
        r#"{preamble}{lamp}material "grey"
opaque
"mib_illum_lambert" ("diffuse" 0.5 0.5 0.5, "lights" [ "Lamp_inst" ])
end material
"#
    )
}

/// Places `object` at z = −1 and renders from the camera.
fn scene(object: &str) -> String {
    let header = header();
    format!(
        r#"{header}{object}
instance "Thing_inst" "Thing"
transform
1.0 0.0 0.0 0.0
0.0 1.0 0.0 0.0
0.0 0.0 1.0 0.0
0.0 0.0 1.0 1.0
end instance
instgroup "rootgrp"
"Camera_inst" "Lamp_inst" "Thing_inst"
end instgroup
render "rootgrp" "Camera_inst" "opt"
"#
    )
}

/// A square of side 2·`h` at the origin of its object, as one polygon.
fn polygon_square(h: f64) -> String {
    format!(
        "object \"Thing\"\ngroup\n{h} {h} 0\n{h} -{h} 0\n-{h} -{h} 0\n-{h} {h} 0\nv 0\nv 1\nv 2\nv 3\np \"grey\" 2 1 0 3\nend group\nend object\n"
    )
}

/// The same square as a degree-1 Bézier surface (u along x, v along y).
fn surface_square(h: f64) -> String {
    format!(
        "object \"Thing\"\nbasis \"bez1\" bezier 1\ngroup\n-{h} -{h} 0\n{h} -{h} 0\n-{h} {h} 0\n{h} {h} 0\nv 0\nv 1\nv 2\nv 3\nsurface \"square\" \"grey\"\n\"bez1\" 0.0 1.0 0.0 1.0\n\"bez1\" 0.0 1.0 0.0 1.0\n0 1 2 3\nend group\nend object\n"
    )
}

/// A flat bicubic Bézier patch over [−1, 1]² whose four sides bulge outwards by `b` at
/// their middles (the middle control points of each side pushed out by `4b/3`).
fn bulging_patch(b: f64) -> String {
    let e = 4.0 * b / 3.0;
    let t = 1.0 / 3.0;
    let mut vectors = String::new();
    for j in 0..4 {
        for i in 0..4 {
            let (s, r) = (-1.0 + 2.0 * t * f64::from(i), -1.0 + 2.0 * t * f64::from(j));
            let (mut x, mut y) = (s, r);
            let middle = |k: i32| k == 1 || k == 2;
            if j == 0 && middle(i) {
                y -= e;
            }
            if j == 3 && middle(i) {
                y += e;
            }
            if i == 0 && middle(j) {
                x -= e;
            }
            if i == 3 && middle(j) {
                x += e;
            }
            vectors.push_str(&format!("{x} {y} 0\n"));
        }
    }
    let vertices: String = (0..16).map(|k| format!("v {k}\n")).collect();
    let refs: Vec<String> = (0..16).map(|k| k.to_string()).collect();
    format!(
        "object \"Thing\"\nbasis \"bez3\" bezier 3\ngroup\n{vectors}{vertices}surface \"patch\" \"grey\"\n\"bez3\" 0.0 1.0 0.0 1.0\n\"bez3\" 0.0 1.0 0.0 1.0\n{}\napproximate surface regular parametric 24 24 \"patch\"\nend group\nend object\n",
        refs.join(" ")
    )
}

/// A quarter disc of radius `r` (x, y ≥ 0): rational quadratic B-spline along the rim
/// (weights 1, √2/2, 1, unless `weights` is false), linear to the centre (a collapsed
/// row).
fn quarter_disc(r: f64, weights: bool) -> String {
    let w = if weights {
        format!(" w {}", 0.5f64.sqrt())
    } else {
        String::new()
    };
    let rational = if weights { "rational " } else { "" };
    format!(
        "object \"Thing\"\nbasis \"arc\" {rational}bspline 2\nbasis \"lin\" {rational}bspline 1\ngroup\n{r} 0 0\n{r} {r} 0\n0 {r} 0\n0 0 0\nv 0\nv 1\nv 2\nv 3\nsurface \"disc\" \"grey\"\n\"arc\" 0.0 1.0 0.0 0.0 0.0 1.0 1.0 1.0\n\"lin\" 0.0 1.0 0.0 0.0 1.0 1.0\n0 1{w} 2 3 3 3\napproximate surface regular parametric 64 1 \"disc\"\nend group\nend object\n"
    )
}

fn load(text: &str, name: &str) -> LoadedScene {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight_mi_surf_{}_{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.mi");
    std::fs::write(&path, text).unwrap();
    let scene = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    let _ = std::fs::remove_dir_all(&dir);
    scene
}

/// Renders at 1 sample per pixel (no output files).
fn render(mut scene: LoadedScene) -> FrameBuffers {
    assert!(scene
        .world
        .query_mut::<(&Camera, &RenderCamera)>()
        .into_iter()
        .next()
        .is_some());
    let mut settings = scene.settings.clone();
    settings.spp = 1;
    settings.adaptive = None;
    let frame = crate::common::render(&mut scene.world, settings);
    frame.outputs.image.expect("an image")
}

/// Width of a pixel on the plane z = −1.
const PIXEL: f64 = 2.0 * 4.0 / 3.0 / 160.0;

/// The point of the plane z = −1 seen through the centre of pixel `k`.
fn plane_point(k: usize) -> (f64, f64) {
    let (i, j) = ((k % 160) as f64, (k / 160) as f64);
    ((i + 0.5) * PIXEL - 4.0 / 3.0, 1.0 - (j + 0.5) * PIXEL)
}

/// Area covered on the plane z = −1 (pixels hit × pixel area).
fn covered_area(image: &FrameBuffers) -> f64 {
    image.object_id.iter().filter(|&&id| id != 0).count() as f64 * PIXEL * PIXEL
}

#[test]
fn a_bilinear_bezier_square_renders_the_pixels_of_the_polygon_square() {
    let poly = render(load(&scene(&polygon_square(0.6)), "poly"));
    let surf = render(load(&scene(&surface_square(0.6)), "surf"));
    let covered = poly.object_id.iter().filter(|&&id| id != 0).count();
    assert!(covered > 4000, "the square is in view: {covered} pixels");
    let mut differ = 0;
    for k in 0..poly.beauty.len() {
        assert_eq!(
            poly.object_id[k] != 0,
            surf.object_id[k] != 0,
            "coverage at pixel {k}"
        );
        let d = (poly.beauty[k] - surf.beauty[k]).abs().max_element();
        if d > 1e-4 {
            differ += 1;
        }
    }
    assert_eq!(differ, 0, "pixels whose colour differs by more than 1e-4");
}

#[test]
fn a_bicubic_bezier_patch_covers_its_closed_form_area() {
    let b = 0.25;
    let image = render(load(&scene(&bulging_patch(b)), "bicubic"));
    // Each side bulges by a cubic of height `b` over the side of length 2: area
    // ∫ 3e·t(1−t)·2 dt = e = 4b/3. The patch reaches y = ±(1 + b), past the view's ±1, so
    // only the left and right bulges are in view.
    let visible = 4.0 + 2.0 * (4.0 * b / 3.0);
    let area = covered_area(&image);
    assert!(
        (area - visible).abs() < 0.01 * visible,
        "covered {area:.4} vs {visible:.4}"
    );
    // The middle row reaches the middle of the side bulges, x = ±(1 + b).
    let row = 60;
    let hit: Vec<f64> = (0..160)
        .filter(|i| image.object_id[row * 160 + i] != 0)
        .map(|i| plane_point(row * 160 + i).0)
        .collect();
    let (lo, hi) = (hit[0], hit[hit.len() - 1]);
    assert!(
        (hi - (1.0 + b)).abs() < 1.5 * PIXEL && (lo + 1.0 + b).abs() < 1.5 * PIXEL,
        "middle row spans [{lo}, {hi}], want ±{}",
        1.0 + b
    );
}

#[test]
fn a_rational_bspline_quarter_disc_covers_a_quarter_circle() {
    let r = 0.9;
    let image = render(load(&scene(&quarter_disc(r, true)), "disc"));
    let area = covered_area(&image);
    let want = PI * r * r / 4.0;
    assert!(
        (area - want).abs() < 0.01 * want,
        "covered {area:.4} vs πr²/4 = {want:.4}"
    );
    // The rim is the circle: every pixel centre more than 1.5 px inside is covered, every
    // one more than 1.5 px outside is not.
    for k in 0..image.object_id.len() {
        let (x, y) = plane_point(k);
        if x < 1.5 * PIXEL || y < 1.5 * PIXEL {
            continue;
        }
        let d = (x * x + y * y).sqrt();
        if d < r - 1.5 * PIXEL {
            assert_ne!(image.object_id[k], 0, "inside the disc at ({x:.3}, {y:.3})");
        } else if d > r + 1.5 * PIXEL {
            assert_eq!(
                image.object_id[k], 0,
                "outside the disc at ({x:.3}, {y:.3})"
            );
        }
    }
    // Without the weights the rim is a parabola: 5r²/6 instead of πr²/4.
    let parabola = covered_area(&render(load(&scene(&quarter_disc(r, false)), "parabola")));
    let want = 5.0 * r * r / 6.0;
    assert!(
        (parabola - want).abs() < 0.01 * want,
        "non-rational: {parabola:.4} vs 5r²/6 = {want:.4}"
    );
}

#[test]
fn surfaces_map_onto_nurbs_with_their_approximations() {
    let text = scene(&bulging_patch(0.25));
    let read = read_mi(Path::new("patch.mi"), text.as_bytes()).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let obj = &read.desc.objects[0];
    assert_eq!(obj.name, "Thing");
    assert_eq!(obj.material.as_deref(), Some("grey"));
    let MeshDesc::Nurbs {
        degree_u,
        count_u,
        knots_u,
        points,
        ..
    } = &obj.mesh
    else {
        panic!("a NURBS surface: {:?}", obj.mesh);
    };
    assert_eq!((*degree_u, *count_u), (3, 4));
    assert_eq!(knots_u, &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
    assert_eq!(points.len(), 16);
    assert!(matches!(
        obj.approximation,
        Some(ApproximationDesc::Regular { u: 24, v: 24 })
    ));
    // `parametric` multiplies by the degree; `view length` is in pixels.
    for (technique, want) in [
        (
            "parametric 2 1",
            ApproximationDesc::Parametric { u: 6, v: 3 },
        ),
        (
            "view length 2 1 5",
            ApproximationDesc::Spatial {
                edge: 2.0,
                space: SpaceDesc::Raster,
                min_subdiv: 1,
                max_subdiv: 5,
            },
        ),
        (
            "distance 0.1 angle 5",
            ApproximationDesc::Curvature {
                distance: 0.1,
                angle: 5.0,
                min_subdiv: 0,
                max_subdiv: 7,
            },
        ),
    ] {
        let t = text.replace("regular parametric 24 24", technique);
        let read = read_mi(Path::new("patch.mi"), t.as_bytes()).unwrap();
        assert_eq!(
            format!("{:?}", read.desc.objects[0].approximation),
            format!("{:?}", Some(want)),
            "{technique}"
        );
    }
}

#[test]
fn several_surfaces_of_one_object_become_a_group_its_instance_places() {
    // Two half squares (left and right) as two surfaces of one object.
    let object = "object \"Thing\"\nbasis \"bez1\" bezier 1\ngroup\n-0.6 -0.6 0\n0 -0.6 0\n0.6 -0.6 0\n-0.6 0.6 0\n0 0.6 0\n0.6 0.6 0\nv 0\nv 1\nv 2\nv 3\nv 4\nv 5\nsurface \"left\" \"grey\"\n\"bez1\" 0.0 1.0 0.0 1.0\n\"bez1\" 0.0 1.0 0.0 1.0\n0 1 3 4\nsurface \"right\" \"grey\"\n\"bez1\" 0.0 1.0 0.0 1.0\n\"bez1\" 0.0 1.0 0.0 1.0\n1 2 4 5\nend group\nend object\n";
    let text = scene(object);
    let read = read_mi(Path::new("two.mi"), text.as_bytes()).unwrap();
    let names: Vec<&str> = read.desc.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["Thing.left", "Thing.right"]);
    let group = read
        .desc
        .groups
        .iter()
        .find(|g| g.name == "Thing")
        .expect("a group");
    assert_eq!(group.members, ["Thing.left", "Thing.right"]);
    let two = render(load(&text, "two"));
    let one = render(load(&scene(&surface_square(0.6)), "one"));
    let mismatched = (0..one.object_id.len())
        .filter(|&k| (one.object_id[k] != 0) != (two.object_id[k] != 0))
        .count();
    assert_eq!(mismatched, 0, "the halves cover the square");
}

#[test]
fn cli_convert_round_trips_a_surface_scene() {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight_mi_surf_cli_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("disc.mi"), scene(&quarter_disc(0.9, true))).unwrap();
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
    run(&["convert", "disc.mi", "-o", "disc.ron"]);
    run(&["convert", "disc.ron", "-o", "again.ron"]);
    let first = std::fs::read_to_string(dir.join("disc.ron")).unwrap();
    assert!(first.contains("Nurbs("), "{first}");
    assert_eq!(
        first,
        std::fs::read_to_string(dir.join("again.ron")).unwrap()
    );
    run(&["render", "disc.mi", "--spp", "1"]);
    let from_mi = std::fs::read(dir.join("out.png")).unwrap();
    run(&["render", "disc.ron", "--spp", "1"]);
    assert!(
        from_mi == std::fs::read(dir.join("out.png")).unwrap(),
        "the RON renders the same bytes"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn malformed_surfaces_give_exact_located_messages() {
    let good = scene(&bulging_patch(0.25));
    let disc = scene(&quarter_disc(0.9, true));
    let line =
        |text: &str, needle: &str| text.lines().position(|l| l.contains(needle)).expect(needle) + 1;
    let surf = line(&good, "surface \"patch\"");
    let cases = [
        (
            good.replace("basis \"bez3\" bezier 3", "basis \"bez3\" bezeir 3"),
            format!("bad.mi:{}:14: error: unknown basis type \"bezeir\"\n  help: did you mean \"bezier\"?", line(&good, "basis \"bez3\"")),
        ),
        (
            good.replace("basis \"bez3\" bezier 3", "basis \"bez3\" taylor 3"),
            format!("bad.mi:{}:1: error: basis \"bez3\" is a taylor basis, which is not supported\n  help: write the surface with a bezier or bspline basis", surf + 1),
        ),
        (
            good.replace("basis \"bez3\" bezier 3", "basis \"bez3\" bezier 9"),
            format!("bad.mi:{}:1: error: basis \"bez3\" has degree 9; surfaces up to degree 7 are supported\n  help: raise the surface to degree 7 or less in the modeller, or write polygons", surf + 1),
        ),
        (
            good.replacen("\"bez3\" 0.0 1.0 0.0 1.0", "\"bez4\" 0.0 1.0 0.0 1.0", 1),
            format!("bad.mi:{}:1: error: unknown basis \"bez4\"\n  help: did you mean \"bez3\"?", surf + 1),
        ),
        (
            good.replacen("\"bez3\" 0.0 1.0 0.0 1.0", "\"bez3\" 0.0 0.5 0.0 1.0", 1),
            format!("bad.mi:{}:8: error: surface \"patch\": the u range [0, 0.5] is not the whole surface [0, 1]; parts of surfaces are not supported\n  help: write the range as 0 1", surf + 1),
        ),
        (
            good.replace("\"bez3\" 0.0 1.0 0.0 1.0\n0 1 2", "\"bez3\" 0.0 1.0 0.0 1.0 2.0\n0 1 2"),
            format!("bad.mi:{}:1: error: surface \"patch\": the 19 values after the v range are not v parameters followed by control points\n  help: k v parameters of basis \"bez3\" take 4 × ((k − 1)·3 + 1) control points (4 along u from the u parameters)", surf + 2),
        ),
        (
            good.replace(" 15\napproximate", " 16\napproximate"),
            format!("bad.mi:{}:36: error: vertex index 16 is out of range (the group has 16 vertices so far)", surf + 3),
        ),
        (
            good.replace(" 15\napproximate", " 15 w 0.5\napproximate"),
            format!("bad.mi:{}:39: error: surface \"patch\": a weight on a control point of a non-rational surface\n  help: declare basis \"bez3\" rational", surf + 3),
        ),
        (
            disc.replace("0 1 w 0.7071067811865476", "0 1 w -1"),
            format!("bad.mi:{}:5: error: surface \"disc\": a control point weight must be > 0, found -1", line(&disc, "0 1 w")),
        ),
        (
            disc.replace("\"arc\" 0.0 1.0 0.0 0.0 0.0 1.0 1.0 1.0", "\"arc\" 0.0 1.0 0.0 0.0 1.0 0.5 1.0 1.0"),
            format!("bad.mi:{}:27: error: surface \"disc\": the u parameters must not decrease: 0.5 follows 1", line(&disc, "\"arc\" 0.0")),
        ),
        (
            good.replace("approximate surface regular parametric 24 24 \"patch\"", "approximate surface regular parametric 24 24 \"ptach\""),
            format!("bad.mi:{}:46: error: unknown surface \"ptach\"\n  help: did you mean \"patch\"?", line(&good, "approximate")),
        ),
        (
            good.replace("approximate surface regular parametric", "approximate surface reguler parametric"),
            format!("bad.mi:{}:21: error: unknown approximation technique \"reguler\"\n  help: did you mean \"regular\"?", line(&good, "approximate")),
        ),
        (
            good.replace("approximate surface", "trim \"curve1\" 0.0 1.0\napproximate surface"),
            format!("bad.mi:{}:1: error: \"trim\" curves on surfaces are not supported\n  help: only whole, untrimmed surfaces are read: remove the trimming curves", line(&good, "approximate")),
        ),
        (
            good.replace("group\n-1", "surface \"x\"\ngroup\n-1"),
            format!("bad.mi:{}:1: error: \"surface\" belongs in a group\n  help: write it between group and end group, after the vertices", line(&good, "basis \"bez3\"") + 1),
        ),
    ];
    let dir = crate::common::scratch_root()
        .join(format!("stagelight_mi_surf_bad_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut failures = Vec::new();
    for (bad, want) in cases {
        let path = dir.join("bad.mi");
        std::fs::write(&path, &bad).unwrap();
        let got = match load_scene(&path) {
            Ok(_) => "ok".to_string(),
            Err(e) => e.to_string(),
        };
        let prefix = format!("{}/", dir.display());
        let got = got.replace(&prefix, "").trim_end().to_string();
        if got != want {
            failures.push(format!("got:  {got}\nwant: {want}"));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

//! Issue 13: the grid and photon diagnostics (`options.diagnostic: Grid(…)` / `Photon(…)`,
//! mental ray `diagnostic grid …` / `diagnostic photon …`, CLI `--diagnostic`). Grid lines
//! fall exactly between the pixel centres that the projected planes `x = k·size` separate;
//! the photon view is black where no photon lands and brightest in a glass ball's caustic.

use std::path::Path;

use glam::Vec3;
use stagelight::diagnostic_view::{GRID_COLOURS, GRID_SURFACE};
use stagelight::scene::desc::{DiagnosticDesc, GridSpaceDesc, PhotonQuantityDesc};
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene_str;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// Pixels per side, field of view and camera height of the grid scene.
const SIDE: usize = 60;
const FOV_DEG: f64 = 60.0;
const HEIGHT: f64 = 5.0;

/// A 10 × 10 plane at z = 0 (its instance moved `shift` along x) seen straight down from
/// height 5; `diagnostic` is the options' diagnostic.
fn plane(diagnostic: &str, shift: f64) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, diagnostic: {diagnostic}),
    cameras: [(name: "cam", fov_y: {FOV_DEG}, resolution: ({SIDE}, {SIDE}),
        placement: LookAt(eye: (0, 0, {HEIGHT}), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "grid.png")])],
    lights: [(name: "sun", kind: Directional(direction: (0, 0, -1)), intensity: 1)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "plane", mesh: Grid(size_x: 10, size_y: 10), material: "grey")],
    instances: [(name: "plane_1", of: "plane", transform: [Translate(({shift}, 0, 0))])],
    groups: [(name: "world", members: ["plane_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

fn beauty(text: &str) -> Vec<Vec3> {
    let mut scene = load_scene_str(text, Path::new("view.ron")).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    frame.outputs.image.expect("an image").beauty
}

/// Columns of row `y` drawn with the x-line colour.
fn x_line_columns(image: &[Vec3], y: usize) -> Vec<usize> {
    (0..SIDE)
        .filter(|&x| image[y * SIDE + x] == GRID_COLOURS[0])
        .collect()
}

/// The columns left of each projected line `x = k·size + offset` (`u = SIDE/2 + x·scale`
/// pixels; the pixel whose centre is the last one before the line).
fn expected_columns(size: f64, offset: f64) -> Vec<usize> {
    let scale = (SIDE as f64 / 2.0) / (HEIGHT * (FOV_DEG.to_radians() / 2.0).tan());
    let mut columns: Vec<usize> = (-20..=20)
        .map(|k| SIDE as f64 / 2.0 + (k as f64 * size + offset) * scale)
        .filter(|u| *u > 0.5 && *u < SIDE as f64 - 0.5)
        .map(|u| (u - 0.5).floor() as usize)
        .collect();
    columns.sort_unstable();
    columns
}

#[test]
fn grid_lines_fall_between_the_pixels_the_projected_planes_separate() {
    let world = beauty(&plane("Grid(space: World, size: 0.5)", 0.0));
    // Row 31: no y = const line passes between it and row 32.
    let got = x_line_columns(&world, 31);
    println!(
        "x lines at columns {got:?} (spacing {:.3} px)",
        0.5 * 10.392
    );
    assert_eq!(got, expected_columns(0.5, 0.0));
    assert!(got.len() >= 10);
    // Everything else on that row is plain surface.
    let surface = (0..SIDE)
        .filter(|x| world[31 * SIDE + x] == GRID_SURFACE)
        .count();
    assert_eq!(surface + got.len(), SIDE);
    // Object space follows the instance: moved by 0.2, its lines move by 0.2 · scale px;
    // world lines stay.
    let object = beauty(&plane("Grid(space: Object, size: 0.5)", 0.2));
    assert_eq!(x_line_columns(&object, 31), expected_columns(0.5, 0.2));
    let moved_world = beauty(&plane("Grid(space: World, size: 0.5)", 0.2));
    assert_eq!(x_line_columns(&moved_world, 31), expected_columns(0.5, 0.0));
}

/// A glass ball (centre (1, 0, 0.9), radius 0.6) over a floor under a point light at
/// (−2, 0, 4), caustics only, seen from straight above x = 2.5 (image x = world x).
fn ball(diagnostic: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, caustics: (photons: 4000, gather: 20), diagnostic: {diagnostic}),
    cameras: [(name: "cam", fov_y: 50, resolution: (40, 40),
        placement: LookAt(eye: (2.5, 0, 6), target: (2.5, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "ball.png")])],
    lights: [(name: "lamp", kind: Point(position: (-2, 0, 4)), intensity: 40)],
    materials: [
        (name: "floor", shader: Lambert(albedo: (0.7, 0.7, 0.7))),
        (name: "glass", shader: Dielectric(ior: 1.5)),
    ],
    objects: [
        (name: "floor", mesh: Grid(size_x: 10, size_y: 10), material: "floor"),
        (name: "ball", mesh: Sphere(radius: 0.6), material: "glass",
         approximation: Parametric(u: 16, v: 8)),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "ball_1", of: "ball", transform: [Translate((1, 0, 0.9))]),
    ],
    groups: [(name: "world", members: ["floor_1", "ball_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

#[test]
fn the_photon_view_is_black_without_photons_and_brightest_in_the_caustic() {
    // The red channel is value / max (clamped): a large max keeps it linear.
    let view = beauty(&ball("Photon(quantity: Density, max: 1e9)"));
    let (hot, peak) =
        view.iter().enumerate().fold(
            (0, 0.0f32),
            |(i, m), (j, v)| if v.x > m { (j, v.x) } else { (i, m) },
        );
    let (x, y) = (hot % 40, hot / 40);
    let black = view.iter().filter(|v| **v == Vec3::ZERO).count();
    println!("densest pixel ({x}, {y}): {peak:e} of max; {black} of 1600 pixels black");
    // The caustic focuses beyond the ball along the light's direction through its centre,
    // near (1.87, 0, 0): pixel (20 + (1.87 − 2.5) · 20 / (6 tan 25°), 20) ≈ (15.5, 20).
    assert!(peak > 0.0);
    assert!(
        (x as f32 - 15.5).abs() < 4.0 && (y as f32 - 20.0).abs() < 4.0,
        "({x}, {y})"
    );
    // Where no caustic photon lands the view is black exactly (no photon within reach):
    // a third of the image here (519 of 1600 pixels when written).
    assert!(black > 400, "{black}");
    // Irradiance on a scale whose max the caustic exceeds: its pixel clips to red.
    let red = beauty(&ball("Photon(quantity: Irradiance, max: 0.001)"));
    assert_eq!(red[hot], Vec3::X);
}

#[test]
fn mi_diagnostic_grid_and_photon_map_onto_the_options() {
    let seed =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_controls/caustic_filter.mi");
    let text = std::fs::read_to_string(seed).unwrap();
    for (statement, want) in [
        (
            "diagnostic grid camera 0.25\n",
            Some(DiagnosticDesc::Grid {
                space: GridSpaceDesc::Camera,
                size: 0.25,
            }),
        ),
        (
            "diagnostic photon irradiance 20\n",
            Some(DiagnosticDesc::Photon {
                quantity: PhotonQuantityDesc::Irradiance,
                max: 20.0,
            }),
        ),
        ("diagnostic photon density 5\ndiagnostic photon off\n", None),
    ] {
        let mi = text.replace("caustic on\ncaustic filter tent\n", statement);
        let read = read_mi(Path::new("d.mi"), mi.as_bytes()).unwrap();
        assert!(read.warnings.is_empty(), "{:?}", read.warnings);
        assert_eq!(read.desc.options.unwrap().diagnostic, want, "{statement}");
    }
    let mi = text.replace(
        "caustic on\ncaustic filter tent\n",
        "diagnostic grid world 0\n",
    );
    let errors = read_mi(Path::new("d.mi"), mi.as_bytes()).unwrap_err();
    assert_eq!(
        errors[0].to_string(),
        "d.mi:3:23: error: diagnostic grid size must be > 0, found 0"
    );
}

#[test]
fn the_cli_draws_the_grid_view() {
    let dir = scratch_dir("diagnostic-grid");
    std::fs::write(dir.join("scene.ron"), plane("None", 0.0)).unwrap();
    let o = run_in(
        &dir,
        &["render", "scene.ron", "--diagnostic", "grid:world:0.5"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert!(dir.join("grid.png").is_file());
    let o = run_in(
        &dir,
        &["render", "scene.ron", "--diagnostic", "grid:world:-1"],
    );
    assert!(!o.status.success());
    assert!(
        stderr_of(&o).contains("the grid size must be a number > 0, found \"-1\""),
        "{}",
        stderr_of(&o)
    );
}

/// The photon view without photon maps to show — none in the scene, or the path integrator,
/// which builds none — is refused before anything runs (it rendered a black image, exit 0).
#[test]
fn the_cli_refuses_a_photon_view_without_photon_maps() {
    let dir = scratch_dir("diagnostic-photon-refused");
    std::fs::write(dir.join("plain.ron"), plane("None", 0.0)).unwrap();
    std::fs::write(dir.join("ball.ron"), ball("None")).unwrap();
    let refused = |args: &[&str], expected: &str| {
        let o = run_in(&dir, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr_of(&o));
        let e = stderr_of(&o);
        assert!(e.starts_with(expected), "{args:?}: {e}");
        assert!(e.contains("\n  help: "), "{args:?}: {e}");
    };
    let photon = ["--diagnostic", "photon:density:1000"];
    refused(
        &[&["render", "plain.ron"][..], &photon].concat(),
        "error: the photon diagnostic shows the photon maps, but this scene builds none",
    );
    refused(
        &[&["render", "ball.ron", "--integrator", "path"][..], &photon].concat(),
        "error: the photon diagnostic shows the photon maps, but the path integrator",
    );
    assert!(!dir.join("grid.png").exists() && !dir.join("ball.png").exists());
}

/// A diagnostic view cannot be divided into farm parts (the merge writes the shaded sums'
/// beauty): `--part` with `--diagnostic` or the scene's `diagnostic` option is refused up
/// front, with nothing written.
#[test]
fn the_cli_refuses_a_diagnostic_view_in_farm_parts() {
    let dir = scratch_dir("diagnostic-part-refused");
    std::fs::write(dir.join("scene.ron"), plane("None", 0.0)).unwrap();
    std::fs::write(dir.join("samples.ron"), plane("Samples", 0.0)).unwrap();
    let refused = |args: &[&str], source: &str| {
        let o = run_in(&dir, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr_of(&o));
        assert_eq!(
            stderr_of(&o),
            format!("error: --part 1/2 cannot render a diagnostic view ({source})\n  help: parts carry the shaded sums, which the merge turns into the beauty image, not the view; render the diagnostic view without --part\n"),
            "{args:?}"
        );
        assert!(!dir.join("p.exr").exists(), "{args:?}");
    };
    let part = ["--part", "1/2", "-o", "p.exr"];
    refused(
        &[
            &["render", "scene.ron", "--diagnostic", "samples"][..],
            &part,
        ]
        .concat(),
        "--diagnostic samples",
    );
    refused(
        &[&["render", "samples.ron"][..], &part].concat(),
        "the scene's `options: (diagnostic: …)` (samples)",
    );
}

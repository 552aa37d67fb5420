//! PNG outputs with an alpha channel: PNG's alpha is straight (unassociated), so partly
//! covered pixels carry the surface's own colour, not the frame buffer's premultiplied one;
//! an output listing `Alpha` alone is a grey image of the coverage. In front of an
//! environment the straight colour leaves out what the missed samples saw, with every pixel
//! filter and adaptive sampling, at any thread count and through farm parts.

use crate::common::png;

/// A sphere of constant emitted radiance 0.5 (black albedo, no lights) on nothing.
const SCENE: &str = r#"Scene(
    options: (samples: 16),
    cameras: [(name: "cam", fov_y: 40, resolution: (24, 24), placement: LookAt(eye: (0, 0, 4), target: (0, 0, 0)),
               outputs: [(file: "rgba.png", passes: [Beauty, Alpha]), (file: "alpha.png", passes: [Alpha]), (file: "rgba.exr", passes: [Beauty, Alpha])])],
    materials: [(name: "glow", shader: Lambert(albedo: (0, 0, 0)), emission: (0.5, 0.5, 0.5))],
    objects: [(name: "ball", mesh: Sphere(radius: 1), material: "glow")],
    instances: [(name: "ball_1", of: "ball")],
    groups: [(name: "world", members: ["ball_1"])],
    render: (root: "world", camera: "cam"),
)"#;

#[test]
fn partly_covered_pixels_keep_the_surface_colour_and_alpha_alone_is_grey() {
    let dir = crate::common::scratch_dir("png-alpha");
    std::fs::write(dir.join("s.ron"), SCENE).unwrap();
    let o = crate::common::run_in(&dir, &["render", "s.ron"]);
    assert!(o.status.success(), "{}", crate::common::stderr_of(&o));
    let rgba = png::read(&dir.join("rgba.png"));
    let alpha = png::read(&dir.join("alpha.png"));
    assert_eq!((rgba.channels, alpha.channels), (4, 1));
    // sRGB of linear 0.5.
    let surface = 188u8;
    let mut edges = 0;
    for p in 0..rgba.pixels() {
        let [r, g, b, a] = rgba.rgba(p).map(|v| (v * 255.0).round() as u8);
        assert_eq!(
            alpha.rgba(p)[0],
            rgba.rgba(p)[3],
            "pixel {p}: the two alphas"
        );
        if a == 0 {
            assert_eq!([r, g, b], [0, 0, 0], "pixel {p}");
        } else if a < 255 {
            edges += 1;
            // Straight colour: the surface's own, up to the 8-bit rounding of a small alpha.
            let tolerance = if a >= 64 { 2 } else { 8 };
            for c in [r, g, b] {
                assert!(
                    c.abs_diff(surface) <= tolerance,
                    "pixel {p}: {c} at alpha {a}"
                );
            }
        } else {
            assert_eq!([r, g, b], [surface; 3], "pixel {p}");
        }
    }
    assert!(edges >= 20, "{edges} partly covered pixels");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A sphere of emitted radiance 0.2 (black albedo: the environment lights nothing) in front
/// of a constant white environment, with `options` (samples, filter); outputs an RGBA PNG and
/// a premultiplied EXR.
fn sphere_before_white_environment(options: &str) -> String {
    format!(
        r#"Scene(
    options: ({options}),
    environment: (shader: Constant(color: (1, 1, 1))),
    cameras: [(name: "cam", fov_y: 40, resolution: (24, 20), placement: LookAt(eye: (0, 0, 4), target: (0, 0, 0)),
               outputs: [(file: "rgba.png", passes: [Beauty, Alpha]), (file: "rgba.exr", passes: [Beauty, Alpha])])],
    materials: [(name: "glow", shader: Lambert(albedo: (0, 0, 0)), emission: (0.2, 0.2, 0.2))],
    objects: [(name: "ball", mesh: Sphere(radius: 1), material: "glow")],
    instances: [(name: "ball_1", of: "ball")],
    groups: [(name: "world", members: ["ball_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// The pixel filters and sample counts the environment-share tests run with.
const OPTIONS: [&str; 3] = [
    "samples: 16",
    "samples: 16, filter: Gaussian(sigma: 0.5, radius: 1.5)",
    "samples: (min: 4, max: 32, contrast: (0.02, 0.02, 0.02))",
];

/// Renders `scene` in a fresh directory named `name` with `args` after `render s.ron`;
/// the directory.
fn render(name: &str, scene: &str, args: &[&str]) -> std::path::PathBuf {
    let dir = crate::common::scratch_dir(name);
    std::fs::write(dir.join("s.ron"), scene).unwrap();
    let mut all = vec!["render", "s.ron"];
    all.extend_from_slice(args);
    let o = crate::common::run_in(&dir, &all);
    assert!(o.status.success(), "{}", crate::common::stderr_of(&o));
    dir
}

/// Checks that the RGBA PNG at `path` of [`sphere_before_white_environment`] shows the
/// environment's white where nothing is covered and the sphere's own colour (sRGB 124, of
/// linear 0.2) in every covered pixel, partly covered ones included. Before the environment
/// share was kept, an edge pixel of alpha a was written as (0.2·a + (1 − a)) / a: white up
/// to a ≈ 0.56, and still 164 at a = 0.9.
fn assert_surface_colour_at_edges(path: &std::path::Path, options: &str) {
    let surface = 124u8;
    let rgba = png::read(path);
    let mut edges = 0;
    for p in 0..rgba.pixels() {
        let [r, g, b, a] = rgba.rgba(p).map(|v| (v * 255.0).round() as u8);
        if a == 0 {
            assert_eq!(
                [r, g, b],
                [255; 3],
                "{options}: pixel {p} sees the environment"
            );
        } else if a < 255 {
            edges += 1;
            for c in [r, g, b] {
                assert!(
                    c.abs_diff(surface) <= 1,
                    "{options}: pixel {p}: {c} at alpha {a}, not the surface's {surface}"
                );
            }
        } else {
            assert_eq!([r, g, b], [surface; 3], "{options}: pixel {p}");
        }
    }
    assert!(edges >= 20, "{options}: {edges} partly covered pixels");
}

#[test]
fn edges_before_an_environment_carry_the_surface_colour_not_the_environment() {
    for (k, options) in OPTIONS.iter().enumerate() {
        let dir = render(
            &format!("png-alpha-env-{k}"),
            &sphere_before_white_environment(options),
            &["--threads", "1"],
        );
        assert_surface_colour_at_edges(&dir.join("rgba.png"), options);
        // The EXR keeps premultiplied colour with the environment in it: c = 0.2·a + (1 − a).
        let exr = exr::prelude::read_first_rgba_layer_from_file(
            dir.join("rgba.exr"),
            |size, _| vec![[0f32; 4]; size.area()],
            |px: &mut Vec<[f32; 4]>, pos, (r, g, b, a): (f32, f32, f32, f32)| {
                px[pos.y() * 24 + pos.x()] = [r, g, b, a]
            },
        )
        .unwrap();
        let mut partial = 0;
        for [r, g, b, a] in exr.layer_data.channel_data.pixels {
            let expected = 0.2 * a + (1.0 - a);
            for c in [r, g, b] {
                assert!(
                    (c - expected).abs() < 1e-5,
                    "{options}: EXR {c} at alpha {a}"
                );
            }
            partial += usize::from(a > 0.0 && a < 1.0);
        }
        assert!(
            partial >= 20,
            "{options}: {partial} partly covered EXR pixels"
        );
        // The same bytes at two threads.
        let two = render(
            &format!("png-alpha-env-{k}-t2"),
            &sphere_before_white_environment(options),
            &["--threads", "2"],
        );
        for file in ["rgba.png", "rgba.exr"] {
            assert!(
                std::fs::read(dir.join(file)).unwrap() == std::fs::read(two.join(file)).unwrap(),
                "{options}: {file} differs between --threads 1 and 2"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
        let _ = std::fs::remove_dir_all(&two);
    }
}

#[test]
fn merged_farm_parts_write_the_local_rgba_png_before_an_environment() {
    for (k, options) in OPTIONS.iter().enumerate() {
        let scene = sphere_before_white_environment(options);
        let dir = render(&format!("png-alpha-farm-{k}"), &scene, &[]);
        let local = std::fs::read(dir.join("rgba.png")).unwrap();
        // Adaptive sampling cannot be split by samples.
        let splits: &[&str] = if options.contains("min") {
            &["tiles"]
        } else {
            &["tiles", "samples"]
        };
        for split in splits {
            let mut parts = Vec::new();
            for part in ["1/3", "2/3", "3/3"] {
                let file = format!("{split}_{}.exr", &part[..1]);
                let o = crate::common::run_in(
                    &dir,
                    &[
                        "render", "s.ron", "--part", part, "--split", split, "-o", &file,
                    ],
                );
                assert!(o.status.success(), "{}", crate::common::stderr_of(&o));
                parts.push(file);
            }
            let merged = format!("merged_{split}.png");
            let mut args = vec!["merge"];
            args.extend(parts.iter().map(String::as_str));
            args.extend(["-o", merged.as_str()]);
            let o = crate::common::run_in(&dir, &args);
            assert!(o.status.success(), "{}", crate::common::stderr_of(&o));
            assert!(
                std::fs::read(dir.join(&merged)).unwrap() == local,
                "{options}: the merged {split} parts differ from the local render"
            );
            assert_surface_colour_at_edges(&dir.join(&merged), options);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

//! Issue 13 (mental ray's `parti_volume` `mode 1` and `nonuniform`, and `mib_volume`) in the
//! engine: fog bounded below a world height dims every pixel by `e^(−σ·length below)` (camera
//! atmosphere and material interior, camera ray and shadow ray); fog with a noise-varied
//! density is deterministic at any thread count and `nonuniform: 0` is the homogeneous image
//! bit for bit; the camera's `Fade` blends every pixel toward its colour by the closed form.

use glam::Vec3;
use stagelight::framebuffer::FrameBuffers;
use stagelight::settings::PixelFilter;

use crate::common::render_text;

const W: u32 = 160;
const H: u32 = 120;

/// A camera at the origin looking down −z (image plane ±4/3 by ±1 at distance 1), a point
/// lamp at the eye, a grey wall at z = −2 of half-size `wall`, and — when `interior` is given
/// — a see-through box over x, y ∈ [−0.5, 0.5], z ∈ [−1.6, −0.6] filled with that fog.
fn scene(atmosphere: &str, interior: Option<&str>, wall: f64) -> String {
    let atmosphere = if atmosphere.is_empty() {
        String::new()
    } else {
        format!("atmosphere: {atmosphere},")
    };
    let (box_material, box_object, box_instance) = match interior {
        Some(fog) => (
            format!(
                r#"(name: "shell", shader: Opacity(opacity: (0, 0, 0), input: Lambert(albedo: (0, 0, 0))), interior: {fog}),"#
            ),
            r#"(name: "box", mesh: Inline(
                vertices: [(-0.5, -0.5, -1.6), (0.5, -0.5, -1.6), (0.5, 0.5, -1.6), (-0.5, 0.5, -1.6),
                           (-0.5, -0.5, -0.6), (0.5, -0.5, -0.6), (0.5, 0.5, -0.6), (-0.5, 0.5, -0.6)],
                polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 4, 7, 3], [1, 2, 6, 5], [3, 7, 6, 2], [0, 1, 5, 4]]),
                material: "shell"),"#
                .to_string(),
            r#"(name: "box_1", of: "box"),"#.to_string(),
        ),
        None => (String::new(), String::new(), String::new()),
    };
    let members = if interior.is_some() {
        r#"["wall_1", "box_1"]"#
    } else {
        r#"["wall_1"]"#
    };
    format!(
        r#"Scene(
    options: (samples: 1, max_depth: 4, refraction_depth: 4),
    cameras: [(name: "cam", fov_y: 90, resolution: ({W}, {H}),
        placement: LookAt(eye: (0, 0, 0), target: (0, 0, -1)), {atmosphere}
        outputs: [(file: "out.png")])],
    lights: [(name: "lamp", kind: Point(position: (0, 0, 0)), intensity: 4)],
    materials: [
        (name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5))),
        {box_material}
    ],
    objects: [
        (name: "wall", mesh: Inline(vertices: [(-{wall}, -{wall}, -2), ({wall}, -{wall}, -2), ({wall}, {wall}, -2), (-{wall}, {wall}, -2)], polygons: [[0, 1, 2, 3]]), material: "grey"),
        {box_object}
    ],
    instances: [(name: "wall_1", of: "wall"), {box_instance}],
    groups: [(name: "world", members: {members})],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// One sample per pixel, within 0.001 px of the pixel centre (a pinpoint filter), no
/// adaptivity.
fn render(text: &str) -> FrameBuffers {
    render_text(text, |s| {
        s.spp = 1;
        s.adaptive = None;
        s.filter = PixelFilter::Gaussian {
            sigma: 1e-3,
            radius: 1e-3,
        };
    })
    .0
}

/// Every pixel's image-plane point `(x, y)` at distance 1, with its index.
fn pixels() -> impl Iterator<Item = (usize, f64, f64)> {
    (0..H).flat_map(|j| {
        (0..W).map(move |i| {
            let x = ((f64::from(i) + 0.5) / f64::from(W) * 2.0 - 1.0) * f64::from(W) / f64::from(H);
            let y = 1.0 - (f64::from(j) + 0.5) / f64::from(H) * 2.0;
            ((j * W + i) as usize, x, y)
        })
    })
}

/// Length of the ray through `(x, y)` (at distance 1) between depths `s0` and `s1`
/// (z = −s) where its y = y·s is below `h`.
fn length_below(x: f64, y: f64, h: f64, s0: f64, s1: f64) -> f64 {
    let (a, b) = if y > 0.0 {
        (s0, s1.min(h / y))
    } else if y < 0.0 {
        (s0.max(h / y), s1)
    } else if h > 0.0 {
        (s0, s1)
    } else {
        (0.0, 0.0)
    };
    (b - a).max(0.0) * (1.0 + x * x + y * y).sqrt()
}

/// Checks every pixel's ratio to the clear image against `e^(−2·k·below)` within 1 %, and
/// returns how many pixels have the fog top crossing their ray (0 < below < the whole).
fn check_height_fog(
    clear: &FrameBuffers,
    fogged: &FrameBuffers,
    k: f64,
    below: impl Fn(f64, f64) -> (f64, f64),
) -> usize {
    let mut crossing = 0;
    for (p, x, y) in pixels() {
        let (l, whole) = below(x, y);
        let want = (-2.0 * k * l).exp();
        let (a, b) = (clear.beauty[p], fogged.beauty[p]);
        assert!(a.x > 0.01, "pixel ({x:.3}, {y:.3}) lit");
        let got = f64::from(b.x) / f64::from(a.x);
        assert!(
            (got - want).abs() < 0.01 * want,
            "pixel ({x:.3}, {y:.3}): ratio {got} vs e^(−2·{k}·{l:.4}) = {want}"
        );
        if l > 1e-3 && l < whole - 1e-3 {
            crossing += 1;
        }
    }
    crossing
}

#[test]
fn height_bounded_atmosphere_dims_by_the_length_below_the_fog_top() {
    // Fog only below y = −0.3: rays toward the lower part of the wall cross its top at
    // s = −0.3 / y and run through it to the wall (camera ray, and the shadow ray back).
    let (k, h) = (0.6, -0.3);
    let clear = render(&scene("", None, 4.0));
    let fog = format!("Fog(sigma_a: ({k}, {k}, {k}), height: {h})");
    let fogged = render(&scene(&fog, None, 4.0));
    let crossing = check_height_fog(&clear, &fogged, k, |x, y| {
        (
            length_below(x, y, h, 0.0, 2.0),
            2.0 * (1.0 + x * x + y * y).sqrt(),
        )
    });
    assert!(crossing > 3000, "{crossing} pixels see the fog top");
}

#[test]
fn height_bounded_interior_dims_by_the_length_below_the_fog_top() {
    // Fog inside the box only below y = 0.1: rays through the box with 0.0625 < y < 0.167
    // leave the fog inside the box.
    let (k, h) = (1.5, 0.1);
    let shell = "Fog(sigma_a: (0, 0, 0))";
    let clear = render(&scene("", Some(shell), 4.0));
    let fog = format!("Fog(sigma_a: ({k}, {k}, {k}), height: {h})");
    let fogged = render(&scene("", Some(&fog), 4.0));
    let mut crossing = 0;
    for (p, x, y) in pixels() {
        if x.abs() > 0.3 || y.abs() > 0.3 {
            // Outside the box (or through its sides): unchanged.
            if x.abs() > 0.9 || y.abs() > 0.9 {
                assert_eq!(clear.beauty[p], fogged.beauty[p], "pixel ({x:.3}, {y:.3})");
            }
            continue;
        }
        let l = length_below(x, y, h, 0.6, 1.6);
        let want = (-2.0 * k * l).exp();
        let got = f64::from(fogged.beauty[p].x) / f64::from(clear.beauty[p].x);
        assert!(
            (got - want).abs() < 0.01 * want,
            "pixel ({x:.3}, {y:.3}): ratio {got} vs e^(−2·{k}·{l:.4}) = {want}"
        );
        let whole = 1.0 * (1.0 + x * x + y * y).sqrt();
        if l > 1e-3 && l < whole - 1e-3 {
            crossing += 1;
        }
    }
    assert!(
        crossing > 150,
        "{crossing} pixels see the fog top inside the box"
    );
}

/// Noisy fog in the atmosphere and in the box, scattering the lamp.
fn noisy(amount: f64) -> String {
    scene(
        &format!("Fog(sigma_a: (0.05, 0.05, 0.05), sigma_s: (0.2, 0.25, 0.3), g: 0.2, nonuniform: {amount}, noise_scale: 0.25)"),
        Some(&format!("Fog(sigma_a: (0.4, 0.3, 0.2), sigma_s: (0.5, 0.6, 0.8), nonuniform: {amount}, noise_scale: 0.1)")),
        4.0,
    )
}

fn bits(fb: &FrameBuffers) -> Vec<u32> {
    fb.beauty
        .iter()
        .flat_map(|c| c.to_array().map(f32::to_bits))
        .chain(fb.alpha.iter().map(|a| a.to_bits()))
        .collect()
}

#[test]
fn nonuniform_zero_is_the_homogeneous_image_bit_for_bit() {
    let homogeneous = scene(
        "Fog(sigma_a: (0.05, 0.05, 0.05), sigma_s: (0.2, 0.25, 0.3), g: 0.2)",
        Some("Fog(sigma_a: (0.4, 0.3, 0.2), sigma_s: (0.5, 0.6, 0.8))"),
        4.0,
    );
    let settings = |s: &mut stagelight::settings::RenderSettings| s.spp = 4;
    let a = render_text(&homogeneous, settings).0;
    let b = render_text(&noisy(0.0), settings).0;
    assert_eq!(bits(&a), bits(&b));
    // And the noise changes the image when it is on.
    let c = render_text(&noisy(0.9), settings).0;
    assert_ne!(bits(&a), bits(&c));
}

#[test]
fn noisy_fog_renders_the_same_bits_at_any_thread_count() {
    let text = noisy(0.9);
    let render = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render_text(&text, |s| s.spp = 2).0)
    };
    let (one, three) = (render(1), render(3));
    assert_eq!(bits(&one), bits(&three));
    assert!(one.beauty.iter().all(|c| c.is_finite()));
}

#[test]
fn a_fade_atmosphere_blends_each_pixel_toward_its_colour_by_distance() {
    // The wall (half-size 1.5 at z = −2) covers the pixels with |x|, |y| < 0.75; a
    // segment of length d = 2·√(1 + x² + y²) blends by f = opacity·min(d / max, 1).
    let colour = Vec3::new(0.2, 0.4, 0.9);
    let clear = render(&scene("", None, 1.5));
    for (opacity, max) in [(1.0f64, 5.0f64), (0.5, 2.5)] {
        let fade = format!("Fade(color: (0.2, 0.4, 0.9), opacity: {opacity}, max: {max})");
        let faded = render(&scene(&fade, None, 1.5));
        let mut on_wall = 0;
        for (p, x, y) in pixels() {
            let (a, b) = (clear.beauty[p], faded.beauty[p]);
            if x.abs() < 0.74 && y.abs() < 0.74 {
                let d = 2.0 * (1.0 + x * x + y * y).sqrt();
                let f = (opacity * (d / max).min(1.0)) as f32;
                let want = a * (1.0 - f) + colour * f;
                assert!(
                    (b - want).abs().max_element() < 1e-4,
                    "pixel ({x:.3}, {y:.3}): {b} vs {want}"
                );
                on_wall += 1;
            } else if x.abs() > 0.76 || y.abs() > 0.76 {
                // Rays leaving the scene cross no medium (as for fog).
                assert_eq!(a, b, "pixel ({x:.3}, {y:.3}) off the wall");
            }
        }
        assert!(on_wall > 4000, "{on_wall}");
    }
}

/// The full report of a bad fixture, one string per diagnostic.
fn report(name: &str) -> Vec<String> {
    let path = format!("tests/fixtures/scenes/bad/{name}");
    match stagelight::scene::load_scene(std::path::Path::new(&path)) {
        Ok(_) => panic!("{name} loaded without errors"),
        Err(e) => e.0.iter().map(ToString::to_string).collect(),
    }
}

#[test]
fn bad_fog_bounds_and_fades_are_located_errors() {
    let f = "tests/fixtures/scenes/bad/fog_bounds.ron";
    assert_eq!(
        report("fog_bounds.ron"),
        [
            format!("{f}:4:59: error: height 1e39 is beyond the f32 range"),
            format!("{f}:4:77: error: nonuniform must be between 0 and 1, found 1.5"),
            format!("{f}:4:95: error: noise_scale must be positive, found 0"),
            format!("{f}:6:77: error: Fade is a camera atmosphere only: a material's interior must be a Fog"),
            format!("{f}:7:92: error: nonuniform must be between 0 and 1, found -0.5"),
        ]
    );
    let f = "tests/fixtures/scenes/bad/fade.ron";
    assert_eq!(
        report("fade.ron"),
        [
            format!("{f}:4:37: error: color must not be negative, found -1\n  help: color takes 0 or more: write 1 if only the sign is wrong"),
            format!("{f}:4:54: error: opacity must be between 0 and 1, found 1.5"),
            format!("{f}:4:64: error: max must not be negative, found -2\n  help: max takes 0 or more: write 2 if only the sign is wrong"),
        ]
    );
}

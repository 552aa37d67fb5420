//! PNG outputs with an alpha channel: PNG's alpha is straight (unassociated), so partly
//! covered pixels carry the surface's own colour, not the frame buffer's premultiplied one;
//! an output listing `Alpha` alone is a grey image of the coverage.

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

//! Lens shaders end to end: thin-lens depth of field blurs an edge by the circle of
//! confusion of the thin-lens formula and keeps the focus plane sharp; the fisheye and
//! spherical projections put known directions at the predicted pixels.

use crate::common;

use common::{all_finite, facing_quad, render_text};
use glam::Vec3;

/// A white `Constant` half-plane `x ≥ 0` at depth `d` (facing the camera at the origin, which
/// looks down −Z), seen through `lens` at `fov_y` degrees and `w × h` pixels.
fn edge_scene(d: f64, lens: &str, fov_y: f64, w: u32, h: u32, samples: u32) -> String {
    format!(
        r#"Scene(
    options: (samples: {samples}),
    cameras: [(name: "cam", fov_y: {fov_y}, resolution: ({w}, {h}),
        placement: LookAt(eye: (0, 0, 0), target: (0, 0, -1)), lens: [{lens}])],
    materials: [(name: "white", shader: Constant(color: (1, 1, 1)))],
    objects: [(name: "half", mesh: Inline(
        vertices: [(0, -100, -{d}), (100, -100, -{d}), (100, 100, -{d}), (0, 100, -{d})],
        polygons: [[0, 1, 2, 3]]), material: "white")],
    instances: [(name: "half_1", of: "half")],
    groups: [(name: "world", members: ["half_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// The row-averaged horizontal profile of the beauty (red channel).
pub(crate) fn profile(fb: &stagelight::framebuffer::FrameBuffers) -> Vec<f64> {
    let (w, h) = (fb.width as usize, fb.height as usize);
    (0..w)
        .map(|x| {
            (0..h)
                .map(|y| f64::from(fb.beauty[y * w + x].x))
                .sum::<f64>()
                / h as f64
        })
        .collect()
}

/// Width of the blur of an edge, pixels: the line-spread function (differences of adjacent
/// pixels) of a uniform disk of radius r has variance r²/4, plus 1/6 px² from pixel
/// integration and the discrete sampling; the diameter is 4·sqrt(σ² − 1/6).
pub(crate) fn blur_diameter(p: &[f64]) -> f64 {
    let q: Vec<f64> = p.windows(2).map(|w| w[1] - w[0]).collect();
    let total: f64 = q.iter().sum();
    let mean: f64 = q.iter().enumerate().map(|(i, v)| i as f64 * v).sum::<f64>() / total;
    let var: f64 = q
        .iter()
        .enumerate()
        .map(|(i, v)| (i as f64 - mean).powi(2) * v)
        .sum::<f64>()
        / total;
    4.0 * (var - 1.0 / 6.0).max(0.0).sqrt()
}

/// Circle of confusion (diameter, pixels) of a thin lens of aperture radius `a` focused at
/// `f`, for a point at depth `d`: the aperture disk maps through the focus point to a disk of
/// radius a·|d − f|/(f·d) in units of tan(angle) on the image plane, which spans
/// 2·tan(fov_y/2) over the image height.
pub(crate) fn circle_of_confusion(a: f64, f: f64, d: f64, fov_y_deg: f64, height: u32) -> f64 {
    let pixels_per_tan = f64::from(height) / (2.0 * (fov_y_deg.to_radians() / 2.0).tan());
    2.0 * a * (d - f).abs() / (f * d) * pixels_per_tan
}

#[test]
fn thin_lens_blur_matches_the_circle_of_confusion() {
    let (a, f, fov, w, h) = (0.25, 2.0, 20.0, 128, 16);
    for d in [4.0, 1.5, 3.0] {
        let lens = format!("ThinLens(radius: {a}, focus_distance: {f})");
        let (fb, _) = render_text(&edge_scene(d, &lens, fov, w, h, 256), |_| {});
        assert!(all_finite(&fb));
        let measured = blur_diameter(&profile(&fb));
        let expected = circle_of_confusion(a, f, d, fov, h);
        eprintln!("d = {d}: blur {measured:.3} px, formula {expected:.3} px");
        assert!(
            (measured - expected).abs() < 1.0,
            "d = {d}: blur {measured:.2} px, thin-lens formula {expected:.2} px"
        );
    }
}

#[test]
fn the_focus_plane_stays_sharp() {
    let lens = "ThinLens(radius: 0.25, focus_distance: 3.0)";
    let (fb, _) = render_text(&edge_scene(3.0, lens, 20.0, 64, 8, 64), |_| {});
    let p = profile(&fb);
    // The edge lies on a pixel boundary: every pixel is black or white, to sampling noise of
    // rays landing exactly on the focus plane (none: the blur is zero).
    let grey = p.iter().filter(|&&v| v > 1e-3 && v < 1.0 - 1e-3).count();
    assert!(grey <= 1, "{grey} grey pixels in focus: {p:?}");
    assert!(blur_diameter(&p) < 1.0);
}

#[test]
fn fstop_sets_the_aperture_from_the_focal_length() {
    // f/2 with fov_y 20°: focal length 12 mm / tan 10° = 68.06 mm, radius 17.01 mm.
    let fov: f64 = 20.0;
    let radius = 0.012 / (fov.to_radians() / 2.0).tan() / 4.0;
    let by_radius = format!("ThinLens(radius: {radius}, focus_distance: 1.0)");
    let by_fstop = "ThinLens(fstop: 2.0, focus_distance: 1.0)";
    let (a, _) = render_text(&edge_scene(1.2, &by_radius, fov, 64, 8, 16), |_| {});
    let (b, _) = render_text(&edge_scene(1.2, by_fstop, fov, 64, 8, 16), |_| {});
    let max_diff = a
        .beauty
        .iter()
        .zip(&b.beauty)
        .map(|(x, y)| (*x - *y).abs().max_element())
        .fold(0.0f32, f32::max);
    assert!(max_diff < 1e-5, "{max_diff}");
}

/// Scene with small white markers at the given camera-space directions.
fn marker_scene(lens: &str, w: u32, h: u32, dirs: &[Vec3]) -> String {
    let objects: Vec<String> = dirs
        .iter()
        .enumerate()
        .map(|(i, d)| facing_quad(&format!("m{i}"), "white", d.normalize() * 10.0, 0.12))
        .collect();
    let names: Vec<String> = (0..dirs.len()).map(|i| format!("\"m{i}_1\"")).collect();
    let instances: Vec<String> = (0..dirs.len())
        .map(|i| format!("(name: \"m{i}_1\", of: \"m{i}\"),"))
        .collect();
    format!(
        r#"Scene(
    options: (samples: 16),
    cameras: [(name: "cam", fov_y: 60, resolution: ({w}, {h}),
        placement: LookAt(eye: (0, 0, 0), target: (0, 0, -1)), lens: [{lens}])],
    materials: [(name: "white", shader: Constant(color: (1, 1, 1)), two_sided: true)],
    objects: [{}],
    instances: [{}],
    groups: [(name: "world", members: [{}])],
    render: (root: "world", camera: "cam"),
)"#,
        objects.join("\n"),
        instances.join("\n"),
        names.join(", ")
    )
}

/// Centroid (x, y in pixels, continuous) of the image inside a window around `near`.
fn centroid(
    fb: &stagelight::framebuffer::FrameBuffers,
    near: (f64, f64),
    radius: f64,
) -> (f64, f64) {
    let w = fb.width as usize;
    let (mut sx, mut sy, mut s) = (0.0, 0.0, 0.0);
    for (i, c) in fb.beauty.iter().enumerate() {
        let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
        let dx = (x - near.0).abs().min(fb.width as f64 - (x - near.0).abs());
        if dx > radius || (y - near.1).abs() > radius {
            continue;
        }
        let v = f64::from(c.x);
        sx += v * x;
        sy += v * y;
        s += v;
    }
    assert!(s > 0.0, "no marker near {near:?}");
    (sx / s, sy / s)
}

fn direction(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), -t.cos())
}

#[test]
fn fisheye_maps_a_direction_to_the_predicted_pixel() {
    // Equidistant, 180° across the 64-pixel height: θ maps to r = θ / 90° half-heights.
    let (w, h) = (64u32, 64u32);
    let cases = [(50.0f32, 30.0f32), (80.0, -120.0), (20.0, 200.0)];
    let dirs: Vec<Vec3> = cases.iter().map(|&(t, p)| direction(t, p)).collect();
    let (fb, _) = render_text(&marker_scene("Fisheye(fov: 180)", w, h, &dirs), |_| {});
    assert!(all_finite(&fb));
    for &(theta, phi) in &cases {
        let r = f64::from(theta) / 90.0;
        let (u, v) = (
            r * f64::from(phi).to_radians().cos(),
            r * f64::from(phi).to_radians().sin(),
        );
        let predicted = ((u + 1.0) * 32.0, (1.0 - v) * 32.0);
        let got = centroid(&fb, predicted, 4.0);
        let err = ((got.0 - predicted.0).powi(2) + (got.1 - predicted.1).powi(2)).sqrt();
        assert!(
            err < 0.5,
            "θ {theta}°, φ {phi}°: marker at {got:?}, predicted {predicted:?}"
        );
    }
}

#[test]
fn fisheye_beyond_180_degrees_sees_nothing() {
    // fov 360 across the height: the corners are at θ = 180°·√2 > 180°: no ray, alpha 0.
    let dirs = [Vec3::new(0.0, 0.0, -1.0)];
    let (fb, _) = render_text(&marker_scene("Fisheye(fov: 360)", 16, 16, &dirs), |_| {});
    assert!(all_finite(&fb));
    assert_eq!(fb.alpha[0], 0.0);
    assert_eq!(fb.beauty[0], Vec3::ZERO);
}

#[test]
fn spherical_puts_an_azimuth_in_the_predicted_column() {
    let (w, h) = (128u32, 64u32);
    // (azimuth toward +X, elevation), degrees; one behind the camera.
    let cases = [(60.0f32, 0.0f32), (-150.0, 20.0), (170.0, -45.0)];
    let dirs: Vec<Vec3> = cases
        .iter()
        .map(|&(az, el)| {
            let (a, e) = (az.to_radians(), el.to_radians());
            Vec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos())
        })
        .collect();
    let (fb, _) = render_text(&marker_scene("Spherical", w, h, &dirs), |_| {});
    assert!(all_finite(&fb));
    for &(az, el) in &cases {
        let col = (f64::from(az) / 360.0 + 0.5) * f64::from(w);
        let row = (0.5 - f64::from(el) / 180.0) * f64::from(h);
        let got = centroid(&fb, (col, row), 4.0);
        assert!(
            (got.0 - col).abs() < 0.5 && (got.1 - row).abs() < 0.5,
            "azimuth {az}°, elevation {el}°: marker at {got:?}, predicted ({col}, {row})"
        );
    }
}

#[test]
fn depth_of_field_after_a_fisheye_chains() {
    // Fisheye then a thin lens focused on the sphere of radius 10 (where the markers are):
    // markers stay where the fisheye puts them and stay sharp-ish; no NaN anywhere.
    let dirs = [direction(40.0, 0.0)];
    let lens = "Fisheye(fov: 180), ThinLens(radius: 0.05, focus_distance: 10)";
    let (fb, _) = render_text(&marker_scene(lens, 64, 64, &dirs), |_| {});
    assert!(all_finite(&fb));
    let predicted = ((40.0 / 90.0 + 1.0) * 32.0, 32.0);
    let got = centroid(&fb, predicted, 4.0);
    assert!((got.0 - predicted.0).abs() < 0.5 && (got.1 - predicted.1).abs() < 0.5);
}

/// The lens, fog and adaptive example scenes give identical bytes at 1 and 2 threads.
#[test]
fn lens_and_fog_scenes_do_not_depend_on_the_thread_count() {
    for name in ["depth_of_field.ron", "fisheye.ron", "fog.ron"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets/scenes")
            .join(name);
        let text = std::fs::read_to_string(&path).unwrap();
        // Shrink the image: replace the resolution with 40×30.
        let start = text.find("resolution: (").unwrap();
        let end = start + text[start..].find(')').unwrap() + 1;
        let text = format!("{}resolution: (40, 30){}", &text[..start], &text[end..]);
        let render = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| render_text(&text, |s| s.spp = s.spp.min(4)).0)
        };
        let (one, two) = (render(1), render(2));
        assert!(all_finite(&one), "{name}");
        let bits = |fb: &stagelight::framebuffer::FrameBuffers| -> Vec<u32> {
            fb.beauty
                .iter()
                .flat_map(|c| c.to_array().map(f32::to_bits))
                .chain(fb.samples.iter().copied())
                .collect()
        };
        assert_eq!(bits(&one), bits(&two), "{name}");
    }
}

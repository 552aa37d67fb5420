//! Photons follow a light's distance terms as direct lighting does: a point light without
//! inverse-square falloff (`inverse_square: false`, mental ray's `mib_light_point`) and a
//! light with near/far `attenuation` deposit, at their photons' first hits, the power its
//! direct lighting delivers there — the integral of the direct irradiance over the floor —
//! so the photon map and the path tracer agree. A light with an `energy` keeps mental ray's
//! plain 1/d² photons. Before, every photon fell off as 1/d² and ignored `attenuation`: a
//! non-inverse-square light's indirect light was a tenth of the path tracer's.

use stagelight::photon::GatherMap;

/// Half the side of the floor (z = 0) and the light's height above its centre.
const HALF: f64 = 2.0;
const HEIGHT: f64 = 1.0;
const PHOTONS: u32 = 20_000;

/// A grey floor under one point light of intensity 1 with the extra fields `light`.
fn scene(light: &str) -> String {
    let side = 2.0 * HALF;
    format!(
        r#"Scene(
    options: (global_illumination: (photons: {PHOTONS})),
    cameras: [(name: "cam", fov_y: 40, resolution: (2, 2),
        placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0), up: (0, 0, 1)),
        outputs: [(file: "floor.png")])],
    lights: [(name: "l", kind: Point(position: (0, 0, {HEIGHT})), intensity: 1{light})],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "floor", mesh: Grid(size_x: {side}, size_y: {side}), material: "grey")],
    instances: [(name: "floor_1", of: "floor")],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// The global map's stored power, W (only first hits: bounces leave the open scene).
fn stored(light: &str) -> f64 {
    let frame = crate::common::photon_frame(&scene(light), "floor.ron");
    let map: GatherMap = frame.outputs.photons.and_then(|m| m.global).expect("map");
    f64::from(map.map.total_power().x)
}

/// The direct irradiance integrated over the floor, W: `∫ I·cosθ·g(d) dA` with
/// `cosθ = h/d`, by the midpoint rule on a 400² grid.
fn delivered(g: impl Fn(f64) -> f64) -> f64 {
    let n = 400;
    let step = 2.0 * HALF / n as f64;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = -HALF + (i as f64 + 0.5) * step;
            let y = -HALF + (j as f64 + 0.5) * step;
            let d = (x * x + y * y + HEIGHT * HEIGHT).sqrt();
            sum += HEIGHT / d * g(d);
        }
    }
    sum * step * step
}

/// The near/far ramp: 1 up to `start`, 0 from `end`, linear between.
fn ramp(start: f64, end: f64) -> impl Fn(f64) -> f64 {
    move |d| ((end - d) / (end - start)).clamp(0.0, 1.0)
}

#[test]
fn photons_deliver_what_direct_lighting_delivers_whatever_the_distance_terms() {
    let cases: [(&str, f64); 4] = [
        ("", delivered(|d| 1.0 / (d * d))),
        (", inverse_square: false", delivered(|_| 1.0)),
        (", attenuation: (1.5, 2.5)", {
            let r = ramp(1.5, 2.5);
            delivered(move |d| r(d) / (d * d))
        }),
        (
            ", inverse_square: false, attenuation: (1.5, 2.5)",
            delivered(ramp(1.5, 2.5)),
        ),
    ];
    for (light, expected) in cases {
        let got = stored(light);
        println!("light{light}: stored {got:.4} W, direct lighting delivers {expected:.4} W");
        // Binomial landing counts and the d² weights (at most 9): within 4 %.
        assert!(
            (got / expected - 1.0).abs() < 0.04,
            "light{light}: stored {got} W, expected {expected} W"
        );
    }
}

#[test]
fn a_light_with_energy_keeps_plain_inverse_square_photons() {
    // mental ray's photon `energy` falls off as 1/d² whatever the light shader does: 4π W
    // through the floor's solid angle, with or without the shader's falloff terms.
    let energy = ", energy: (12.566371, 12.566371, 12.566371)";
    let expected = delivered(|d| 1.0 / (d * d));
    for extra in ["", ", inverse_square: false, attenuation: (1.5, 2.5)"] {
        let got = stored(&format!("{energy}{extra}"));
        println!("light{energy}{extra}: stored {got:.4} W (expected {expected:.4})");
        assert!(
            (got / expected - 1.0).abs() < 0.03,
            "{extra}: {got} vs {expected}"
        );
    }
}

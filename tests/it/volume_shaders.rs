//! Volume shaders end to end: fog transmittance `e^(−σt·d)` on the camera segment
//! (atmosphere) and inside a fog-filled object (material interior), single scattering of a
//! point light against a 1-D integral in f64, both integrators, no NaN.

use crate::common;

use common::{all_finite, render_text};
use glam::Vec3;
use stagelight::settings::Integrator;

/// An emissive `Constant` plane of radiance `l` at depth `d` seen head-on by a narrow camera
/// (5×5 pixels, 1°), with `extra` camera fields, materials, objects and instance names.
fn plane_scene(
    d: f64,
    l: (f64, f64, f64),
    camera: &str,
    materials: &str,
    objects: &str,
    members: &str,
) -> String {
    format!(
        r#"Scene(
    options: (samples: 16, max_depth: 8, refraction_depth: 8),
    cameras: [(name: "cam", fov_y: 1, resolution: (5, 5),
        placement: LookAt(eye: (0, 0, 0), target: (0, 0, -1)) {camera})],
    materials: [(name: "glow", shader: Constant(color: ({}, {}, {}))) {materials}],
    objects: [(name: "plane", mesh: Inline(
        vertices: [(-10, -10, -{d}), (10, -10, -{d}), (10, 10, -{d}), (-10, 10, -{d})],
        polygons: [[0, 1, 2, 3]]), material: "glow") {objects}],
    instances: [(name: "plane_1", of: "plane") {}],
    groups: [(name: "world", members: ["plane_1" {members}])],
    render: (root: "world", camera: "cam"),
)"#,
        l.0,
        l.1,
        l.2,
        members
            .split(',')
            .filter(|m| !m.trim().is_empty())
            .map(|m| {
                let m = m.trim().trim_matches('"');
                format!(", (name: \"{m}\", of: \"{}\")", m.trim_end_matches("_1"))
            })
            .collect::<String>(),
    )
}

/// An axis-aligned box `[-5, 5]² × [z0, z1]` as an inline mesh, outward-facing quads.
fn slab(name: &str, material: &str, z0: f64, z1: f64) -> String {
    format!(
        r#", (name: "{name}", mesh: Inline(
        vertices: [(-5, -5, {z0}), (5, -5, {z0}), (5, 5, {z0}), (-5, 5, {z0}),
                   (-5, -5, {z1}), (5, -5, {z1}), (5, 5, {z1}), (-5, 5, {z1})],
        polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 4, 7, 3], [1, 2, 6, 5], [3, 7, 6, 2], [0, 1, 5, 4]]),
        material: "{material}")"#
    )
}

/// A see-through shell (opacity 0) filled with `fog`.
fn shell_material(fog: &str) -> String {
    format!(
        r#", (name: "shell", shader: Opacity(opacity: (0, 0, 0), input: Lambert(albedo: (0, 0, 0))),
        interior: {fog})"#
    )
}

fn rel_err(got: Vec3, want: Vec3) -> f32 {
    ((got - want).abs() / want).max_element()
}

#[test]
fn atmosphere_attenuates_by_exp_minus_sigma_d() {
    let (d, l) = (4.0f32, Vec3::new(2.0, 1.0, 0.5));
    let sigma_a = Vec3::new(0.1, 0.25, 0.5);
    let camera = ", atmosphere: Fog(sigma_a: (0.1, 0.25, 0.5))";
    let scene = plane_scene(d as f64, (2.0, 1.0, 0.5), camera, "", "", "");
    for integrator in [Integrator::Direct, Integrator::Path] {
        let (fb, _) = render_text(&scene, |s| s.integrator = integrator);
        assert!(all_finite(&fb));
        let t = Vec3::new(
            (-sigma_a.x * d).exp(),
            (-sigma_a.y * d).exp(),
            (-sigma_a.z * d).exp(),
        );
        let c = fb.beauty[12];
        assert!(
            rel_err(c, l * t) < 1e-3,
            "{integrator:?}: {c} vs L·e^(−σd) = {}",
            l * t
        );
    }
}

#[test]
fn fog_interior_attenuates_only_inside_the_object() {
    // A 1.5 m thick fog-filled shell between the camera and the plane at 6 m.
    let sigma_a = Vec3::new(0.2, 0.4, 0.8);
    let materials = shell_material("Fog(sigma_a: (0.2, 0.4, 0.8))");
    let objects = slab("box", "shell", -4.5, -3.0);
    let scene = plane_scene(
        6.0,
        (1.0, 1.0, 1.0),
        "",
        &materials,
        &objects,
        ", \"box_1\"",
    );
    for integrator in [Integrator::Direct, Integrator::Path] {
        let (fb, _) = render_text(&scene, |s| s.integrator = integrator);
        assert!(all_finite(&fb));
        let t = Vec3::new(
            (-sigma_a.x * 1.5).exp(),
            (-sigma_a.y * 1.5).exp(),
            (-sigma_a.z * 1.5).exp(),
        );
        let c = fb.beauty[12];
        assert!(rel_err(c, t) < 1e-3, "{integrator:?}: {c} vs {t}");
    }
}

/// Single scattering along the −Z axis from `z0` to `z1` (distances from the camera) of a
/// point light of intensity `i` at `light`, in fog (σs, σt, g), with the segment starting at
/// distance `enter` from the camera in the fog: Simpson's rule in f64.
fn single_scatter_reference(
    sigma_s: f64,
    sigma_t: f64,
    g: f64,
    i: f64,
    light: [f64; 3],
    (z0, z1): (f64, f64),
) -> f64 {
    let n = 20_000;
    let h = (z1 - z0) / n as f64;
    let f = |t: f64| {
        let x = [0.0, 0.0, -t];
        let to = [light[0] - x[0], light[1] - x[1], light[2] - x[2]];
        let r = (to[0] * to[0] + to[1] * to[1] + to[2] * to[2]).sqrt();
        // cos between the direction toward the light and the ray direction (0, 0, −1).
        let cos = -to[2] / r;
        let phase =
            (1.0 - g * g) / (4.0 * std::f64::consts::PI * (1.0 + g * g - 2.0 * g * cos).powf(1.5));
        (-sigma_t * (t - z0)).exp() * sigma_s * phase * i / (r * r) * (-sigma_t * r).exp()
    };
    let mut sum = f(z0) + f(z1);
    for k in 1..n {
        sum += f(z0 + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

#[test]
fn single_scattering_of_a_point_light_in_a_slab_matches_the_integral() {
    // Slab from 2 m to 3 m in front of the camera, light inside it, 0.3 m off the axis.
    let (sigma_s, sigma_a, g) = (0.5, 0.1, 0.4);
    let fog = format!("Fog(sigma_a: ({sigma_a}, {sigma_a}, {sigma_a}), sigma_s: ({sigma_s}, {sigma_s}, {sigma_s}), g: {g})");
    let materials = shell_material(&fog);
    let objects = slab("box", "shell", -3.0, -2.0);
    // The emitting plane behind is black (it only closes the scene).
    let scene = plane_scene(8.0, (0.0, 0.0, 0.0), "", &materials, &objects, ", \"box_1\"")
        .replace(
            "    materials:",
            "    lights: [(name: \"bulb\", kind: Point(position: (0.3, 0, -2.5)), intensity: 1)],\n    materials:",
        );
    let want = single_scatter_reference(
        sigma_s,
        sigma_s + sigma_a,
        g,
        1.0,
        [0.3, 0.0, -2.5],
        (2.0, 3.0),
    );
    for integrator in [Integrator::Direct, Integrator::Path] {
        let (fb, _) = render_text(&scene, |s| {
            s.integrator = integrator;
            s.spp = 256;
        });
        assert!(all_finite(&fb));
        let got = f64::from(fb.beauty[12].x);
        eprintln!("{integrator:?}: {got:.6} vs integral {want:.6}");
        assert!(
            ((got - want) / want).abs() < 0.02,
            "{integrator:?}: {got} vs {want}"
        );
    }
}

#[test]
fn atmosphere_single_scattering_matches_the_integral() {
    // The whole camera segment (to a black wall at 5 m) in fog, light 0.5 m off the axis.
    let (sigma_s, g) = (0.2, -0.3);
    let camera = format!(", atmosphere: Fog(sigma_s: ({sigma_s}, {sigma_s}, {sigma_s}), g: {g})");
    let scene = plane_scene(5.0, (0.0, 0.0, 0.0), &camera, "", "", "").replace(
        "    materials:",
        "    lights: [(name: \"bulb\", kind: Point(position: (0, 0.5, -1.5)), intensity: 2)],\n    materials:",
    );
    let want = single_scatter_reference(sigma_s, sigma_s, g, 2.0, [0.0, 0.5, -1.5], (0.0, 5.0));
    let (fb, _) = render_text(&scene, |s| s.spp = 256);
    let got = f64::from(fb.beauty[12].y);
    eprintln!("atmosphere: {got:.6} vs integral {want:.6}");
    assert!(((got - want) / want).abs() < 0.02, "{got} vs {want}");
}

#[test]
fn fog_attenuates_shadow_rays_to_lights_in_the_scene() {
    // A Lambert floor lit by a point light 2 m above it, through atmosphere of σa = 0.3:
    // the direct light at the pixel is e^(−σa·2) of the fog-free value (the camera segment
    // is removed by comparing against the same attenuation on the camera ray).
    let base = |fog: &str| {
        format!(
            r#"Scene(
    options: (samples: 4),
    cameras: [(name: "cam", fov_y: 1, resolution: (3, 3),
        placement: LookAt(eye: (0, 1, 0), target: (0, 0, 0), up: (0, 0, -1)) {fog})],
    lights: [(name: "bulb", kind: Point(position: (0, 2, 0)), intensity: 4)],
    materials: [(name: "floor", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "floor", mesh: Inline(vertices: [(-5, 0, -5), (-5, 0, 5), (5, 0, 5), (5, 0, -5)],
        polygons: [[0, 1, 2, 3]]), material: "floor")],
    instances: [(name: "floor_1", of: "floor")],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)"#
        )
    };
    let (clear, _) = render_text(&base(""), |_| {});
    let (fogged, _) = render_text(&base(", atmosphere: Fog(sigma_a: (0.3, 0.3, 0.3))"), |_| {});
    let ratio = fogged.beauty[4].x / clear.beauty[4].x;
    // Light path 2 m, camera path 1 m.
    let want = (-0.3f32 * 3.0).exp();
    assert!((ratio - want).abs() < 1e-3 * want, "{ratio} vs {want}");
}

#[test]
fn fog_filled_shells_attenuate_shadows_instead_of_blocking_them() {
    // A floor lit from 3 m above through a 1 m slab of absorbing fog inside a see-through
    // shell: the lit floor keeps e^(−σa·1) of its light (the camera sees it beside the slab).
    let scene = |with_slab: bool| {
        let (materials, objects, members) = if with_slab {
            (
                shell_material("Fog(sigma_a: (0.7, 0.7, 0.7))"),
                slab("box", "shell", 1.0, 2.0),
                ", \"box_1\"",
            )
        } else {
            (String::new(), String::new(), "")
        };
        // Z is up here: the slab z ∈ [1, 2] lies between the floor (z = 0) and the light.
        format!(
            r#"Scene(
    options: (samples: 4),
    cameras: [(name: "cam", fov_y: 1, resolution: (3, 3),
        placement: LookAt(eye: (0, -0.5, 0.5), target: (0, 0, 0), up: (0, 0, 1)))],
    lights: [(name: "bulb", kind: Point(position: (0, 0, 3)), intensity: 4)],
    materials: [(name: "floor", shader: Lambert(albedo: (0.5, 0.5, 0.5))) {materials}],
    objects: [(name: "floor", mesh: Inline(vertices: [(-5, -5, 0), (5, -5, 0), (5, 5, 0), (-5, 5, 0)],
        polygons: [[0, 1, 2, 3]]), material: "floor") {objects}],
    instances: [(name: "floor_1", of: "floor") {}],
    groups: [(name: "world", members: ["floor_1" {members}])],
    render: (root: "world", camera: "cam"),
)"#,
            if with_slab {
                ", (name: \"box_1\", of: \"box\")"
            } else {
                ""
            }
        )
    };
    let (clear, _) = render_text(&scene(false), |_| {});
    let (shaded, _) = render_text(&scene(true), |_| {});
    assert!(all_finite(&shaded));
    let ratio = shaded.beauty[4].x / clear.beauty[4].x;
    let want = (-0.7f32).exp();
    assert!((ratio - want).abs() < 1e-3 * want, "{ratio} vs {want}");
}

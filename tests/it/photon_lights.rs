//! Issue 16: per-light photon controls — `energy` replaces a light's physical power for
//! photons (`(0, 0, 0)`: mental ray's light without energy, no photons) and
//! `caustic_photons` / `globillum_photons` give a light its own photon count.

use std::path::Path;

use stagelight::frame::Frame;
use stagelight::photon::GatherMap;
use stagelight::scene::load_scene_str;

/// A grey floor under two point lights (`a` at height 1, `b` at height 2, intensity 1 each),
/// a global map of `photons` photons; `a` and `b` carry the extra fields given.
fn scene(photons: u32, a: &str, b: &str) -> String {
    format!(
        r#"Scene(
    options: (global_illumination: (photons: {photons})),
    cameras: [(name: "cam", fov_y: 40, resolution: (2, 2),
        placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0), up: (0, 0, 1)),
        outputs: [(file: "floor.png")])],
    lights: [
        (name: "a", kind: Point(position: (0, 0, 1)), intensity: 1{a}),
        (name: "b", kind: Point(position: (1, 0, 2)), intensity: 1{b}),
    ],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "floor", mesh: Grid(size_x: 40, size_y: 40), material: "grey")],
    instances: [(name: "floor_1", of: "floor")],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

fn global_map(text: &str) -> Option<GatherMap> {
    let mut scene = load_scene_str(text, Path::new("floor.ron")).unwrap_or_else(|e| panic!("{e}"));
    let mut frame = Frame::new(scene.settings.clone());
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .take_while(|s| s.name != "bake_lightmaps")
        .collect();
    stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame).expect("photons");
    frame.outputs.photons.and_then(|m| m.global)
}

/// Solid angle of the floor `[-20, 20]²` (z = 0) seen from `(x, 0, h)`, sr.
fn floor_solid_angle(x: f64, h: f64) -> f64 {
    let f = |u: f64, v: f64| (u * v / (h * (u * u + v * v + h * h).sqrt())).atan();
    let (x1, x2) = (-20.0 - x, 20.0 - x);
    f(x2, 20.0) - f(x1, 20.0) - f(x2, -20.0) + f(x1, -20.0)
}

/// Power of an isotropic light of intensity `i` landing on the floor from `(x, 0, h)`, W
/// (the global map stores only first hits: bounces leave the open scene).
fn landing(i: f64, x: f64, h: f64) -> f64 {
    i * floor_solid_angle(x, h)
}

fn total(m: &GatherMap) -> f64 {
    m.map.total_power().x as f64
}

#[test]
fn energy_replaces_the_physical_power_of_photons() {
    let physical = global_map(&scene(8000, "", "")).unwrap();
    // Each light emits 4π W physically; energies 8π and 0: only `a`, at twice its power.
    let four_pi = 4.0 * std::f64::consts::PI;
    let doubled = format!(", energy: ({0}, {0}, {0})", 2.0 * four_pi);
    let only_a = global_map(&scene(8000, &doubled, ", energy: (0, 0, 0)")).unwrap();
    let expected = (
        landing(1.0, 0.0, 1.0) + landing(1.0, 1.0, 2.0),
        landing(2.0, 0.0, 1.0),
    );
    println!(
        "stored power: physical {:.3} W (expected {:.3}), energies (8π, 0) {:.3} W \
         (expected {:.3})",
        total(&physical),
        expected.0,
        total(&only_a),
        expected.1
    );
    // Binomial landing counts, σ ≈ 1.2 %: within 5 %.
    assert!((total(&physical) / expected.0 - 1.0).abs() < 0.05);
    assert!((total(&only_a) / expected.1 - 1.0).abs() < 0.05);
    // Every photon now comes from `a` and carries 8π / 8000 W.
    let each = (2.0 * four_pi / 8000.0) as f32;
    assert!(only_a
        .map
        .photons()
        .iter()
        .all(|p| (p.power.x - each).abs() < 1e-5 * each));
    // No light with energy: no photons at all.
    let none = global_map(&scene(4000, ", energy: (0, 0, 0)", ", energy: (0, 0, 0)"));
    assert!(none.is_none_or(|m| m.map.is_empty()));
}

#[test]
fn a_light_with_its_own_count_emits_it_and_the_estimate_keeps_its_value() {
    // `b` emits 12000 of its own; `a` takes the map's 8000 alone.
    let own = global_map(&scene(8000, "", ", globillum_photons: 12000")).unwrap();
    assert_eq!(own.emitted, 20_000);
    let expected = landing(1.0, 0.0, 1.0) + landing(1.0, 1.0, 2.0);
    println!(
        "stored power with per-light counts: {:.4} W (expected {expected:.4})",
        total(&own)
    );
    assert!((total(&own) / expected - 1.0).abs() < 0.04);
    // `b`'s photons carry 4π / 12000 W, `a`'s 4π / 8000.
    let four_pi = 4.0 * std::f32::consts::PI;
    let from_b = own
        .map
        .photons()
        .iter()
        .filter(|p| (p.power.x - four_pi / 12000.0).abs() < 1e-6)
        .count();
    assert!(from_b > 5000, "{from_b}");
    // A count of 0 silences a light; the same scene gives the same map twice.
    let silent = global_map(&scene(
        4000,
        ", globillum_photons: 0",
        ", globillum_photons: 0",
    ));
    assert!(silent.is_some_and(|m| m.map.is_empty() && m.emitted == 0));
    let again = global_map(&scene(8000, "", ", globillum_photons: 12000")).unwrap();
    assert_eq!(again.map.photons(), own.map.photons());
}

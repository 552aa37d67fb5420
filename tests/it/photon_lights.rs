//! Issue 16: per-light photon controls — `energy` replaces a light's physical power for
//! photons (`(0, 0, 0)`: mental ray's light without energy, no photons) and
//! `caustic_photons` / `globillum_photons` give a light its own photon count.

use stagelight::photon::GatherMap;

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
    let frame = crate::common::photon_frame(text, "floor.ron");
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
    // A count of 0 silences a light (with both silent, the photon pass skips: no map at
    // all); the same scene gives the same map twice.
    let silent = global_map(&scene(
        4000,
        ", globillum_photons: 0",
        ", globillum_photons: 0",
    ));
    assert!(silent.is_none());
    let again = global_map(&scene(8000, "", ", globillum_photons: 12000")).unwrap();
    assert_eq!(again.map.photons(), own.map.photons());
}

/// Global illumination on, but no light sends photons into the map — an ambient light only, a
/// light of photon `energy` 0, a light with `globillum_photons: 0` —: `trace_photons` skips
/// with the reason (`plan` and the render agree) instead of running and storing nothing, and
/// the render still succeeds.
#[test]
fn lights_that_send_no_photons_skip_the_photon_pass() {
    let dir = crate::common::scratch_dir("photons-no-emitter");
    let scene = |light: &str| {
        format!(
            r#"Scene(
    options: (samples: 1, global_illumination: (photons: 1000, gather: 20)),
    cameras: [(name: "cam", fov_y: 40, resolution: (8, 6), placement: LookAt(eye: (0, 2, 6), target: (0, 0, 0)), outputs: [(file: "out.png")])],
    lights: [{light}],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "floor", mesh: Inline(vertices: [(-10, 0, -10), (-10, 0, 10), (10, 0, 10), (10, 0, -10)], polygons: [[0, 1, 2, 3]]), material: "grey")],
    instances: [(name: "floor_1", of: "floor")],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)"#
        )
    };
    let reason = "no light emits photons for the maps requested (ambient lights send none; every other light has photon energy 0 or 0 photons for them)";
    let point = r#"(name: "key", kind: Point(position: (2, 4, 3)), intensity: 30"#;
    let cases = [
        (
            "ambient",
            r#"(name: "amb", kind: Ambient, intensity: 0.5)"#.to_string(),
            false,
        ),
        ("energy0", format!("{point}, energy: (0, 0, 0))"), false),
        ("count0", format!("{point}, globillum_photons: 0)"), false),
        (
            "caustics_count_only",
            format!("{point}, caustic_photons: 0)"),
            true,
        ),
        ("plain", format!("{point})"), true),
    ];
    for (name, light, runs) in cases {
        let file = format!("{name}.ron");
        std::fs::write(dir.join(&file), scene(&light)).unwrap();
        let o = crate::common::run_in(&dir, &["plan", &file]);
        assert!(
            o.status.success(),
            "{name}: {}",
            crate::common::stderr_of(&o)
        );
        let plan = String::from_utf8(o.stdout).unwrap();
        let line = plan
            .lines()
            .find(|l| l.contains("trace_photons"))
            .unwrap_or_else(|| panic!("{name}: {plan}"));
        if runs {
            assert!(line.contains(" run "), "{name}: {line}");
        } else {
            assert!(line.ends_with(&format!("skip {reason}")), "{name}: {line}");
            let png = format!("{name}.png");
            let o = crate::common::run_in(&dir, &["render", &file, "-o", &png]);
            assert!(
                o.status.success(),
                "{name}: {}",
                crate::common::stderr_of(&o)
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

//! Hostile numbers in area lights, light attenuation, the environment and shadow-tinting
//! materials: every scene is rejected with located errors or renders finite, non-negative
//! pixels (a property test in the manner of `bad_values.rs`, over its own template).

use std::path::Path;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use stagelight::frame::Frame;
use stagelight::scene::load_scene_str;

/// Number placeholders in the template, in order.
const SLOTS: usize = 20;

const TEMPLATE: &str = r#"Scene(
    options: (samples: 2, integrator: Path, max_depth: 3),
    environment: (shader: Constant(color: ({}, 0.5, 0.5)), intensity: {}, samples: 2),
    cameras: [(name: "cam", fov_y: 40, resolution: (10, 8),
        placement: LookAt(eye: (0, -4, 2), target: (0, 0, 0), up: (0, 0, 1)))],
    lights: [
        (name: "d", kind: Disc(center: (0, 0, {}), normal: (0, {}, -1), radius: {}), samples: 2, visible: true),
        (name: "s", kind: Sphere(center: ({}, 0, 3), radius: {}), samples: 2, visible: true, attenuation: ({}, {})),
        (name: "c", kind: Cylinder(start: (-1, 1, 2), end: ({}, 1, 2), radius: {}), intensity: {}, samples: 2),
        (name: "p", kind: Point(position: (0, 0, {})), intensity: 5, attenuation: (1, {})),
    ],
    materials: [
        (name: "m", shader: Lambert(albedo: (0.5, 0.5, 0.5))),
        (name: "sheet", shader: Opacity(opacity: ({}, 0.5, {}), input: Lambert(albedo: (0.8, 0.1, 0.1)))),
    ],
    objects: [
        (name: "floor", mesh: Inline(vertices: [(-3, -3, 0), (3, -3, 0), (3, 3, 0), (-3, 3, 0)], polygons: [[0, 1, 2, 3]]), material: "m"),
        (name: "sheet", mesh: Inline(vertices: [(-1, -1, {}), (1, -1, 1), (1, 1, 1), (-1, 1, {})], polygons: [[0, 1, 2, 3]]), material: "sheet"),
    ],
    instances: [(name: "f", of: "floor"), (name: "s", of: "sheet")],
    groups: [(name: "world", members: ["f", "s"])],
    render: (root: "world", camera: "cam"),
)
"#;

const ORDINARY: [&str; SLOTS] = [
    "0.5", "1", "2", "0", "0.5", "1", "0.4", "1", "6", "1", "0.2", "3", "4", "8", "0.5", "0.5",
    "1", "1", "0", "0",
];

fn hostile() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "NaN", "inf", "-inf", "0", "-0.0", "-1", "1e39", "-1e39", "1e-45", "1e30", "-1e-30", "3",
    ])
}

fn fill(values: &[&str]) -> String {
    let mut out = String::new();
    let mut rest = TEMPLATE;
    let mut k = 0;
    while let Some(i) = rest.find("{}") {
        out.push_str(&rest[..i]);
        out.push_str(values[k]);
        k += 1;
        rest = &rest[i + 2..];
    }
    out.push_str(rest);
    out
}

fn render_finite(text: &str) -> Result<bool, TestCaseError> {
    match load_scene_str(text, Path::new("bad_lights.ron")) {
        Err(errors) => {
            for d in &errors.0 {
                prop_assert!(d.line >= 1 && d.column >= 1, "unlocated: {d}");
                prop_assert!(!d.message.is_empty());
            }
            Ok(false)
        }
        Ok(mut scene) => {
            let mut frame = Frame::new(scene.settings.clone());
            let stages: Vec<_> = stagelight::systems::STAGES
                .iter()
                .copied()
                .filter(|s| s.name != "write_output")
                .collect();
            stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame)
                .map_err(|e| TestCaseError::fail(format!("render failed: {e}\n{text}")))?;
            let fb = frame.outputs.image.expect("image");
            prop_assert!(
                fb.beauty
                    .iter()
                    .all(|c| c.is_finite() && c.min_element() >= 0.0),
                "non-finite pixel for\n{text}"
            );
            Ok(true)
        }
    }
}

#[test]
fn the_template_is_valid_and_renders() {
    assert!(render_finite(&fill(&ORDINARY)).unwrap());
}

#[test]
fn hostile_light_numbers_are_rejected_with_a_location_or_render_finite_pixels() {
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 200,
            failure_persistence: None,
            ..Config::default()
        },
        proptest::test_runner::TestRng::deterministic_rng(
            proptest::test_runner::RngAlgorithm::ChaCha,
        ),
    );
    let strategy = (
        prop::collection::vec((any::<bool>(), hostile()), SLOTS),
        0usize..SLOTS,
    );
    let (mut rejected, mut rendered) = (0, 0);
    runner
        .run(&strategy, |(picks, forced)| {
            let values: Vec<&str> = picks
                .iter()
                .enumerate()
                .map(|(k, &(bad, v))| {
                    if (bad && k % 5 == forced % 5) || k == forced {
                        v
                    } else {
                        ORDINARY[k]
                    }
                })
                .collect();
            let _ = render_finite(&fill(&values))?;
            Ok(())
        })
        .unwrap();
    for k in 0..SLOTS {
        for v in ["NaN", "0", "-1", "1e30", "1e-45"] {
            let mut values = ORDINARY;
            values[k] = v;
            match render_finite(&fill(&values)) {
                Ok(true) => rendered += 1,
                Ok(false) => rejected += 1,
                Err(e) => panic!("slot {k} = {v}: {e}"),
            }
        }
    }
    println!("rejected {rejected}, rendered {rendered}");
    assert!(rejected > 0 && rendered > 0, "{rejected} {rendered}");
}

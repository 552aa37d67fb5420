//! Degenerate, NaN and infinite inputs anywhere in a scene are either rejected with a located
//! error or handled — never a panic and never a NaN or infinite pixel. A property test fills
//! every number of a small but complete scene (vertices, transforms, colours, intensities,
//! light sizes, camera, photon gather radii) with ordinary or hostile values.

use std::path::Path;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use stagelight::components::{Camera, RenderCamera};
use stagelight::frame::Frame;
use stagelight::scene::load_scene_str;

/// Number placeholders in the template, in order.
const SLOTS: usize = 24;

/// The template: `{}` marks are replaced by generated numbers.
const TEMPLATE: &str = r#"Scene(
    cameras: [(name: "cam", fov_y: {}, resolution: (12, 9),
        placement: LookAt(eye: ({}, {}, 4), target: (0, 0, {}), up: (0, 1, 0)))],
    lights: [
        (name: "p", kind: Point(position: ({}, 1, 2)), intensity: {}),
        (name: "r", kind: Rect(corner: (-1, -1, 3), edge_u: ({}, 0, 0), edge_v: (0, {}, 0)), color: ({}, 1, 1), samples: 2),
        (name: "s", kind: Spot(position: (0, 0, 3), target: (0, 0, 0), cone_angle: {}, penumbra: {})),
    ],
    materials: [
        (name: "m", shader: Lambert(albedo: ({}, 0.5, 0.5)), emission: (0, {}, 0)),
    ],
    objects: [(name: "tri", mesh: Inline(
        vertices: [({}, 0, 0), (1, {}, 0), (0, 1, {}), (1, 1, 0)],
        polygons: [[0, 1, 2], [1, 3, 2]]), material: "m")],
    instances: [(name: "t", of: "tri", transform: [Scale(({}, 1, 1)), Rotate(axis: (0, 0, 1), degrees: {}), Translate(({}, 0, 0)), Matrix(((1, 0, 0, {}), (0, 1, 0, 0), (0, 0, {}, 0), (0, 0, 0, 1)))])],
    groups: [(name: "world", members: ["t"])],
    render: (root: "world", camera: "cam"),
    options: (samples: 2, caustics: (photons: 300, radius: {}),
        global_illumination: (photons: 300, radius: {}, final_gather: 2)),
)
"#;

/// Ordinary values for each slot (used where the generator does not pick a hostile one).
const ORDINARY: [&str; SLOTS] = [
    "40.0", "0.5", "0.2", "0", "0.3", "5.0", "2", "2", "1", "30.0", "5.0", "0.5", "1", "0", "0",
    "0", "1", "15", "0.1", "0", "1", // Photon map gather radii (0 = automatic).
    "0", "0", // Spare slot (keep the count stable if the template grows).
    "0",
];

fn hostile() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "NaN", "inf", "-inf", "0", "-0.0", "-1", "1e39", "-1e39", "1e-45", "1e30", "-1e-30", "180",
        // Far but ordinary coordinates: the loader rebases them (hard case H5).
        "1e6", "-3.5e7",
    ])
}

fn fill(values: &[&str]) -> String {
    let mut out = String::new();
    let mut k = 0;
    let mut rest = TEMPLATE;
    while let Some(i) = rest.find("{}") {
        out.push_str(&rest[..i]);
        out.push_str(values[k]);
        k += 1;
        rest = &rest[i + 2..];
    }
    out.push_str(rest);
    out
}

#[test]
fn the_template_is_valid_and_renders() {
    let text = fill(&ORDINARY);
    let scene =
        load_scene_str(&text, Path::new("bad_values.ron")).unwrap_or_else(|e| panic!("{e}"));
    let _ = scene;
}

#[test]
fn hostile_numbers_are_rejected_with_a_location_or_render_finite_pixels() {
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 300,
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
    let rejected = std::cell::Cell::new(0usize);
    let rendered = std::cell::Cell::new(0usize);
    runner
        .run(&strategy, |(picks, forced)| {
            let values: Vec<&str> = picks
                .iter()
                .enumerate()
                .map(|(k, &(bad, v))| {
                    if (bad && k % 7 == forced % 7) || k == forced {
                        v
                    } else {
                        ORDINARY[k]
                    }
                })
                .collect();
            let text = fill(&values);
            match load_scene_str(&text, Path::new("bad_values.ron")) {
                Err(errors) => {
                    rejected.set(rejected.get() + 1);
                    for d in &errors.0 {
                        prop_assert!(d.line >= 1 && d.column >= 1, "unlocated: {d}");
                        prop_assert!(d.file.ends_with("bad_values.ron"), "{d}");
                        prop_assert!(!d.message.is_empty());
                    }
                }
                Ok(mut scene) => {
                    rendered.set(rendered.get() + 1);
                    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
                        prop_assert!(camera.fov_y.is_finite());
                    }
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
                    prop_assert!(fb.alpha.iter().all(|a| a.is_finite()));
                    prop_assert!(fb.normal.iter().all(|n| n.is_finite()));
                }
            }
            Ok(())
        })
        .unwrap();
    // Both outcomes must actually occur, or the test proves little.
    let (rejected, rendered) = (rejected.get(), rendered.get());
    assert!(
        rejected > 20 && rendered > 20,
        "rejected {rejected}, rendered {rendered}"
    );
}

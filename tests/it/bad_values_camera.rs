//! Hostile numbers in lens shaders, volume shaders and adaptive samples: rejected with a
//! located error, or rendered with finite, non-negative pixels — never a panic or a NaN.

use std::path::Path;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use stagelight::frame::Frame;
use stagelight::scene::load_scene_str;

/// Number placeholders in the template, in order.
const SLOTS: usize = 14;

const TEMPLATE: &str = r#"Scene(
    options: (samples: (min: 2, max: 4, contrast: ({}, 0.1, 0.1))),
    cameras: [(name: "cam", fov_y: {}, resolution: (10, 8),
        placement: LookAt(eye: (0.3, 0.2, 4), target: (0, 0, 0)),
        lens: [Fisheye(fov: {}), ThinLens(radius: {}, focus_distance: {})],
        atmosphere: Fog(sigma_a: ({}, 0.1, 0.1), sigma_s: (0.2, {}, 0.2), g: {}))],
    lights: [
        (name: "p", kind: Point(position: ({}, 1, 2)), intensity: 5),
        (name: "r", kind: Rect(corner: (-1, -1, 3), edge_u: (2, 0, 0), edge_v: (0, 2, 0)), samples: 2),
    ],
    materials: [
        (name: "m", shader: Lambert(albedo: (0.5, 0.5, 0.5))),
        (name: "fog", shader: Opacity(opacity: ({}, 0, 0), input: Lambert(albedo: (0.5, 0.5, 0.5))),
         interior: Fog(sigma_a: ({}, 0.3, 0.3), sigma_s: (0.5, {}, 0.5), g: {})),
    ],
    objects: [
        (name: "tri", mesh: Inline(vertices: [(-3, -3, -1), (3, -3, -1), (0, 3, -1)],
            polygons: [[0, 1, 2]]), material: "m"),
        (name: "box", mesh: Inline(
            vertices: [(-1, -1, -0.5), (1, -1, -0.5), (1, 1, -0.5), (-1, 1, -0.5),
                       (-1, -1, {}), (1, -1, 0.5), (1, 1, 0.5), (-1, 1, 0.5)],
            polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 4, 7, 3], [1, 2, 6, 5], [3, 7, 6, 2], [0, 1, 5, 4]]),
            material: "fog"),
    ],
    instances: [(name: "t", of: "tri"), (name: "b", of: "box")],
    groups: [(name: "world", members: ["t", "b"])],
    render: (root: "world", camera: "cam"),
)
"#;

const ORDINARY: [&str; SLOTS] = [
    "0.1", "40", "180", "0.05", "4", "0.05", "0.2", "0.3", "0.5", "0", "0.2", "0.5", "-0.2", "0.5",
];

fn hostile() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "NaN",
        "inf",
        "-inf",
        "0",
        "-0.0",
        "-1",
        "1e39",
        "-1e39",
        "1e-45",
        "1e30",
        "-1e-30",
        "360",
        "0.999999",
        "-0.999999",
        "1e6",
    ])
}

fn fill(values: &[&str]) -> String {
    let mut out = String::new();
    let mut rest = TEMPLATE;
    for v in values {
        let i = rest.find("{}").expect("slot");
        out.push_str(&rest[..i]);
        out.push_str(v);
        rest = &rest[i + 2..];
    }
    assert!(!rest.contains("{}"), "unfilled slot");
    out.push_str(rest);
    out
}

fn render(text: &str) -> Result<stagelight::framebuffer::FrameBuffers, String> {
    let mut scene = load_scene_str(text, Path::new("bad_camera.ron")).map_err(|e| {
        for d in &e.0 {
            assert!(d.line >= 1 && d.column >= 1, "unlocated: {d}");
            assert!(d.file.ends_with("bad_camera.ron"), "{d}");
        }
        e.to_string()
    })?;
    let mut frame = Frame::new(scene.settings.clone());
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame)
        .unwrap_or_else(|e| panic!("render failed: {e}\n{text}"));
    Ok(frame.outputs.image.expect("image"))
}

#[test]
fn the_template_renders() {
    let fb = render(&fill(&ORDINARY)).unwrap_or_else(|e| panic!("{e}"));
    assert!(fb.beauty.iter().any(|c| c.max_element() > 0.0));
}

#[test]
fn hostile_lens_and_volume_numbers_are_rejected_or_render_finite_pixels() {
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 150,
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
    let (rejected, rendered) = (std::cell::Cell::new(0), std::cell::Cell::new(0));
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
            let text = fill(&values);
            match render(&text) {
                Err(_) => rejected.set(rejected.get() + 1),
                Ok(fb) => {
                    rendered.set(rendered.get() + 1);
                    prop_assert!(
                        fb.beauty
                            .iter()
                            .all(|c| c.is_finite() && c.min_element() >= 0.0),
                        "non-finite pixel for\n{text}"
                    );
                    prop_assert!(fb.alpha.iter().all(|a| a.is_finite()));
                }
            }
            Ok(())
        })
        .unwrap();
    let (rejected, rendered) = (rejected.get(), rendered.get());
    assert!(
        rejected > 20 && rendered > 20,
        "rejected {rejected}, rendered {rendered}"
    );
}

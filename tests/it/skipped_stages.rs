//! "Simulate only the effects a scene calls for": stages with nothing to do cost nothing
//! measurable and change nothing. On the Cornell box (no procedural geometry, no parametric
//! surfaces or displacement, no photon maps, no bake requests) the run conditions of those stages take
//! under 1 µs, and the image is byte-identical to one rendered by a table in which those
//! stages were never registered.

use std::path::PathBuf;
use std::time::Instant;

use stagelight::camera_space::CameraSpace;
use stagelight::components::{Camera, Pass, RenderCamera};
use stagelight::exr_output::encode_exr;
use stagelight::frame::Frame;
use stagelight::scene::{load_scene, LoadedScene};
use stagelight::schedule::{run_stages, Stage};
use stagelight::systems::STAGES;

/// Stages the Cornell box does not call for.
const UNUSED: [&str; 4] = [
    "expand_geometry",
    "tessellate",
    "trace_photons",
    "bake_lightmaps",
];

fn cornell() -> LoadedScene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/cornell_box.ron");
    let mut scene = load_scene(&path).expect("cornell box");
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        camera.width = 48;
        camera.height = 48;
    }
    scene
}

#[test]
fn run_conditions_of_unused_stages_cost_under_a_microsecond() {
    let scene = cornell();
    let frame = Frame::new(scene.settings.clone());
    for name in UNUSED {
        let stage = STAGES
            .iter()
            .find(|s| s.name == name)
            .expect("stage in the table");
        assert!(
            !(stage.condition)(&scene.world, &frame).run,
            "{name} should skip"
        );
        // Best of several batches: the machine is shared, the minimum is the cost.
        let calls = 10_000u32;
        let best = (0..5)
            .map(|_| {
                let t = Instant::now();
                for _ in 0..calls {
                    std::hint::black_box((stage.condition)(
                        std::hint::black_box(&scene.world),
                        &frame,
                    ));
                }
                t.elapsed().as_secs_f64() / calls as f64
            })
            .fold(f64::INFINITY, f64::min);
        assert!(
            best < 1e-6,
            "{name}: run condition took {:.3} µs",
            best * 1e6
        );
    }
}

fn render(stages: &[Stage]) -> Vec<u8> {
    let mut scene = cornell();
    let mut frame = Frame::new(scene.settings.clone());
    let table: Vec<Stage> = stages
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    run_stages(&table, &mut scene.world, &mut frame).expect("render");
    let camera = CameraSpace::of_render_camera(&scene.world, Default::default()).unwrap();
    encode_exr(
        frame.outputs.image.as_ref().expect("image"),
        &camera,
        &[Pass::Beauty, Pass::Depth, Pass::Normal],
    )
    .unwrap()
}

#[test]
fn unused_stages_change_no_byte_of_the_image() {
    let full = render(STAGES);
    let minimal: Vec<Stage> = STAGES
        .iter()
        .copied()
        .filter(|s| !UNUSED.contains(&s.name))
        .collect();
    assert_eq!(minimal.len() + UNUSED.len(), STAGES.len());
    assert!(
        render(&minimal) == full,
        "an unused stage changed the image"
    );
}

/// A render camera with `outputs: []` rendered from the command line: nothing would read the
/// image, so `shade` and `build_accel` skip with the reason (they used to render every pixel
/// and throw it away); `plan` says the same; with `-o` the image is rendered and written.
#[test]
fn a_camera_without_outputs_renders_nothing_from_the_command_line() {
    let dir = crate::common::scratch_dir("no-outputs");
    let text = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/test_plane.ron"),
    )
    .unwrap();
    let listed = r#"outputs: [(file: "test_plane.png", passes: [Beauty])]"#;
    assert!(text.contains(listed));
    let text = text.replace(listed, "outputs: []");
    std::fs::write(dir.join("none.ron"), text).unwrap();
    let o = crate::common::run_in(&dir, &["render", "none.ron", "--stats-json", "s.json"]);
    assert!(o.status.success(), "{}", crate::common::stderr_of(&o));
    let stage = |name: &str| {
        let r = crate::common::stage_row(&dir.join("s.json"), name);
        (r.ran, r.reason)
    };
    let reason = "the render camera has no outputs and no part file keeps its image";
    assert_eq!(stage("shade"), (false, reason.to_string()));
    assert_eq!(
        stage("build_accel"),
        (false, "no render camera traces rays".to_string())
    );
    let o = crate::common::run_in(&dir, &["plan", "none.ron"]);
    let plan = String::from_utf8(o.stdout).unwrap();
    assert!(
        plan.contains(&format!("shade            skip {reason}")),
        "{plan}"
    );
    let o = crate::common::run_in(&dir, &["render", "none.ron", "-o", "x.png"]);
    assert!(o.status.success(), "{}", crate::common::stderr_of(&o));
    assert!(dir.join("x.png").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The same with shapes to expand and dice: with no output to read the image, the geometry
/// stages skip too (a sphere was expanded and diced, then thrown away); with `-o` they run.
#[test]
fn a_camera_without_outputs_expands_and_dices_nothing() {
    let dir = crate::common::scratch_dir("no-outputs-geometry");
    let text = r#"Scene(
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    lights: [(name: "p", kind: Point(position: (0, -6, 3)), intensity: 5.0)],
    objects: [(name: "ball", mesh: Sphere(radius: 1.0), material: "grey")],
    instances: [(name: "b", of: "ball")],
    groups: [(name: "world", members: ["b"])],
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
        placement: LookAt(eye: (0, -6, 3), target: (0, 0, 0)), outputs: [])],
    render: (root: "world", camera: "cam"),
)"#;
    std::fs::write(dir.join("none.ron"), text).unwrap();
    let stages = |args: &[&str]| {
        let o = crate::common::run_in(&dir, args);
        assert!(o.status.success(), "{}", crate::common::stderr_of(&o));
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("s.json")).unwrap()).unwrap();
        ["expand_geometry", "tessellate", "build_accel"].map(|name| {
            let s = json["stages"]
                .as_array()
                .unwrap()
                .iter()
                .find(|s| s["stage"] == name)
                .unwrap()
                .clone();
            (
                s["ran"].as_bool().unwrap(),
                s["reason"].as_str().unwrap().to_string(),
            )
        })
    };
    let skipped = (false, "no render camera traces rays".to_string());
    assert_eq!(
        stages(&["render", "none.ron", "--stats-json", "s.json"]),
        [skipped.clone(), skipped.clone(), skipped]
    );
    let ran = stages(&[
        "render",
        "none.ron",
        "-o",
        "x.png",
        "--stats-json",
        "s.json",
    ]);
    assert!(ran.iter().all(|(ran, _)| *ran), "{ran:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

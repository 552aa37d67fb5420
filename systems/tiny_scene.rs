//! Tiny scenes for the stages' unit tests: a RON scene built from parts, loaded through the
//! real loader, and a frame for it. Test-only.

use std::path::Path;

use hecs::World;

use crate::frame::{Frame, Tasks};
use crate::scene::load_scene_str;

/// A lit square in front of a 16×12 camera, plus `objects` (RON list entries), an instance
/// `<name>_inst` of each object named in `instances`, `options` fields and extra fields of
/// the square's instance (`square`, e.g. a bake request); the root group holds them all.
pub fn scene(options: &str, square: &str, objects: &str, instances: &[&str]) -> String {
    let members: String = std::iter::once("\"square_inst\"".to_string())
        .chain(instances.iter().map(|i| format!("\"{i}\"")))
        .collect::<Vec<_>>()
        .join(", ");
    let extra_instances: String = instances
        .iter()
        .map(|i| format!("(name: \"{i}\", of: \"{}\"),", i.trim_end_matches("_inst")))
        .collect();
    format!(
        r#"Scene(
    options: (samples: 1, {options}),
    cameras: [(name: "cam", fov_y: 60.0, resolution: (16, 12),
        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "tiny.exr", passes: [Beauty])])],
    lights: [(name: "lamp", kind: Point(position: (0, 0, 2)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [
        (name: "square", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
            polygons: [[0, 1, 2, 3]], uvs: [(0, 0), (1, 0), (1, 1), (0, 1)]), material: "grey"),
        {objects}
    ],
    instances: [(name: "square_inst", of: "square", {square}), {extra_instances}],
    groups: [(name: "root", members: [{members}])],
    render: (root: "root", camera: "cam"),
)"#
    )
}

/// Loads `text` and makes a frame for a render (and a bake when `bake`).
pub fn load(text: &str, bake: bool) -> (World, Frame) {
    let scene = match load_scene_str(text, Path::new("tiny.ron")) {
        Ok(s) => s,
        Err(e) => panic!("tiny scene does not load:\n{e}\n{text}"),
    };
    let mut frame = Frame::new(scene.settings);
    frame.inputs.tasks = Tasks { render: true, bake };
    (scene.world, frame)
}

/// Runs the stages before `name` (as the runner would), leaving their outputs in `frame`.
pub fn run_until(name: &str, world: &mut World, frame: &mut Frame) {
    super::run_before(name, world, frame).expect("earlier stages run");
}

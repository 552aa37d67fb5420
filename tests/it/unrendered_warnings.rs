//! What a scene asks for but a render never does is a located warning, not silence: the
//! outputs of a camera other than the render camera (written only with `--camera`), and an
//! instance no group reachable from the render root lists. `check`, `plan` and `render`
//! print them and still succeed; the example scenes have none.

use std::path::Path;

use stagelight::scene::load_scene;

use crate::common::{dir_names, example_scenes, run_in, scratch_dir, stderr_of};

const SCENE: &str = r#"Scene(
    cameras: [
        (name: "top", fov_y: 40, resolution: (8, 8), placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0)), outputs: [(file: "top.png")]),
        (name: "side", fov_y: 40, resolution: (8, 8), placement: LookAt(eye: (5, 0, 0), target: (0, 0, 0)), outputs: [(file: "side.png")]),
    ],
    lights: [(name: "key", kind: Point(position: (0, 4, 2)), intensity: 10.0)],
    objects: [(name: "tri", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]))],
    instances: [(name: "t", of: "tri"), (name: "orphan", of: "tri")],
    groups: [(name: "world", members: ["t"])],
    render: (root: "world", camera: "top"),
)
"#;

const SIDE: &str = "s.ron:4:126: warning: camera \"side\" has outputs, but the scene renders camera \"top\": a render writes them only with --camera side\n  \
    help: `render --camera side` renders it; `render: (camera: \"side\")` makes it the scene's render camera\n";

const ORPHAN: &str = "s.ron:8:48: warning: instance \"orphan\" is never placed: no group reachable from the render root \"world\" lists it\n  \
    help: add \"orphan\" to the `members` of group \"world\" (or of a group placed in it), or remove the instance\n";

#[test]
fn check_warns_of_another_cameras_outputs_and_an_unplaced_instance() {
    let dir = scratch_dir("unrendered-check");
    std::fs::write(dir.join("s.ron"), SCENE).unwrap();
    let o = run_in(&dir, &["check", "s.ron"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(stderr_of(&o), format!("{SIDE}{ORPHAN}"));
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        "s.ron: ok (6 entities)\n"
    );
}

#[test]
fn plan_and_render_print_the_same_warnings() {
    let dir = scratch_dir("unrendered-render");
    std::fs::write(dir.join("s.ron"), SCENE).unwrap();
    let o = run_in(&dir, &["plan", "s.ron"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(
        stderr_of(&o).starts_with(&format!("{SIDE}{ORPHAN}")),
        "{}",
        stderr_of(&o)
    );
    let o = run_in(&dir, &["render", "s.ron"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(stderr_of(&o), format!("{SIDE}{ORPHAN}wrote top.png\n"));
    assert_eq!(dir_names(&dir), ["s.ron", "top.png"]);
}

/// A scene that renders everything it names has neither warning: one camera, every
/// instance placed (through a nested group too).
#[test]
fn a_scene_that_renders_all_it_names_has_no_warning() {
    let dir = scratch_dir("unrendered-none");
    let text = SCENE
        .replacen(", outputs: [(file: \"side.png\")]", "", 1)
        .replacen(
            r#"(name: "orphan", of: "tri")"#,
            r#"(name: "orphan", of: "tri"), (name: "inner", of: "sub")"#,
            1,
        )
        .replacen(
            r#"groups: [(name: "world", members: ["t"])]"#,
            r#"groups: [(name: "world", members: ["t", "inner"]), (name: "sub", members: ["orphan"])]"#,
            1,
        );
    std::fs::write(dir.join("s.ron"), text).unwrap();
    let o = run_in(&dir, &["check", "s.ron"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(stderr_of(&o), "");
}

#[test]
fn the_example_scenes_have_no_located_warnings() {
    for path in example_scenes() {
        let scene = load_scene(Path::new(&path)).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            scene.located_warnings.is_empty(),
            "{}: {:?}",
            path.display(),
            scene.located_warnings
        );
    }
}

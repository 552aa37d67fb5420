//! A refused scene shows the warnings found before its errors, as a compiler does: an
//! ignored request or an unused value is often the clue to the error — whether the reader
//! itself refused the file (RIB, `.mi`) or validation did.

use stagelight::scene::load_scene;

use crate::common::{dir_names, refused_tail, run_in, scratch_dir, stderr_of};

const RIB: &str = r#"Hider "hidden"
Format 32 32 1
Projection "perspective" "fov" 40
Translate 0 0 5
WorldBegin
LightSource "pointlight" 1 "intensity" -3
Sphere 1 -1 1 360
WorldEnd
"#;

const RON: &str = r#"Scene(
    materials: [(name: "ink", shader: Lambert(albedo: (0.5, 0.5, 0.5)),
        contour: Simple(color: (0, 0, 0, 1), width: 0.5))],
    lights: [(name: "sun", kind: Point(position: (0, 0, 3)), intensity: -10.0)],
    objects: [(name: "ball", mesh: Sphere(radius: 1.0), material: "ink")],
    instances: [(name: "b", of: "ball")],
    groups: [(name: "world", members: ["b"])],
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)), outputs: [(file: "o.png")])],
    render: (root: "world", camera: "cam"),
)
"#;

#[test]
fn a_rib_reader_warning_is_shown_with_a_validation_error() {
    let dir = scratch_dir("warn-err-rib");
    std::fs::write(dir.join("a.rib"), RIB).unwrap();
    let o = run_in(&dir, &["render", "a.rib", "-o", "o.png"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "a.rib:1:1: warning: ignored request \"Hider\"\n\
         a.rib:6:40: error: intensity must not be negative, found -3\n  \
         help: intensity takes 0 or more: write 3 if only the sign is wrong\n\
         1 error and 1 warning in a.rib; nothing rendered\n"
    );
    assert_eq!(dir_names(&dir), ["a.rib"]);
}

#[test]
fn a_validation_warning_is_shown_with_a_validation_error() {
    let dir = scratch_dir("warn-err-ron");
    std::fs::write(dir.join("s.ron"), RON).unwrap();
    let o = run_in(&dir, &["check", "s.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "s.ron:3:18: warning: material \"ink\" has a contour shader, but no camera output shows contours\n  \
         help: add an output such as `(file: \"lines.svg\")` or a `Contours` pass\n\
         s.ron:4:73: error: intensity must not be negative, found -10\n  \
         help: intensity takes 0 or more: write 10 if only the sign is wrong\n\
         1 error and 1 warning in s.ron\n"
    );
}

#[test]
fn the_library_error_carries_the_warnings() {
    let dir = scratch_dir("warn-err-lib");
    std::fs::write(dir.join("s.ron"), RON).unwrap();
    let Err(refused) = load_scene(&dir.join("s.ron")) else {
        panic!("the scene has a negative intensity");
    };
    assert_eq!(refused.0.len(), 1);
    assert_eq!(refused.1.len(), 1);
    assert!(refused.1[0].contains(": warning: material \"ink\" has a contour shader"));
    let shown = refused.to_string();
    assert!(shown.find("warning:") < shown.find("error:"), "{shown}");
}

#[test]
fn a_rib_reader_warning_is_shown_with_a_reader_error() {
    let dir = scratch_dir("warn-err-rib-reader");
    let text = RIB.replace("Sphere 1 -1 1 360", "Sphere 1 -1 1 360 extra");
    std::fs::write(dir.join("a.rib"), text).unwrap();
    for command in ["render", "convert"] {
        let o = run_in(&dir, &[command, "a.rib", "-o", "o.ron"]);
        assert_eq!(o.status.code(), Some(1));
        assert_eq!(
            stderr_of(&o),
            format!(
                "a.rib:1:1: warning: ignored request \"Hider\"\n\
                 a.rib:7:19: error: unknown request \"extra\"\n\
                 1 error and 1 warning in a.rib{}\n",
                refused_tail(command)
            ),
            "{command}"
        );
        assert_eq!(dir_names(&dir), ["a.rib"]);
    }
}

#[test]
fn a_mi_reader_warning_is_shown_with_a_reader_error() {
    let dir = scratch_dir("warn-err-mi-reader");
    let plane = std::fs::read_to_string("assets/seeds/mi/plane.mi").unwrap();
    let text = plane.replace("samples -1 2\n", "samples -1 2\nbogus_option 3\n");
    let line = 1 + text.lines().position(|l| l == "bogus_option 3").unwrap();
    let output = 1 + text.lines().position(|l| l.starts_with("output")).unwrap();
    std::fs::write(dir.join("p.mi"), text).unwrap();
    let o = run_in(&dir, &["check", "p.mi"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        format!(
            "p.mi:{output}:14: warning: output \"test.rgb\" is written as \"test.png\" (stagelight writes PNG and EXR files, not format \"rgb\")\n\
             p.mi:{line}:1: error: unknown option \"bogus_option\"\n\
             1 error and 1 warning in p.mi\n"
        )
    );
}

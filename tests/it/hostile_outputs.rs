//! Issue 18, families 5 and 6: outputs never overwrite an input or each other (refused
//! before anything runs, `check` included), and a run's files are committed all or nothing.

use crate::common::{
    dir_names, quad_object, refused_tail, run_in, scratch_dir, small_scene, stderr_of,
};

const HELP: &str = "  help: give every output its own file, and none the name of an input";

fn quad_scene(outputs: &str, extra_instance: &str) -> String {
    small_scene(
        &quad_object("quad"),
        &format!(r#"(name: "q", of: "quad"{extra_instance})"#),
        outputs,
        "",
    )
}

#[test]
fn stats_json_onto_the_scene_is_refused_and_the_scene_kept() {
    let dir = scratch_dir("out-stats-scene");
    let text = quad_scene(r#"(file: "out.png")"#, "");
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    let o = run_in(&dir, &["render", "scene.ron", "--stats-json", "scene.ron"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        format!("error: --stats-json scene.ron would overwrite the scene file scene.ron\n{HELP}\n1 error in scene.ron; nothing rendered\n")
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("scene.ron")).unwrap(),
        text
    );
    assert_eq!(dir_names(&dir), ["scene.ron"]);
}

#[test]
fn stats_json_onto_the_image_is_refused() {
    let dir = scratch_dir("out-stats-image");
    std::fs::write(dir.join("scene.ron"), quad_scene("", "")).unwrap();
    let o = run_in(
        &dir,
        &[
            "render",
            "scene.ron",
            "-o",
            "out.png",
            "--stats-json",
            "./out.png",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        format!("error: --stats-json ./out.png is also written by -o out.png\n{HELP}\n1 error in scene.ron; nothing rendered\n")
    );
    assert_eq!(dir_names(&dir), ["scene.ron"]);
}

#[test]
fn two_camera_outputs_with_one_file_are_refused_at_check() {
    let dir = scratch_dir("out-camera-twice");
    std::fs::write(
        dir.join("scene.ron"),
        quad_scene(r#"(file: "a.exr"), (file: "a.exr", passes: [Depth])"#, ""),
    )
    .unwrap();
    for command in ["check", "render"] {
        let expected = format!("scene.ron:10:97: error: camera \"cam\" output 2 (\"a.exr\") is also written by camera \"cam\" output 1 (\"a.exr\")\n{HELP}\n1 error in scene.ron{}\n", refused_tail(command));
        let o = run_in(&dir, &[command, "scene.ron"]);
        assert_eq!(o.status.code(), Some(1), "{command}");
        assert_eq!(stderr_of(&o), expected, "{command}");
    }
    assert_eq!(dir_names(&dir), ["scene.ron"]);
}

#[test]
fn two_bake_outputs_with_one_file_are_refused_at_check() {
    let dir = scratch_dir("out-bake-twice");
    std::fs::write(
        dir.join("scene.ron"),
        quad_scene(
            "",
            r#", bake: (resolution: (8, 8), outputs: [(kind: AmbientOcclusion(samples: 1), file: "t.exr"), (kind: Positions, file: "t.exr")])"#,
        ),
    )
    .unwrap();
    for command in ["check", "bake"] {
        let expected = format!("scene.ron:7:17: error: bake request on instance \"q\" (\"./t.exr\") is also written by bake request on instance \"q\" (\"./t.exr\")\n{HELP}\n1 error in scene.ron{}\n", refused_tail(command));
        let o = run_in(&dir, &[command, "scene.ron"]);
        assert_eq!(o.status.code(), Some(1), "{command}");
        assert_eq!(stderr_of(&o), expected, "{command}");
    }
    assert_eq!(dir_names(&dir), ["scene.ron"]);
}

#[test]
fn an_output_onto_a_texture_input_is_refused() {
    let dir = scratch_dir("out-texture");
    crate::common::png::write_rgb(&dir.join("tex.png"), 2, 2, &[[200, 100, 50]; 4]);
    let before = std::fs::read(dir.join("tex.png")).unwrap();
    let scene = quad_scene("", "").replace(
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5))"#,
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5)), bind: {"albedo": Image(file: "tex.png")}"#,
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["render", "scene.ron", "-o", "tex.png"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        format!("error: -o tex.png would overwrite an input of the scene tex.png\n{HELP}\n1 error in scene.ron; nothing rendered\n")
    );
    assert_eq!(std::fs::read(dir.join("tex.png")).unwrap(), before);
}

#[test]
fn convert_onto_its_own_scene_is_refused() {
    let dir = scratch_dir("out-convert");
    let text = quad_scene("", "");
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    let o = run_in(&dir, &["convert", "scene.ron", "-o", "./scene.ron"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        "error: -o ./scene.ron would overwrite the scene input scene.ron\n  help: write the RON scene to another file\n"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("scene.ron")).unwrap(),
        text
    );
}

#[test]
fn a_failing_second_output_leaves_the_first_as_it_was() {
    let dir = scratch_dir("out-all-or-nothing");
    std::fs::write(dir.join("a.exr"), b"previous run").unwrap();
    std::fs::create_dir(dir.join("b.exr")).unwrap();
    std::fs::write(
        dir.join("scene.ron"),
        quad_scene(r#"(file: "a.exr"), (file: "b.exr")"#, ""),
    )
    .unwrap();
    let o = run_in(
        &dir,
        &[
            "render",
            "scene.ron",
            "--spp",
            "1",
            "--stats-json",
            "s.json",
        ],
    );
    // Refused before the first stage now (it failed at the commit, which rolled back the
    // first file: `src/image_io/atomic.rs` tests that roll-back).
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:10:97: error: camera \"cam\" output 2 (\"b.exr\") is a directory\n  help: give the path of a file, not of a directory\n1 error in scene.ron; nothing rendered\n"
    );
    assert_eq!(std::fs::read(dir.join("a.exr")).unwrap(), b"previous run");
    assert_eq!(dir_names(&dir), ["a.exr", "b.exr", "scene.ron"]);
}

/// A RIB archive is an input: `-o` onto it is refused and the archive kept.
#[test]
fn an_output_onto_a_rib_archive_is_refused() {
    let dir = scratch_dir("out-rib-archive");
    std::fs::write(
        dir.join("scene.rib"),
        "Display \"out.png\" \"file\" \"rgb\"\nFormat 8 8 1\nProjection \"perspective\" \"fov\" 40\nWorldBegin\nReadArchive \"part.exr\"\nWorldEnd\n",
    )
    .unwrap();
    std::fs::write(dir.join("part.exr"), "Sphere 1 -1 1 360\n").unwrap();
    let o = run_in(&dir, &["render", "scene.rib", "-o", "part.exr"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        format!("error: -o part.exr would overwrite an input of the scene part.exr\n{HELP}\n1 error in scene.rib; nothing rendered\n")
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("part.exr")).unwrap(),
        "Sphere 1 -1 1 360\n"
    );
    assert_eq!(dir_names(&dir), ["part.exr", "scene.rib"]);
}

/// An `-o` that is also one of the scene's own outputs is a usage error (exit 2) like an
/// `-o` over an input: a flag takes part in the clash (it exited 1, as a scene error).
#[test]
fn an_output_flag_equal_to_a_scene_output_is_a_usage_error() {
    let dir = scratch_dir("out-flag-scene-output");
    std::fs::write(
        dir.join("scene.ron"),
        quad_scene(r#"(file: "a.png"), (file: "b.exr", passes: [Depth])"#, ""),
    )
    .unwrap();
    let o = run_in(&dir, &["render", "scene.ron", "-o", "b.exr"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        format!("scene.ron:10:97: error: camera \"cam\" output 2 (\"b.exr\") is also written by -o b.exr\n{HELP}\n1 error in scene.ron; nothing rendered\n")
    );
    assert_eq!(dir_names(&dir), ["scene.ron"]);
}

/// An OBJ mesh's MTL file is an input of the scene, not the scene file: it read "would
/// overwrite the scene file cube.mtl" (the MTL came first in the list of inputs).
#[test]
fn an_output_onto_an_mtl_file_names_it_an_input() {
    let dir = scratch_dir("out-mtl");
    std::fs::write(
        dir.join("cube.obj"),
        "mtllib cube.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n",
    )
    .unwrap();
    std::fs::write(dir.join("cube.mtl"), "newmtl red\nKd 0.8 0.1 0.1\n").unwrap();
    let text = small_scene(
        r#"(name: "box", mesh: Obj(file: "cube.obj")),"#,
        r#"(name: "b", of: "box")"#,
        r#"(file: "cube.mtl", format: Png)"#,
        "",
    );
    std::fs::write(dir.join("scene.ron"), text).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        format!("scene.ron:10:80: error: camera \"cam\" output 1 (\"cube.mtl\") would overwrite an input of the scene cube.mtl\n{HELP}\n1 error in scene.ron\n")
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("cube.mtl")).unwrap(),
        "newmtl red\nKd 0.8 0.1 0.1\n"
    );
}

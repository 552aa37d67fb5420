//! Issue 18, family 1: finite but extreme coordinates are refused with a located error that
//! names the object and the supported extent, at `check` and `render`, never a panic in the
//! BVH build.

use crate::common::{quad_object, refused_tail, run_in, scratch_dir, small_scene, stderr_of};

const HELP: &str = "  help: scale the scene down (far-away scenes are rebased automatically: only the extent counts), or leave out the distant geometry";

fn message(object: &str, reach: &str) -> String {
    format!("object \"{object}\": its placed geometry reaches {reach} units from the scene origin; the supported scene extent is ±1e12 units around it")
}

#[test]
fn a_quad_scaled_by_1e19_is_refused_by_check_and_render() {
    let dir = scratch_dir("extent-scaled");
    let scene = small_scene(
        &quad_object("quad"),
        r#"(name: "q", of: "quad", transform: [Scale((1e19, 1e19, 1e19))])"#,
        r#"(file: "out.png")"#,
        "",
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    for command in ["check", "render"] {
        let expected = format!(
            "scene.ron:5:9: error: {}\n{HELP}\n1 error in scene.ron{}\n",
            message("quad", "1.0e19"),
            refused_tail(command)
        );
        let o = run_in(&dir, &[command, "scene.ron"]);
        assert_eq!(o.status.code(), Some(1), "{command}: {}", stderr_of(&o));
        assert_eq!(stderr_of(&o), expected, "{command}");
    }
    assert!(!dir.join("out.png").exists());
}

#[test]
fn obj_vertices_at_1e38_are_refused() {
    let dir = scratch_dir("extent-obj");
    std::fs::write(
        dir.join("far.obj"),
        "v -1e38 -1e38 0\nv 1e38 -1e38 0\nv 1e38 1e38 0\nv -1e38 1e38 0\nf 1 2 3 4\n",
    )
    .unwrap();
    let scene = small_scene(
        r#"(name: "far", mesh: Obj(file: "far.obj")),"#,
        r#"(name: "f", of: "far")"#,
        "",
        "",
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        format!(
            "scene.ron:5:9: error: {}\n{HELP}\n1 error in scene.ron\n",
            message("far", "1.0e38")
        )
    );
}

#[test]
fn generated_geometry_beyond_the_extent_is_refused_when_built() {
    let dir = scratch_dir("extent-generated");
    // A scaled geometry shader is refused at load by its transform; a huge one by its
    // triangles once `build_accel` has them.
    let scene = small_scene(
        r#"(name: "ball", mesh: Sphere(radius: 1), material: "grey"),
        (name: "floor", mesh: Grid(size_x: 1e13, size_y: 1e13), material: "grey"),"#,
        r#"(name: "b", of: "ball", transform: [Scale((1e20, 1e20, 1e20))])"#,
        "",
        "",
    );
    std::fs::write(dir.join("scaled.ron"), &scene).unwrap();
    let o = run_in(&dir, &["check", "scaled.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        format!(
            "scaled.ron:5:9: error: {}\n{HELP}\n1 error in scaled.ron\n",
            message("ball", "1.0e20")
        )
    );
    let scene = scene
        .replace(r#"(name: "b", of: "ball""#, r#"(name: "g", of: "floor""#)
        .replace(r#"members: ["b"]"#, r#"members: ["g"]"#)
        .replace(r#", transform: [Scale((1e20, 1e20, 1e20))]"#, "");
    std::fs::write(dir.join("huge.ron"), &scene).unwrap();
    let o = run_in(&dir, &["check", "huge.ron"]);
    assert!(
        o.status.success(),
        "the grid's size is only known once it is built"
    );
    let o = run_in(&dir, &["render", "huge.ron", "-o", "out.png"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        format!(
            "huge.ron:6:9: error: {}\n{HELP}\n",
            message("floor", "5.0e12")
        )
    );
    assert!(!dir.join("out.png").exists());
}

#[test]
fn a_quad_within_the_extent_renders() {
    let dir = scratch_dir("extent-ok");
    let scene = small_scene(
        &quad_object("quad"),
        r#"(name: "q", of: "quad", transform: [Scale((1e11, 1e11, 1))])"#,
        "",
        "",
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(
        &dir,
        &["render", "scene.ron", "-o", "out.png", "--spp", "1"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let img = crate::common::png::read(&dir.join("out.png"));
    assert!(
        crate::common::png::rgb8(&img, 4, 4)[0] > 0,
        "the quad fills the view and is lit"
    );
}

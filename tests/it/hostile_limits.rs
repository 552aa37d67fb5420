//! Issue 18, families 3, 4 and 9: bounded recursion (RON nesting, phenomenon chains),
//! bounded thread counts and file sizes, and a UTF-8 byte order mark accepted.

use crate::common::{quad_object, run_in, scratch_dir, small_scene, stderr_of};

#[test]
fn threads_above_the_limit_are_refused() {
    let dir = scratch_dir("threads-limit");
    let o = run_in(&dir, &["render", "scene.ron", "--threads", "100000"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        "error: invalid value '100000' for '--threads <THREADS>': 100000 is not in 1..=1024\n\nFor more information, try '--help'.\n"
    );
}

#[test]
fn deeply_nested_shader_nodes_state_the_limit() {
    let dir = scratch_dir("ron-nesting");
    let mut node = "(0.5, 0.5, 0.5)".to_string();
    for _ in 0..80 {
        node = format!("Mul({node}, (1, 1, 1))");
    }
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "").replace(
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5))"#,
        &format!(r#"shader: Lambert(albedo: (1, 1, 1)), bind: {{"albedo": {node}}}"#),
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    let stderr = stderr_of(&o);
    assert!(
        stderr.starts_with("scene.ron:2:"),
        "located in the file: {stderr}"
    );
    assert!(
        stderr.contains(": error: values nested deeper than 128 levels\n  help: a scene file nests at most that deep: declare inner shader nodes as phenomena and call them with Graph(…)\n"),
        "{stderr}"
    );
    assert!(!stderr.contains("recursion_limit"), "{stderr}");
}

#[test]
fn a_chain_of_phenomena_beyond_the_limit_is_refused_where_it_starts() {
    let dir = scratch_dir("phenomenon-chain");
    let n = 3000;
    let mut phenomena = Vec::new();
    for i in 0..n {
        let body = if i + 1 < n {
            format!(r#"Graph("p{}", {{}})"#, i + 1)
        } else {
            "(0.5, 0.5, 0.5)".to_string()
        };
        phenomena.push(format!(r#"(name: "p{i}", output: {body})"#));
    }
    let scene = small_scene(
        &quad_object("quad"),
        r#"(name: "q", of: "quad")"#,
        "",
        &format!("    phenomena: [\n{}\n    ],\n", phenomena.join(",\n")),
    )
    .replace(
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5))"#,
        r#"shader: Lambert(albedo: (1, 1, 1)), bind: {"albedo": Graph("p0", {})}"#,
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:13:22: error: phenomenon \"p0\" starts a chain of 3000 nested phenomenon calls (p0 → p1 → … → p2999); the limit is 64\n  help: call fewer phenomena inside each other: inline some of them\n1 error in scene.ron; nothing rendered\n"
    );
}

#[test]
fn an_endless_include_stops_at_the_size_limit() {
    let dir = scratch_dir("include-dev-zero");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.ron")).unwrap();
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "").replacen(
        "Scene(\n",
        "Scene(\n    include: [\"zero.ron\"],\n",
        1,
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:2:15: error: cannot read include file \"zero.ron\": larger than 64 MiB, the limit for a scene file\n1 error in scene.ron; nothing rendered\n"
    );
}

#[test]
fn a_byte_order_mark_before_the_scene_is_accepted() {
    let dir = scratch_dir("bom");
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "");
    std::fs::write(dir.join("scene.ron"), format!("\u{feff}{scene}")).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
}

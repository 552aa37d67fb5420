//! Issue 18, family 2: runs that would need more memory than the budget are refused up
//! front, at `check` and before the first stage, with a located error naming the element,
//! the estimate and the budget. The big cases run under `ulimit -v` (4 GiB of address
//! space): had anything of the estimated size been allocated, the process would abort
//! instead of printing the refusal.

use std::process::Command;

use crate::common::{quad_object, run_in, scratch_dir, small_scene, stderr_of};

const HELP_TAIL: &str = ", or raise the budget with --memory-limit BYTES";

/// Runs `stagelight args…` in `dir` under a 4 GiB address-space limit.
fn run_limited(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    let bin = env!("CARGO_BIN_EXE_stagelight");
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v 4194304 && exec \"{bin}\" \"$@\""))
        .arg("sh")
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run stagelight")
}

#[test]
fn a_100000_squared_frame_is_refused_before_allocating() {
    let dir = scratch_dir("budget-frame");
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "")
        .replace("resolution: (8, 8)", "resolution: (100000, 100000)");
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let expected = format!(
        "scene.ron:9:15: error: camera \"cam\": the frame buffers of 100000×100000 pixels need about 2.3 TiB, more than the memory budget of 4.0 GiB (the address-space limit (ulimit -v))\n  help: lower the camera's resolution{HELP_TAIL}\n1 error in scene.ron; nothing rendered\n"
    );
    for args in [
        &["check", "scene.ron"][..],
        &["render", "scene.ron", "-o", "out.png"],
    ] {
        let o = run_limited(&dir, args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr_of(&o));
        assert_eq!(stderr_of(&o), expected, "{args:?}");
    }
    assert!(!dir.join("out.png").exists());
}

#[test]
fn grids_surfaces_scatters_photons_and_bakes_are_estimated_from_their_parameters() {
    let dir = scratch_dir("budget-elements");
    let scene = small_scene(
        r#"(name: "floor", mesh: Grid(nx: 16384, ny: 16384), material: "grey"),
        (name: "ball", mesh: Sphere(radius: 1), approximation: Parametric(u: 4096, v: 4096)),
        (name: "pebble", mesh: Sphere(radius: 0.1), approximation: Parametric(u: 4, v: 4)),
        (name: "ground", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]])),
        (name: "pebbles", mesh: Scatter(prototype: "pebble", surface: "ground", count: 10000000)),"#,
        r#"(name: "f", of: "floor"), (name: "b", of: "ball"), (name: "p", of: "pebbles"),
           (name: "g", of: "ground", bake: (resolution: (16384, 16384), outputs: [(kind: AmbientOcclusion())]))"#,
        "",
        "    options: (caustics: (photons: 4000000000)),\n",
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_limited(&dir, &["check", "scene.ron", "--memory-limit", "1G"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    let budget = "more than the memory budget of 1.0 GiB (--memory-limit)";
    let expected = [
        format!("scene.ron:5:9: error: object \"floor\": 536870912 triangles of a 16384×16384 grid need about 192.0 GiB, {budget}\n  help: use fewer or coarser triangles{HELP_TAIL}"),
        format!("scene.ron:6:9: error: object \"ball\": 268435456 triangles of 8 patch(es) diced 4096×4096 need about 96.0 GiB, {budget}\n  help: use fewer or coarser triangles{HELP_TAIL}"),
        format!("scene.ron:9:9: error: object \"pebbles\": 10000000 scattered copies of 256 triangles need about 920.3 GiB, {budget}\n  help: use fewer or coarser triangles{HELP_TAIL}"),
        format!("scene.ron:17:25: error: options.caustics: the 4000000000 photons of the photon map need about 953.7 GiB, {budget}\n  help: emit fewer photons{HELP_TAIL}"),
        format!("scene.ron:12:12: error: bake request on instance \"g\": 2 texture(s) of 16384×16384 texels need about 64.0 GiB, {budget}\n  help: lower the bake resolution{HELP_TAIL}"),
    ];
    let stderr = stderr_of(&o);
    for e in &expected {
        assert!(stderr.contains(e.as_str()), "missing\n{e}\nin\n{stderr}");
    }
    assert!(
        stderr.ends_with("5 errors in scene.ron; nothing rendered\n"),
        "{stderr}"
    );
}

#[test]
fn a_tiny_spatial_edge_fails_at_tessellate_before_dicing() {
    let dir = scratch_dir("budget-spatial");
    let scene = small_scene(
        r#"(name: "ball", mesh: Sphere(radius: 1), approximation: Spatial(edge: 0.000001, max_subdiv: 12)),"#,
        r#"(name: "b", of: "ball")"#,
        "",
        "",
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "1G"]);
    assert!(
        o.status.success(),
        "adaptive rates are only known at tessellate"
    );
    let o = run_limited(
        &dir,
        &[
            "render",
            "scene.ron",
            "-o",
            "out.png",
            "--memory-limit",
            "1G",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        "error: object \"ball\": its approximation would make 268435456 triangles, more than the 2796202 the memory budget allows (coarsen the approximation, or raise --memory-limit)\n"
    );
    assert!(!dir.join("out.png").exists());
}

#[test]
fn a_scene_within_the_budget_renders() {
    let dir = scratch_dir("budget-ok");
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "");
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(
        &dir,
        &[
            "render",
            "scene.ron",
            "-o",
            "out.png",
            "--spp",
            "1",
            "--memory-limit",
            "64M",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "1K"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:9:15: error: camera \"cam\": the frame buffers of 8×8 pixels need about 16.0 KiB, more than the memory budget of 1.0 KiB (--memory-limit)\n  help: lower the camera's resolution, or raise the budget with --memory-limit BYTES\n1 error in scene.ron; nothing rendered\n"
    );
}

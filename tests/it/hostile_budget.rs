//! Issue 18, family 2: runs that would need more memory than the budget are refused up
//! front, at `check` and before the first stage, with a located error naming the element,
//! the estimate and the budget. The big cases run under `ulimit -v` (4 GiB of address
//! space): had anything of the estimated size been allocated, the process would abort
//! instead of printing the refusal.

use crate::common::{
    quad_object, refused_tail, run_in, run_limited, scratch_dir, small_scene, stderr_of,
};

const HELP_TAIL: &str = ", or raise the budget with --memory-limit BYTES";

#[test]
fn a_100000_squared_frame_is_refused_before_allocating() {
    let dir = scratch_dir("budget-frame");
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "")
        .replace("resolution: (8, 8)", "resolution: (100000, 100000)");
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    for args in [
        &["check", "scene.ron"][..],
        &["render", "scene.ron", "-o", "out.png"],
    ] {
        let expected = format!(
            "scene.ron:9:55: error: camera \"cam\": the frame buffers of 100000×100000 pixels need about 2.3 TiB, more than the memory budget of 4.0 GiB (the address-space limit (ulimit -v))\n  help: lower the camera's resolution{HELP_TAIL}\n1 error in scene.ron{}\n",
            refused_tail(args[0])
        );
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
        format!("scene.ron:6:64: error: object \"ball\": 268435456 triangles of 8 patch(es) diced 4096×4096 need about 96.0 GiB, {budget}\n  help: use fewer or coarser triangles{HELP_TAIL}"),
        format!("scene.ron:9:9: error: object \"pebbles\": 10000000 scattered copies of 256 triangles need about 920.3 GiB, {budget}\n  help: use fewer or coarser triangles{HELP_TAIL}"),
        format!("scene.ron:17:25: error: options.caustics: the 4000000000 photons of the photon map need about 953.7 GiB, {budget}\n  help: emit fewer photons{HELP_TAIL}"),
        format!("scene.ron:12:12: error: bake request on instance \"g\": 2 texture(s) of 16384×16384 texels need about 64.0 GiB, {budget}\n  help: lower the bake resolution{HELP_TAIL}"),
    ];
    let stderr = stderr_of(&o);
    for e in &expected {
        assert!(stderr.contains(e.as_str()), "missing\n{e}\nin\n{stderr}");
    }
    assert!(stderr.ends_with("5 errors in scene.ron\n"), "{stderr}");
}

/// An adaptive approximation's triangles are known only once diced: `check` warns, at the
/// approximation, that its worst case (every patch edge at 2^max_subdiv segments) exceeds
/// the budget, and `render` refuses it at `tessellate`, located at the same value.
#[test]
fn a_tiny_spatial_edge_warns_at_check_and_fails_at_tessellate_before_dicing() {
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
        "a worst case is a warning: {}",
        stderr_of(&o)
    );
    assert_eq!(
        stderr_of(&o),
        "scene.ron:5:64: warning: object \"ball\": its adaptive approximation may make up to 268435456 triangles (8 patch(es) × 4096² at max_subdiv 12, about 96.0 GiB), more than the 2796202 the memory budget of 1.0 GiB (--memory-limit) allows one object; render refuses it if dicing makes more\n  help: adaptive rates usually stay far below this bound; to be sure it fits, set `max_subdiv: 8` (at most 1048576 triangles), or raise the budget with --memory-limit BYTES\n"
    );
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        "scene.ron: ok (5 entities)\n"
    );
    // Within the budget's bound, no warning.
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "100G"]);
    assert!(o.status.success());
    assert_eq!(stderr_of(&o), "");
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
        "scene.ron:5:64: error: object \"ball\": its approximation would make 268435456 triangles, about 96.0 GiB, more than the 2796202 the memory budget of 1.0 GiB (--memory-limit) allows one object\n  help: coarsen the approximation (a larger `edge` or `distance`, a smaller `max_subdiv`), or raise the budget with --memory-limit BYTES\n"
    );
    assert!(!dir.join("out.png").exists());
}

/// A raster-space approximation around the camera (points behind it want the finest rate):
/// the same warning at `check`, the same located refusal at `render`.
#[test]
fn a_raster_approximation_around_the_camera_is_warned_and_refused_where_it_is_written() {
    let dir = scratch_dir("budget-raster");
    let scene = small_scene(
        r#"(name: "dome", mesh: Sphere(radius: 10),
            approximation: Spatial(edge: 0.5, space: Raster, max_subdiv: 12)),"#,
        r#"(name: "d", of: "dome")"#,
        "",
        "",
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "4G"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert!(
        stderr_of(&o).starts_with("scene.ron:6:28: warning: object \"dome\": its adaptive approximation may make up to 268435456 triangles"),
        "{}",
        stderr_of(&o)
    );
    let o = run_limited(
        &dir,
        &[
            "render",
            "scene.ron",
            "-o",
            "out.png",
            "--memory-limit",
            "4G",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert!(
        stderr_of(&o)
            .starts_with("scene.ron:6:28: error: object \"dome\": its approximation would make "),
        "{}",
        stderr_of(&o)
    );
    assert!(!dir.join("out.png").exists());
}

/// `--memory-limit` reads `KB`, `MB`, `GB`, `TB` as the binary units `K`, `M`, `G`, `T`.
#[test]
fn a_memory_limit_in_gb_is_the_binary_unit() {
    let dir = scratch_dir("budget-units");
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "");
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "1KB"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr_of(&o).contains("more than the memory budget of 1.0 KiB (--memory-limit)"),
        "{}",
        stderr_of(&o)
    );
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "1GB"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "1Q"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr_of(&o).contains("unknown unit \"q\" (use K, M, G or T, binary: 1G = 1073741824 bytes; KB, MB, GB, TB and KiB… mean the same)"),
        "{}",
        stderr_of(&o)
    );
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
        "scene.ron:9:55: error: camera \"cam\": the frame buffers of 8×8 pixels need about 16.0 KiB, more than the memory budget of 1.0 KiB (--memory-limit)\n  help: lower the camera's resolution, or raise the budget with --memory-limit BYTES\n1 error in scene.ron\n"
    );
}

/// The frame's refusal is located at the value to change, the resolution's width: RIB's
/// `Format`, `.mi`'s `resolution`, RON's `resolution` (tester report 45, problem 5: it was
/// located at the `WorldBegin` and at the camera instance).
#[test]
fn a_frame_over_the_budget_is_located_at_its_resolution() {
    let dir = scratch_dir("budget-frame-located");
    let rib = "Display \"out.png\" \"file\" \"rgb\"\nFormat 64 64 1\nProjection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nWorldBegin\nPolygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]\nWorldEnd\n";
    std::fs::write(dir.join("f.rib"), rib).unwrap();
    let mi = "link \"base.so\"\n$include <base.mi>\noptions \"opt\" samples 0 0 object space end options\ncamera \"Cam\" output \"rgb\" \"png\" \"out.png\" focal 1 aperture 1 aspect 1\n  resolution 64 64\nend camera\ninstance \"Cam_inst\" \"Cam\" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance\nmaterial \"m\" opaque \"mib_illum_lambert\" (\"ambient\" 1 1 1) end material\nobject \"Tri\" group 0 0 0  1 0 0  0 1 0  v 0 v 1 v 2  p \"m\" 0 1 2 end group end object\ninstance \"Tri_inst\" \"Tri\" material \"m\" end instance\ninstgroup \"root\" \"Cam_inst\" \"Tri_inst\" end instgroup\nrender \"root\" \"Cam_inst\" \"opt\"\n";
    std::fs::write(dir.join("f.mi"), mi).unwrap();
    let refusal = "the frame buffers of 64×64 pixels need about 1.0 MiB, more than the memory budget of 64.0 KiB (--memory-limit)\n  help: lower the camera's resolution, or raise the budget with --memory-limit BYTES";
    for (scene, at) in [
        ("f.rib", "f.rib:2:8: error: camera \"camera\""),
        ("f.mi", "f.mi:5:14: error: camera \"Cam_inst\""),
    ] {
        let o = run_in(&dir, &["check", scene, "--memory-limit", "64K"]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
        assert_eq!(
            stderr_of(&o),
            format!("{at}: {refusal}\n1 error in {scene}\n")
        );
    }
}

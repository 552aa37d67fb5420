//! The command line end to end: exit codes, outputs, overrides, reports, determinism across
//! thread counts, and refusal of bad scenes without partial output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_stagelight"))
}

fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/scenes")
        .join(name)
}

fn scratch(test: &str) -> PathBuf {
    let dir =
        crate::common::scratch_root().join(format!("stagelight-cli-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(cmd: &mut Command) -> Output {
    cmd.output().expect("run stagelight")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn render_writes_the_requested_png() {
    let dir = scratch("png");
    let out = dir.join("plane.png");
    let o = run(bin()
        .args(["render"])
        .arg(asset("test_plane.ron"))
        .arg("-o")
        .arg(&out)
        .args(["--spp", "1"]));
    assert!(o.status.success(), "{}", stderr(&o));
    let img = crate::common::png::read(&out);
    assert_eq!((img.width, img.height), (508, 380));
    // The plane faces the light at the camera: the centre is lit, a corner (background) black.
    let rgb = |x, y| crate::common::png::rgb8(&img, x, y);
    assert!(rgb(254, 190)[0] > 100);
    assert_eq!(rgb(0, 0)[0], 0);
}

#[test]
fn exr_is_byte_identical_at_one_and_two_threads() {
    let dir = scratch("threads");
    let mut files = Vec::new();
    for threads in ["1", "2"] {
        let out = dir.join(format!("cornell_{threads}.exr"));
        let o = run(bin()
            .args(["render"])
            .arg(asset("cornell_box.ron"))
            .arg("-o")
            .arg(&out)
            .args(["--spp", "2", "--threads", threads]));
        assert!(o.status.success(), "{}", stderr(&o));
        files.push(std::fs::read(&out).unwrap());
    }
    assert!(
        files[0] == files[1],
        "EXR differs between --threads 1 and --threads 2"
    );
}

#[test]
fn stats_json_lists_every_stage_with_its_reason() {
    let dir = scratch("stats");
    let json = dir.join("stats.json");
    let o = run(bin()
        .args(["render"])
        .arg(asset("test_plane.ron"))
        .arg("-o")
        .arg(dir.join("p.png"))
        .args(["--spp", "1", "--stats"])
        .arg("--stats-json")
        .arg(&json));
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("build_accel") && stdout.contains("write_output"),
        "{stdout}"
    );
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let stages = v["stages"].as_array().unwrap();
    let names: Vec<&str> = stages
        .iter()
        .map(|s| s["stage"].as_str().unwrap())
        .collect();
    let pos = |n: &str| {
        names
            .iter()
            .position(|x| *x == n)
            .unwrap_or_else(|| panic!("{n} missing in {names:?}"))
    };
    assert!(pos("expand_geometry") < pos("tessellate") && pos("tessellate") < pos("build_accel"));
    assert!(pos("build_accel") < pos("bake_lightmaps") && pos("bake_lightmaps") < pos("shade"));
    assert!(pos("shade") < pos("write_output"));
    for s in stages {
        for key in ["stage", "ran", "reason", "seconds", "items"] {
            assert!(s.get(key).is_some(), "missing {key} in {s}");
        }
        let name = s["stage"].as_str().unwrap();
        let expect_ran = matches!(name, "build_accel" | "shade" | "write_output");
        assert_eq!(s["ran"], expect_ran, "{s}");
        assert!(!s["reason"].as_str().unwrap().is_empty());
    }
    assert_eq!(stages[pos("bake_lightmaps")]["reason"], "no bake requests");
    assert_eq!(
        stages[pos("expand_geometry")]["reason"],
        "no procedural geometry"
    );
    let stages: Vec<&serde_json::Value> = stages
        .iter()
        .filter(|s| s["stage"] == "build_accel")
        .collect();
    assert_eq!(stages[0]["items"], 2);
}

#[test]
fn check_accepts_every_example() {
    for scene in ["test_plane.ron", "cornell_box.ron", "default_surface.ron"] {
        let o = run(bin().arg("check").arg(asset(scene)));
        assert!(o.status.success(), "{scene}: {}", stderr(&o));
    }
}

fn write(path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
}

#[test]
fn bad_scene_exits_1_with_location_and_writes_nothing() {
    let dir = scratch("bad");
    let scene = dir.join("bad.ron");
    let out = dir.join("never.png");
    write(
        &scene,
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
               placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)),
               outputs: [(file: "never.png")])],
    materials: [(name: "chrome", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "quad", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]), material: "chrom")],
    instances: [(name: "q", of: "quad")],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
)
"#,
    );
    let o = run(bin().arg("render").arg(&scene).arg("-o").arg(&out));
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("bad.ron:6:122: error: unknown material \"chrom\""),
        "{err}"
    );
    assert!(err.contains("chrom"), "{err}");
    assert!(err.contains("did you mean \"chrome\""), "{err}");
    assert!(!out.exists());
    let o = run(bin().arg("check").arg(&scene));
    assert_eq!(o.status.code(), Some(1));
}

#[test]
fn usage_errors_exit_2() {
    let o = run(bin().args(["render", "--no-such-flag"]));
    assert_eq!(o.status.code(), Some(2));
    let o = run(bin()
        .arg("render")
        .arg(asset("test_plane.ron"))
        .args(["-o", "image.bmp"]));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("name a .png or .exr file for the image, or an .svg or .eps file"));
    let o = run(bin()
        .args(["render", "--spp", "0"])
        .arg(asset("test_plane.ron")));
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn missing_scene_file_is_a_scene_error() {
    let o = run(bin().args(["check", "/definitely/not/here.ron"]));
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("here.ron"));
}

#[test]
fn bench_reports_throughput_per_stage_and_writes_nothing_here() {
    let dir = scratch("bench");
    let o = run(bin()
        .current_dir(&dir)
        .args(["bench", "--json", "--threads", "1"])
        .arg(asset("test_plane.ron")));
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["threads"], 1);
    let shade = v["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["stage"] == "shade")
        .unwrap();
    assert_eq!(shade["ran"], true);
    assert_eq!(shade["items"], 508 * 380 * 4);
    assert!(shade["items_per_second_per_thread"].as_f64().unwrap() > 0.0);
    // Rays per stage: a camera ray per sample plus a pixel-centre ray per pixel; the lamp
    // casts no shadows, so no shadow rays.
    assert_eq!(shade["rays_closest"], 508 * 380 * 5);
    assert_eq!(shade["rays_occlusion"], 0);
    assert!(shade["rays_per_second_per_thread"].as_f64().unwrap() > 0.0);
    // Process CPU time of the stage: positive, the per-CPU-second rates follow from it, and
    // one worker thread cannot use much more CPU than the wall time it took.
    let cpu = shade["cpu_seconds"].as_f64().unwrap();
    let wall = shade["seconds"].as_f64().unwrap();
    assert!(
        cpu > 0.0 && cpu <= wall * 1.25 + 0.05,
        "cpu {cpu} s, wall {wall} s"
    );
    let per_cpu = shade["items_per_cpu_second"].as_f64().unwrap();
    assert!((per_cpu * cpu / (508.0 * 380.0 * 4.0) - 1.0).abs() < 1e-9);
    let rays_per_cpu = shade["rays_per_cpu_second"].as_f64().unwrap();
    assert!((rays_per_cpu * cpu / (508.0 * 380.0 * 5.0) - 1.0).abs() < 1e-9);
    assert!(
        std::fs::read_dir(&dir).unwrap().next().is_none(),
        "bench wrote into the working directory"
    );
    let o = run(bin()
        .current_dir(&dir)
        .arg("bench")
        .arg(asset("test_plane.ron")));
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("items/s/thread")
            && text.contains("rays/s/thread")
            && text.contains("items/cpu-s")
            && text.contains("rays/cpu-s")
            && text.contains("skipped: no bake requests"),
        "{text}"
    );
}

#[test]
fn bench_integrator_flag_puts_the_path_tracer_in_the_ledger() {
    let dir = scratch("bench_integrator");
    let closest = |integrator: &str| {
        let o = run(bin()
            .current_dir(&dir)
            .args([
                "bench",
                "--json",
                "--threads",
                "1",
                "--integrator",
                integrator,
            ])
            .arg(asset("test_plane.ron")));
        assert!(o.status.success(), "{}", stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let shade = v["stages"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["stage"] == "shade")
            .unwrap()
            .clone();
        assert_eq!(shade["items"], 508 * 380 * 4);
        shade["rays_closest"].as_u64().unwrap()
    };
    // Direct: a camera ray per sample plus a pixel-centre ray (as above); the path tracer
    // also traces a continuation ray from every sample that hits the lit plane.
    assert_eq!(closest("direct"), 508 * 380 * 5);
    assert!(closest("path") > 508 * 380 * 6);
}

#[test]
fn integrator_flag_selects_the_path_tracer_deterministically() {
    let dir = scratch("integrator");
    let mut bytes = Vec::new();
    for (integrator, threads) in [("path", "1"), ("path", "2"), ("direct", "2")] {
        let out = dir.join(format!("glass_{integrator}_{threads}.exr"));
        let o = run(bin()
            .args(["render"])
            .arg(asset("glass.ron"))
            .arg("-o")
            .arg(&out)
            .args([
                "--spp",
                "1",
                "--threads",
                threads,
                "--integrator",
                integrator,
            ]));
        assert!(o.status.success(), "{}", stderr(&o));
        bytes.push(std::fs::read(&out).unwrap());
    }
    assert_eq!(
        bytes[0], bytes[1],
        "path tracer differs across thread counts"
    );
    assert_ne!(bytes[1], bytes[2], "--integrator made no difference");
    let o = run(bin()
        .args(["render"])
        .arg(asset("glass.ron"))
        .args(["--integrator", "whitted"]));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn id_passes_go_to_exr_and_are_refused_for_png() {
    let dir = scratch("ids");
    let scene = dir.join("ids.ron");
    let text = r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)),
        outputs: [(file: "ids.exr", passes: [Beauty, ObjectId, MaterialId]), (file: "ids.png", passes: [ObjectId])])],
    objects: [(name: "tri", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]))],
    instances: [(name: "t", of: "tri")],
    groups: [(name: "world", members: ["t"])],
    render: (root: "world", camera: "cam"),
)
"#;
    write(&scene, text);
    let o = run(bin().arg("check").arg(&scene));
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("ids.ron:4:105: error: a PNG output cannot hold the ObjectId pass"),
        "{}",
        stderr(&o)
    );
    write(
        &scene,
        &text.replace(", (file: \"ids.png\", passes: [ObjectId])", ""),
    );
    let o = run(bin().current_dir(&dir).arg("render").arg(&scene));
    assert!(o.status.success(), "{}", stderr(&o));
    let read = exr::prelude::read_all_flat_layers_from_file(dir.join("ids.exr")).unwrap();
    let ids = read.layer_data[0]
        .channel_data
        .list
        .iter()
        .find(|c| c.name.to_string() == "id.object")
        .expect("id.object channel");
    match &ids.sample_data {
        exr::prelude::FlatSamples::U32(v) => {
            assert!(v.contains(&0) && v.contains(&1), "{v:?}");
        }
        other => panic!("id.object is not u32: {other:?}"),
    }
}

#[test]
fn imager_fills_the_background_and_applies_exposure_to_png() {
    let dir = scratch("imager");
    let scene = dir.join("imager.ron");
    let text = r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (16, 16),
        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)),
        outputs: [(file: "out.png"), (file: "out.exr")],
        imager: (background: (1, 0, 0), gain: 2.0, gamma: 2.2))],
    materials: [(name: "grey", shader: Constant(color: (0.1, 0.1, 0.1)))],
    objects: [(name: "quad", mesh: Inline(vertices: [(-0.2, -0.2, 0), (0.2, -0.2, 0), (0.2, 0.2, 0), (-0.2, 0.2, 0)], polygons: [[0, 1, 2, 3]]), material: "grey")],
    instances: [(name: "q", of: "quad")],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
)
"#;
    write(&scene, text);
    let o = run(bin()
        .current_dir(&dir)
        .arg("render")
        .arg(&scene)
        .args(["--spp", "4"]));
    assert!(o.status.success(), "{}", stderr(&o));
    let png = crate::common::png::read(&dir.join("out.png"));
    // Background: the imager's red.
    assert_eq!(crate::common::png::rgb8(&png, 0, 0), [255, 0, 0]);
    // Covered centre: RenderMan exposure (2 · 0.1)^(1/2.2) = 0.481 → 123.
    assert_eq!(crate::common::png::rgb8(&png, 8, 8), [123, 123, 123]);
    // The EXR keeps scene-linear radiance and a black background.
    let exr = exr::prelude::read_first_rgba_layer_from_file(
        dir.join("out.exr"),
        |res, _| vec![0.0f32; res.width() * res.height()],
        |px: &mut Vec<f32>, pos, (r, _g, _b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * 16 + pos.x()] = r
        },
    )
    .unwrap();
    let red = &exr.layer_data.channel_data.pixels;
    assert_eq!(red[0], 0.0);
    assert!((red[8 * 16 + 8] - 0.1).abs() < 1e-6);
    // A non-positive gamma is a located error.
    write(&scene, &text.replace("gamma: 2.2", "gamma: 0.0"));
    let o = run(bin().arg("check").arg(&scene));
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("imager.ron:5:59: error: gamma must be positive, found 0"),
        "{}",
        stderr(&o)
    );
}

/// `convert -o` into another directory than the scene's: the RON names the scene's relative
/// inputs (a RON include, a glTF file's meshes) through the path between the directories,
/// so it renders the same bytes; without the rewrite, both fail to load there.
#[test]
fn convert_into_another_directory_keeps_the_inputs() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    for (test, scene) in [
        ("convert_ron_include", "assets/scenes/cornell_box.ron"),
        ("convert_glb", "assets/gltf/lightmap_room.glb"),
    ] {
        crate::common::convert_renders_the_same_png(test, &root.join(scene));
    }
}

/// A bake file named by an absolute or `..` path stays in the bench's scratch directory:
/// `bench` and `sweep` write nothing outside it (they once wrote, and overwrote, the file the
/// scene named).
#[test]
fn bench_and_sweep_keep_bake_files_named_outside_in_their_scratch() {
    let dir = scratch("bench_bake_outside");
    let outside = dir.join("precious.exr");
    std::fs::write(&outside, "precious").unwrap();
    let scene = crate::common::small_scene(
        &crate::common::quad_object("quad"),
        &format!(
            r#"(name: "quad_1", of: "quad", bake: (resolution: (8, 8), outputs: [
                (kind: AmbientOcclusion(samples: 4), file: "{}"),
                (kind: Albedo, format: Exr, file: "../up.exr")]))"#,
            outside.display()
        ),
        "",
        "",
    );
    let work = dir.join("work");
    std::fs::create_dir_all(&work).unwrap();
    std::fs::write(work.join("scene.ron"), scene).unwrap();
    let o = run(bin()
        .current_dir(&work)
        .args(["bench", "--threads", "1", "scene.ron"]));
    assert!(o.status.success(), "{}", stderr(&o));
    let o = run(bin().current_dir(&work).args([
        "sweep",
        "scene.ron",
        "--knob",
        "bake_samples=1",
        "--reference-spp",
        "4",
        "--out",
        "sweep",
    ]));
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(&outside).unwrap(), b"precious");
    assert!(!dir.join("up.exr").exists());
    let mut names = crate::common::dir_names(&work);
    names.sort();
    assert_eq!(names, ["scene.ron", "sweep"]);
}

/// Standard output closed by its reader (`stagelight plan | head -1`): the commands that
/// print to it end quietly with status 0 instead of panicking on the broken pipe.
#[test]
fn a_closed_standard_output_ends_the_command_quietly() {
    for args in [
        vec!["plan"],
        vec!["plan", "--json"],
        vec!["check"],
        vec!["bench", "--json"],
    ] {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = bin()
            .args(&args)
            .arg(asset("test_plane.ron"))
            .stdout(writer)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"), "{args:?}: {}", stderr(&o));
    }
}

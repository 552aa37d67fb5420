//! `stagelight plan` (the stages in order with run/skip and the reason, nothing run), the
//! agreement of the plan with what a run then does, and `render --bake` reporting every
//! file it wrote (camera outputs and baked textures alike).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use stagelight::frame::{Frame, Tasks};
use stagelight::scene::load_scene_str;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_stagelight"))
}

fn scratch(test: &str) -> PathBuf {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight-cli-plan-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(cmd: &mut Command) -> Output {
    cmd.output().expect("run stagelight")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A floor with UVs and a bake request, a quadric ball (procedural, to be tessellated), a
/// light and a camera with one output. `options` are extra option fields.
fn scene(options: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, {options}),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (16, 16),
               placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0)),
               outputs: [(file: "view.png")])],
    lights: [(name: "sun", kind: Point(position: (0, 0, 3)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [
        (name: "floor", mesh: Inline(
            vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
        (name: "ball", mesh: Sphere(radius: 0.3), material: "grey",
         approximation: Parametric(u: 8, v: 4)),
    ],
    instances: [
        (name: "floor_1", of: "floor",
         bake: (resolution: (8, 8), outputs: [(kind: AmbientOcclusion(samples: 4))])),
        (name: "ball_1", of: "ball", transform: [Translate((0, 0, 0.5))]),
    ],
    groups: [(name: "world", members: ["floor_1", "ball_1"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

fn write(path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
}

#[test]
fn plan_prints_every_stage_with_its_reason_and_writes_nothing() {
    let dir = scratch("print");
    let path = dir.join("scene.ron");
    write(&path, &scene(""));
    let o = run(bin().arg("plan").arg(&path).current_dir(&dir));
    assert!(o.status.success(), "{}", text(&o.stderr));
    let lines: Vec<String> = text(&o.stdout).lines().skip(1).map(String::from).collect();
    assert_eq!(
        lines,
        [
            " 1 expand_geometry  run  1 geometry shader(s), 0 scatter(s)",
            " 2 tessellate       run  1 surface(s), 0 subdivision mesh(es), 0 true displacement(s)",
            " 3 build_accel      run  2 instance(s) with 2 triangles so far, more to be generated",
            " 4 trace_photons    skip caustics and global illumination are off",
            " 5 bake_lightmaps   skip 1 bake request(s), but this run does not bake (use `stagelight bake` or `render --bake`)",
            " 6 shade            run  render camera 16×16",
            " 7 draw_contours    skip no material in use has a contour shader",
            " 8 write_output     run  1 camera output(s)",
        ]
    );
    assert!(text(&o.stdout).starts_with(&format!("plan for {} (render):", path.display())));
    let o = run(bin()
        .arg("plan")
        .arg(&path)
        .arg("--bake-only")
        .current_dir(&dir));
    let out = text(&o.stdout);
    assert!(
        out.contains(" 5 bake_lightmaps   run  1 bake request(s)"),
        "{out}"
    );
    assert!(
        out.contains(" 6 shade            skip this run only bakes"),
        "{out}"
    );
    assert!(
        out.contains(" 8 write_output     skip no shaded image"),
        "{out}"
    );
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 1, "plan wrote nothing but the scene is there");
}

/// `plan` takes the `render` flags that decide which stages run: `--disable` and
/// `--photon-cache` (with `--integrator`), and says that a photon map file it cannot check
/// without the geometry may make `trace_photons` load the maps instead.
#[test]
fn plan_takes_disable_and_photon_cache_as_render_does() {
    let dir = scratch("flags");
    let path = dir.join("scene.ron");
    write(
        &path,
        &scene("global_illumination: (photons: 500, gather: 8)"),
    );
    let plan = |args: &[&str]| {
        let o = run(bin().arg("plan").arg(&path).args(args).current_dir(&dir));
        assert!(o.status.success(), "{args:?}: {}", text(&o.stderr));
        text(&o.stdout)
    };
    let out = plan(&["--disable", "geometry", "--photon-cache", "cache"]);
    assert!(
        out.contains("\n 1 expand_geometry  skip geometry shaders disabled (1 geometry shader(s), 0 scatter(s) left empty)\n"),
        "{out}"
    );
    assert!(
        out.contains("\n 4 trace_photons    run  global illumination (500 photons); runs unless cache/<hash>.pmap holds these maps (then they are loaded from it and the stage is reported skipped; the hash needs the built geometry), else keeps them there\n"),
        "{out}"
    );
    let out = plan(&["--integrator", "path", "--disable", "output"]);
    assert!(
        out.contains("\n 4 trace_photons    skip the path integrator does not read photon maps\n"),
        "{out}"
    );
    let o = run(bin().arg("plan").arg(&path).args(["--disable", "lenses"]));
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o.stderr).starts_with("error: invalid value 'lenses' for '--disable <FEATURES>'"),
        "{}",
        text(&o.stderr)
    );
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 1, "plan wrote nothing but the scene is there");
}

#[test]
fn the_plan_is_what_the_run_does() {
    for (options, tasks) in [
        (
            "",
            Tasks {
                render: true,
                bake: false,
            },
        ),
        (
            "",
            Tasks {
                render: true,
                bake: true,
            },
        ),
        (
            "",
            Tasks {
                render: false,
                bake: true,
            },
        ),
        (
            "global_illumination: (photons: 500, gather: 8)",
            Tasks {
                render: true,
                bake: false,
            },
        ),
        (
            "integrator: Path, caustics: (photons: 500)",
            Tasks {
                render: true,
                bake: false,
            },
        ),
    ] {
        let dir = scratch("agree");
        let text = scene(options);
        let loaded = load_scene_str(&text, &dir.join("scene.ron")).expect("scene loads");
        let mut frame = Frame::new(loaded.settings.clone());
        frame.inputs.tasks = tasks;
        frame.inputs.bake_dir = dir.clone();
        frame.inputs.outputs.directory = Some(dir.clone());
        let planned = stagelight::systems::plan(&loaded.world, &mut frame);

        let mut world = loaded.world;
        let mut frame = Frame::new(loaded.settings);
        frame.inputs.tasks = tasks;
        frame.inputs.bake_dir = dir.clone();
        frame.inputs.outputs.directory = Some(dir.clone());
        stagelight::systems::run(&mut world, &mut frame).expect("run");
        for (p, r) in planned.iter().zip(&frame.report.stages) {
            assert_eq!((p.stage, p.run), (r.stage, r.ran), "{options} {tasks:?}");
            if p.stage != "build_accel" {
                assert_eq!(p.reason, r.reason, "{} ({options})", p.stage);
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn render_with_bake_reports_every_file_it_wrote() {
    let dir = scratch("bake");
    let path = dir.join("scene.ron");
    write(&path, &scene(""));
    let json = dir.join("stats.json");
    let o = run(bin()
        .arg("render")
        .arg(&path)
        .arg("--bake")
        .arg("--stats-json")
        .arg(&json)
        .current_dir(&dir));
    assert!(o.status.success(), "{}", text(&o.stderr));
    let err = text(&o.stderr);
    let wrote: Vec<&str> = err.lines().filter(|l| l.starts_with("wrote ")).collect();
    assert_eq!(wrote, ["wrote ./floor_1_ao.exr", "wrote view.png"], "{err}");
    assert!(dir.join("floor_1_ao.exr").is_file() && dir.join("view.png").is_file());
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(
        report["written"],
        serde_json::json!(["./floor_1_ao.exr", "view.png"])
    );
    let stages = report["stages"].as_array().unwrap();
    let files_of =
        |name: &str| stages.iter().find(|s| s["stage"] == name).unwrap()["files"].clone();
    assert_eq!(
        files_of("bake_lightmaps"),
        serde_json::json!(["./floor_1_ao.exr"])
    );
    assert_eq!(files_of("write_output"), serde_json::json!(["view.png"]));
}

#[test]
fn dash_o_is_a_run_input_that_leaves_the_scene_alone() {
    let dir = scratch("dash-o");
    let path = dir.join("scene.ron");
    write(&path, &scene(""));
    let o = run(bin()
        .arg("render")
        .arg(&path)
        .args(["-o", "other.exr"])
        .current_dir(&dir));
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(dir.join("other.exr").is_file());
    assert!(
        !dir.join("view.png").exists(),
        "-o replaces the first output"
    );
    let o = run(bin()
        .arg("render")
        .arg(&path)
        .args(["-o", "x.tiff"])
        .current_dir(&dir));
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        text(&o.stderr).trim_end(),
        "error: cannot tell the output format of x.tiff from its extension\n  help: name a .png or .exr file for the image, or an .svg or .eps file for the contour lines"
    );
}

/// `plan` refuses, with `check`'s message and exit status, what `check` and `render` refuse
/// before the first stage: a 100000² frame past the memory budget, and an output that would
/// overwrite the scene file. It printed a plan and exited 0.
#[test]
fn plan_refuses_what_check_refuses_before_the_first_stage() {
    let dir = scratch("refused");
    let path = dir.join("scene.ron");
    let huge = scene("").replace("resolution: (16, 16)", "resolution: (100000, 100000)");
    let self_output = scene("").replace(
        r#"outputs: [(file: "view.png")]"#,
        r#"outputs: [(file: "scene.ron", format: Exr)]"#,
    );
    for (text_of_scene, why) in [
        (huge, "the frame buffers of 100000×100000 pixels"),
        (self_output, "would overwrite the scene file scene.ron"),
    ] {
        write(&path, &text_of_scene);
        let plan = run(bin().args(["plan", "scene.ron"]).current_dir(&dir));
        let check = run(bin().args(["check", "scene.ron"]).current_dir(&dir));
        assert_eq!(
            (plan.status.code(), check.status.code()),
            (Some(1), Some(1))
        );
        assert_eq!(text(&plan.stdout), "");
        let (p, c) = (text(&plan.stderr), text(&check.stderr));
        assert!(p.contains(why), "{p}");
        assert_eq!(
            p,
            c.replace(
                "1 error in scene.ron\n",
                "1 error in scene.ron; nothing planned\n"
            )
        );
    }
}

/// `plan --camera NAME -o FILE` plans the render those flags make: a camera without outputs
/// skips `shade` (as `render --camera` would render nothing), with `-o` it runs, and the
/// plan's `shade` row then says what `render` with the same flags reports.
#[test]
fn plan_takes_camera_and_output_as_render_does() {
    let dir = scratch("camera");
    let path = dir.join("scene.ron");
    let two = scene("").replace(
        r#"outputs: [(file: "view.png")])],"#,
        r#"outputs: [(file: "view.png")]),
              (name: "side", fov_y: 40.0, resolution: (8, 8),
               placement: LookAt(eye: (4, 0, 1), target: (0, 0, 0)), outputs: [])],"#,
    );
    assert_ne!(two, scene(""));
    write(&path, &two);
    let shade_row = |args: &[&str]| {
        let o = run(bin().arg("plan").arg(&path).args(args).current_dir(&dir));
        assert!(o.status.success(), "{args:?}: {}", text(&o.stderr));
        let out = text(&o.stdout);
        out.lines()
            .find(|l| l.split_whitespace().nth(1) == Some("shade"))
            .unwrap_or_else(|| panic!("no shade row in\n{out}"))
            .to_string()
    };
    assert!(shade_row(&[]).contains("shade            run "));
    let side = shade_row(&["--camera", "side"]);
    assert_eq!(
        side,
        " 6 shade            skip the render camera has no outputs and no part file keeps its image"
    );
    let written = shade_row(&["--camera", "side", "-o", "side.exr", "--spp", "2"]);
    assert!(written.contains("shade            run "), "{written}");
    // The run agrees, and the plan wrote nothing.
    assert!(!dir.join("side.exr").exists());
    let o = run(bin()
        .args([
            "render",
            "scene.ron",
            "--camera",
            "side",
            "-o",
            "side.exr",
            "--spp",
            "2",
        ])
        .args(["--stats-json", "s.json"])
        .current_dir(&dir));
    assert!(o.status.success(), "{}", text(&o.stderr));
    let row = crate::common::stage_row(&dir.join("s.json"), "shade");
    assert!(row.ran);
    assert_eq!((row.items, row.unit.as_str()), (8 * 8 * 2, "samples"));
    let o = run(bin().arg("plan").arg(&path).args(["--camera", "top"]));
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o.stderr).contains("\"top\""), "{}", text(&o.stderr));
}

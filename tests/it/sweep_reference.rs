//! What `stagelight sweep` compares with and what it refuses before the first run: a knob
//! whose accuracy is a setting (`max_depth`, `tessellation`) is measured against a reference
//! at its most accurate setting, never the scene's own; a `--reference` of another size is
//! refused naming both sizes, leaving no `--out`; knobs the swept integrator ignores are
//! usage errors; and a closed standard error does not end the sweep.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use crate::common::cli::{scratch_dir, stagelight_in};

fn sweep(dir: &Path, args: &[&str]) -> Output {
    stagelight_in(dir)
        .arg("sweep")
        .args(args)
        .output()
        .expect("run stagelight")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn setup(test: &str, scene: &str) -> PathBuf {
    let dir = scratch_dir(&format!("sweep-reference-{test}"));
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    dir
}

/// The `rel_mse` column of `OUT/sweep.csv`.
fn rel_mse(out: &Path) -> Vec<f64> {
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "rel_mse").unwrap();
    lines
        .map(|l| l.split(',').nth(col).unwrap().parse().unwrap())
        .collect()
}

fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("sweep.json")).unwrap()).unwrap()
}

/// An open white box (albedo 0.8) lit by a panel under its lid: light bounces many times.
/// Its own `max_depth` is 2.
const BOX: &str = r#"Scene(
    options: (samples: 64, max_depth: 2),
    cameras: [(name: "cam", fov_y: 60.0, resolution: (16, 16),
        placement: LookAt(eye: (0, -2.5, 1), target: (0, 0, 1), up: (0, 0, 1)))],
    lights: [(name: "panel", kind: Rect(corner: (-0.3, -0.3, 1.99), edge_u: (0, 0.6, 0), edge_v: (0.6, 0, 0)), intensity: 8.0, samples: 1)],
    materials: [(name: "white", shader: Lambert(albedo: (0.8, 0.8, 0.8)))],
    objects: [
        (name: "box", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (-1, -1, 2), (1, -1, 2), (1, 1, 2), (-1, 1, 2)],
            polygons: [[0, 1, 2, 3], [7, 6, 5, 4], [3, 2, 6, 7], [0, 3, 7, 4], [1, 5, 6, 2]]), material: "white"),
    ],
    instances: [(name: "box_1", of: "box")],
    groups: [(name: "world", members: ["box_1"])],
    render: (root: "world", camera: "cam"),
)
"#;

/// The tester's case: with the scene's own depth (2) in the reference, depth 2 measured
/// relMSE 5e-4 and depth 8 3e-1. Against the reference at depth 16 the error falls as the
/// depth rises (0.40, 0.16, 0.004 measured), and the scene's own depth is not the best.
#[test]
fn max_depth_is_measured_against_a_deep_reference() {
    let dir = setup("depth", BOX);
    let o = sweep(
        &dir,
        &[
            "scene.ron",
            "--knob",
            "max_depth=1,2,8",
            "--integrator",
            "path",
            "--reference-spp",
            "512",
            "--out",
            "out",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).starts_with("sweep: reference: 512 samples, max_depth=16\n"),
        "{}",
        stderr(&o)
    );
    let e = rel_mse(&dir.join("out"));
    assert!(
        e[1] < 0.7 * e[0] && e[2] < 0.2 * e[1],
        "relMSE by depth 1, 2, 8: {e:?}"
    );
    assert_eq!(
        summary(&dir.join("out"))["reference"],
        "path tracer, 512 samples, max_depth=16"
    );
    // The reference's depth is in its cache key: a sweep to depth 32 renders its own.
    let o = sweep(
        &dir,
        &[
            "scene.ron",
            "--knob",
            "max_depth=32",
            "--integrator",
            "path",
            "--reference-spp",
            "512",
            "--out",
            "out",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).starts_with("sweep: reference: 512 samples, max_depth=32\n"),
        "{}",
        stderr(&o)
    );
}

/// The mean of every channel of every `OUT/reference_*.exr` (the cached references).
fn reference_mean(out: &Path) -> f64 {
    let files: Vec<PathBuf> = std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("reference_")
        })
        .collect();
    assert_eq!(files.len(), 1, "{files:?}");
    let (px, _, _) = stagelight::sweep::runner::read_exr_rgb(&files[0]).unwrap();
    px.iter().map(|p| f64::from(p.x + p.y + p.z)).sum::<f64>() / (3 * px.len()) as f64
}

/// The tester's case: the global photon map carries every bounce, but the photon and spp
/// sweeps of a final-gathering scene were scored against a path tracer cut at the scene's
/// depth. Now its reference is at depth 16 and says so; under `--integrator path` the runs
/// are cut at the scene's depth as the reference is, which keeps it (and says so). In the
/// white box the depth-16 reference is far brighter than the depth-2 one.
#[test]
fn a_photon_map_scene_is_measured_against_a_deep_reference() {
    let gi = BOX.replace(
        "max_depth: 2)",
        "max_depth: 2, global_illumination: (photons: 2000, gather: 16, final_gather: 4))",
    );
    let dir = setup("photon-depth", &gi);
    let args = |out: &'static str, integrator: &'static str| {
        [
            "scene.ron",
            "--knob",
            "spp=1,2",
            "--integrator",
            integrator,
            "--reference-spp",
            "16",
            "--out",
            out,
        ]
    };
    let o = sweep(&dir, &args("gi", "direct"));
    assert!(o.status.success(), "{}", stderr(&o));
    let raised =
        "max_depth=16 (the scene's is 2, but the swept runs' photon maps carry light past it)";
    assert!(
        stderr(&o).starts_with(&format!("sweep: reference: 16 samples, {raised}\n")),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        summary(&dir.join("gi"))["reference"],
        format!("path tracer, 16 samples, {raised}")
    );
    let o = sweep(&dir, &args("path", "path"));
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        summary(&dir.join("path"))["reference"],
        "path tracer, 16 samples, max_depth=2 (the scene's, as in the swept runs)"
    );
    let (deep, cut) = (
        reference_mean(&dir.join("gi")),
        reference_mean(&dir.join("path")),
    );
    assert!(
        deep > 1.3 * cut,
        "reference means: depth 16 {deep}, depth 2 {cut}"
    );
}

/// A coarsely diced ball (4 × 4 patches) under a sun.
const BALL: &str = r#"Scene(
    options: (samples: 16),
    cameras: [(name: "cam", fov_y: 30.0, resolution: (24, 24),
        placement: LookAt(eye: (0, -6, 0), target: (0, 0, 0), up: (0, 0, 1)))],
    lights: [(name: "sun", kind: Directional(direction: (0.3, 1, -0.4)), intensity: 2.0)],
    materials: [(name: "m", shader: Lambert(albedo: (0.8, 0.8, 0.8)))],
    objects: [(name: "ball", mesh: Sphere(radius: 1.0), material: "m",
               approximation: Parametric(u: 4, v: 4))],
    instances: [(name: "ball_1", of: "ball")],
    groups: [(name: "world", members: ["ball_1"])],
    render: (root: "world", camera: "cam"),
)
"#;

/// The reference is diced as finely as the finest factor swept (0.25: 16 × 16 patches), so
/// the error falls as the tessellation gets finer; with the scene's own dicing in the
/// reference, factor 1 measured the least.
#[test]
fn tessellation_is_measured_against_the_finest_dicing() {
    let dir = setup("tessellation", BALL);
    let o = sweep(
        &dir,
        &[
            "scene.ron",
            "--knob",
            "tessellation=4,1,0.25",
            "--reference-spp",
            "64",
            "--out",
            "out",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let e = rel_mse(&dir.join("out"));
    assert!(
        e[1] < 0.7 * e[0] && e[2] < 0.7 * e[1],
        "relMSE by factor 4, 1, 0.25: {e:?}"
    );
    assert_eq!(
        summary(&dir.join("out"))["reference"],
        "path tracer, 64 samples, tessellation=0.25, max_depth=4 (the scene's, as in the swept runs)"
    );
}

/// The sweep test's floor under a panel at `width` × `height`, with a 16 × 16 AO bake.
fn floor(width: u32, height: u32) -> String {
    format!(
        r#"Scene(
    options: (samples: 1),
    cameras: [(name: "cam", fov_y: 50.0, resolution: ({width}, {height}),
        placement: LookAt(eye: (0, -3, 3), target: (0, 0, 0)))],
    lights: [(name: "panel", kind: Rect(corner: (-0.5, -0.5, 2), edge_u: (0, 1, 0), edge_v: (1, 0, 0)), intensity: 4.0, samples: 1)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.6, 0.6, 0.6)))],
    objects: [
        (name: "floor", mesh: Inline(vertices: [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)],
            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]), material: "grey"),
    ],
    instances: [
        (name: "floor_1", of: "floor", bake: (resolution: (16, 16), outputs: [(kind: AmbientOcclusion(samples: 4), format: Exr)])),
    ],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

/// A 12 × 9 reference for 12 × 12 runs (the same pixel count would not tell them apart) is
/// refused before anything renders, naming both sizes, and leaves no `--out` behind; so is
/// one for a bake sweep, once its first bake tells the texture's size.
#[test]
fn a_reference_of_another_size_is_refused_leaving_no_output_directory() {
    let dir = setup("size", &floor(12, 12));
    std::fs::write(dir.join("wide.ron"), floor(12, 9)).unwrap();
    let o = stagelight_in(&dir)
        .args(["render", "wide.ron", "-o", "ref.exr"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let help = "  help: give a linear EXR image of the runs' size (without --reference, the sweep renders one and caches it in --out)";
    let o = sweep(
        &dir,
        &[
            "scene.ron",
            "--knob",
            "spp=1,2",
            "--reference",
            "ref.exr",
            "--out",
            "out",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        format!("error: --reference ref.exr is 12×9 pixels, the runs render 12×12\n{help}\n")
    );
    assert!(!dir.join("out").exists());
    let o = sweep(
        &dir,
        &[
            "scene.ron",
            "--knob",
            "bake_samples=4",
            "--reference",
            "ref.exr",
            "--out",
            "out",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        format!(
            "sweep: bake_samples = 4 (seed 0)\nerror: --reference ref.exr is 12×9 pixels, the runs render 16×16\n{help}\n"
        )
    );
    assert!(!dir.join("out").exists());
}

/// `light_samples` under the path integrator, which samples each light once per vertex, and
/// a photon knob, whose maps it does not read: usage errors, not flat tables.
#[test]
fn knobs_the_swept_integrator_ignores_are_usage_errors() {
    let dir = setup("ignored", &floor(8, 8));
    let help = "  help: sweep it with `--integrator direct`, or under the path integrator sweep spp or max_depth";
    let o = sweep(
        &dir,
        &[
            "scene.ron",
            "--knob",
            "light_samples=1,64",
            "--integrator",
            "path",
            "--out",
            "out",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o),
        format!("error: knob light_samples changes nothing in the swept runs: the path integrator takes one sample of every light per vertex (weighted by multiple importance sampling), whatever the light's `samples`\n{help}\n")
    );
    assert!(!dir.join("out").exists());
    let caustics = floor(8, 8).replace(
        "options: (samples: 1)",
        "options: (samples: 1, integrator: Path, caustics: (photons: 100, gather: 8))",
    );
    std::fs::write(dir.join("caustics.ron"), caustics).unwrap();
    let o = sweep(
        &dir,
        &["caustics.ron", "--knob", "photons=100,400", "--out", "out"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o),
        format!("error: knob photons changes nothing in the swept runs: the path integrator does not read photon maps\n{help}\n")
    );
    // `--integrator direct` sweeps them.
    let o = sweep(
        &dir,
        &[
            "caustics.ron",
            "--knob",
            "photons=100",
            "--integrator",
            "direct",
            "--reference-spp",
            "1",
            "--out",
            "out",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

/// With its standard error closed (`stagelight sweep … 2>&1 | head -2`), the sweep's progress
/// lines are dropped: it runs to its end, writes its result and exits 0 (it panicked, 101).
#[test]
fn a_closed_standard_error_does_not_end_the_sweep() {
    let dir = setup("closed-stderr", &floor(8, 8));
    let mut child = Command::new(env!("CARGO_BIN_EXE_stagelight"))
        .current_dir(&dir)
        .args([
            "sweep",
            "scene.ron",
            "--knob",
            "spp=1,2",
            "--reference-spp",
            "4",
        ])
        .args(["--out", "out"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stderr.take());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.starts_with("spp,"), "{stdout}");
    assert!(dir.join("out/sweep.csv").exists());
}

//! `stagelight sweep` of the photon knobs end to end on a small caustic (a glass ball on a
//! floor under a small panel light): every knob runs from the CLI and changes the caustic,
//! `--crop` fits the caustic's error, and a bad crop is refused with the reason.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_stagelight"))
}

fn scratch(test: &str) -> PathBuf {
    let dir = crate::common::scratch_root().join(format!(
        "stagelight-sweep-photons-{test}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(cmd: &mut Command) -> Output {
    cmd.output().expect("run stagelight")
}

/// The caustic beside the ball, pixels [X0, X1) × [Y0, Y1) of the 64 × 48 image.
const CROP: &str = "35,25,46,31";

/// `scripts/glass_ball.ron` at 64 × 48 with only a caustic map of `photons` photons.
fn scene(photons: u32) -> String {
    format!(
        r#"Scene(
    options: (samples: 8, max_depth: 6, refraction_depth: 6,
        caustics: (photons: {photons}, gather: 50)),
    cameras: [(name: "cam", fov_y: 40, resolution: (64, 48),
        placement: LookAt(eye: (0, -3.5, 2.2), target: (0.2, 0, 0.3), up: (0, 0, 1)))],
    lights: [(name: "panel", kind: Rect(corner: (-2.6, 0.1, 2.5), edge_u: (0.2, 0, 0), edge_v: (0, -0.2, 0)),
         intensity: 800, samples: 2)],
    materials: [
        (name: "floor", shader: Lambert(albedo: (0.7, 0.7, 0.7))),
        (name: "glass", shader: Dielectric(ior: 1.5)),
    ],
    objects: [
        (name: "floor", mesh: Grid(size_x: 6, size_y: 6), material: "floor"),
        (name: "ball", mesh: Sphere(radius: 0.5), material: "glass", approximation: Parametric(u: 48, v: 24)),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "ball_1", of: "ball", transform: [Translate((0, 0, 0.5))]),
    ],
    groups: [(name: "world", members: ["floor_1", "ball_1"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

/// Writes the scene (20 000 caustic photons) and a reference rendered with 1 000 000 at the
/// scene's 8 samples per pixel and seed: the same camera samples, so the crop's error is the
/// photon map's, not the pixel sampling's of the caustic's sharp edges.
fn setup(test: &str) -> (PathBuf, PathBuf, PathBuf) {
    let dir = scratch(test);
    let scene_file = dir.join("scene.ron");
    std::fs::write(&scene_file, scene(20_000)).unwrap();
    let reference_scene = dir.join("reference.ron");
    std::fs::write(&reference_scene, scene(1_000_000)).unwrap();
    let reference = dir.join("reference.exr");
    let o = run(bin()
        .arg("render")
        .arg(&reference_scene)
        .args(["--spp", "8", "-o"])
        .arg(&reference));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (dir, scene_file, reference)
}

/// Sweeps `knob` against the reference with the caustic crop; returns the JSON summary.
fn sweep(dir: &Path, scene: &Path, reference: &Path, knob: &str) -> serde_json::Value {
    let out = dir.join(knob.split('=').next().unwrap());
    let o = run(bin()
        .arg("sweep")
        .arg(scene)
        .args(["--knob", knob, "--crop", CROP, "--reference"])
        .arg(reference)
        .arg("--out")
        .arg(&out));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        String::from_utf8_lossy(&o.stdout).contains(&format!("crop {CROP}: ")),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    let svg = std::fs::read_to_string(out.join("sweep.svg")).unwrap();
    assert!(svg.contains(&format!("relMSE (crop {CROP})")));
    serde_json::from_slice(&std::fs::read(out.join("sweep.json")).unwrap()).unwrap()
}

/// The crop's and the whole image's relMSE per row.
fn errors(json: &serde_json::Value) -> (Vec<f64>, Vec<f64>) {
    let rows = json["rows"].as_array().unwrap();
    (
        rows.iter()
            .map(|r| r["crop_error"]["rel_mse"].as_f64().unwrap())
            .collect(),
        rows.iter()
            .map(|r| r["error"]["rel_mse"].as_f64().unwrap())
            .collect(),
    )
}

#[test]
fn photon_knobs_sweep_the_caustic_crop_from_the_cli() {
    let (dir, scene, reference) = setup("knobs");

    // More photons: the caustic's error falls, and it is the crop's error that is fitted.
    let json = sweep(&dir, &scene, &reference, "photons=1000,8000,64000");
    let (crop, whole) = errors(&json);
    assert!(
        crop[0] > 2.0 * crop[1] && crop[1] > 2.0 * crop[2],
        "caustic error does not fall with photons: {crop:?}"
    );
    assert!(
        crop[0] > whole[0],
        "the caustic dominates the error: {crop:?} vs {whole:?}"
    );
    assert_eq!(json["crop"]["x0"], 35);
    // Fitted where the times rise with the photon count; runs this short can come out of
    // order under load, and then the summary says so instead of fitting noise.
    match json["slope"].as_f64() {
        Some(slope) => assert!(slope < 0.0, "{json}"),
        None => assert!(
            json["no_fit"]
                .as_str()
                .is_some_and(|why| why.starts_with("the times do not rise")),
            "{json}"
        ),
    }
    let csv = std::fs::read_to_string(dir.join("photons/sweep.csv")).unwrap();
    assert!(csv
        .lines()
        .next()
        .unwrap()
        .ends_with(",crop_rel_mse,crop_bias2,crop_variance"));

    // A tiny gather radius leaves few photons per estimate: noisier than the automatic one.
    let (crop, _) = errors(&sweep(&dir, &scene, &reference, "gather_radius=0,0.004"));
    assert!(crop[1] > 2.0 * crop[0], "gather_radius: {crop:?}");

    // Fewer photons per estimate: noisier.
    let (crop, _) = errors(&sweep(&dir, &scene, &reference, "gather_count=4,100"));
    assert!(crop[0] > 1.5 * crop[1], "gather_count: {crop:?}");

    // Progressive passes trace the photons again each pass: the error falls. (The automatic
    // radius starts each point at its k-nearest radius, so one pass is already sharp: 3.3e-3,
    // 8 passes 2.0e-3.)
    let (crop, _) = errors(&sweep(&dir, &scene, &reference, "passes=1,8"));
    assert!(crop[0] > 1.4 * crop[1], "passes: {crop:?}");

    // Every filter value is a different estimate of the same caustic.
    let json = sweep(&dir, &scene, &reference, "filter=box,cone,gauss");
    let (crop, _) = errors(&json);
    let labels: Vec<&str> = json["rows"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["value"].as_str().unwrap())
        .collect();
    assert_eq!(labels, ["box", "cone:1.1", "gauss"]);
    assert!(
        crop[0] != crop[1] && crop[1] != crop[2] && crop[0] != crop[2],
        "filter: {crop:?}"
    );
}

#[test]
fn a_bad_crop_is_refused_with_the_reason() {
    let dir = scratch("bad_crop");
    let scene_file = dir.join("scene.ron");
    std::fs::write(&scene_file, scene(1000)).unwrap();
    let o =
        run(bin()
            .arg("sweep")
            .arg(&scene_file)
            .args(["--knob", "photons=100", "--crop", "1,2,3"]));
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("expected four whole numbers X0,Y0,X1,Y1, found 3 in \"1,2,3\""),
        "{err}"
    );
    // A crop past the image's edge: the reference's size is named, nothing is written.
    let out = dir.join("out");
    let reference = dir.join("reference.exr");
    let o = run(bin()
        .arg("render")
        .arg(&scene_file)
        .args(["--spp", "1", "-o"])
        .arg(&reference));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run(bin()
        .arg("sweep")
        .arg(&scene_file)
        .args([
            "--knob",
            "photons=100",
            "--crop",
            "60,40,65,48",
            "--reference",
        ])
        .arg(&reference)
        .arg("--out")
        .arg(&out));
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(
            "the crop 60,40,65,48 (pixels [X0, X1) × [Y0, Y1)) does not fit the reference's 64×48 pixels"
        ),
        "{err}"
    );
    assert!(!out.join("sweep.csv").exists());
}

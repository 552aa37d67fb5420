//! `stagelight sweep` end to end: the table, JSON and plot are written, the error falls as
//! the knob buys accuracy, a cached reference is reused, and knobs the scene lacks are
//! refused.

use std::path::PathBuf;
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_stagelight"))
}

fn scratch(test: &str) -> PathBuf {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight-sweep-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(cmd: &mut Command) -> Output {
    cmd.output().expect("run stagelight")
}

/// A small lit scene: a floor under a rectangular light with a blocker (soft shadow), and a
/// bake request for the bake knob.
const SCENE: &str = r#"Scene(
    options: (samples: 1),
    cameras: [(name: "cam", fov_y: 50.0, resolution: (64, 48),
        placement: LookAt(eye: (0, -3, 3), target: (0, 0, 0)))],
    lights: [(name: "panel", kind: Rect(corner: (-0.5, -0.5, 2), edge_u: (0, 1, 0), edge_v: (1, 0, 0)), intensity: 4.0, samples: 1)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.6, 0.6, 0.6)))],
    objects: [
        (name: "floor", mesh: Inline(vertices: [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)],
            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]), material: "grey"),
        (name: "blocker", mesh: Inline(vertices: [(-0.3, -0.3, 0.8), (0.3, -0.3, 0.8), (0.3, 0.3, 0.8), (-0.3, 0.3, 0.8)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
    ],
    instances: [
        (name: "floor_1", of: "floor", bake: (resolution: (16, 16), outputs: [(kind: AmbientOcclusion(samples: 4))])),
        (name: "blocker_1", of: "blocker"),
    ],
    groups: [(name: "world", members: ["floor_1", "blocker_1"])],
    render: (root: "world", camera: "cam"),
)
"#;

fn setup(test: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(test);
    let scene = dir.join("scene.ron");
    std::fs::write(&scene, SCENE).unwrap();
    (dir, scene)
}

fn rel_mse_column(csv: &str) -> Vec<f64> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header
        .iter()
        .position(|h| *h == "rel_mse")
        .expect("rel_mse column");
    lines
        .map(|l| l.split(',').nth(col).unwrap().parse().unwrap())
        .collect()
}

#[test]
fn spp_sweep_writes_table_json_plot_and_error_falls() {
    let (dir, scene) = setup("spp");
    let out = dir.join("out");
    let o = run(bin()
        .arg("sweep")
        .arg(&scene)
        .args([
            "--knob",
            "spp=1,8,64",
            "--reference-spp",
            "256",
            "--seeds",
            "2",
        ])
        .arg("--out")
        .arg(&out));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    assert!(csv.starts_with("spp,"), "{csv}");
    for col in [
        "shade_seconds",
        "total_seconds",
        "mse",
        "rel_mse",
        "max_error",
        "non_finite",
        "bias2",
        "variance",
    ] {
        assert!(
            csv.lines().next().unwrap().split(',').any(|h| h == col),
            "missing {col}"
        );
    }
    let rel = rel_mse_column(&csv);
    assert_eq!(rel.len(), 3);
    assert!(
        rel[0] > rel[1] && rel[1] > rel[2],
        "relMSE does not fall: {rel:?}"
    );
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(json["knob"], "spp");
    // The reported slope is the least-squares fit of log relMSE against log seconds of the
    // table's own rows (the timings themselves are too noisy on a shared machine to bound).
    // 8× steps of spp keep the times in order, unless the machine's load reorders runs this
    // short: then the summary refuses to fit (and says why) instead of fitting noise.
    match json["slope"].as_f64() {
        Some(slope) => {
            let points: Vec<(f64, f64)> = json["rows"]
                .as_array()
                .unwrap()
                .iter()
                .map(|r| {
                    (
                        r["seconds"].as_f64().unwrap().log10(),
                        r["error"]["rel_mse"].as_f64().unwrap().log10(),
                    )
                })
                .collect();
            let n = points.len() as f64;
            let (mx, my) = (
                points.iter().map(|p| p.0).sum::<f64>() / n,
                points.iter().map(|p| p.1).sum::<f64>() / n,
            );
            let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
            let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
            assert!(
                (slope - sxy / sxx).abs() < 1e-6 * (1.0 + slope.abs()),
                "slope {slope} vs fit {}",
                sxy / sxx
            );
        }
        None => assert!(
            json["no_fit"]
                .as_str()
                .is_some_and(|why| why.starts_with("the times do not rise")),
            "{json}"
        ),
    }
    assert_eq!(json["rows"][0]["seeds"], 2);
    assert!(json["rows"][0]["error"]["variance"].as_f64().unwrap() > 0.0);
    let svg = std::fs::read_to_string(out.join("sweep.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("relMSE"));
    // A second sweep reuses the cached reference.
    let o = run(bin()
        .arg("sweep")
        .arg(&scene)
        .args(["--knob", "spp=2", "--reference-spp", "256"])
        .arg("--out")
        .arg(&out));
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("reference: cached"));
}

#[test]
fn bake_samples_sweep_compares_baked_textures() {
    let (dir, scene) = setup("bake");
    let out = dir.join("out");
    let o = run(bin()
        .arg("sweep")
        .arg(&scene)
        .args(["--knob", "bake_samples=4,64", "--reference-spp", "1024"])
        .arg("--out")
        .arg(&out));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rel = rel_mse_column(&std::fs::read_to_string(out.join("sweep.csv")).unwrap());
    assert!(rel[0] > rel[1], "{rel:?}");
    // The reference is the scene's AO bake at 1024 rays per texel, not a path-traced image.
    assert!(
        String::from_utf8_lossy(&o.stderr)
            .starts_with("sweep: reference: AO bake, 1024 rays per texel\n"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(json["reference"], "AO bake, 1024 rays per texel");
}

/// `--denoise`: the swept bakes are denoised in texel space (the reference is not), which at
/// the same sample count lowers the error against the converged reference; the table names
/// the knob `bake_samples+denoise`. A render knob refuses it.
#[test]
fn denoise_flag_denoises_the_swept_bakes_only() {
    let (dir, scene) = setup("denoise");
    let out = dir.join("out");
    let sweep = |denoise: bool| {
        let mut cmd = bin();
        cmd.arg("sweep")
            .arg(&scene)
            .args(["--knob", "bake_samples=4", "--reference-spp", "1024"])
            .arg("--out")
            .arg(&out);
        if denoise {
            cmd.arg("--denoise");
        }
        let o = run(&mut cmd);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read_to_string(out.join("sweep.csv")).unwrap()
    };
    let plain = sweep(false);
    let denoised = sweep(true);
    assert!(plain.starts_with("bake_samples,"), "{plain}");
    assert!(denoised.starts_with("bake_samples+denoise,"), "{denoised}");
    let (p, d) = (rel_mse_column(&plain)[0], rel_mse_column(&denoised)[0]);
    assert!(d < 0.5 * p, "relMSE {p} plain, {d} denoised");
    let o = run(bin()
        .arg("sweep")
        .arg(&scene)
        .args(["--knob", "spp=1,4", "--denoise"])
        .arg("--out")
        .arg(dir.join("r")));
    // A usage error, as README says of them all.
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&o.stderr).trim_end(),
        "error: --denoise filters baked textures, but knob spp renders images; sweep `--knob bake_samples=…` with it"
    );
}

#[test]
fn knobs_the_scene_lacks_are_errors_and_unknown_knobs_usage_errors() {
    let (dir, scene) = setup("absent");
    let o = run(bin()
        .arg("sweep")
        .arg(&scene)
        .args(["--knob", "tessellation=1,0.5"])
        .arg("--out")
        .arg(dir.join("o")));
    assert_eq!(o.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&o.stderr)
            .contains("knob tessellation is not in this scene: no object has an approximation"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let o = run(bin()
        .arg("sweep")
        .arg(&scene)
        .args(["--knob", "photons=1000,4000"])
        .arg("--out")
        .arg(dir.join("p")));
    assert_eq!(o.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains(
            "knob photons is not in this scene: the scene turns on neither caustics nor global_illumination"
        ),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let o = run(bin()
        .arg("sweep")
        .arg(&scene)
        .args(["--knob", "photon_count=1,2"]));
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown knob \"photon_count\""));
}

/// `--integrator path` applies to the swept runs: against a path-traced reference the path
/// tracer converges (no bias plateau), while direct lighting keeps its bias.
#[test]
fn integrator_flag_applies_to_the_swept_runs() {
    let (dir, scene) = setup("integrator");
    let bias = |integrator: &str| {
        let out = dir.join(format!("out_{integrator}"));
        let o = run(bin()
            .arg("sweep")
            .arg(&scene)
            .args([
                "--knob",
                "spp=64",
                "--reference-spp",
                "256",
                "--seeds",
                "2",
                "--integrator",
                integrator,
            ])
            .arg("--out")
            .arg(&out));
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("sweep.json")).unwrap()).unwrap();
        json["rows"][0]["error"]["bias2"].as_f64().unwrap()
    };
    let (path, direct) = (bias("path"), bias("direct"));
    assert!(direct > 10.0 * path, "bias² path {path}, direct {direct}");
}

/// `--knob adaptive_contrast`: refused on a scene with a fixed sample count; on a scene with
/// `samples: (min, max, contrast)` lower contrast buys lower error.
#[test]
fn adaptive_contrast_sweep_needs_adaptive_samples_and_error_falls() {
    let (dir, scene) = setup("adaptive");
    let o = run(bin()
        .arg("sweep")
        .arg(&scene)
        .args(["--knob", "adaptive_contrast=0.2,0.05"])
        .arg("--out")
        .arg(dir.join("o")));
    assert_eq!(o.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("knob adaptive_contrast is not in this scene"),
        "{stderr}"
    );
    let adaptive = dir.join("adaptive.ron");
    std::fs::write(
        &adaptive,
        SCENE.replace("samples: 1),", "samples: (min: 2, max: 64)),"),
    )
    .unwrap();
    let out = dir.join("adaptive_out");
    let o = run(bin()
        .arg("sweep")
        .arg(&adaptive)
        .args([
            "--knob",
            "adaptive_contrast=0.5,0.01",
            "--reference-spp",
            "256",
        ])
        .arg("--out")
        .arg(&out));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rel = rel_mse_column(&std::fs::read_to_string(out.join("sweep.csv")).unwrap());
    assert!(rel[0] > rel[1], "{rel:?}");
}

/// The cached reference is keyed by everything the scene reads: unchanged files reuse it,
/// an edit of an included file (here the material's albedo) renders a new one.
#[test]
fn an_edited_include_renders_a_new_reference() {
    let dir = scratch("include");
    let scene = dir.join("scene.ron");
    let grey = r#"(name: "grey", shader: Lambert(albedo: (0.6, 0.6, 0.6)))"#;
    let without = SCENE.replace(
        &format!("materials: [{grey}],"),
        r#"include: ["materials.ron"],"#,
    );
    assert_ne!(without, SCENE);
    std::fs::write(&scene, without).unwrap();
    let materials = |albedo: &str| {
        let text = format!(
            "Scene(materials: [{}])",
            grey.replace("0.6, 0.6, 0.6", albedo)
        );
        std::fs::write(dir.join("materials.ron"), text).unwrap();
    };
    let sweep = || {
        let o = run(bin()
            .arg("sweep")
            .arg(&scene)
            .args(["--knob", "spp=1", "--reference-spp", "4", "--out"])
            .arg(dir.join("out")));
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).contains("reference: cached")
    };
    materials("0.6, 0.6, 0.6");
    assert!(!sweep(), "the first sweep renders its reference");
    assert!(sweep(), "an unchanged scene reuses it");
    materials("0.1, 0.1, 0.1");
    assert!(!sweep(), "an edited include renders a new reference");
    assert!(sweep());
}

/// A `--crop` outside the camera's image is refused before the reference is rendered, as a
/// usage error, leaving no output directory (it was refused after rendering the reference,
/// which stayed in `--out`).
#[test]
fn a_crop_outside_the_camera_is_refused_before_the_reference_is_rendered() {
    let (dir, scene) = setup("crop-outside");
    let o = run(bin()
        .arg("sweep")
        .arg(&scene)
        .args(["--knob", "spp=1,2", "--reference-spp", "1"])
        .args(["--crop", "0,0,100,100"])
        .arg("--out")
        .arg(dir.join("o")));
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("error: the crop 0,0,100,100 (pixels [X0, X1) × [Y0, Y1)) does not fit the camera's 64×48 pixels\n  help: give X1 ≤ 64 and Y1 ≤ 48"),
        "{e}"
    );
    assert!(!e.contains("reference:"), "{e}");
    assert!(!dir.join("o").exists());
}

/// A `--reference` that is not an EXR file (a PNG, a scene) is a usage error naming the flag
/// and what it takes, before the scene is read; nothing is written.
#[test]
fn a_reference_that_is_not_an_exr_file_is_refused_naming_the_flag() {
    let (dir, scene) = setup("reference-png");
    std::fs::write(dir.join("ref.png"), b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR").unwrap();
    let help = "  help: give a linear EXR image of the runs' size (without --reference, the sweep renders one and caches it in --out)";
    for (reference, said) in [
        (
            "ref.png",
            "--reference ref.png is not an EXR file".to_string(),
        ),
        (
            "scene.ron",
            "--reference scene.ron is not an EXR file".to_string(),
        ),
        (
            "missing.exr",
            "--reference missing.exr: cannot read it: file not found".to_string(),
        ),
    ] {
        let o = run(bin().current_dir(&dir).arg("sweep").arg(&scene).args([
            "--knob",
            "spp=1,2",
            "--reference",
            reference,
            "--out",
            "o",
        ]));
        assert_eq!(o.status.code(), Some(2), "{reference}");
        assert_eq!(
            String::from_utf8_lossy(&o.stderr),
            format!("error: {said}\n{help}\n")
        );
        assert!(!dir.join("o").exists());
    }
}

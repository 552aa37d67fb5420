//! Interrupting a render or a bake with SIGINT stops it, exits 130 and leaves no output file
//! (not even a partial or temporary one).

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn scratch(test: &str) -> PathBuf {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight-sigint-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Starts `stagelight args…`, sends SIGINT after `delay`, returns the exit code.
fn interrupt(args: &[&str], dir: &PathBuf, delay: Duration) -> Option<i32> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_stagelight"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start stagelight");
    std::thread::sleep(delay);
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(status.success());
    let start = Instant::now();
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return s.code();
        }
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "did not stop after SIGINT"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn leftovers(dir: &PathBuf) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect()
}

#[test]
fn sigint_during_render_exits_130_and_writes_nothing() {
    let dir = scratch("render");
    let scene = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/cornell_box.ron");
    let code = interrupt(
        &[
            "render",
            scene.to_str().unwrap(),
            "-o",
            "out.exr",
            "--spp",
            "65536",
        ],
        &dir,
        Duration::from_millis(800),
    );
    assert_eq!(code, Some(130));
    assert!(
        leftovers(&dir).is_empty(),
        "files left: {:?}",
        leftovers(&dir)
    );
}

#[test]
fn sigint_during_bake_exits_130_and_writes_nothing() {
    let dir = scratch("bake");
    let scene = dir.join("scene.ron");
    std::fs::write(
        &scene,
        r#"Scene(
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "floor", mesh: Inline(
        vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
        uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]), material: "grey")],
    instances: [(name: "floor_1", of: "floor", bake: (resolution: (2048, 2048),
        outputs: [(kind: AmbientOcclusion(samples: 4096))]))],
    groups: [(name: "world", members: ["floor_1"])],
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)))],
    render: (root: "world", camera: "cam"),
)
"#,
    )
    .unwrap();
    let out = dir.join("textures");
    let code = interrupt(
        &["bake", scene.to_str().unwrap(), "-o", out.to_str().unwrap()],
        &dir,
        Duration::from_millis(800),
    );
    assert_eq!(code, Some(130));
    assert!(!out.exists() || leftovers(&out).is_empty());
}

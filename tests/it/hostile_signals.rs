//! Issue 18, family 7: SIGTERM stops a run like SIGINT (exit 130, nothing written), a run
//! stops within half a second even inside one pixel's samples, and the hidden temporaries a
//! killed process left are removed by the next run into the same directory.

use std::process::Stdio;
use std::time::{Duration, Instant};

use crate::common::{
    dir_names, quad_object, run_in, scratch_dir, small_scene, stagelight_in, stderr_of,
};

/// Starts `stagelight args…` in `dir`, sends `signal` after `delay`; returns the exit code,
/// the seconds from the signal to the exit, and stderr.
fn signal_after(
    dir: &std::path::Path,
    args: &[&str],
    signal: &str,
    delay: Duration,
) -> (Option<i32>, f64, String) {
    let mut child = stagelight_in(dir)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start stagelight");
    std::thread::sleep(delay);
    let sent = Instant::now();
    let status = std::process::Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(status.success());
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        assert!(sent.elapsed() < Duration::from_secs(20), "did not stop");
        std::thread::sleep(Duration::from_millis(5));
    }
    let seconds = sent.elapsed().as_secs_f64();
    let out = child.wait_with_output().unwrap();
    (out.status.code(), seconds, stderr_of(&out))
}

#[test]
fn sigterm_inside_one_pixels_samples_exits_130_within_half_a_second() {
    let dir = scratch_dir("sigterm");
    std::fs::write(
        dir.join("scene.ron"),
        small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", ""),
    )
    .unwrap();
    // 10⁹ samples in each of 64 pixels: cancellation between pixels alone would never come.
    let (code, seconds, stderr) = signal_after(
        &dir,
        &[
            "render",
            "scene.ron",
            "-o",
            "out.exr",
            "--spp",
            "1000000000",
        ],
        "-TERM",
        Duration::from_millis(700),
    );
    assert_eq!(code, Some(130), "{stderr}");
    assert!(
        stderr.ends_with("interrupted; no output written\n"),
        "{stderr}"
    );
    assert!(seconds < 0.5, "took {seconds:.3} s after SIGTERM");
    assert_eq!(dir_names(&dir), ["scene.ron"]);
}

#[test]
fn stale_temporaries_of_dead_processes_are_removed_by_the_next_run() {
    let dir = scratch_dir("stale-temps");
    std::fs::write(
        dir.join("scene.ron"),
        small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", ""),
    )
    .unwrap();
    // What a SIGKILL during a commit leaves: no Linux pid reaches 4,999,999.
    std::fs::write(dir.join(".out.png.4999999.tmp"), b"partial").unwrap();
    std::fs::write(dir.join(".old.png.4999999.tmp"), b"partial").unwrap();
    std::fs::write(dir.join("notes.tmp"), b"not ours").unwrap();
    let o = run_in(
        &dir,
        &["render", "scene.ron", "-o", "out.png", "--spp", "1"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert_eq!(dir_names(&dir), ["notes.tmp", "out.png", "scene.ron"]);
}

#[test]
fn sigint_inside_the_bvh_build_exits_130_within_half_a_second() {
    let dir = scratch_dir("sigint-bvh");
    // 2,000,000 triangles: the build takes well over the 400 ms before the signal (980,000
    // built within them on a quiet host once build temporaries left huge pages, and the
    // render finished first), and the builder cannot poll the flag, so the interrupt
    // handler's deadline ends the run.
    let grid = r#"(name: "grid", mesh: Grid(size_x: 2, size_y: 2, nx: 1000, ny: 1000), material: "grey"),"#;
    std::fs::write(
        dir.join("scene.ron"),
        small_scene(grid, r#"(name: "g", of: "grid")"#, "", ""),
    )
    .unwrap();
    let (code, seconds, stderr) = signal_after(
        &dir,
        &["render", "scene.ron", "-o", "out.exr"],
        "-INT",
        Duration::from_millis(400),
    );
    assert_eq!(code, Some(130), "{stderr}");
    assert!(
        stderr.ends_with("interrupted; no output written\n"),
        "{stderr}"
    );
    eprintln!("stopped {seconds:.3} s after SIGINT inside the BVH build");
    assert!(seconds < 0.5, "took {seconds:.3} s after SIGINT");
    assert_eq!(dir_names(&dir), ["scene.ron"]);
}

//! Issue 18, family 7: SIGTERM stops a run like SIGINT (exit 130, nothing written), a run
//! stops within half a second even inside one pixel's samples, and the hidden temporaries a
//! killed process left are removed by the next run into the same directory. A sweep stops
//! the same way and removes its scratch textures, but keeps a reference it cached, for the
//! next sweep;
//! SIGINT stops a run even when it was ignored at the start (a script's background job).

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
    let mut cmd = stagelight_in(dir);
    cmd.args(args);
    signal_command(cmd, signal, || std::thread::sleep(delay))
}

/// Starts `cmd`, sends `signal` once `ready` returns; returns the exit code, the seconds
/// from the signal to the exit, and stderr.
fn signal_command(
    mut cmd: std::process::Command,
    signal: &str,
    ready: impl FnOnce(),
) -> (Option<i32>, f64, String) {
    let mut child = cmd
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start stagelight");
    ready();
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

/// `stagelight args…` in `dir` with SIGINT ignored, as a script's `cmd &` starts it.
fn with_sigint_ignored(dir: &std::path::Path, args: &[&str]) -> std::process::Command {
    let mut cmd = std::process::Command::new("sh");
    cmd.arg("-c")
        .arg("trap '' INT; exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_stagelight"))
        .args(args)
        .current_dir(dir);
    cmd
}

#[test]
fn sigterm_during_a_sweep_exits_130_and_writes_nothing() {
    let dir = scratch_dir("sigterm-sweep");
    std::fs::write(
        dir.join("scene.ron"),
        small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", ""),
    )
    .unwrap();
    // 10⁹ samples per pixel of the reference: it would never end.
    let args = [
        "sweep",
        "scene.ron",
        "--knob",
        "spp=1,2",
        "--reference-spp",
        "1000000000",
        "--out",
        "out",
    ];
    let (code, _, stderr) = signal_after(&dir, &args, "-TERM", Duration::from_millis(700));
    assert_eq!(code, Some(130), "{stderr}");
    assert_eq!(
        stderr,
        "sweep: reference: 1000000000 samples, max_depth=4 (the scene's, as in the swept runs)\ninterrupted; no output written\n"
    );
    assert_eq!(dir_names(&dir), ["scene.ron"]);
}

/// The names in `dir` that start with `reference_` (a sweep's cached references).
fn references(dir: &std::path::Path) -> Vec<String> {
    dir_names(dir)
        .into_iter()
        .filter(|n| n.starts_with("reference_"))
        .collect()
}

/// A sweep interrupted after its reference was cached (a bake sweep, whose scratch textures
/// exist then too, and a render sweep) removes its scratch directory but keeps the complete
/// reference, which the next sweep of the scene reads instead of rendering it again.
#[test]
fn a_sweep_interrupted_after_its_reference_keeps_it_for_the_next_sweep() {
    let bake = r#", bake: (resolution: (16, 16), outputs: [(kind: AmbientOcclusion(samples: 4))])"#;
    // The reference and the first value are quick; 10⁸ samples per texel or pixel are not.
    for (name, instance, slow, quick) in [
        (
            "bake",
            format!(r#"(name: "q", of: "quad"{bake})"#),
            "bake_samples=1,100000000",
            "bake_samples=1",
        ),
        (
            "render",
            r#"(name: "q", of: "quad")"#.to_string(),
            "spp=1,100000000",
            "spp=1",
        ),
    ] {
        let dir = scratch_dir(&format!("sigterm-{name}-sweep"));
        std::fs::write(
            dir.join("scene.ron"),
            small_scene(&quad_object("quad"), &instance, "", ""),
        )
        .unwrap();
        let out = dir.join("out");
        let sweep = |knob: &str| {
            let mut cmd = stagelight_in(&dir);
            cmd.args([
                "sweep",
                "scene.ron",
                "--knob",
                knob,
                "--reference-spp",
                "1",
                "--out",
                "out",
            ]);
            cmd
        };
        let (code, _, stderr) = signal_command(sweep(slow), "-TERM", || {
            let start = Instant::now();
            // The reference is cached (and a bake sweep's scratch directory made) before the
            // last value runs.
            while !((name == "render" || out.join("scratch").exists())
                && out.exists()
                && !references(&out).is_empty())
            {
                assert!(
                    start.elapsed() < Duration::from_secs(60),
                    "{name}: no reference"
                );
                std::thread::sleep(Duration::from_millis(10));
            }
            std::thread::sleep(Duration::from_millis(300));
        });
        assert_eq!(code, Some(130), "{name}: {stderr}");
        assert!(
            stderr.ends_with("interrupted; no output written\n"),
            "{name}: {stderr}"
        );
        assert_eq!(dir_names(&dir), ["out", "scene.ron"], "{name}");
        let kept = references(&out);
        assert_eq!(dir_names(&out), kept, "{name}: the reference alone is left");
        assert_eq!(kept.len(), 1, "{name}");
        let reference = out.join(&kept[0]);
        let bytes = std::fs::read(&reference).unwrap();
        // The next sweep reads it instead of rendering its reference again.
        let o = sweep(quick).output().unwrap();
        assert!(o.status.success(), "{name}: {}", stderr_of(&o));
        let stderr = stderr_of(&o);
        // A rendered reference states its trace depth; a bake's has none.
        let depth = if name == "render" {
            ", max_depth=4 (the scene's, as in the swept runs)"
        } else {
            ""
        };
        assert!(
            stderr.starts_with(&format!(
                "sweep: reference: cached out/{}{depth}\n",
                kept[0]
            )),
            "{name}: {stderr}"
        );
        assert!(!stderr.contains("reference: 1 samples"), "{name}: {stderr}");
        assert_eq!(std::fs::read(&reference).unwrap(), bytes, "{name}");
        assert_eq!(
            dir_names(&out),
            [kept[0].as_str(), "sweep.csv", "sweep.json", "sweep.svg"],
            "{name}"
        );
    }
}

#[test]
fn sigint_stops_render_and_sweep_even_when_ignored_at_the_start() {
    let dir = scratch_dir("sigint-ignored");
    std::fs::write(
        dir.join("scene.ron"),
        small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", ""),
    )
    .unwrap();
    for args in [
        &[
            "render",
            "scene.ron",
            "-o",
            "out.exr",
            "--spp",
            "1000000000",
        ][..],
        &[
            "sweep",
            "scene.ron",
            "--knob",
            "spp=1,2",
            "--reference-spp",
            "1000000000",
            "--out",
            "out",
        ][..],
    ] {
        let cmd = with_sigint_ignored(&dir, args);
        let (code, _, stderr) = signal_command(cmd, "-INT", || {
            std::thread::sleep(Duration::from_millis(700))
        });
        assert_eq!(code, Some(130), "{args:?}: {stderr}");
        assert!(
            stderr.ends_with("interrupted; no output written\n"),
            "{args:?}: {stderr}"
        );
        assert_eq!(dir_names(&dir), ["scene.ron"], "{args:?}");
    }
}

/// `merge` stops on SIGTERM, and on SIGINT ignored at the start, as `render` does: exit 130,
/// "interrupted", nothing written. It had no handler until its stages ran, so SIGTERM
/// while it read its parts killed it (no message, status 143) and an ignored SIGINT was
/// lost (a background `merge … &` wrote its output after `kill -INT`). Its second part is a
/// FIFO that nothing writes, so the merge waits in reading it until the signal comes.
#[test]
fn merge_stops_on_sigterm_and_an_ignored_sigint_while_reading_its_parts() {
    let dir = scratch_dir("merge-signals");
    std::fs::write(
        dir.join("scene.ron"),
        small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", ""),
    )
    .unwrap();
    let o = run_in(
        &dir,
        &["render", "scene.ron", "--part", "1/2", "-o", "part_1.exr"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let fifo = std::process::Command::new("mkfifo")
        .arg(dir.join("part_2.exr"))
        .status()
        .expect("mkfifo");
    assert!(fifo.success());
    let args = ["merge", "part_1.exr", "part_2.exr", "-o", "out.png"];
    let plain = {
        let mut cmd = stagelight_in(&dir);
        cmd.args(args);
        cmd
    };
    for (cmd, signal) in [(plain, "-TERM"), (with_sigint_ignored(&dir, &args), "-INT")] {
        let (code, seconds, stderr) = signal_command(cmd, signal, || {
            std::thread::sleep(Duration::from_millis(700))
        });
        assert_eq!(code, Some(130), "{signal}: {stderr}");
        assert_eq!(stderr, "interrupted; no output written\n", "{signal}");
        assert!(seconds < 0.5, "{signal}: took {seconds:.3} s");
        assert_eq!(
            dir_names(&dir),
            ["part_1.exr", "part_2.exr", "scene.ron"],
            "{signal}"
        );
    }
}

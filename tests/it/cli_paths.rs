//! Paths given to flags are checked before the first stage: a directory flag naming a file,
//! an output whose directory runs through a file, `convert -o` naming a directory (exit 2,
//! the flag and the path named, nothing written); `convert -o` creates a missing directory
//! as `render -o` does. Output paths that cannot be written (a directory that takes no file
//! or cannot be created) are refused as well, the scene's own outputs located at their `file`.

use crate::common::{dir_names, quad_object, run_in, scratch_dir, small_scene, stderr_of};

const DIR_HELP: &str = "  help: give a directory (it is created when missing)";

#[test]
fn a_directory_flag_naming_a_file_is_refused_before_the_run() {
    let dir = scratch_dir("paths-dir-flags");
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "");
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    std::fs::write(dir.join("afile"), "x").unwrap();
    for (args, flag, path) in [
        (
            &["photons", "scene.ron", "--photon-cache", "afile"][..],
            "--photon-cache",
            "afile",
        ),
        (
            &["render", "scene.ron", "--photon-cache", "afile"][..],
            "--photon-cache",
            "afile",
        ),
        (&["bake", "scene.ron", "-o", "afile"][..], "-o", "afile"),
        (
            &["sweep", "scene.ron", "--knob", "spp=1,2", "--out", "afile"][..],
            "--out",
            "afile",
        ),
        (
            &["farm", "scene.ron", "--parts", "2", "--out", "afile"][..],
            "--out",
            "afile",
        ),
        (
            &[
                "farm",
                "scene.ron",
                "--parts",
                "2",
                "--out",
                "f",
                "--bake",
                "-o",
                "afile/t",
            ][..],
            "-o",
            "afile/t",
        ),
    ] {
        let o = run_in(&dir, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr_of(&o));
        assert_eq!(
            stderr_of(&o),
            format!("error: {flag} {path}: afile is a file, not a directory\n{DIR_HELP}\n"),
            "{args:?}"
        );
        assert_eq!(dir_names(&dir), ["afile", "scene.ron"], "{args:?}");
    }
    let o = run_in(&dir, &["render", "scene.ron", "-o", "afile/out.png"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        "error: -o afile/out.png: afile is a file, not a directory\n  help: give a path whose directories are directories (they are created when missing)\n"
    );
}

#[test]
fn convert_creates_the_output_directory_and_refuses_a_directory_as_output() {
    let dir = scratch_dir("paths-convert");
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "");
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["convert", "scene.ron", "-o", "conv/deeper/x.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert_eq!(dir_names(&dir.join("conv/deeper")), ["x.ron"]);
    let o = run_in(&dir, &["check", "conv/deeper/x.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));

    let o = run_in(&dir, &["convert", "scene.ron", "-o", "conv"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        "error: -o conv is a directory\n  help: give the file to write, e.g. -o conv/scene.ron\n"
    );
    assert_eq!(dir_names(&dir), ["conv", "scene.ron"]);
}

const WRITE_HELP: &str =
    "  help: give a path in a directory you can write (missing directories are created)";

/// `--stats-json` and `-o` are checked like every flag's path, before the scene is read: a
/// directory, a path through a file, a directory that takes no file (`/sys`) or cannot be
/// created (`/proc/…`) is a usage error naming the flag, and nothing is written.
#[test]
fn stats_json_and_output_paths_that_cannot_be_written_are_refused_before_the_scene_is_read() {
    let dir = scratch_dir("paths-unwritable-flags");
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "");
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    std::fs::write(dir.join("afile"), "x").unwrap();
    std::fs::create_dir(dir.join("adir")).unwrap();
    let cases: [(&[&str], String); 7] = [
        (
            &["render", "scene.ron", "-o", "a.png", "--stats-json", "adir"],
            "error: --stats-json adir is a directory\n  help: give the file to write, e.g. --stats-json adir/stats.json\n".into(),
        ),
        (
            &["bake", "scene.ron", "--stats-json", "afile/s.json"],
            "error: --stats-json afile/s.json: afile is a file, not a directory\n  help: give a path whose directories are directories (they are created when missing)\n".into(),
        ),
        (
            &["render", "scene.ron", "-o", "a.png", "--stats-json", "/sys/stagelight.json"],
            format!("error: --stats-json /sys/stagelight.json: cannot write into /sys: permission denied\n{WRITE_HELP}\n"),
        ),
        (
            &["render", "scene.ron", "-o", "/proc/stagelight-x/a.png"],
            format!("error: -o /proc/stagelight-x/a.png: cannot create the directory /proc/stagelight-x: no such file or directory\n{WRITE_HELP}\n"),
        ),
        (
            &["bake", "scene.ron", "-o", "/proc/stagelight-slb"],
            format!("error: -o /proc/stagelight-slb: cannot create the directory /proc/stagelight-slb: no such file or directory\n{WRITE_HELP}\n"),
        ),
        (
            &["sweep", "scene.ron", "--knob", "spp=1,2", "--out", "/sys/stagelight-sweep"],
            "error: --out /sys/stagelight-sweep: cannot create the directory /sys/stagelight-sweep: operation not permitted\n".to_string() + WRITE_HELP + "\n",
        ),
        (
            &["farm", "scene.ron", "--parts", "2", "--out", "f", "-o", "/sys/m.png"],
            format!("error: -o /sys/m.png: cannot write into /sys: permission denied\n{WRITE_HELP}\n"),
        ),
    ];
    for (args, expected) in cases {
        let o = run_in(&dir, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr_of(&o));
        assert_eq!(stderr_of(&o), expected, "{args:?}");
        assert_eq!(dir_names(&dir), ["adir", "afile", "scene.ron"], "{args:?}");
        assert!(dir_names(&dir.join("adir")).is_empty(), "{args:?}");
    }
}

/// The scene's own outputs are checked once the scene is loaded, before the first stage:
/// each refusal is located at the output's `file`, exits 1 (the scene, not a flag, names the
/// path), and `check` refuses the same, and `farm` before writing a script.
#[test]
fn scene_outputs_that_cannot_be_written_are_refused_at_their_file_before_the_first_stage() {
    let dir = scratch_dir("paths-unwritable-scene");
    let outputs = r#"(file: "adir.png"), (file: "afile/x.png"), (file: "/sys/x.exr"), (file: "/proc/stagelight-x/y.exr")"#;
    let scene = small_scene(
        &quad_object("quad"),
        r#"(name: "q", of: "quad")"#,
        outputs,
        "",
    );
    std::fs::write(dir.join("scene.ron"), &scene).unwrap();
    std::fs::write(dir.join("afile"), "x").unwrap();
    std::fs::create_dir(dir.join("adir.png")).unwrap();
    let line = scene.lines().position(|l| l.contains("adir.png")).unwrap() + 1;
    let text = scene.lines().nth(line - 1).unwrap();
    let at = |file: &str| format!("scene.ron:{line}:{}", text.find(file).unwrap() + 1);
    let expected = |tail: &str| {
        format!(
            "{}: error: camera \"cam\" output 1 (\"adir.png\") is a directory\n  help: give the path of a file, not of a directory\n\
             {}: error: camera \"cam\" output 2 (\"afile/x.png\"): afile is a file, not a directory\n  help: give a path whose directories are directories (they are created when missing)\n\
             {}: error: camera \"cam\" output 3 (\"/sys/x.exr\"): cannot write into /sys: permission denied\n{WRITE_HELP}\n\
             {}: error: camera \"cam\" output 4 (\"/proc/stagelight-x/y.exr\"): cannot create the directory /proc/stagelight-x: no such file or directory\n{WRITE_HELP}\n\
             4 errors in scene.ron{tail}\n",
            at("\"adir.png\""),
            at("\"afile/x.png\""),
            at("\"/sys/x.exr\""),
            at("\"/proc/stagelight-x/y.exr\""),
        )
    };
    for (args, tail) in [
        (&["check", "scene.ron"][..], ""),
        // 10⁹ samples per pixel: refused before the first stage, or the test would not end.
        (
            &["render", "scene.ron", "--spp", "1000000000"][..],
            "; nothing rendered",
        ),
        (
            &["farm", "scene.ron", "--parts", "1", "--out", "f"][..],
            "; no scripts written",
        ),
    ] {
        let o = run_in(&dir, args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr_of(&o));
        assert_eq!(stderr_of(&o), expected(tail), "{args:?}");
        assert_eq!(
            dir_names(&dir),
            ["adir.png", "afile", "scene.ron"],
            "{args:?}"
        );
    }
}

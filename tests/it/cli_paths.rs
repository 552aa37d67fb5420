//! Paths given to flags are checked before the first stage: a directory flag naming a file,
//! an output whose directory runs through a file, `convert -o` naming a directory (exit 2,
//! the flag and the path named, nothing written); `convert -o` creates a missing directory
//! as `render -o` does.

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

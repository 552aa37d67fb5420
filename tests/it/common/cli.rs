//! Running the `stagelight` binary on scenes written into a scratch directory.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary under test, started in `dir`.
pub fn stagelight_in(dir: &Path) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_stagelight"));
    cmd.current_dir(dir);
    cmd
}

/// A fresh, empty scratch directory for test `name`.
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir =
        crate::common::scratch_root().join(format!("stagelight-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `stagelight args…` in `dir`.
pub fn run_in(dir: &Path, args: &[&str]) -> Output {
    stagelight_in(dir)
        .args(args)
        .output()
        .expect("run stagelight")
}

/// Runs `stagelight args…` in `dir` under a 4 GiB address-space limit (`ulimit -v`): had
/// anything of a refused estimate's size been allocated, the process would abort instead of
/// printing the refusal.
pub fn run_limited(dir: &Path, args: &[&str]) -> Output {
    let bin = env!("CARGO_BIN_EXE_stagelight");
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v 4194304 && exec \"{bin}\" \"$@\""))
        .arg("sh")
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run stagelight")
}

/// The process's stderr as text.
pub fn stderr_of(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The names in `dir`, sorted.
pub fn dir_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A small scene (an 8×8 camera looking at the z = 0 plane from z = 3, a grey material)
/// with the given objects, instances (all members of the root group), camera outputs and
/// extra top-level fields. Line 5 holds the first object.
pub fn small_scene(objects: &str, instances: &str, outputs: &str, extra: &str) -> String {
    let members: Vec<String> = instances
        .split("(name: \"")
        .skip(1)
        .map(|s| format!("\"{}\"", s.split('"').next().unwrap_or_default()))
        .collect();
    format!(
        "Scene(\n    materials: [(name: \"grey\", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],\n    lights: [(name: \"sun\", kind: Point(position: (0, 0, 3)), intensity: 10.0)],\n    objects: [\n        {objects}\n    ],\n    instances: [{instances}],\n    groups: [(name: \"world\", members: [{}])],\n    cameras: [(name: \"cam\", fov_y: 40.0, resolution: (8, 8),\n        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)), outputs: [{outputs}])],\n    render: (root: \"world\", camera: \"cam\"),\n{extra})\n",
        members.join(", ")
    )
}

/// The unit quad `[-1, 1]²` in z = 0 as an inline mesh object named `name`.
pub fn quad_object(name: &str) -> String {
    format!(
        "(name: \"{name}\", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]), material: \"grey\"),"
    )
}

/// The `stagelight` binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_stagelight"))
}

/// A fresh, empty directory for `test` (unique per process).
pub fn scratch(test: &str) -> PathBuf {
    scratch_dir(test)
}

/// Runs `cmd` to completion.
pub fn run(cmd: &mut Command) -> Output {
    cmd.output().expect("run stagelight")
}

/// Its standard error as text.
pub fn stderr(o: &Output) -> String {
    stderr_of(o)
}

/// `stagelight convert SCENE -o NAME.ron` says where it wrote, and that RON renders (1 spp)
/// to the same PNG bytes as `scene` itself, a non-trivial image.
pub fn convert_renders_the_same_png(test: &str, scene: &Path) {
    let tmp = scratch_dir(test);
    let stem = scene.file_stem().unwrap().to_string_lossy();
    let ron = tmp.join(format!("{stem}.ron"));
    let run = |args: &[&std::ffi::OsStr]| {
        let out = bin().args(args).output().expect("run stagelight");
        assert!(out.status.success(), "{args:?}\n{}", stderr_of(&out));
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let said = run(&[
        "convert".as_ref(),
        scene.as_os_str(),
        "-o".as_ref(),
        ron.as_os_str(),
    ]);
    assert!(
        said.ends_with(&format!("wrote {}\n", ron.display())),
        "{said}"
    );
    let (a, b) = (tmp.join("a.png"), tmp.join("b.png"));
    for (scene, png) in [(scene, &a), (&ron, &b)] {
        let spp: &[&std::ffi::OsStr] = &["--spp".as_ref(), "1".as_ref(), "-o".as_ref()];
        run(&[
            &["render".as_ref(), scene.as_os_str()],
            spp,
            &[png.as_os_str()],
        ]
        .concat());
    }
    let (a, b) = (std::fs::read(a).unwrap(), std::fs::read(b).unwrap());
    assert!(a.len() > 1000);
    assert!(a == b, "the PNGs differ");
    let _ = std::fs::remove_dir_all(&tmp);
}

/// What the last line of a refusal says `command` did not do: `1 error in a.ron; nothing
/// rendered` (render), `…; nothing baked` (bake), `…; nothing converted` (convert), and no
/// tail for `check`, which only counts.
pub fn refused_tail(command: &str) -> &'static str {
    match command {
        "check" => "",
        "render" => "; nothing rendered",
        "bake" => "; nothing baked",
        "convert" => "; nothing converted",
        "farm" => "; no scripts written",
        other => panic!("no refusal tail for {other}"),
    }
}

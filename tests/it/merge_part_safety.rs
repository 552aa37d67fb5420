//! A merge never writes over a part file it reads — whether `-o` or the scene's own camera
//! output names it — and `farm` refuses, before writing a script, a merge job that would
//! (its `-o`, or a camera output, in `--out` under a part file's name). Plus the help lines
//! of what `merge`, `farm` and `sweep` refuse about part files, formats, bake requests,
//! `sbatch` and knobs.

use std::path::Path;

use crate::common::cli::{dir_names, run_in, scratch_dir, stderr_of};

/// A small scene whose camera writes `output`.
fn scene(output: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 2),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (48, 16),
               placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0)),
               outputs: [(file: "{output}")])],
    lights: [(name: "sun", kind: Point(position: (0.5, 0, 3)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "floor", mesh: Inline(
        vertices: [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)],
        polygons: [[0, 1, 2, 3]]), material: "grey")],
    instances: [(name: "floor_1", of: "floor")],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

fn ok(dir: &Path, args: &[&str]) {
    let o = run_in(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

/// Renders parts 1 and 2 of 2 of `scene` into `part_1.exr` and `part_2.exr`.
fn two_parts(dir: &Path, scene: &str) {
    for k in 1..=2 {
        let (part, file) = (format!("{k}/2"), format!("part_{k}.exr"));
        ok(dir, &["render", scene, "--part", &part, "-o", &file]);
    }
}

/// `args` exits with `code` and prints exactly `expected` on stderr.
fn refused(dir: &Path, args: &[&str], code: i32, expected: &str) {
    let o = run_in(dir, args);
    assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stderr_of(&o));
    assert_eq!(stderr_of(&o), expected, "{args:?}");
}

/// The tester's case: the camera writes `part_1.exr`, the parts are rendered to
/// `part_1.exr` and `part_2.exr`, and `merge part_1.exr part_2.exr` wrote the merged image
/// over part 1 ("wrote part_1.exr", exit 0). It is refused like `-o part_1.exr`, located
/// at the camera output, and the part is untouched.
#[test]
fn a_camera_output_that_is_a_part_file_is_refused_and_the_part_kept() {
    let dir = scratch_dir("merge-part-output");
    std::fs::write(dir.join("s.ron"), scene("part_1.exr")).unwrap();
    two_parts(&dir, "s.ron");
    let part = std::fs::read(dir.join("part_1.exr")).unwrap();
    let scene = std::path::absolute(dir.join("s.ron")).unwrap();
    let scene = scene.display();
    refused(
        &dir,
        &["merge", "part_1.exr", "part_2.exr"],
        1,
        &format!(
            "{scene}:5:33: error: camera \"cam\" output 1 (\"part_1.exr\") would overwrite the part file part_1.exr being merged\n  help: keep the part files apart from the scene's outputs: render the parts into a directory of their own (`render --part K/N -o parts/part_K.exr`) and merge them from there\n1 error in {scene}; nothing merged\n"
        ),
    );
    // Through another spelling of the same file too.
    let o = run_in(&dir, &["merge", "./part_1.exr", "part_2.exr"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(std::fs::read(dir.join("part_1.exr")).unwrap(), part);
    // `-o` elsewhere takes the camera output's place: the merge runs.
    ok(
        &dir,
        &["merge", "part_1.exr", "part_2.exr", "-o", "merged.exr"],
    );
    assert_eq!(std::fs::read(dir.join("part_1.exr")).unwrap(), part);
    assert_eq!(
        dir_names(&dir),
        ["merged.exr", "part_1.exr", "part_2.exr", "s.ron"]
    );
}

/// `farm` checks the part files its array writes into `--out` against its merge job's
/// outputs: `-o job/part_2.exr` passed (the merge job failed after every part ran), and a
/// camera output `job/part_1.exr` passed (the merge job replaced part 1 with the image).
#[test]
fn farm_refuses_a_merge_job_that_would_overwrite_a_part_file() {
    let dir = scratch_dir("farm-part-output");
    std::fs::write(dir.join("s.ron"), scene("out.png")).unwrap();
    std::fs::write(dir.join("fo.ron"), scene("job/part_1.exr")).unwrap();
    let job = std::path::absolute(dir.join("job")).unwrap();
    let job = job.display();
    refused(
        &dir,
        &["farm", "s.ron", "--parts", "3", "--out", "job", "-o", "job/part_2.exr"],
        2,
        "error: -o job/part_2.exr would overwrite the part file job/part_2.exr that part 2/3 writes and the merge job reads\n  help: give -o a path apart from the part files in --out DIR\n1 error in s.ron; no scripts written\n",
    );
    refused(
        &dir,
        &["farm", "fo.ron", "--parts", "2", "--out", "job"],
        1,
        "fo.ron:5:33: error: camera \"cam\" output 1 (\"job/part_1.exr\") would overwrite the part file job/part_1.exr that part 1/2 writes and the merge job reads\n  help: give --out a directory of its own for the part files, apart from the scene's outputs\n1 error in fo.ron; no scripts written\n",
    );
    assert!(!dir.join("job").exists(), "scripts written into {job}");
    // Names the array does not write pass: part 4 of 3, and a padded number.
    for other in ["job/part_4.exr", "job/part_02.exr"] {
        ok(
            &dir,
            &["farm", "s.ron", "--parts", "3", "--out", "job", "-o", other],
        );
    }
}

/// A part file given as `sweep --reference` was refused with the EXR library's words and
/// exit 1; a plain EXR image and a truncated part file given to `merge`, an `-o` of no
/// known format, `farm --bake` of a scene without bake requests and an unknown knob had no
/// help line.
#[test]
fn refusals_about_part_files_formats_bakes_and_knobs_have_help_lines() {
    let dir = scratch_dir("part-helps");
    std::fs::write(dir.join("s.ron"), scene("out.png")).unwrap();
    two_parts(&dir, "s.ron");
    ok(&dir, &["render", "s.ron", "-o", "plain.exr"]);
    refused(
        &dir,
        &["sweep", "s.ron", "--knob", "spp=1,2", "--reference", "part_1.exr", "--out", "sw"],
        2,
        "error: --reference part_1.exr is a stagelight part file, which holds a part's sample sums, not an image\n  help: merge the parts first (`stagelight merge PART.exr… -o reference.exr`) and give the merged EXR, or give a linear EXR image of the runs' size (without --reference, the sweep renders one and caches it in --out)\n",
    );
    refused(
        &dir,
        &["merge", "plain.exr", "part_2.exr", "-o", "m.png"],
        1,
        "error: plain.exr: not a stagelight part file (no `stagelight` attribute): an EXR image, not a part of a render\n  help: merge the EXR part files that `stagelight render --part K/N -o PART.exr` (or `stagelight bake --part K/N`) writes\nnothing written\n",
    );
    let bytes = std::fs::read(dir.join("part_2.exr")).unwrap();
    std::fs::write(dir.join("cut.exr"), &bytes[..bytes.len() / 2]).unwrap();
    let o = run_in(&dir, &["merge", "part_1.exr", "cut.exr", "-o", "m.png"]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr_of(&o);
    assert!(
        e.starts_with("error: cut.exr: not a readable EXR file ("),
        "{e}"
    );
    assert!(e.ends_with("); it may be truncated\n  help: render this part again (`stagelight render --part K/N -o PART.exr`); a part file is whole once its render has exited with status 0\nnothing written\n"), "{e}");
    let format = "cannot tell the output format of out.jpg from its extension\n  help: name a .png or .exr file for the image, or an .svg or .eps file for the contour lines\n";
    refused(
        &dir,
        &["merge", "part_1.exr", "part_2.exr", "-o", "out.jpg"],
        2,
        &format!("error: {format}"),
    );
    refused(
        &dir,
        &[
            "farm", "s.ron", "--parts", "2", "--out", "job", "-o", "out.jpg",
        ],
        2,
        &format!("error: {format}"),
    );
    let bake = run_in(&dir, &["bake", "s.ron"]);
    assert_eq!(bake.status.code(), Some(1));
    refused(
        &dir,
        &["farm", "s.ron", "--bake", "--parts", "2", "--out", "job"],
        1,
        "error: s.ron has no bake requests\n  help: add `bake: (resolution: (512, 512), outputs: [(kind: AmbientOcclusion())])` to an instance\n",
    );
    assert_eq!(stderr_of(&bake), "error: s.ron has no bake requests\n  help: add `bake: (resolution: (512, 512), outputs: [(kind: AmbientOcclusion())])` to an instance\n");
    refused(
        &dir,
        &["sweep", "s.ron", "--knob", "foo=1", "--out", "sw"],
        2,
        "error: unknown knob \"foo\"\n  help: the knobs are spp, adaptive_contrast, light_samples, max_depth, bvh_quality, tessellation, bake_samples, photons, gather_radius, gather_count, passes and filter (e.g. --knob spp=1,4,16,64)\n",
    );
    assert_eq!(
        dir_names(&dir),
        ["cut.exr", "part_1.exr", "part_2.exr", "plain.exr", "s.ron"]
    );
}

/// `farm --submit` where no `sbatch` is on PATH wrote the scripts, then failed inside
/// `submit.sh` ("sbatch: command not found", exit status 127). It now says so before
/// writing anything; with an `sbatch` on PATH it submits.
#[test]
fn farm_submit_checks_for_sbatch_first() {
    let dir = scratch_dir("farm-sbatch");
    std::fs::write(dir.join("s.ron"), scene("out.png")).unwrap();
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let path_with = |extra: &Path| {
        let system = std::env::var_os("PATH").unwrap_or_default();
        let mut dirs = vec![extra.to_path_buf()];
        // The system's directories, less any that holds a real sbatch.
        dirs.extend(std::env::split_paths(&system).filter(|d| !d.join("sbatch").exists()));
        std::env::join_paths(dirs).unwrap()
    };
    let farm = |path: &std::ffi::OsStr| {
        crate::common::cli::stagelight_in(&dir)
            .args(["farm", "s.ron", "--parts", "2", "--out", "job", "--submit"])
            .env("PATH", path)
            .output()
            .unwrap()
    };
    let o = farm(&path_with(&bin));
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    let submit = std::path::absolute(dir.join("job/submit.sh")).unwrap();
    assert_eq!(
        stderr_of(&o),
        format!(
            "error: --submit needs `sbatch`, which is not on PATH (is this a Slurm submit host?)\n  help: leave out --submit to write the scripts, then run `bash '{}'` on a machine where sbatch works\n",
            submit.display()
        )
    );
    assert!(!dir.join("job").exists());
    let sbatch = bin.join("sbatch");
    std::fs::write(&sbatch, "#!/bin/sh\necho \"$$;cluster\"\n").unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&sbatch, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    // The fake first, then every system directory (the scripts need the shell's tools, and
    // a host with Slurm installed keeps its real sbatch behind the fake one).
    let system = std::env::var_os("PATH").unwrap_or_default();
    let fake_first =
        std::env::join_paths(std::iter::once(bin.clone()).chain(std::env::split_paths(&system)))
            .unwrap();
    let o = farm(&fake_first);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        out.contains("render array job ") && out.contains("merge job "),
        "{out}"
    );
}

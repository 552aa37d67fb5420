//! `render --part K/N`, `stagelight merge` and `stagelight farm` from the command line: the
//! merged image is byte-identical to a single render, mismatched or incomplete sets of
//! parts are refused with nothing written, and the generated Slurm scripts, run as Slurm
//! would run them, produce the single render's bytes.

use std::path::Path;
use std::process::Command;

use crate::common::cli::{bin, run, scratch, stderr};

const SCENE: &str = r#"Scene(
    options: (samples: 3),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (40, 24),
               placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0)),
               outputs: [(file: "view.png")])],
    lights: [(name: "sun", kind: Point(position: (0.5, 0, 3)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [
        (name: "floor", mesh: Inline(
            vertices: [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
        (name: "ball", mesh: Sphere(radius: 0.6), material: "grey",
         approximation: Parametric(u: 16, v: 8)),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "ball_1", of: "ball", transform: [Translate((0, 0, 0.6))]),
    ],
    groups: [(name: "world", members: ["floor_1", "ball_1"])],
    render: (root: "world", camera: "cam"),
)
"#;

fn setup(test: &str) -> std::path::PathBuf {
    let dir = scratch(&format!("cli-farm-{test}"));
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
    dir
}

fn stagelight(dir: &Path, args: &[&str]) -> std::process::Output {
    run(bin().current_dir(dir).args(args))
}

fn ok(dir: &Path, args: &[&str]) {
    let o = stagelight(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
}

fn render_parts(dir: &Path, count: u32, split: &str, extra: &[&str]) -> Vec<String> {
    (1..=count)
        .map(|k| {
            let name = format!("part_{k}.exr");
            let part = format!("{k}/{count}");
            let mut args = vec![
                "render",
                "scene.ron",
                "--part",
                &part,
                "--split",
                split,
                "-o",
                &name,
            ];
            args.extend_from_slice(extra);
            ok(dir, &args);
            name
        })
        .collect()
}

/// A pinhole's camera rays go to the tree as packets when a pixel takes at least
/// `PACKET_MIN_RAYS` (8) samples at once, one by one otherwise. At 16 samples the single
/// render traces each pixel's rays as a packet, while each of four samples-split parts takes
/// four samples per pixel, one ray at a time: the merge is the single render's bytes, so
/// the packets gave every sample the same hit (the ball has 256 triangles: the tree, not the
/// small-scene path).
#[test]
fn camera_ray_packets_give_the_one_by_one_samples_bit_for_bit() {
    let dir = setup("packets");
    ok(
        &dir,
        &["render", "scene.ron", "--spp", "16", "-o", "single.exr"],
    );
    let parts = render_parts(&dir, 4, "samples", &["--spp", "16"]);
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["-o", "merged.exr"]);
    ok(&dir, &args);
    let single = std::fs::read(dir.join("single.exr")).unwrap();
    let merged = std::fs::read(dir.join("merged.exr")).unwrap();
    assert!(
        single == merged,
        "the packet render differs from the one-by-one parts"
    );
}

#[test]
fn merged_parts_are_byte_identical_to_the_single_render() {
    let dir = setup("identical");
    ok(&dir, &["render", "scene.ron", "-o", "single.png"]);
    ok(&dir, &["render", "scene.ron", "-o", "single.exr"]);
    for (count, split) in [(3, "tiles"), (2, "samples"), (4, "samples")] {
        let parts = render_parts(&dir, count, split, &[]);
        let mut args = vec!["merge"];
        args.extend(parts.iter().map(String::as_str).rev());
        for out in ["merged.png", "merged.exr"] {
            let mut a = args.clone();
            a.extend(["-o", out]);
            ok(&dir, &a);
        }
        for ext in ["png", "exr"] {
            let single = std::fs::read(dir.join(format!("single.{ext}"))).unwrap();
            let merged = std::fs::read(dir.join(format!("merged.{ext}"))).unwrap();
            assert!(single == merged, "{count} {split} parts: {ext} differs");
        }
    }
    // Without -o the merge writes the camera's own outputs, as the render does.
    let parts = render_parts(&dir, 2, "tiles", &[]);
    let o = stagelight(&dir, &["merge", &parts[0], &parts[1]]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("wrote view.png"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(dir.join("view.png")).unwrap(),
        std::fs::read(dir.join("single.png")).unwrap()
    );
}

/// `merge --stats` counts the samples the parts took, in their own runs: `shade` gives no
/// rate for them (`n/a`, as merged bake parts say), not samples over the merge's time.
#[test]
fn a_merge_s_stats_give_no_sample_rate() {
    let dir = setup("merge-stats");
    let parts = render_parts(&dir, 2, "tiles", &[]);
    let o = stagelight(
        &dir,
        &["merge", &parts[0], &parts[1], "-o", "merged.png", "--stats"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let shade: Vec<&str> = stdout
        .lines()
        .find(|l| l.starts_with("shade "))
        .unwrap_or_else(|| panic!("no shade row:\n{stdout}"))
        .split_whitespace()
        .collect();
    // stage, ran, seconds, items (40×24 pixels × 3 samples), unit, items/s.
    assert_eq!(
        (shade[1], shade[3], shade[4], shade[5]),
        ("yes", "2880", "samples", "n/a"),
        "{stdout}"
    );
}

/// `merge --threads N` runs on N worker threads, as `render` and `bake` do (the report says
/// so), and the merged bytes do not depend on it; the flag is checked as theirs is.
#[test]
fn a_merge_runs_on_the_threads_given_with_the_same_bytes() {
    let dir = setup("merge-threads");
    let parts = render_parts(&dir, 2, "tiles", &[]);
    for threads in ["1", "2"] {
        let out = format!("merged_{threads}.exr");
        let o = stagelight(
            &dir,
            &[
                "merge",
                &parts[0],
                &parts[1],
                "--threads",
                threads,
                "-o",
                &out,
                "--stats",
            ],
        );
        assert!(o.status.success(), "{}", stderr(&o));
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        let total = stdout
            .lines()
            .find(|l| l.starts_with("total "))
            .unwrap_or_else(|| panic!("no total:\n{stdout}"));
        assert!(
            total.ends_with(&format!(" s on {threads} thread(s)")),
            "{total}"
        );
    }
    assert!(
        std::fs::read(dir.join("merged_1.exr")).unwrap()
            == std::fs::read(dir.join("merged_2.exr")).unwrap(),
        "the merge differs between 1 and 2 threads"
    );
    for bad in ["0", "1025"] {
        let render = stagelight(&dir, &["render", "scene.ron", "--threads", bad]);
        let merge = stagelight(&dir, &["merge", &parts[0], "--threads", bad]);
        assert_eq!(merge.status.code(), render.status.code(), "--threads {bad}");
        let first = |o: &std::process::Output| stderr(o).lines().next().unwrap_or("").to_string();
        assert_eq!(first(&merge), first(&render), "--threads {bad}");
        assert!(
            first(&merge).contains("'--threads <THREADS>'"),
            "{}",
            first(&merge)
        );
    }
}

/// Parts name their scene by its absolute path: merged from another directory without
/// `--scene`, they find the scene the relative `scene.ron` named where they were rendered.
/// Once that scene is gone, the merge says so and asks for `--scene`, writing nothing.
#[test]
fn parts_merged_from_another_directory_find_their_scene() {
    let dir = setup("elsewhere");
    ok(&dir, &["render", "scene.ron", "-o", "single.png"]);
    let parts = render_parts(&dir, 2, "tiles", &[]);
    let away = dir.join("away");
    std::fs::create_dir_all(&away).unwrap();
    let parts: Vec<String> = parts.iter().map(|p| format!("../{p}")).collect();
    ok(&away, &["merge", &parts[0], &parts[1], "-o", "merged.png"]);
    assert_eq!(
        std::fs::read(away.join("merged.png")).unwrap(),
        std::fs::read(dir.join("single.png")).unwrap()
    );
    std::fs::rename(dir.join("scene.ron"), dir.join("moved.ron")).unwrap();
    let o = stagelight(&away, &["merge", &parts[0], &parts[1], "-o", "again.png"]);
    assert_eq!(o.status.code(), Some(1));
    let scene = std::fs::canonicalize(&dir).unwrap().join("scene.ron");
    assert_eq!(
        stderr(&o),
        format!(
            "error: the parts came from the scene {}, which is not there\n  help: pass the scene they came from with --scene SCENE\nnothing written\n",
            scene.display()
        )
    );
    assert!(!away.join("again.png").exists());
    ok(
        &away,
        &[
            "merge",
            &parts[0],
            &parts[1],
            "--scene",
            "../moved.ron",
            "-o",
            "again.png",
        ],
    );
}

#[test]
fn mismatched_missing_duplicate_and_damaged_parts_are_refused_with_nothing_written() {
    let dir = setup("refusals");
    render_parts(&dir, 2, "tiles", &["--seed", "1"]);
    std::fs::rename(dir.join("part_2.exr"), dir.join("seed1_part_2.exr")).unwrap();
    render_parts(&dir, 2, "tiles", &["--seed", "2"]);
    let refused = |args: &[&str], expected: &str| {
        let o = stagelight(&dir, args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        assert_eq!(stderr(&o), expected, "{args:?}");
        assert!(!dir.join("out.png").exists(), "{args:?} wrote a file");
    };
    refused(
        &["merge", "part_1.exr", "seed1_part_2.exr", "-o", "out.png"],
        "error: seed1_part_2.exr and part_1.exr are parts of different renders: seed 1 vs 2\n  help: merge only the parts of one `stagelight render --part K/N` run\nnothing written\n",
    );
    refused(
        &["merge", "part_2.exr", "-o", "out.png"],
        "error: missing part 1/2\n  help: re-run `stagelight render --part 1/2` (or resubmit array index 1)\nnothing written\n",
    );
    refused(
        &["merge", "part_1.exr", "part_2.exr", "part_1.exr", "-o", "out.png"],
        "error: part 1/2 is given twice: part_1.exr and part_1.exr\n  help: pass each part file once\nnothing written\n",
    );
    let bytes = std::fs::read(dir.join("part_2.exr")).unwrap();
    std::fs::write(dir.join("cut.exr"), &bytes[..bytes.len() * 2 / 3]).unwrap();
    let o = stagelight(&dir, &["merge", "part_1.exr", "cut.exr", "-o", "out.png"]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.starts_with("error: cut.exr: "), "{e}");
    assert!(e.ends_with("\nnothing written\n"), "{e}");
    assert!(!dir.join("out.png").exists());
    // Parts of a different scene.
    std::fs::write(
        dir.join("other.ron"),
        SCENE.replace("intensity: 2.0", "intensity: 3.0"),
    )
    .unwrap();
    ok(
        &dir,
        &["render", "other.ron", "--part", "2/2", "-o", "other_2.exr"],
    );
    let o = stagelight(
        &dir,
        &["merge", "part_1.exr", "other_2.exr", "-o", "out.png"],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).starts_with(
            "error: other_2.exr and part_1.exr are parts of different renders: scene content "
        ),
        "{}",
        stderr(&o)
    );
    // A scene edited after its parts were rendered.
    std::fs::write(
        dir.join("scene.ron"),
        SCENE.replace("samples: 3", "samples: 3, seed: 9"),
    )
    .unwrap();
    let o = stagelight(
        &dir,
        &["merge", "part_1.exr", "part_2.exr", "-o", "out.png"],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("scene.ron changed since the parts were rendered"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("out.png").exists());
}

/// `bytes` with the part-file metadata text `from` replaced by `to` (the same length), as
/// editing the `stagelight` header attribute in place does.
fn edited(bytes: &[u8], from: &str, to: &str) -> Vec<u8> {
    let at = bytes
        .windows(from.len())
        .position(|w| w == from.as_bytes())
        .unwrap_or_else(|| panic!("no {from:?} in the part file"));
    let mut out = bytes.to_vec();
    out[at..at + to.len()].copy_from_slice(to.as_bytes());
    out
}

#[test]
fn parts_whose_label_or_seed_was_edited_are_refused_as_damaged() {
    let dir = setup("edited");
    render_parts(&dir, 3, "tiles", &[]);
    let read = |name: &str| std::fs::read(dir.join(name)).unwrap();
    // Part 2's and part 3's labels swapped, the pixels untouched.
    std::fs::write(
        dir.join("q2.exr"),
        edited(&read("part_2.exr"), "\npart 2/3\n", "\npart 3/3\n"),
    )
    .unwrap();
    std::fs::write(
        dir.join("q3.exr"),
        edited(&read("part_3.exr"), "\npart 3/3\n", "\npart 2/3\n"),
    )
    .unwrap();
    // Every part's seed changed alike.
    for k in 1..=3 {
        let part = read(&format!("part_{k}.exr"));
        std::fs::write(
            dir.join(format!("s{k}.exr")),
            edited(&part, "\nseed 0\n", "\nseed 5\n"),
        )
        .unwrap();
    }
    for (args, file) in [
        (
            ["merge", "part_1.exr", "q2.exr", "q3.exr", "-o", "out.png"],
            "q2.exr",
        ),
        (
            ["merge", "s1.exr", "s2.exr", "s3.exr", "-o", "out.png"],
            "s1.exr",
        ),
    ] {
        let o = stagelight(&dir, &args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        assert_eq!(
            stderr(&o),
            format!("error: {file}: damaged part file (its metadata or data do not match its checksum)\nnothing written\n"),
            "{args:?}"
        );
        assert!(!dir.join("out.png").exists(), "{args:?} wrote a file");
    }
    // A part of the format before the checksum covered the metadata.
    std::fs::write(
        dir.join("old.exr"),
        edited(
            &read("part_1.exr"),
            "format stagelight part 5",
            "format stagelight part 3",
        ),
    )
    .unwrap();
    let o = stagelight(
        &dir,
        &[
            "merge",
            "old.exr",
            "part_2.exr",
            "part_3.exr",
            "-o",
            "out.png",
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr(&o),
        "error: old.exr: part file of the older format \"stagelight part 3\", whose checksum leaves out its part number and settings (this stagelight writes \"stagelight part 5\")\n  help: render the parts again with this stagelight (`stagelight render --part K/N`)\nnothing written\n"
    );
    assert!(!dir.join("out.png").exists());
    ok(
        &dir,
        &[
            "merge",
            "part_1.exr",
            "part_2.exr",
            "part_3.exr",
            "-o",
            "out.png",
        ],
    );
}

#[test]
fn part_flags_are_checked() {
    let dir = setup("flags");
    let o = stagelight(&dir, &["render", "scene.ron", "--part", "2/4"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o),
        "error: --part 2/4 writes a part file: give it with -o PART.exr\n  help: e.g. -o part_2.exr, then `stagelight merge part_*.exr -o image.png`\n"
    );
    // Whatever else `-o` could name, a part file is an EXR: said before the render formats.
    for output in ["p.ron", "p.png"] {
        let o = stagelight(
            &dir,
            &["render", "scene.ron", "--part", "1/3", "-o", output],
        );
        assert_eq!(o.status.code(), Some(2));
        assert_eq!(
            stderr(&o),
            format!("error: --part 1/3 writes a part file, which is an OpenEXR file: -o {output} must end in .exr\n  help: e.g. -o part_1.exr, then `stagelight merge part_*.exr -o image.png`\n")
        );
    }
    let o = stagelight(
        &dir,
        &["render", "scene.ron", "--part", "5/4", "-o", "p.exr"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("expected K/N with 1 ≤ K ≤ N"),
        "{}",
        stderr(&o)
    );
    std::fs::write(
        dir.join("adaptive.ron"),
        SCENE.replace(
            "samples: 3",
            "samples: (min: 2, max: 8, contrast: (0.1, 0.1, 0.1))",
        ),
    )
    .unwrap();
    let o = stagelight(
        &dir,
        &[
            "render",
            "adaptive.ron",
            "--part",
            "1/2",
            "--split",
            "samples",
            "-o",
            "p.exr",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).starts_with("error: --split samples cannot divide adaptive sampling"),
        "{}",
        stderr(&o)
    );
}

/// The scripts `stagelight farm` writes, run the way Slurm runs them (one process per
/// array index with `SLURM_ARRAY_TASK_ID` set, then the merge), give the local render.
#[test]
fn farm_scripts_run_as_slurm_would_give_the_local_render() {
    let dir = setup("farm");
    ok(&dir, &["render", "scene.ron", "-o", "single.png"]);
    let o = stagelight(
        &dir,
        &[
            "farm",
            "scene.ron",
            "--parts",
            "3",
            "--out",
            "job",
            "-o",
            "farm.png",
            "--cpus-per-task",
            "1",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let render = std::fs::read_to_string(dir.join("job/render.sbatch")).unwrap();
    assert!(render.contains("#SBATCH --array=1-3\n"), "{render}");
    for k in 1..=3 {
        let s = Command::new("bash")
            .arg(dir.join("job/render.sbatch"))
            .current_dir(&dir)
            .env("SLURM_ARRAY_TASK_ID", k.to_string())
            .env("SLURM_CPUS_PER_TASK", "1")
            .status()
            .unwrap();
        assert!(s.success());
    }
    let s = Command::new("bash")
        .arg(dir.join("job/merge.sbatch"))
        .current_dir(&dir)
        .status()
        .unwrap();
    assert!(s.success());
    assert_eq!(
        std::fs::read(dir.join("farm.png")).unwrap(),
        std::fs::read(dir.join("single.png")).unwrap()
    );
}

#[test]
fn an_archive_edited_after_the_parts_were_rendered_is_refused() {
    let dir = scratch("cli-farm-archive");
    std::fs::write(
        dir.join("scene.rib"),
        "Display \"out.png\" \"file\" \"rgb\"\nFormat 16 12 1\nProjection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nWorldBegin\nLightSource \"pointlight\" 1 \"from\" [0 2 -2] \"intensity\" 4\nReadArchive \"ball.rib\"\nWorldEnd\n",
    )
    .unwrap();
    std::fs::write(dir.join("ball.rib"), "Sphere 1 -1 1 360\n").unwrap();
    for k in 1..=2 {
        let part = format!("{k}/2");
        let name = format!("part_{k}.exr");
        ok(&dir, &["render", "scene.rib", "--part", &part, "-o", &name]);
    }
    ok(
        &dir,
        &["merge", "part_1.exr", "part_2.exr", "-o", "before.png"],
    );
    // Only the archive changes: the scene file's bytes are the same.
    std::fs::write(dir.join("ball.rib"), "Sphere 1.5 -1.5 1.5 360\n").unwrap();
    let o = stagelight(
        &dir,
        &["merge", "part_1.exr", "part_2.exr", "-o", "out.png"],
    );
    assert_eq!(o.status.code(), Some(1));
    // The scene file is unchanged: the message names the archive it reads too.
    assert!(
        stderr(&o).contains("/scene.rib or a file it reads (ball.rib) changed since the parts were rendered (content hash "),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("out.png").exists());
}

/// The scene's content hash covers its textures: a texture replaced after the parts were
/// rendered is refused at the merge, the scene file unchanged.
#[test]
fn a_texture_edited_after_the_parts_were_rendered_is_refused() {
    let dir = setup("texture");
    let texture = |rgb: [u8; 3]| {
        crate::common::png::write_rgb(&dir.join("t.png"), 2, 2, &[rgb, [255; 3], [255; 3], rgb])
    };
    texture([200, 40, 40]);
    let textured = SCENE.replace(
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5))"#,
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5)), bind: {"albedo": Image(file: "t.png")}"#,
    );
    assert_ne!(textured, SCENE);
    std::fs::write(dir.join("scene.ron"), textured).unwrap();
    let parts = render_parts(&dir, 2, "tiles", &[]);
    ok(&dir, &["merge", &parts[0], &parts[1], "-o", "before.png"]);
    texture([40, 200, 40]);
    let o = stagelight(&dir, &["merge", &parts[0], &parts[1], "-o", "out.png"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("/scene.ron or a file it reads (t.png) changed since the parts were rendered (content hash "),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("out.png").exists());
}

/// `farm` refuses what its parts or its merge job would refuse, with their messages and
/// before it writes a script (the merge job failed only after every part had run): an `-o`
/// of no known format, an `-o` that is an input of the scene, more CPUs per part than
/// `render --threads` takes, and a diagnostic view, which parts cannot carry.
#[test]
fn farm_refuses_what_its_parts_or_merge_would_refuse_before_writing_scripts() {
    let dir = setup("farm-refusals");
    crate::common::png::write_rgb(&dir.join("t.png"), 2, 2, &[[200, 40, 40]; 4]);
    let textured = SCENE.replace(
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5))"#,
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5)), bind: {"albedo": Image(file: "t.png")}"#,
    );
    std::fs::write(dir.join("textured.ron"), textured).unwrap();
    let farm = |scene: &str, extra: &[&str]| {
        let mut args = vec!["farm", scene, "--parts", "2", "--out", "job"];
        args.extend_from_slice(extra);
        let o = stagelight(&dir, &args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(!dir.join("job").exists(), "{args:?} wrote scripts");
        stderr(&o)
    };
    for (scene, output) in [("scene.ron", "out.jpg"), ("textured.ron", "t.png")] {
        let render = stagelight(&dir, &["render", scene, "-o", output]);
        assert_eq!(render.status.code(), Some(2));
        // The same messages; the count line says what each command did not do.
        assert_eq!(
            farm(scene, &["--spp", "1", "-o", output]),
            stderr(&render).replace("; nothing rendered", "; no scripts written")
        );
    }
    assert!(stderr(&stagelight(
        &dir,
        &["render", "textured.ron", "-o", "t.png"]
    ))
    .starts_with("error: -o t.png would overwrite an input of the scene t.png\n"));
    let e = farm("scene.ron", &["--cpus-per-task", "2000"]);
    assert!(e.contains("2000 is not in 1..=1024"), "{e}");
    std::fs::write(
        dir.join("samples.ron"),
        SCENE.replace("samples: 3", "samples: 3, diagnostic: Samples"),
    )
    .unwrap();
    let e = farm("samples.ron", &[]);
    assert!(
        e.starts_with("error: --part 1/2 cannot render a diagnostic view"),
        "{e}"
    );
}

/// The `(ran, reason)` of each stage in a `--stats-json` file.
fn stage_reasons(path: &Path) -> Vec<(String, bool, String)> {
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    v["stages"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            (
                s["stage"].as_str().unwrap().to_string(),
                s["ran"].as_bool().unwrap(),
                s["reason"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

/// The stage `name` of a `--stats-json` file: whether it ran and why.
fn stage(path: &Path, name: &str) -> (bool, String) {
    let (_, ran, reason) = stage_reasons(path)
        .into_iter()
        .find(|(s, ..)| s == name)
        .unwrap_or_else(|| panic!("no stage {name}"));
    (ran, reason)
}

/// A part with no work (the 40×24 image has 6 tiles; 3 samples per pixel) skips `shade`
/// and the geometry stages, which only it would read, and still writes its part file,
/// empty: the merge of such a set is the single render's bytes. Part 1 of a samples split
/// without samples of its own still traces the centre-sample passes, which the merge takes
/// from it. They all ran every stage ("shade yes 0 samples").
#[test]
fn a_part_with_no_work_skips_its_stages_and_writes_an_empty_part_file() {
    let dir = setup("idle");
    ok(&dir, &["render", "scene.ron", "-o", "single.exr"]);
    let tiles = "part 7/7 (tiles) owns no tile: the 40×24 image has 6 tiles of 16×16 pixels";
    ok(
        &dir,
        &[
            "render",
            "scene.ron",
            "--part",
            "7/7",
            "-o",
            "part_7.exr",
            "--stats-json",
            "p7.json",
        ],
    );
    let json = dir.join("p7.json");
    for name in ["tessellate", "build_accel"] {
        assert_eq!(stage(&json, name), (false, tiles.to_string()), "{name}");
    }
    assert_eq!(
        stage(&json, "shade"),
        (false, format!("{tiles}; its part file is written empty"))
    );
    assert_eq!(
        stage(&json, "write_output"),
        (true, "part 7/7 (tiles): the part file, empty".to_string())
    );
    let parts = render_parts(&dir, 7, "tiles", &[]);
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["-o", "merged.exr"]);
    ok(&dir, &args);
    assert!(
        std::fs::read(dir.join("single.exr")).unwrap()
            == std::fs::read(dir.join("merged.exr")).unwrap()
    );

    // 3 samples among 5 parts: 0..0, 0..1, 1..1, 1..2, 2..3.
    for k in [1, 3] {
        let part = format!("{k}/5");
        let json = format!("s{k}.json");
        let out = format!("s{k}.exr");
        ok(
            &dir,
            &[
                "render",
                "scene.ron",
                "--part",
                &part,
                "--split",
                "samples",
                "-o",
                &out,
                "--stats-json",
                &json,
            ],
        );
    }
    let idle = "part 3/5 (samples) takes no samples: 3 samples per pixel, fewer than the 5 parts";
    let json = dir.join("s3.json");
    assert_eq!(stage(&json, "build_accel"), (false, idle.to_string()));
    assert_eq!(
        stage(&json, "shade"),
        (false, format!("{idle}; its part file is written empty"))
    );
    let json = dir.join("s1.json");
    assert!(stage(&json, "build_accel").0);
    assert_eq!(
        stage(&json, "shade"),
        (
            true,
            "render camera 40×24, part 1/5 (samples) takes no samples: 3 samples per pixel, fewer than the 5 parts; it computes only the centre-sample passes (depth, normal, ids), which the merge takes from part 1".to_string()
        )
    );
    let parts = render_parts(&dir, 5, "samples", &[]);
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["-o", "merged.exr"]);
    ok(&dir, &args);
    assert!(
        std::fs::read(dir.join("single.exr")).unwrap()
            == std::fs::read(dir.join("merged.exr")).unwrap()
    );
}

/// `farm` refuses more parts than there is work for, naming the largest useful count, and
/// a render whose merge would write nothing (the camera has no outputs, no `-o`), before
/// it writes a script. It wrote 40 scripts' worth of idle parts, and a job whose merge
/// wrote nothing and exited 0.
#[test]
fn farm_refuses_idle_parts_and_a_render_that_writes_nothing() {
    let dir = setup("farm-idle");
    let farm = |scene: &str, extra: &[&str], code: i32| {
        let mut args = vec!["farm", scene, "--out", "job"];
        args.extend_from_slice(extra);
        let o = stagelight(&dir, &args);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stderr(&o));
        assert!(!dir.join("job").exists(), "{args:?} wrote scripts");
        stderr(&o)
    };
    assert_eq!(
        farm("scene.ron", &["--parts", "7"], 2),
        "error: --parts 7 is more parts than there is work for: the 40×24 image has only 6 tiles of 16×16 pixels, so 1 part would own no tile\n  help: use --parts 6 or fewer\n"
    );
    assert_eq!(
        farm("scene.ron", &["--parts", "100000"], 2),
        "error: --parts 100000 is more parts than there is work for: the 40×24 image has only 6 tiles of 16×16 pixels, so 99994 parts would own no tile\n  help: use --parts 6 or fewer\n"
    );
    assert_eq!(
        farm("scene.ron", &["--parts", "5", "--split", "samples", "--spp", "2"], 2),
        "error: --parts 5 is more parts than there is work for: a pixel takes only 2 samples, so 3 parts would take none\n  help: use --parts 2 or fewer, more samples (--spp), or --split tiles (up to 6 parts)\n"
    );
    std::fs::write(
        dir.join("silent.ron"),
        SCENE.replace(r#"outputs: [(file: "view.png")]"#, "outputs: []"),
    )
    .unwrap();
    assert_eq!(
        farm("silent.ron", &["--parts", "2"], 1),
        "error: the render camera has no outputs, so the merge job would write nothing after every part rendered\n  help: name the merged image with -o FILE, e.g. -o image.png\n"
    );
    ok(&dir, &["farm", "scene.ron", "--parts", "6", "--out", "six"]);
    ok(
        &dir,
        &[
            "farm",
            "silent.ron",
            "--parts",
            "2",
            "--out",
            "named",
            "-o",
            "m.png",
        ],
    );
}

/// The `submit with:` hint quotes the path as the scripts do: pasted into bash it runs
/// `submit.sh` of a directory with a space, a `$` and a quote in its name.
#[test]
fn the_submit_hint_is_shell_quoted() {
    let dir = setup("farm-quote");
    let out = "we ird/out $x 'q'";
    let o = stagelight(&dir, &["farm", "scene.ron", "--parts", "2", "--out", out]);
    let e = stderr(&o);
    let hint = e.lines().last().unwrap();
    let script = std::path::absolute(dir.join(out))
        .unwrap()
        .join("submit.sh");
    let quoted = format!("'{}'", script.display().to_string().replace('\'', r"'\''"));
    assert_eq!(hint, format!("submit with: bash {quoted}"));
    // bash reads the quoted word back as the path.
    let word = hint.strip_prefix("submit with: bash ").unwrap();
    let echoed = Command::new("bash")
        .args(["-c", &format!("printf %s {word}")])
        .output()
        .unwrap();
    assert_eq!(
        String::from_utf8_lossy(&echoed.stdout),
        script.display().to_string()
    );
}

/// `merge --scene other.ron` with parts rendered from `scene.ron` says which scene the parts
/// came from (they record it); it said "other.ron changed since the parts were rendered".
#[test]
fn merge_with_another_scene_names_the_scene_the_parts_came_from() {
    let dir = setup("other-scene");
    std::fs::write(
        dir.join("other.ron"),
        SCENE.replace("samples: 3", "samples: 2"),
    )
    .unwrap();
    let parts = render_parts(&dir, 2, "tiles", &[]);
    let o = stagelight(
        &dir,
        &[
            "merge",
            &parts[0],
            &parts[1],
            "--scene",
            "other.ron",
            "-o",
            "m.png",
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    let recorded = std::path::absolute(dir.join("scene.ron")).unwrap();
    let e = stderr(&o);
    let (first, rest) = e.split_once(" (content hash ").unwrap();
    assert_eq!(
        first,
        format!(
            "error: the parts came from the scene {}, not from other.ron",
            recorded.display()
        )
    );
    assert!(
        rest.ends_with(&format!(
            ")\n  help: leave out --scene to merge with {}, or render the parts again from other.ron\nnothing written\n",
            recorded.display()
        )),
        "{e}"
    );
    assert!(!dir.join("m.png").exists());
}

/// With adaptive sampling a tiles part takes the first pass (`min` samples) of the pixels
/// around its tiles too, and its report counts them: the parts' samples add up to the single
/// render's plus `min` for every such pixel of every part. They were left out (the parts'
/// samples added up to the single render's while their rays did not).
#[test]
fn adaptive_tile_parts_count_the_first_pass_around_their_tiles() {
    let dir = setup("adaptive-counts");
    let adaptive = SCENE.replace(
        "samples: 3",
        "samples: (min: 2, max: 8, contrast: (0.02, 0.02, 0.02))",
    );
    std::fs::write(dir.join("scene.ron"), adaptive).unwrap();
    let samples = |json: &str| {
        let v: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join(json)).unwrap()).unwrap();
        let shade = v["stages"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["stage"] == "shade")
            .cloned();
        shade.unwrap()["items"].as_u64().unwrap()
    };
    ok(
        &dir,
        &[
            "render",
            "scene.ron",
            "-o",
            "single.exr",
            "--stats-json",
            "single.json",
        ],
    );
    let (w, h, n) = (40usize, 24usize, 3u32);
    let owner = |x: usize, y: usize| ((y / 16) * w.div_ceil(16) + x / 16) as u32 % n + 1;
    let mut parts_total = 0;
    let mut around = 0;
    for k in 1..=n {
        let part = format!("{k}/{n}");
        let json = format!("p{k}.json");
        let out = format!("part_{k}.exr");
        ok(
            &dir,
            &[
                "render",
                "scene.ron",
                "--part",
                &part,
                "-o",
                &out,
                "--stats-json",
                &json,
            ],
        );
        parts_total += samples(&json);
        around += (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| owner(x, y) != k)
            .filter(|&(x, y)| {
                (y.saturating_sub(1)..(y + 2).min(h))
                    .any(|ny| (x.saturating_sub(1)..(x + 2).min(w)).any(|nx| owner(nx, ny) == k))
            })
            .count() as u64;
    }
    assert!(around > 0);
    assert_eq!(parts_total, samples("single.json") + 2 * around);
    ok(
        &dir,
        &[
            "merge",
            "part_1.exr",
            "part_2.exr",
            "part_3.exr",
            "-o",
            "merged.exr",
        ],
    );
    assert!(
        std::fs::read(dir.join("single.exr")).unwrap()
            == std::fs::read(dir.join("merged.exr")).unwrap()
    );
}

/// A file that is not an EXR file (a scene, a PNG) given to `merge` is said not to be a part
/// file, with what part files are; it is not called truncated.
#[test]
fn merging_a_file_that_is_not_an_exr_says_it_is_not_a_part_file() {
    let dir = setup("merge-not-exr");
    std::fs::write(dir.join("x.png"), b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR").unwrap();
    for file in ["scene.ron", "x.png"] {
        let o = stagelight(&dir, &["merge", file]);
        assert_eq!(o.status.code(), Some(1), "{file}");
        assert_eq!(
            stderr(&o),
            format!("error: {file}: not a part file: it is not an EXR file\n  help: merge the EXR part files that `stagelight render --part K/N -o PART.exr` (or `stagelight bake --part K/N`) writes\nnothing written\n")
        );
    }
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["scene.ron", "x.png"]);
}

/// A `.mi` scene's `$include`d file edited after the parts were rendered: the merge names
/// the scene and the files it includes, not the unchanged scene alone (tester report 45,
/// problem 4); the parts record one hash, so it cannot say which of them changed.
#[test]
fn an_include_edited_after_the_parts_were_rendered_is_named_with_the_scene() {
    let dir = scratch("cli-farm-mi-include");
    let scene = r#"link "base.so"
$include <base.mi>
options "opt" samples 0 0 object space end options
camera "Cam" output "rgb" "png" "out.png" focal 1 aperture 1 aspect 1 resolution 16 12 end camera
instance "Cam_inst" "Cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
$include "mat.mi"
object "Tri" group
$include "verts.mi"
v 0 v 1 v 2  p "m" 0 1 2 end group end object
instance "Tri_inst" "Tri" material "m" end instance
instgroup "root" "Cam_inst" "Tri_inst" end instgroup
render "root" "Cam_inst" "opt"
"#;
    std::fs::write(dir.join("m.mi"), scene).unwrap();
    let material = |grey: f64| {
        let text = format!("material \"m\" opaque \"mib_illum_lambert\" (\"ambient\" {grey} {grey} {grey}) end material\n");
        std::fs::write(dir.join("mat.mi"), text).unwrap();
    };
    material(1.0);
    std::fs::write(dir.join("verts.mi"), "0 0 0  1 0 0  0 1 0\n").unwrap();
    for k in 1..=2 {
        let part = format!("{k}/2");
        let name = format!("p{k}.exr");
        ok(&dir, &["render", "m.mi", "--part", &part, "-o", &name]);
    }
    // Only the included material changes: m.mi's bytes are the same.
    material(0.5);
    let o = stagelight(&dir, &["merge", "p1.exr", "p2.exr", "-o", "out.png"]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    let named = "/m.mi or a file it reads (mat.mi, verts.mi) changed since the parts were rendered (content hash ";
    assert!(err.starts_with("error: ") && err.contains(named), "{err}");
    assert!(
        err.ends_with(")\n  help: render the parts again, or pass the scene they came from with --scene\nnothing written\n"),
        "{err}"
    );
    assert!(!dir.join("out.png").exists());
}

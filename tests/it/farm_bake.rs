//! Bakes past one machine: `bake --part K/N` writes bake part files and `stagelight merge`
//! assembles, dilates and encodes them into the single bake's bytes — for every example
//! scene with bake requests and a scene with several requests and every kind of file (EXR,
//! PNG, bent normals, mask), for N = 1, 2, 3, 7 — and refuses incomplete or mixed sets with
//! nothing written.

use std::path::{Path, PathBuf};

use stagelight::components::{BakeKind, BakeRequest, BakeResolution};
use stagelight::farm::bake_part::{merge, BakePartFile, LoadedBakePart};
use stagelight::farm::bake_part_file::{decode, encode};
use stagelight::farm::{Part, PartRun, Split};
use stagelight::frame::{Frame, Tasks};
use stagelight::image_io::PendingFile;
use stagelight::scene::load_scene;

use crate::common::cli::{dir_names, run_in, scratch_dir, stderr_of};

/// Bakes `path` with every request shrunk to at most 40 texels a side and 4 AO rays, as
/// `part` when given, or from `merged` parts. Returns the files the run would write.
fn bake(
    path: &Path,
    part: Option<Part>,
    merged: Option<stagelight::farm::bake_part::MergedBake>,
) -> Vec<PendingFile> {
    let mut scene = load_scene(path).unwrap_or_else(|e| panic!("{}:\n{e}", path.display()));
    for request in scene.world.query_mut::<&mut BakeRequest>() {
        request.resolution = BakeResolution::Fixed {
            width: 40,
            height: 24,
        };
        for t in &mut request.targets {
            if let BakeKind::AmbientOcclusion { samples, .. } = &mut t.kind {
                *samples = (*samples).min(4);
            }
        }
    }
    let mut frame = Frame::new(scene.settings.clone());
    frame.inputs.tasks = Tasks {
        render: false,
        bake: true,
    };
    frame.inputs.bake_dir = PathBuf::from("out");
    frame.inputs.hold_files = true;
    frame.inputs.part = part.map(|part| PartRun {
        part,
        scene: path.display().to_string(),
        scene_hash: 1,
    });
    frame.inputs.merged_bake = merged;
    stagelight::systems::run(&mut scene.world, &mut frame)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    std::mem::take(&mut frame.held_files)
}

fn part_of(path: &Path, index: u32, count: u32) -> LoadedBakePart {
    let files = bake(
        path,
        Some(Part {
            index,
            count,
            split: Split::Tiles,
        }),
        None,
    );
    assert_eq!(files.len(), 1, "a bake part writes one part file");
    assert_eq!(
        files[0].path,
        Path::new("out").join(format!("bake_part_{index}_of_{count}.exr"))
    );
    let file: BakePartFile = decode(&files[0].bytes).unwrap();
    assert_eq!(encode(&file).unwrap(), files[0].bytes, "encoding is stable");
    LoadedBakePart {
        path: files[0].path.clone(),
        file,
    }
}

fn scenes_with_bakes() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .filter(|p| std::fs::read_to_string(p).unwrap().contains("bake: ("))
        .collect();
    scenes.sort();
    scenes
}

#[test]
fn every_example_bake_merges_bit_identically_for_any_part_count() {
    let scenes = scenes_with_bakes();
    assert!(!scenes.is_empty(), "assets/scenes has bake requests");
    for path in scenes {
        let single = bake(&path, None, None);
        assert!(!single.is_empty());
        for count in [1, 2, 3, 7] {
            let parts: Vec<LoadedBakePart> =
                (1..=count).map(|k| part_of(&path, k, count)).collect();
            let merged = merge(&parts).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let files = bake(&path, None, Some(merged));
            assert_eq!(files.len(), single.len());
            for (a, b) in files.iter().zip(&single) {
                assert_eq!(a.path, b.path);
                assert!(
                    a.bytes == b.bytes,
                    "{}: {} differs after merging {count} parts",
                    path.display(),
                    a.path.display()
                );
            }
        }
    }
}

/// Two requests (AO with bent normals and a mask in EXR; a lightmap and normals in PNG)
/// around a block that leaves invalid texels under it.
const SCENE: &str = r#"Scene(
    options: (samples: 2, seed: 5),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
               placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0)),
               outputs: [(file: "view.png")])],
    lights: [(name: "sun", kind: Directional(direction: (0.3, 0.2, -1)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [
        (name: "floor", mesh: Inline(
            vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
        (name: "block", mesh: Inline(
            vertices: [(-0.3, -0.3, 0.4), (0.3, -0.3, 0.4), (0.3, 0.3, 0.4), (-0.3, 0.3, 0.4)],
            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
    ],
    instances: [
        (name: "floor_1", of: "floor", bake: (resolution: (37, 21), uvs: Mesh, mask: true,
            outputs: [(kind: AmbientOcclusion(samples: 8, bent_normals: true))])),
        (name: "block_1", of: "block", bake: (resolution: (20, 20), uvs: Mesh, padding: 3,
            outputs: [(kind: Lightmap(), format: Png8), (kind: Normals(), format: Png16)])),
    ],
    groups: [(name: "world", members: ["floor_1", "block_1"])],
    render: (root: "world", camera: "cam"),
)
"#;

fn setup(test: &str) -> PathBuf {
    let dir = scratch_dir(&format!("farm-bake-{test}"));
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
    dir
}

fn ok(dir: &Path, args: &[&str]) {
    let o = run_in(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

fn bake_parts(dir: &Path, count: u32, out: &str, extra: &[&str]) {
    for k in 1..=count {
        let part = format!("{k}/{count}");
        let mut args = vec!["bake", "scene.ron", "--part", &part, "-o", out];
        args.extend_from_slice(extra);
        ok(dir, &args);
    }
}

#[test]
fn cli_bake_parts_merge_into_the_single_bakes_files() {
    let dir = setup("cli");
    ok(&dir, &["bake", "scene.ron", "-o", "single"]);
    let expected = dir_names(&dir.join("single"));
    assert_eq!(
        expected,
        [
            "block_1_lightmap.png",
            "block_1_normals.png",
            "floor_1_ao.exr",
            "floor_1_bent_normals.exr",
            "floor_1_mask.png"
        ]
    );
    bake_parts(&dir, 3, "parts", &["--threads", "1"]);
    assert_eq!(
        dir_names(&dir.join("parts")),
        [
            "bake_part_1_of_3.exr",
            "bake_part_2_of_3.exr",
            "bake_part_3_of_3.exr"
        ]
    );
    let o = run_in(
        &dir,
        &[
            "merge",
            "parts/bake_part_3_of_3.exr",
            "parts/bake_part_1_of_3.exr",
            "parts/bake_part_2_of_3.exr",
            "-o",
            "merged",
            "--stats",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    // The merge places the triangles (coverage, seams) but traces nothing: no BVH.
    let report = String::from_utf8_lossy(&o.stdout).to_string() + &stderr_of(&o);
    let row = report
        .lines()
        .find(|l| l.starts_with("build_accel"))
        .unwrap_or_else(|| panic!("no build_accel row in {report}"));
    assert!(
        row.contains(" yes ")
            && row.ends_with(
                "2 instance(s) with 4 triangles; placed without a BVH: a bake merge traces no rays"
            ),
        "{row}"
    );
    assert_eq!(dir_names(&dir.join("merged")), expected);
    for name in &expected {
        assert!(
            std::fs::read(dir.join("single").join(name)).unwrap()
                == std::fs::read(dir.join("merged").join(name)).unwrap(),
            "{name} differs"
        );
    }
}

/// Parts baked with `--integrator path` record it, and the merge (which has no
/// `--integrator`) bakes with it: the single path-traced bake's bytes. It refused them as
/// "baked with other settings".
#[test]
fn cli_bake_parts_with_an_integrator_override_merge_into_the_single_bake() {
    let dir = setup("integrator");
    ok(
        &dir,
        &["bake", "scene.ron", "--integrator", "path", "-o", "single"],
    );
    bake_parts(&dir, 3, "parts", &["--integrator", "path"]);
    let parts: Vec<String> = (1..=3)
        .map(|k| format!("parts/bake_part_{k}_of_3.exr"))
        .collect();
    let mut args: Vec<&str> = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["-o", "merged"]);
    ok(&dir, &args);
    let names = dir_names(&dir.join("single"));
    assert_eq!(dir_names(&dir.join("merged")), names);
    for name in &names {
        assert!(
            std::fs::read(dir.join("single").join(name)).unwrap()
                == std::fs::read(dir.join("merged").join(name)).unwrap(),
            "{name} differs"
        );
    }
}

#[test]
fn cli_merge_refuses_incomplete_mixed_and_damaged_bake_parts_and_writes_nothing() {
    let dir = setup("refusals");
    bake_parts(&dir, 2, "a", &[]);
    bake_parts(&dir, 2, "b", &["--seed", "9"]);
    let refused = |args: &[&str], expected: &str| {
        let o = run_in(&dir, args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        assert_eq!(stderr_of(&o), expected, "{args:?}");
        assert!(!dir.join("out").exists(), "{args:?} wrote something");
    };
    refused(
        &["merge", "a/bake_part_2_of_2.exr", "-o", "out"],
        "error: missing part 1/2\n  help: re-run `stagelight bake --part 1/2` (or resubmit array index 1)\nnothing written\n",
    );
    refused(
        &["merge", "a/bake_part_1_of_2.exr", "a/bake_part_1_of_2.exr", "a/bake_part_2_of_2.exr", "-o", "out"],
        "error: part 1/2 is given twice: a/bake_part_1_of_2.exr and a/bake_part_1_of_2.exr\n  help: pass each part file once\nnothing written\n",
    );
    refused(
        &["merge", "a/bake_part_1_of_2.exr", "b/bake_part_2_of_2.exr", "-o", "out"],
        "error: b/bake_part_2_of_2.exr and a/bake_part_1_of_2.exr are parts of different bakes: seed 9 vs 5\n  help: merge only the parts of one `stagelight bake --part K/N` run\nnothing written\n",
    );
    // A render part among bake parts: said as such, not as another version's file.
    let o = run_in(
        &dir,
        &["render", "scene.ron", "--part", "2/2", "-o", "r2.exr"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    refused(
        &["merge", "a/bake_part_1_of_2.exr", "r2.exr", "-o", "out"],
        "error: r2.exr: a render part file, not a bake part file like the first part\n  help: merge the parts of one render, or of one bake\nnothing written\n",
    );
    // Part labels swapped in place, the texels untouched.
    let bytes = std::fs::read(dir.join("a/bake_part_2_of_2.exr")).unwrap();
    let from = b"\npart 2/2\n";
    let at = bytes.windows(from.len()).position(|w| w == from).unwrap();
    let mut relabelled = bytes.clone();
    relabelled[at..at + from.len()].copy_from_slice(b"\npart 1/2\n");
    std::fs::write(dir.join("relabelled.exr"), relabelled).unwrap();
    refused(
        &["merge", "relabelled.exr", "a/bake_part_1_of_2.exr", "-o", "out"],
        "error: relabelled.exr: damaged bake part file (its metadata or data do not match its checksum)\nnothing written\n",
    );
    std::fs::write(dir.join("cut.exr"), &bytes[..bytes.len() - 100]).unwrap();
    let o = run_in(
        &dir,
        &["merge", "a/bake_part_1_of_2.exr", "cut.exr", "-o", "out"],
    );
    assert_eq!(o.status.code(), Some(1));
    let e = stderr_of(&o);
    assert!(
        e.starts_with("error: cut.exr: not a readable EXR file")
            && e.ends_with("nothing written\n"),
        "{e}"
    );
    assert!(!dir.join("out").exists());
    // A scene edited after the parts were baked.
    std::fs::write(dir.join("scene.ron"), SCENE.replace("seed: 5", "seed: 6")).unwrap();
    let o = run_in(
        &dir,
        &[
            "merge",
            "a/bake_part_1_of_2.exr",
            "a/bake_part_2_of_2.exr",
            "-o",
            "out",
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr_of(&o).starts_with(&format!(
            "error: {} changed since the parts were baked",
            std::fs::canonicalize(&dir)
                .unwrap()
                .join("scene.ron")
                .display()
        )),
        "{}",
        stderr_of(&o)
    );
    assert!(!dir.join("out").exists());
}

#[test]
fn farm_bake_scripts_run_as_slurm_would_give_the_local_bake() {
    let dir = setup("slurm");
    ok(&dir, &["bake", "scene.ron", "-o", "single"]);
    ok(
        &dir,
        &[
            "farm",
            "scene.ron",
            "--bake",
            "--parts",
            "2",
            "--out",
            "job",
            "-o",
            "farmed",
        ],
    );
    for k in 1..=2 {
        let s = std::process::Command::new("bash")
            .arg(dir.join("job/render.sbatch"))
            .current_dir(&dir)
            .env("SLURM_ARRAY_TASK_ID", k.to_string())
            .env("SLURM_CPUS_PER_TASK", "1")
            .status()
            .unwrap();
        assert!(s.success());
    }
    assert!(dir.join("job/bake_part_2_of_2.exr").exists());
    let s = std::process::Command::new("bash")
        .arg(dir.join("job/merge.sbatch"))
        .current_dir(&dir)
        .status()
        .unwrap();
    assert!(s.success());
    let names = dir_names(&dir.join("single"));
    assert_eq!(dir_names(&dir.join("farmed")), names);
    for name in &names {
        assert!(
            std::fs::read(dir.join("single").join(name)).unwrap()
                == std::fs::read(dir.join("farmed").join(name)).unwrap(),
            "{name} differs"
        );
    }
    let o = run_in(
        &dir,
        &[
            "farm",
            "scene.ron",
            "--bake",
            "--spp",
            "4",
            "--parts",
            "2",
            "--out",
            "x",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "--spp does not apply to bakes");
}

/// A bake merge's `--stats` line gives the parts' rays with the merge's own time: no rate
/// from those two (it printed "0.00 Mrays/s"). A scene edited since the parts were baked,
/// given with `--scene`, asks for new parts (not for `--scene` again). A `-o` that is a file
/// is refused before the merge.
#[test]
fn cli_merge_stats_give_no_ray_rate_and_an_edited_scene_asks_for_new_parts() {
    let dir = setup("merge-stats");
    bake_parts(&dir, 2, "parts", &[]);
    let parts = ["parts/bake_part_1_of_2.exr", "parts/bake_part_2_of_2.exr"];
    // A texture directory that is a file is refused before the merge (exit 2).
    std::fs::write(dir.join("afile"), "x").unwrap();
    let o = run_in(&dir, &["merge", parts[0], parts[1], "-o", "afile"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        "error: -o afile: afile is a file, not a directory\n  help: give a directory (it is created when missing)\n"
    );
    let o = run_in(
        &dir,
        &["merge", parts[0], parts[1], "-o", "merged", "--stats"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let bakes: Vec<&str> = stdout.lines().filter(|l| l.starts_with("bake ")).collect();
    assert_eq!(bakes.len(), 2, "{stdout}");
    for line in bakes {
        assert!(
            line.contains(" rays traced by the parts (Mrays/s n/a), merged in ")
                && !line.contains("Mrays/s)"),
            "{line}"
        );
    }
    std::fs::write(dir.join("scene.ron"), SCENE.replace("seed: 5", "seed: 6")).unwrap();
    let o = run_in(
        &dir,
        &[
            "merge",
            parts[0],
            parts[1],
            "-o",
            "again",
            "--scene",
            "scene.ron",
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    let e = stderr_of(&o);
    assert!(
        e.starts_with("error: scene.ron changed since the parts were baked")
            && e.ends_with("\n  help: bake the parts again from scene.ron\nnothing written\n"),
        "{e}"
    );
    assert!(!dir.join("again").exists());
}

/// `(stage, ran, reason)` of every stage in the `--stats-json` file `dir/name`, and whether
/// every skipped stage reports 0 seconds.
fn stage_rows(dir: &Path, name: &str) -> (Vec<(String, bool, String)>, bool) {
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join(name)).unwrap()).unwrap();
    let stages = v["stages"].as_array().unwrap();
    let rows = stages
        .iter()
        .map(|s| {
            (
                s["stage"].as_str().unwrap().to_string(),
                s["ran"].as_bool().unwrap(),
                s["reason"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    let skipped_take_no_time = stages
        .iter()
        .filter(|s| s["ran"] == false)
        .all(|s| s["seconds"].as_f64() == Some(0.0));
    (rows, skipped_take_no_time)
}

/// `(stage, run, reason)` of every stage in the plan of `bake --part K/N` of `dir/scene.ron`.
fn planned_rows(dir: &Path, index: u32, count: u32) -> Vec<(String, bool, String)> {
    let scene = load_scene(&dir.join("scene.ron")).unwrap();
    let mut frame = Frame::new(scene.settings.clone());
    frame.inputs.tasks = Tasks {
        render: false,
        bake: true,
    };
    frame.inputs.caller_keeps_image = false;
    frame.inputs.part = Some(PartRun {
        part: Part {
            index,
            count,
            split: Split::Tiles,
        },
        scene: "scene.ron".into(),
        scene_hash: 1,
    });
    stagelight::systems::plan(&scene.world, &mut frame)
        .into_iter()
        .map(|p| (p.stage.to_string(), p.run, p.reason))
        .collect()
}

/// A bake part past the last texel tile of fixed-size texture requests (6 + 4 tiles) needs
/// no geometry: the geometry stages skip with the part's reason (as in a render part that
/// owns no tile; the plan says the same) and `bake_lightmaps` writes only its (empty) part
/// file: the merge gives the single bake's files. `farm --bake` refuses more parts than
/// tiles. Part 11/11 used to build the BVH (`build_accel yes … 10 triangles`) and report
/// `bake_lightmaps` skipped with the seconds it spent; `farm --bake --parts 40` wrote its
/// scripts.
#[test]
fn a_bake_part_without_texels_is_skipped_and_farm_refuses_idle_bake_parts() {
    let dir = setup("idle");
    ok(&dir, &["bake", "scene.ron", "-o", "single"]);
    ok(
        &dir,
        &[
            "bake",
            "scene.ron",
            "--part",
            "11/11",
            "-o",
            "parts",
            "--stats-json",
            "p11.json",
        ],
    );
    let idle = "part 11/11 owns no texel: the bake requests have 10 tiles of 16×16 texels";
    let row = |stage: &str, ran: bool, reason: &str| (stage.to_string(), ran, reason.to_string());
    let expected = vec![
        row("expand_geometry", false, "no procedural geometry"),
        row(
            "tessellate",
            false,
            "no parametric surfaces or displacement",
        ),
        row("build_accel", false, idle),
        row(
            "trace_photons",
            false,
            "caustics and global illumination are off",
        ),
        row(
            "bake_lightmaps",
            true,
            &format!("2 bake request(s); {idle}: only its empty part file is written"),
        ),
        row("shade", false, "this run only bakes"),
        row(
            "draw_contours",
            false,
            "no material in use has a contour shader",
        ),
        row("write_output", false, "no shaded image"),
    ];
    let (rows, skipped_take_no_time) = stage_rows(&dir, "p11.json");
    assert_eq!(rows, expected);
    assert!(skipped_take_no_time);
    assert_eq!(planned_rows(&dir, 11, 11), expected);
    bake_parts(&dir, 11, "parts", &[]);
    let mut args = vec!["merge".to_string()];
    args.extend((1..=11).map(|k| format!("parts/bake_part_{k}_of_11.exr")));
    args.extend(["-o".into(), "merged".into()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    ok(&dir, &args);
    let names = dir_names(&dir.join("single"));
    assert_eq!(dir_names(&dir.join("merged")), names);
    for name in &names {
        assert!(
            std::fs::read(dir.join("single").join(name)).unwrap()
                == std::fs::read(dir.join("merged").join(name)).unwrap(),
            "{name} differs"
        );
    }
    let o = run_in(
        &dir,
        &[
            "farm",
            "scene.ron",
            "--bake",
            "--parts",
            "11",
            "--out",
            "job",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        "error: --parts 11 is more parts than there is work for: the bake requests have only 10 tiles of 16×16 texels, so 1 part would own no texel\n  help: use --parts 10 or fewer\n"
    );
    assert!(!dir.join("job").exists());
    ok(
        &dir,
        &[
            "farm",
            "scene.ron",
            "--bake",
            "--parts",
            "10",
            "--out",
            "job",
        ],
    );
}

/// A density-sized request is sized by the geometry: a part past the last tile (6 + 1 tiles)
/// still builds it, and `bake_lightmaps` finds the part idle only after sizing the requests;
/// reported skipped, its reason says what the seconds it reports were spent on.
#[test]
fn an_idle_bake_part_of_a_density_sized_request_says_what_it_timed() {
    let dir = setup("idle-density");
    let density = SCENE.replace("resolution: (20, 20)", "texels_per_unit: 8.0");
    assert_ne!(density, SCENE);
    std::fs::write(dir.join("scene.ron"), density).unwrap();
    ok(
        &dir,
        &[
            "bake",
            "scene.ron",
            "--part",
            "8/8",
            "-o",
            "parts",
            "--stats-json",
            "p8.json",
        ],
    );
    let (rows, _) = stage_rows(&dir, "p8.json");
    let of = |stage: &str| rows.iter().find(|r| r.0 == stage).unwrap().clone();
    assert_eq!(
        of("build_accel"),
        (
            "build_accel".into(),
            true,
            "2 instance(s) with 4 triangles".into()
        )
    );
    assert_eq!(
        of("bake_lightmaps"),
        (
            "bake_lightmaps".into(),
            false,
            "part 8/8 owns no texel: the bake requests have 7 tiles of 16×16 texels; its part file is written empty (the time reported: sizing the requests from the geometry and writing that file)".into()
        )
    );
    assert_eq!(planned_rows(&dir, 8, 8)[2], of("build_accel"));
}

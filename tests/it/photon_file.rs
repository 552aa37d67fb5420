//! Photon map files (mental ray `photonmap file`) from the command line: `photon_map` in
//! options and `--photon-cache DIR` keep the maps; a run whose content hash matches loads
//! them (the report says so), renders the same bytes, and leaves the file alone; a changed
//! light rebuilds; a corrupt file is traced again with a warning; `stagelight photons`
//! traces once for later runs.

use std::path::Path;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// A glass ball over a floor under a point light: caustics and a small global map (also the
/// farm's photon-job scene).
pub fn scene(intensity: f32, gather: u32, photon_map: &str) -> String {
    format!(
        r#"Scene(
    options: (
        samples: 1,
        max_depth: 6,
        refraction_depth: 6,
        caustics: (photons: 4000, gather: {gather}),
        global_illumination: (photons: 1000, gather: 16, final_gather: 2),
        {photon_map}
    ),
    cameras: [(name: "cam", fov_y: 40, resolution: (12, 10),
        placement: LookAt(eye: (0, -4.5, 3.0), target: (0, 0, 0.5), up: (0, 0, 1)),
        outputs: [(file: "out.png")])],
    lights: [(name: "lamp", kind: Point(position: (0, 0, 4)), intensity: {intensity})],
    materials: [
        (name: "floor", shader: Lambert(albedo: (0.7, 0.7, 0.7))),
        (name: "glass", shader: Dielectric(ior: 1.5)),
    ],
    objects: [
        (name: "floor", mesh: Grid(size_x: 6, size_y: 6), material: "floor"),
        (name: "ball", mesh: Sphere(radius: 0.6), material: "glass",
         approximation: Parametric(u: 16, v: 8)),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "ball_1", of: "ball", transform: [Translate((0, 0, 0.9))]),
    ],
    groups: [(name: "world", members: ["floor_1", "ball_1"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

const KEPT: &str = r#"photon_map: (file: "scene.pmap"),"#;

/// Renders `scene.ron` in `dir` with `--stats-json`; returns the `trace_photons` entry
/// and stderr.
fn render(dir: &Path, extra: &[&str]) -> (serde_json::Value, String) {
    let mut args = vec!["render", "scene.ron", "--stats-json", "stats.json"];
    args.extend_from_slice(extra);
    let o = run_in(dir, &args);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("stats.json")).unwrap()).unwrap();
    let stage = v["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["stage"] == "trace_photons")
        .unwrap()
        .clone();
    (stage, stderr_of(&o))
}

fn hash_of(file: &[u8]) -> String {
    let key = stagelight::photon::file::peek_key(file).expect("a photon map file");
    format!("{key:016x}")
}

#[test]
fn a_kept_map_is_loaded_when_its_hash_matches_and_renders_the_same_bytes() {
    let dir = scratch_dir("pmap-reuse");
    std::fs::write(dir.join("scene.ron"), scene(40.0, 20, "")).unwrap();
    render(&dir, &[]);
    let traced = std::fs::read(dir.join("out.png")).unwrap();

    std::fs::write(dir.join("scene.ron"), scene(40.0, 20, KEPT)).unwrap();
    let (first, _) = render(&dir, &[]);
    assert_eq!(first["ran"], true, "{first}");
    let written = std::fs::read(dir.join("scene.pmap")).unwrap();
    let hash = hash_of(&written);
    assert_eq!(std::fs::read(dir.join("out.png")).unwrap(), traced);

    let (second, _) = render(&dir, &[]);
    assert_eq!(second["ran"], false, "{second}");
    assert_eq!(
        second["reason"],
        format!("loaded from scene.pmap (hash {hash})")
    );
    assert_eq!(
        second["files"],
        serde_json::json!([]),
        "a reused file is not rewritten"
    );
    assert_eq!(std::fs::read(dir.join("scene.pmap")).unwrap(), written);
    assert_eq!(
        std::fs::read(dir.join("out.png")).unwrap(),
        traced,
        "a loaded map renders the bytes the traced one did"
    );

    // The gather count only reads the map: still reused, same hash.
    std::fs::write(dir.join("scene.ron"), scene(40.0, 30, KEPT)).unwrap();
    let (knob, _) = render(&dir, &[]);
    assert_eq!(knob["ran"], false, "{knob}");

    // A brighter light changes the photons: traced again, file rewritten with a new hash.
    std::fs::write(dir.join("scene.ron"), scene(80.0, 30, KEPT)).unwrap();
    let (changed, _) = render(&dir, &[]);
    assert_eq!(changed["ran"], true, "{changed}");
    let rewritten = std::fs::read(dir.join("scene.pmap")).unwrap();
    assert_ne!(hash_of(&rewritten), hash);

    // `rebuild: true` traces even when the hash matches.
    let rebuild = r#"photon_map: (file: "scene.pmap", rebuild: true),"#;
    std::fs::write(dir.join("scene.ron"), scene(80.0, 30, rebuild)).unwrap();
    assert_eq!(render(&dir, &[]).0["ran"], true);
    assert_eq!(std::fs::read(dir.join("scene.pmap")).unwrap(), rewritten);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_corrupt_or_truncated_file_is_traced_again_with_a_warning() {
    let dir = scratch_dir("pmap-corrupt");
    std::fs::write(dir.join("scene.ron"), scene(40.0, 20, KEPT)).unwrap();
    render(&dir, &[]);
    let good = std::fs::read(dir.join("scene.pmap")).unwrap();
    let image = std::fs::read(dir.join("out.png")).unwrap();
    let mut flipped = good.clone();
    let last = flipped.len() - 100;
    flipped[last] ^= 1;
    for (bad, why) in [
        (good[..good.len() / 2].to_vec(), "the file is truncated"),
        (flipped, "the checksum does not match (the file is corrupt)"),
        (b"hello".to_vec(), "not a stagelight photon map file"),
    ] {
        std::fs::write(dir.join("scene.pmap"), &bad).unwrap();
        let (stage, stderr) = render(&dir, &[]);
        assert_eq!(stage["ran"], true, "{stage}");
        // The documented warning style, `FILE: warning: …` (it printed " WARN cannot …").
        assert!(
            stderr.lines().any(|l| l == format!(
                "scene.pmap: warning: cannot reuse this photon map file: {why}; tracing the photons again and rewriting it"
            )),
            "{stderr}"
        );
        assert_eq!(std::fs::read(dir.join("scene.pmap")).unwrap(), good);
        assert_eq!(std::fs::read(dir.join("out.png")).unwrap(), image);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_photons_command_fills_a_cache_that_renders_at_any_thread_count_load() {
    let dir = scratch_dir("pmap-cache");
    std::fs::write(dir.join("scene.ron"), scene(40.0, 20, "")).unwrap();
    render(&dir, &["--threads", "1"]);
    let traced = std::fs::read(dir.join("out.png")).unwrap();

    let o = run_in(
        &dir,
        &[
            "photons",
            "scene.ron",
            "--photon-cache",
            "cache",
            "--threads",
            "2",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let names = crate::common::cli::dir_names(&dir.join("cache"));
    assert_eq!(names.len(), 1, "{names:?}");
    let file = std::fs::read(dir.join("cache").join(&names[0])).unwrap();
    assert_eq!(names[0], format!("{}.pmap", hash_of(&file)));
    assert_eq!(
        stderr_of(&o),
        format!("wrote cache/{}\n", names[0]),
        "the photons command writes the map and nothing else"
    );
    let again = run_in(&dir, &["photons", "scene.ron", "--photon-cache", "cache"]);
    assert!(again.status.success());
    assert_eq!(
        stderr_of(&again),
        format!(
            "photon maps loaded from cache/{} (hash {})\n",
            names[0],
            hash_of(&file)
        )
    );

    let _ = std::fs::remove_file(dir.join("out.png"));
    let (stage, _) = render(&dir, &["--photon-cache", "cache", "--threads", "1"]);
    assert_eq!(stage["ran"], false, "{stage}");
    assert_eq!(std::fs::read(dir.join("out.png")).unwrap(), traced);

    // Traced at 1 thread, the cache file has the same bytes as at 2.
    let one = dir.join("one");
    let o = run_in(
        &dir,
        &[
            "photons",
            "scene.ron",
            "--photon-cache",
            "one",
            "--threads",
            "1",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert_eq!(std::fs::read(one.join(&names[0])).unwrap(), file);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn photons_without_a_place_to_keep_them_or_without_maps_is_refused() {
    let dir = scratch_dir("pmap-refused");
    std::fs::write(dir.join("scene.ron"), scene(40.0, 20, "")).unwrap();
    let o = run_in(&dir, &["photons", "scene.ron"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        "error: nowhere to keep the photon maps of scene.ron\n  help: give --photon-cache DIR, or add `photon_map: (file: \"scene.pmap\")` to the scene's options\n"
    );
    let plain = scene(40.0, 20, "")
        .replace("caustics: (photons: 4000, gather: 20),", "")
        .replace(
            "global_illumination: (photons: 1000, gather: 16, final_gather: 2),",
            "",
        );
    std::fs::write(dir.join("scene.ron"), plain).unwrap();
    let o = run_in(&dir, &["photons", "scene.ron", "--photon-cache", "cache"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "error: scene.ron traces no photons: caustics and global illumination are off\n  help: photon maps are built for caustics or global illumination, with the Direct integrator: turn on `caustics: (…)` or `global_illumination: (…)` in the scene's options\n"
    );
    assert!(!dir.join("cache").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_photon_map_file_that_names_an_input_is_refused_before_anything_runs() {
    let dir = scratch_dir("pmap-input");
    let text = scene(40.0, 20, r#"photon_map: (file: "scene.ron"),"#);
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    let o = run_in(&dir, &["render", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    let line = text.lines().position(|l| l.contains("photon_map")).unwrap() + 1;
    assert_eq!(
        stderr_of(&o),
        format!("scene.ron:{line}:28: error: options photon_map file (\"scene.ron\") would overwrite the scene file scene.ron\n  help: give every output its own file, and none the name of an input\n1 error in scene.ron; nothing rendered\n")
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("scene.ron")).unwrap(),
        text
    );
    assert!(!dir.join("out.png").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_pass_of_a_progressive_map_is_kept_and_loaded() {
    let dir = scratch_dir("pmap-progressive");
    let progressive = |text: String| {
        text.replace(
            "caustics: (photons: 4000, gather: 20),",
            "caustics: (photons: 1500, gather: 20, progressive: (passes: 3, alpha: 0.7)),",
        )
    };
    std::fs::write(dir.join("scene.ron"), progressive(scene(40.0, 20, ""))).unwrap();
    render(&dir, &[]);
    let traced = std::fs::read(dir.join("out.png")).unwrap();
    std::fs::write(dir.join("scene.ron"), progressive(scene(40.0, 20, KEPT))).unwrap();
    assert_eq!(render(&dir, &[]).0["ran"], true);
    let (loaded, _) = render(&dir, &[]);
    assert_eq!(loaded["ran"], false, "{loaded}");
    assert_eq!(std::fs::read(dir.join("out.png")).unwrap(), traced);
    let file =
        stagelight::photon::file::decode(&std::fs::read(dir.join("scene.pmap")).unwrap()).unwrap();
    assert_eq!(file.caustics.unwrap().later.len(), 2, "passes 2 and 3 kept");
    let _ = std::fs::remove_dir_all(&dir);
}

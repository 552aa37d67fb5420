//! The farm's photon job: for a render that traces photon maps, `stagelight farm` writes a
//! `photons.sbatch` that traces them once into `OUT/photons`, the parts load them from there
//! (none traces or writes a map), and the merge is byte-identical to the local render.

use std::path::Path;
use std::process::Command;

use crate::common::cli::{bin, dir_names, run, scratch, stderr};

const SCENE: &str = r#"Scene(
    options: (samples: 1, max_depth: 6, refraction_depth: 6,
        caustics: (photons: 3000, gather: 20)),
    cameras: [(name: "cam", fov_y: 40, resolution: (20, 12),
        placement: LookAt(eye: (0, -4.5, 3.0), target: (0, 0, 0.5), up: (0, 0, 1)))],
    lights: [(name: "lamp", kind: Point(position: (0, 0, 4)), intensity: 40)],
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
"#;

fn script(dir: &Path, name: &str, task: Option<u32>) -> String {
    let mut cmd = Command::new("bash");
    cmd.arg(dir.join("job").join(name))
        .current_dir(dir)
        .env("SLURM_CPUS_PER_TASK", "1");
    if let Some(k) = task {
        cmd.env("SLURM_ARRAY_TASK_ID", k.to_string());
    }
    let o = cmd.output().unwrap();
    assert!(o.status.success(), "{name}: {}", stderr(&o));
    stderr(&o)
}

#[test]
fn the_photon_job_traces_once_and_every_part_loads_its_maps() {
    let dir = scratch("farm-photons");
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
    let o = run(bin()
        .current_dir(&dir)
        .args(["render", "scene.ron", "-o", "single.png"]));
    assert!(o.status.success(), "{}", stderr(&o));
    let o = run(bin().current_dir(&dir).args([
        "farm",
        "scene.ron",
        "--parts",
        "3",
        "--out",
        "job",
        "-o",
        "farm.png",
    ]));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.join("job/photons.sbatch").exists());

    let traced = script(&dir, "photons.sbatch", None);
    let cache = dir.join("job/photons");
    let files = dir_names(&cache);
    assert_eq!(files.len(), 1, "{files:?}");
    assert!(traced.contains(&files[0]), "{traced}");
    let map = std::fs::read(cache.join(&files[0])).unwrap();
    for k in 1..=3 {
        let log = script(&dir, "render.sbatch", Some(k));
        assert!(
            !log.contains(".pmap"),
            "part {k} traced its own maps: {log}"
        );
    }
    assert_eq!(dir_names(&cache), files, "no part wrote a map");
    assert_eq!(std::fs::read(cache.join(&files[0])).unwrap(), map);
    script(&dir, "merge.sbatch", None);
    assert_eq!(
        std::fs::read(dir.join("farm.png")).unwrap(),
        std::fs::read(dir.join("single.png")).unwrap()
    );

    // A scene without photon maps gets no photon job.
    let plain = SCENE.replace("caustics: (photons: 3000, gather: 20)", "");
    std::fs::write(dir.join("plain.ron"), plain).unwrap();
    let o = run(bin().current_dir(&dir).args([
        "farm",
        "plain.ron",
        "--parts",
        "2",
        "--out",
        "plain_job",
    ]));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!dir.join("plain_job/photons.sbatch").exists());
    let submit = std::fs::read_to_string(dir.join("plain_job/submit.sh")).unwrap();
    assert!(!submit.contains("photons.sbatch"), "{submit}");
    let _ = std::fs::remove_dir_all(&dir);
}

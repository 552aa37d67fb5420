//! The farm's photon job: for a render that traces photon maps, `stagelight farm` writes a
//! `photons.sbatch` that traces them once into `OUT/photons`, the parts load them from there
//! (none traces or writes a map), and the merge is byte-identical to the local render.

use std::path::Path;
use std::process::Command;

use crate::common::cli::{bin, dir_names, run, scratch, stderr};

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
    // Three tiles across, so that each of the 3 parts owns one (a part past the last tile
    // would skip `trace_photons` for that reason).
    let text = crate::photon_file::scene(40.0, 20, "")
        .replace("resolution: (12, 10)", "resolution: (40, 10)");
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
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
    let plain = text
        .replace("caustics: (photons: 4000, gather: 20),", "")
        .replace(
            "global_illumination: (photons: 1000, gather: 16, final_gather: 2),",
            "",
        );
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

//! Farm parts run by hand at once with one `--photon-cache DIR` (docs/farm.md's fallback
//! without the photon job, and what `render.sbatch` does when the photon job is skipped):
//! every part traces the same maps and commits the same `DIR/<hash>.pmap` at about the same
//! moment. Each part succeeds, and the cache holds one whole file, the one `stagelight
//! photons` writes, with no temporary left beside it.

use std::process::Stdio;

use crate::common::cli::{dir_names, run_in, scratch_dir, stagelight_in, stderr_of};

const PARTS: usize = 6;
const ROUNDS: usize = 4;

#[test]
fn parts_tracing_into_one_photon_cache_at_once_all_succeed() {
    let dir = scratch_dir("pcache-race");
    std::fs::write(
        dir.join("scene.ron"),
        crate::photon_file::scene(40.0, 20, ""),
    )
    .unwrap();
    let o = run_in(&dir, &["photons", "scene.ron", "--photon-cache", "ref"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let names = dir_names(&dir.join("ref"));
    let expected = std::fs::read(dir.join("ref").join(&names[0])).unwrap();
    for round in 0..ROUNDS {
        let _ = std::fs::remove_dir_all(dir.join("pc"));
        let parts: Vec<_> = (1..=PARTS)
            .map(|k| {
                stagelight_in(&dir)
                    .args(["render", "scene.ron", "--threads", "1", "--part"])
                    .arg(format!("{k}/{PARTS}"))
                    .args(["--photon-cache", "pc/cache", "-o"])
                    .arg(format!("pc/p{k}.exr"))
                    .stdout(Stdio::null())
                    .stderr(Stdio::piped())
                    .spawn()
                    .expect("start stagelight")
            })
            .collect();
        let failed: Vec<String> = parts
            .into_iter()
            .enumerate()
            .filter_map(|(k, part)| {
                let o = part.wait_with_output().expect("wait for stagelight");
                let failed = !o.status.success();
                failed.then(|| format!("round {round}, part {}: {}", k + 1, stderr_of(&o)))
            })
            .collect();
        assert_eq!(failed, Vec::<String>::new(), "every part succeeds");
        assert_eq!(dir_names(&dir.join("pc/cache")), names, "round {round}");
        let kept = std::fs::read(dir.join("pc/cache").join(&names[0])).unwrap();
        assert!(kept == expected, "round {round}: the cache file is whole");
        let written: Vec<String> = (1..=PARTS).map(|k| format!("p{k}.exr")).collect();
        let mut listed = dir_names(&dir.join("pc"));
        listed.retain(|n| n != "cache");
        assert_eq!(listed, written, "round {round}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

//! The photon pass from the command line: `--stats` reports `trace_photons` with the photons
//! it stored (photons/s), or skipped with its reason.

use std::path::PathBuf;
use std::process::Command;

fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/scenes")
        .join(name)
}

/// `render --stats-json` on `scene` with extra arguments; returns the `trace_photons` entry.
fn photon_stage(test: &str, scene: &str, extra: &[&str]) -> serde_json::Value {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight-photons-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let json = dir.join("stats.json");
    let o = Command::new(env!("CARGO_BIN_EXE_stagelight"))
        .arg("render")
        .arg(asset(scene))
        .arg("-o")
        .arg(dir.join("out.png"))
        .args(["--spp", "1", "--stats", "--stats-json"])
        .arg(&json)
        .args(extra)
        .output()
        .expect("run stagelight");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("trace_photons"), "{stdout}");
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    v["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["stage"] == "trace_photons")
        .expect("trace_photons in the report")
        .clone()
}

#[test]
fn stats_report_the_photon_pass_with_photons_stored() {
    let s = photon_stage("on", "caustics.ron", &[]);
    assert_eq!(s["ran"], true, "{s}");
    assert_eq!(s["unit"], "photons");
    assert!(s["items"].as_u64().unwrap() > 1000, "{s}");
    assert!(s["items_per_second"].as_f64().unwrap() > 0.0, "{s}");
    assert_eq!(
        s["reason"],
        "caustics (200000 photons) + global illumination (20000 photons)"
    );
}

#[test]
fn stats_report_the_photon_pass_skipped_with_its_reason() {
    let s = photon_stage("off", "test_plane.ron", &[]);
    assert_eq!(s["ran"], false);
    assert_eq!(s["reason"], "caustics and global illumination are off");
    let s = photon_stage("path", "caustics.ron", &["--integrator", "path"]);
    assert_eq!(s["ran"], false);
    assert_eq!(s["reason"], "the path integrator does not read photon maps");
}

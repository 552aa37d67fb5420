//! `trace_photons` is skipped, with its reason in `plan` and `--stats-json`, when no map
//! that is on can store a photon: every instance's flag lacks the receive bit, or every
//! material reflects or refracts every photon (a mirror). A receiver that stores keeps it.

use std::path::Path;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// A 2×2 square under a point light seen from above, `options` and the square's
/// `shader`; the instance gets `flags` (`, globillum: 0`).
fn square(options: &str, shader: &str, flags: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, {options}),
    cameras: [(name: "cam", fov_y: 60, resolution: (8, 8),
        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "s.png")])],
    lights: [(name: "lamp", kind: Point(position: (0, 0, 2)), intensity: 2.0)],
    materials: [(name: "m", shader: {shader})],
    objects: [(name: "sq", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], polygons: [[0, 1, 2, 3]]), material: "m")],
    instances: [(name: "sq_1", of: "sq"{flags})],
    groups: [(name: "world", members: ["sq_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// `(ran, reason, items, rays)` of `trace_photons` after a render with `--stats-json`,
/// checked against the plan's line.
fn photons(dir: &Path, text: &str) -> (bool, String, u64, u64) {
    std::fs::write(dir.join("s.ron"), text).unwrap();
    let o = run_in(dir, &["plan", "s.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let plan = String::from_utf8_lossy(&o.stdout).to_string();
    let line = plan
        .lines()
        .find(|l| l.contains(" trace_photons "))
        .unwrap()
        .to_string();
    let o = run_in(dir, &["render", "s.ron", "--stats-json", "stats.json"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("stats.json")).unwrap()).unwrap();
    let s = json["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["stage"] == "trace_photons")
        .unwrap()
        .clone();
    let ran = s["ran"].as_bool().unwrap();
    let reason = s["reason"].as_str().unwrap().to_string();
    let word = if ran { "run " } else { "skip" };
    assert_eq!(line, format!(" 4 trace_photons    {word} {reason}"));
    (
        ran,
        reason,
        s["items"].as_u64().unwrap(),
        s["rays"].as_u64().unwrap(),
    )
}

const LAMBERT: &str = "Lambert(albedo: (0.5, 0.5, 0.5))";
const GI: &str = "global_illumination: (photons: 1000)";

#[test]
fn no_instance_that_receives_skips_the_photon_pass() {
    let dir = scratch_dir("photon-receivers-flags");
    assert_eq!(
        photons(&dir, &square(GI, LAMBERT, ", globillum: 0")),
        (
            false,
            "global illumination is on, but no instance receives photons (globillum 0 or 1 on every one: the receive bit 2 is off)".into(),
            0,
            0
        )
    );
    // Casting only (1) stores nothing either; receiving only (2) stores the first hits.
    assert!(!photons(&dir, &square(GI, LAMBERT, ", globillum: 1")).0);
    let (ran, _, stored, rays) = photons(&dir, &square(GI, LAMBERT, ", globillum: 2"));
    assert!(ran && stored > 0 && rays >= 1000, "{stored} {rays}");
}

#[test]
fn a_mirror_alone_stores_no_caustic() {
    let dir = scratch_dir("photon-receivers-mirror");
    let caustics = "caustics: (photons: 1000)";
    let mirror = "Mirror(color: (0.9, 0.9, 0.9))";
    assert_eq!(
        photons(&dir, &square(caustics, mirror, "")),
        (
            false,
            "caustics are on, but no material stores photons (mirror and glass reflect or refract every one; a photon shader stores none where it reflects and refracts everything)".into(),
            0,
            0
        )
    );
    // Both maps on, neither can store: both reasons.
    let both = format!("{caustics}, {GI}");
    let (ran, reason, ..) = photons(&dir, &square(&both, mirror, ""));
    assert!(!ran);
    assert!(
        reason.starts_with("caustics and global illumination are on, but no photon can be stored (caustics: no material stores photons"),
        "{reason}"
    );
    // A diffuse surface receives the global map's photons.
    let (ran, _, stored, _) = photons(&dir, &square(GI, LAMBERT, ""));
    assert!(ran && stored > 0);
}

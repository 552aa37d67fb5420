//! Density-sized bakes (`texels_per_unit`): the texture size comes from the placed mesh's
//! area in f64 (the same wherever the instance is placed, rounded to a power of two with a
//! tolerance of a few f32 ulps), and the memory estimate sizes them the same way before any
//! stage runs instead of at `max_size`.

use crate::common::{run_in, scratch_dir, stderr_of};

/// A 0.2 × 0.2 quad (corners ±0.1) with unit-square UVs.
const QUAD: &str = r#"(name: "o", mesh: Inline(vertices: [(-0.1,0,0.1),(0.1,0,0.1),(0.1,0,-0.1),(-0.1,0,-0.1)], polygons: [[0,1,2,3]], uvs: [(0,0),(1,0),(1,1),(0,1)]))"#;

fn scene(instances: &[String]) -> String {
    let names: Vec<String> = (0..instances.len()).map(|k| format!("\"i{k}\"")).collect();
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8), placement: LookAt(eye: (0, 3, 3), target: (0, 0, 0), up: (0, 1, 0)), outputs: [])],
    objects: [{QUAD}],
    instances: [
        {}
    ],
    groups: [(name: "world", members: [{}])],
    render: (root: "world", camera: "cam"),
)
"#,
        instances.join(",\n        "),
        names.join(", ")
    )
}

/// Instance `k` of the quad with `transform` and `bake`.
fn instance(k: usize, transform: &str, bake: &str) -> String {
    format!(r#"(name: "i{k}", of: "o", transform: [{transform}], bake: ({bake}))"#)
}

/// The `W×H` of every `bake NAME:` line of `--stats`, in order.
fn sizes(stderr_and_stdout: &str) -> Vec<(String, String)> {
    stderr_and_stdout
        .lines()
        .filter_map(|l| l.strip_prefix("bake "))
        .filter_map(|l| {
            let (name, rest) = l.split_once(": ")?;
            let size = rest.split_once(" texels")?.0;
            Some((name.to_string(), size.to_string()))
        })
        .collect()
}

fn bake_sizes(dir: &std::path::Path, text: &str) -> Vec<(String, String)> {
    std::fs::write(dir.join("scene.ron"), text).unwrap();
    let o = run_in(dir, &["bake", "scene.ron", "-o", "out", "--stats"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let all = format!("{}{}", String::from_utf8_lossy(&o.stdout), stderr_of(&o));
    sizes(&all)
}

/// The tester's three 0.2 m quads at 40 texels/unit: each really bakes 8 × 8 texels, so
/// `check` and `bake` accept them under a budget of 1 GiB (they were estimated at
/// 4096² each, 4 GiB apiece, and refused).
#[test]
fn small_density_bakes_are_estimated_at_their_real_size() {
    let dir = scratch_dir("bake-density-estimate");
    let bake = "texels_per_unit: 40.0, outputs: [(kind: AmbientOcclusion(samples: 4))]";
    let text = scene(&[
        instance(0, "", bake),
        instance(1, "Translate((1,0,0))", bake),
        instance(2, "Translate((2,0,0))", bake),
    ]);
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    for args in [
        &["check", "scene.ron", "--memory-limit", "1G"][..],
        &["check", "scene.ron"],
    ] {
        let o = run_in(&dir, args);
        assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
    }
    let o = run_in(
        &dir,
        &[
            "bake",
            "scene.ron",
            "-o",
            "out",
            "--stats",
            "--memory-limit",
            "1G",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let all = format!("{}{}", String::from_utf8_lossy(&o.stdout), stderr_of(&o));
    let expected: Vec<(String, String)> = ["i0", "i1", "i2"]
        .iter()
        .map(|n| (n.to_string(), "8×8".to_string()))
        .collect();
    assert_eq!(sizes(&all), expected, "{all}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A density bake that truly needs too much is still refused before anything runs, at the
/// request, at the size its placed area gives (the quad scaled to 40 m at 100 texels/unit:
/// 4000 → 4096, under a `max_size` of 8192).
#[test]
fn a_density_bake_that_truly_needs_too_much_is_refused_at_its_real_size() {
    let dir = scratch_dir("bake-density-refused");
    let bake =
        "texels_per_unit: 100.0, max_size: 8192, outputs: [(kind: AmbientOcclusion(samples: 4))]";
    let text = scene(&[instance(0, "Scale((200,1,200))", bake)]);
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    let o = run_in(&dir, &["check", "scene.ron", "--memory-limit", "1G"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:5:9: error: bake request on instance \"i0\": 2 texture(s) of 4096×4096 texels need about 4.0 GiB, more than the memory budget of 1.0 GiB (--memory-limit)\n  help: lower the bake resolution, or raise the budget with --memory-limit BYTES\n1 error in scene.ron\n"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The same quad at 40 texels/unit is 8 × 8 (√0.04 · 40 = 8 exactly) wherever it is placed
/// and however it is rotated; it was 16 × 16 at x = 0, 0.5 and 1 (its f32 area gave a side
/// of 8.0000002).
#[test]
fn a_density_bake_has_the_same_size_wherever_it_is_placed() {
    let dir = scratch_dir("bake-density-placement");
    let bake = "texels_per_unit: 40.0, outputs: [(kind: AmbientOcclusion(samples: 1))]";
    let placements = [
        "",
        "Translate((0.5,0,0))",
        "Translate((1,0,0))",
        "Translate((2,0,0))",
        "Translate((3.7,0,-1.3))",
        "Translate((-5,2,0.25))",
        "Translate((1000.25,0,0))",
        "Rotate(axis: (0, 1, 0), degrees: 30), Translate((0.3,0,0.7))",
        "Rotate(axis: (1, 1, 0), degrees: 71), Translate((-7,0,3))",
    ];
    let instances: Vec<String> = placements
        .iter()
        .enumerate()
        .map(|(k, t)| instance(k, t, bake))
        .collect();
    let got = bake_sizes(&dir, &scene(&instances));
    let expected: Vec<(String, String)> = (0..placements.len())
        .map(|k| (format!("i{k}"), "8×8".to_string()))
        .collect();
    assert_eq!(got, expected);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Sides exactly at a power of two take that power, and a side just above it the next:
/// the 0.2 m quad at 40, 80 and 160 texels/unit is 8, 16 and 32 texels wide; at 40.1 (a
/// side of 8.02) it is 16; scaled 5× (1 m) at 64 texels/unit 64 and at 65 128.
#[test]
fn density_sizes_at_power_of_two_boundaries_are_exact() {
    let dir = scratch_dir("bake-density-boundaries");
    let cases = [
        ("", 40.0, "8×8"),
        ("Translate((2,0,0))", 80.0, "16×16"),
        ("Translate((4,0,0))", 160.0, "32×32"),
        ("Translate((6,0,0))", 40.1, "16×16"),
        ("Scale((5,1,5)), Translate((8,0,0))", 64.0, "64×64"),
        ("Scale((5,1,5)), Translate((10,0,0))", 65.0, "128×128"),
    ];
    let instances: Vec<String> = cases
        .iter()
        .enumerate()
        .map(|(k, (t, density, _))| {
            let bake = format!(
                "texels_per_unit: {density:?}, outputs: [(kind: AmbientOcclusion(samples: 1))]"
            );
            instance(k, t, &bake)
        })
        .collect();
    let got = bake_sizes(&dir, &scene(&instances));
    let expected: Vec<(String, String)> = cases
        .iter()
        .enumerate()
        .map(|(k, (_, _, size))| (format!("i{k}"), size.to_string()))
        .collect();
    assert_eq!(got, expected);
    let _ = std::fs::remove_dir_all(&dir);
}

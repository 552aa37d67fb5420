//! Requests that bake less than they ask for warn, located at the request: mesh UVs partly
//! outside the unit square (that part of the surface is not baked; the reported density
//! counts only the baked part), and an indirect lightmap with `max_depth: 0` (no bounce,
//! so no indirect light).

use crate::common::{run_in, scratch_dir, stderr_of};

/// A 2 × 2 quad whose `uvs` and `bake` are given.
fn quad_scene(uvs: &str, bake: &str) -> String {
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8), placement: LookAt(eye: (0, 3, 3), target: (0, 0, 0), up: (0, 1, 0)), outputs: [])],
    lights: [(name: "L", kind: Point(position: (0, 2, 0)), intensity: 10.0)],
    objects: [(name: "o", mesh: Inline(vertices: [(-1,0,1),(1,0,1),(1,0,-1),(-1,0,-1)], polygons: [[0,1,2,3]], uvs: [{uvs}]))],
    instances: [(name: "p", of: "o", bake: ({bake}))],
    groups: [(name: "world", members: ["p"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

/// Bakes `text` with `--stats`: (stderr, the `bake p:` line).
fn bake(test: &str, text: &str) -> (String, String) {
    let dir = scratch_dir(test);
    std::fs::write(dir.join("scene.ron"), text).unwrap();
    let o = run_in(&dir, &["bake", "scene.ron", "-o", "out", "--stats"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    // The warnings, without the `wrote …` lines.
    let stderr: String = stderr_of(&o)
        .lines()
        .filter(|l| !l.starts_with("wrote "))
        .map(|l| format!("{l}\n"))
        .collect();
    let all = format!("{}{stderr}", String::from_utf8_lossy(&o.stdout));
    let line = all
        .lines()
        .find(|l| l.starts_with("bake p:"))
        .unwrap_or_default()
        .to_string();
    let _ = std::fs::remove_dir_all(&dir);
    (stderr, line)
}

/// The tester's `outside.obj` as an inline quad: UVs from −0.5 to 1.5, so the 16 × 16
/// texture holds the middle 1 × 1 of the quad. It warns that 75% of the UV area is not
/// baked, and reports 16 texels per unit (256 texels on 1 m²), not 8 (on the whole 4 m²).
#[test]
fn uvs_partly_outside_the_unit_square_warn_and_report_the_baked_density() {
    let (stderr, line) = bake(
        "bake-warn-outside",
        &quad_scene(
            "(-0.5,-0.5),(1.5,-0.5),(1.5,1.5),(-0.5,1.5)",
            "resolution: (16, 16), outputs: [(kind: AmbientOcclusion(samples: 4))]",
        ),
    );
    assert_eq!(stderr.matches("warning:").count(), 1, "{stderr}");
    assert!(
        stderr.contains("scene.ron:5:17: warning: bake request on instance \"p\": 75.0% of its UV area lies outside the unit square [0, 1]²; that part of the surface is not baked\n  help: bake UVs must lie in the unit square: set `uvs: Unwrap` to generate lightmap UVs\n"),
        "{stderr}"
    );
    assert!(
        line.starts_with("bake p: 16×16 texels, 16.0 texels/unit, 256 covered,"),
        "{line}"
    );
}

/// UVs on the unit square: no warning, 8 texels per unit on the 2 m quad.
#[test]
fn uvs_inside_the_unit_square_do_not_warn() {
    let (stderr, line) = bake(
        "bake-warn-inside",
        &quad_scene(
            "(0,0),(1,0),(1,1),(0,1)",
            "resolution: (16, 16), outputs: [(kind: AmbientOcclusion(samples: 4))]",
        ),
    );
    assert!(!stderr.contains("warning"), "{stderr}");
    assert!(
        line.starts_with("bake p: 16×16 texels, 8.0 texels/unit, 256 covered,"),
        "{line}"
    );
}

/// `Lightmap(indirect: true, max_depth: 0)` gathers no bounce: a warning at the request
/// (docs/baking.md: `max_depth` is the number of bounces; the bake still runs, direct only).
#[test]
fn an_indirect_lightmap_with_max_depth_zero_warns() {
    let (stderr, _) = bake(
        "bake-warn-depth",
        &quad_scene(
            "(0,0),(1,0),(1,1),(0,1)",
            "resolution: (4, 4), outputs: [(kind: Lightmap(indirect: true, samples: 4, max_depth: 0))]",
        ),
    );
    assert_eq!(
        stderr,
        "scene.ron:5:17: warning: bake request on instance \"p\": `Lightmap(indirect: true, max_depth: 0)` bakes no indirect light: `max_depth` counts its bounces, and 0 allows none\n  help: set `max_depth: 1` or more for indirect light, or `indirect: false` for direct light only\n"
    );
}

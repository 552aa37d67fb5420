//! A bake's `rays` are the rays it traced, as the accelerator counts them: the per-request
//! counts add up to the `bake_lightmaps` stage's, and an open plane's indirect lightmap
//! reports exactly its probe, shadow and gather rays.

use crate::common::{run_in, scratch_dir, stderr_of};

/// `--stats-json` of baking `text`: the per-request rays and the bake stage's rays.
fn bake_rays(test: &str, text: &str) -> (Vec<u64>, u64) {
    let dir = scratch_dir(test);
    std::fs::write(dir.join("scene.ron"), text).unwrap();
    let o = run_in(
        &dir,
        &[
            "bake",
            "scene.ron",
            "-o",
            "out",
            "--stats-json",
            "stats.json",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("stats.json")).unwrap()).unwrap();
    let bakes = json["bakes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["rays"].as_u64().unwrap())
        .collect();
    let stage = json["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["stage"] == "bake_lightmaps")
        .unwrap()["rays"]
        .as_u64()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (bakes, stage)
}

/// The tester's open 2 × 2 plane under a point light, 16 × 16 texels, one sample position
/// each, `Lightmap(indirect: true, samples: 16, max_depth: 3)`: every texel traces 2 probe
/// rays (the probe stops once most escape), 1 shadow ray and 16 gather rays, all of which
/// escape: 256 × 19 = 4864 (it reported 17152, counting `samples × (max_depth + 1)`).
#[test]
fn an_open_plane_indirect_lightmap_counts_the_rays_it_traced() {
    let text = r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8), placement: LookAt(eye: (0, 3, 3), target: (0, 0, 0), up: (0, 1, 0)), outputs: [])],
    lights: [(name: "L", kind: Point(position: (0, 2, 0)), intensity: 10.0)],
    objects: [(name: "o", mesh: Inline(vertices: [(-1,0,1),(1,0,1),(1,0,-1),(-1,0,-1)], polygons: [[0,1,2,3]], uvs: [(0,0),(1,0),(1,1),(0,1)]))],
    instances: [(name: "p", of: "o", bake: (resolution: (16, 16), texel_samples: 1,
            outputs: [(kind: Lightmap(indirect: true, samples: 16, max_depth: 3))]))],
    groups: [(name: "world", members: ["p"])],
    render: (root: "world", camera: "cam"),
)
"#;
    assert_eq!(bake_rays("bake-rays-plane", text), (vec![4864], 4864));
}

/// A box on a floor, both baked (AO, an indirect lightmap, lights that trace no ray for
/// points they cannot reach): the requests' rays sum to the stage's.
#[test]
fn per_request_rays_add_up_to_the_stage_rays() {
    let text = r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8), placement: LookAt(eye: (3, 3, 3), target: (0, 0, 0), up: (0, 1, 0)), outputs: [])],
    lights: [(name: "L", kind: Point(position: (0.3, 3, 0.2)), intensity: 10.0),
             (name: "S", kind: Spot(position: (0, 4, 0), target: (0, 0, 0), cone_angle: 20), intensity: 5.0)],
    objects: [
        (name: "cube", mesh: Inline(vertices: [(-0.5,0,-0.5),(0.5,0,-0.5),(0.5,0,0.5),(-0.5,0,0.5),
                                             (-0.5,1,-0.5),(0.5,1,-0.5),(0.5,1,0.5),(-0.5,1,0.5)],
            polygons: [[0,1,2,3],[4,7,6,5],[0,4,5,1],[1,5,6,2],[2,6,7,3],[3,7,4,0]])),
        (name: "floor", mesh: Inline(vertices: [(-3,0,3),(3,0,3),(3,0,-3),(-3,0,-3)], polygons: [[0,1,2,3]], uvs: [(0,0),(1,0),(1,1),(0,1)])),
    ],
    instances: [
        (name: "c", of: "cube", bake: (resolution: (32, 32), uvs: Unwrap,
            outputs: [(kind: AmbientOcclusion(samples: 16)), (kind: Lightmap(indirect: true, samples: 8, max_depth: 2))])),
        (name: "f", of: "floor", bake: (resolution: (16, 16),
            outputs: [(kind: Lightmap(indirect: true, samples: 4))])),
    ],
    groups: [(name: "world", members: ["c", "f"])],
    render: (root: "world", camera: "cam"),
)
"#;
    let (bakes, stage) = bake_rays("bake-rays-sum", text);
    assert_eq!(bakes.len(), 2);
    assert!(stage > 0);
    assert_eq!(bakes.iter().sum::<u64>(), stage, "{bakes:?}");
}

//! The throughput ledger counts rays per stage exactly: closest-hit and occlusion queries
//! traced by `shade` and `bake_lightmaps` (issue 6, section 3).

use std::path::Path;

use stagelight::frame::{Frame, Tasks};

/// A 2×2 plane every camera ray hits, a point light above it (one shadow ray per hit), a
/// diffuse material (no secondary rays with the direct integrator), and an AO bake of the
/// plane.
const SCENE: &str = r#"Scene(
    options: (samples: 4, seed: 1, integrator: Direct),
    cameras: [(name: "cam", fov_y: 30.0, resolution: (12, 8),
        placement: LookAt(eye: (0, 0, 2), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "counts.exr", passes: [Beauty])])],
    lights: [(name: "bulb", kind: Point(position: (0.3, 0.2, 1.5)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "plane", material: "grey", mesh: Inline(
        vertices: [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)],
        polygons: [[0, 1, 2, 3]],
        uvs: [(0, 0), (1, 0), (1, 1), (0, 1)]))],
    instances: [(name: "plane_1", of: "plane", bake: (
        resolution: (4, 4), uvs: Mesh, texel_samples: 1, padding: 0,
        outputs: [(kind: AmbientOcclusion(samples: 64), format: Exr)]))],
    groups: [(name: "world", members: ["plane_1"])],
    render: (root: "world", camera: "cam"),
)"#;

fn run(threads: usize) -> Frame {
    let mut scene =
        stagelight::scene::load_scene_str(SCENE, Path::new("counts.ron")).expect("scene loads");
    let mut frame = Frame::new(scene.settings.clone());
    frame.inputs.tasks = Tasks {
        render: true,
        bake: true,
    };
    frame.inputs.bake_dir = crate::common::scratch_root().join(format!(
        "stagelight-ray-counts-{threads}-{}",
        std::process::id()
    ));
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame))
        .expect("render and bake");
    let _ = std::fs::remove_dir_all(&frame.inputs.bake_dir);
    frame
}

#[test]
fn shade_and_bake_report_exact_ray_counts() {
    for threads in [1, 2] {
        let frame = run(threads);
        let report = &frame.report;
        let shade = report.stage("shade").unwrap();
        let samples = 12 * 8 * 4;
        assert_eq!(shade.items, samples);
        // One camera ray per sample, plus the pixel-centre ray of the depth/normal/id passes.
        assert_eq!(shade.rays_closest, samples + 12 * 8);
        assert_eq!(
            shade.rays_occlusion, samples,
            "one shadow ray per shaded sample"
        );
        assert_eq!(shade.rays, shade.rays_closest + shade.rays_occlusion);
        assert!(shade.rays_per_second_per_thread > 0.0);

        // 16 texels, one sample position each, 64 AO rays per position: occlusion queries
        // first, then closest hits for the inside-geometry probe only where a ray is blocked
        // (none on this open scene).
        let bake = report.stage("bake_lightmaps").unwrap();
        assert_eq!(bake.rays, 16 * 64, "{bake:?}");
        assert_eq!(
            bake.rays, frame.outputs.bake_reports[0].rays,
            "the bake's own count agrees"
        );

        for quiet in ["expand_geometry", "tessellate", "build_accel"] {
            assert_eq!(
                report.stage(quiet).unwrap().rays,
                0,
                "{quiet} traces nothing"
            );
        }
    }
}

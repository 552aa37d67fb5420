//! The throughput ledger counts rays per stage exactly: closest-hit and occlusion queries
//! traced by `shade` and `bake_lightmaps` (issue 6, section 3); a farm part of a samples split
//! other than part 1 traces no pixel-centre rays (the merge takes the centre passes from
//! part 1).

use std::path::Path;

use stagelight::farm::{Part, PartRun, Split};
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

        // 16 texels, one sample position each: the inside-geometry probe's own rays
        // (closest hits, 8 drawn; "inside" needs more than 3/4 of them to meet back faces,
        // so on this open scene the first 2 misses make "outside" certain) and then 64 AO
        // occlusion rays per position.
        let bake = report.stage("bake_lightmaps").unwrap();
        assert_eq!(bake.rays_closest, 16 * 2, "{bake:?}");
        assert_eq!(bake.rays_occlusion, 16 * 64, "{bake:?}");
        assert_eq!(bake.rays, 16 * 2 + 16 * 64, "{bake:?}");
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

/// Renders part `index` of 2 of a samples split of [`SCENE`] (2 of its 4 samples per pixel).
fn samples_part(index: u32) -> Frame {
    let mut scene =
        stagelight::scene::load_scene_str(SCENE, Path::new("counts.ron")).expect("scene loads");
    let mut frame = Frame::new(scene.settings.clone());
    frame.inputs.part = Some(PartRun {
        part: Part {
            index,
            count: 2,
            split: Split::Samples,
        },
        scene: "counts.ron".into(),
        scene_hash: 1,
    });
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame)
        .expect("render the part");
    frame
}

/// Part 1 of a samples split traces the pixel-centre rays of the depth, normal and id passes
/// beside its samples' camera rays; part 2 traces only its samples' (its part file holds no
/// centre passes: depth +∞, normal and ids zero, where part 1's see the plane everywhere).
#[test]
fn only_part_1_of_a_samples_split_traces_the_centre_passes() {
    let pixels = 12 * 8;
    for (index, centre_rays) in [(1, pixels), (2, 0)] {
        let frame = samples_part(index);
        let shade = frame.report.stage("shade").unwrap();
        assert_eq!(
            shade.items,
            pixels * 2,
            "part {index}: its 2 samples per pixel"
        );
        assert_eq!(
            shade.rays_closest,
            pixels * 2 + centre_rays,
            "part {index}: camera rays"
        );
        assert_eq!(
            shade.rays_occlusion,
            pixels * 2,
            "part {index}: shadow rays"
        );
        let fb = frame.outputs.image.as_ref().unwrap();
        if index == 1 {
            assert!(
                fb.depth.iter().all(|d| d.is_finite()),
                "part 1 sees the plane"
            );
            assert!(fb.object_id.iter().all(|&id| id == 1));
            assert!(fb.material_id.iter().all(|&id| id == 1));
        } else {
            assert!(fb.depth.iter().all(|&d| d == f32::INFINITY));
            assert!(fb.normal.iter().all(|&n| n == glam::Vec3::ZERO));
            assert!(fb.object_id.iter().all(|&id| id == 0));
            assert!(fb.material_id.iter().all(|&id| id == 0));
        }
    }
}

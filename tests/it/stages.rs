//! The stage table end to end on small worlds: run conditions and their reasons,
//! determinism across thread counts, finite output, and the written files.

use crate::common;

use glam::{Affine3A, Vec3};
use stagelight::camera_space::CameraSpace;
use stagelight::components::{LightShape, Pass, Shader};
use stagelight::exr_output::encode_exr;
use stagelight::frame::Frame;
use stagelight::settings::{PixelFilter, RenderSettings};

fn lit_world() -> hecs::World {
    let mut world = hecs::World::new();
    let grey = common::material(
        &mut world,
        Shader::Lambert {
            albedo: Vec3::splat(0.6),
        },
    );
    let flat = common::material(
        &mut world,
        Shader::Constant {
            color: Vec3::new(0.2, 0.4, 0.8),
        },
    );
    common::instance(&mut world, common::square(3.0), Affine3A::IDENTITY, grey);
    // A small occluder casting a soft shadow, and a constant-colour quad.
    common::instance(
        &mut world,
        common::square(0.4),
        Affine3A::from_translation(Vec3::new(0.0, 0.0, 0.8)),
        grey,
    );
    common::instance(
        &mut world,
        common::square(0.3),
        Affine3A::from_translation(Vec3::new(1.5, 1.5, 0.2)),
        flat,
    );
    common::camera(
        &mut world,
        Vec3::new(0.5, -3.0, 4.0),
        Vec3::ZERO,
        50.0,
        40,
        30,
    );
    common::light(
        &mut world,
        LightShape::Rect {
            corner: Vec3::new(-0.5, -0.5, 2.5),
            edge_u: Vec3::Y,
            edge_v: Vec3::X,
        },
        Vec3::splat(4.0),
        8,
    );
    common::light(
        &mut world,
        LightShape::Spot {
            position: Vec3::new(2.0, 0.0, 3.0),
            direction: Vec3::new(-2.0, 0.0, -3.0).normalize(),
            cone_angle: 25f32.to_radians(),
            penumbra: 5f32.to_radians(),
            beam_distribution: 2.0,
        },
        Vec3::splat(30.0),
        1,
    );
    world
}

fn settings() -> RenderSettings {
    RenderSettings {
        spp: 8,
        filter: PixelFilter::Gaussian {
            sigma: 0.5,
            radius: 1.5,
        },
        seed: 42,
        ..RenderSettings::default()
    }
}

#[test]
fn empty_world_skips_every_stage_with_a_reason() {
    let mut world = hecs::World::new();
    let frame = common::render(&mut world, RenderSettings::default());
    let build = frame.report.stage("build_accel").unwrap();
    assert!(!build.ran);
    assert_eq!(build.reason, "no instance has triangles");
    let shade = frame.report.stage("shade").unwrap();
    assert!(!shade.ran);
    assert_eq!(shade.reason, "no render camera");
    assert!(frame.outputs.geometry.is_none() && frame.outputs.image.is_none());
}

#[test]
fn camera_without_geometry_shades_black_and_skips_build() {
    let mut world = hecs::World::new();
    common::camera(&mut world, Vec3::Z, Vec3::ZERO, 40.0, 8, 6);
    let frame = common::render(&mut world, RenderSettings::default());
    assert!(!frame.report.stage("build_accel").unwrap().ran);
    let shade = frame.report.stage("shade").unwrap();
    assert!(shade.ran);
    assert_eq!(shade.items, 8 * 6 * 4);
    let fb = frame.outputs.image.unwrap();
    assert!(fb.beauty.iter().all(|c| *c == Vec3::ZERO));
    assert!(fb.alpha.iter().all(|a| *a == 0.0));
}

#[test]
fn geometry_without_camera_skips_build_accel() {
    let mut world = hecs::World::new();
    let m = common::material(&mut world, Shader::Lambert { albedo: Vec3::ONE });
    common::instance(&mut world, common::square(1.0), Affine3A::IDENTITY, m);
    let frame = common::render(&mut world, RenderSettings::default());
    let build = frame.report.stage("build_accel").unwrap();
    assert!(!build.ran);
    assert_eq!(build.reason, "no render camera traces rays");
}

#[test]
fn report_counts_work_items() {
    let mut world = lit_world();
    let frame = common::render(&mut world, settings());
    let build = frame.report.stage("build_accel").unwrap();
    assert!(build.ran);
    assert_eq!(build.items, 6);
    assert_eq!(build.unit, "triangles");
    assert_eq!(build.reason, "3 instance(s) with 6 triangles");
    assert_eq!(frame.report.stage("shade").unwrap().items, 40 * 30 * 8);
}

/// The camera space of [`lit_world`]'s camera, which the EXR writer derives from.
fn lit_camera() -> CameraSpace {
    CameraSpace::of_render_camera(&lit_world(), Default::default()).unwrap()
}

fn render_with_threads(threads: usize) -> Frame {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut world = lit_world();
        common::render(&mut world, settings())
    })
}

#[test]
fn same_bytes_at_one_and_two_threads() {
    let a = render_with_threads(1);
    let b = render_with_threads(2);
    let passes = [
        Pass::Beauty,
        Pass::Depth,
        Pass::Normal,
        Pass::ObjectId,
        Pass::MaterialId,
    ];
    let camera = lit_camera();
    let ea = encode_exr(a.outputs.image.as_ref().unwrap(), &camera, &passes).unwrap();
    let eb = encode_exr(b.outputs.image.as_ref().unwrap(), &camera, &passes).unwrap();
    assert!(ea == eb, "EXR bytes differ between 1 and 2 threads");
    assert_eq!(a.report.threads, 1);
    assert_eq!(b.report.threads, 2);
}

#[test]
fn every_pass_is_finite_and_sane() {
    let frame = render_with_threads(2);
    let fb = frame.outputs.image.unwrap();
    assert!(fb
        .beauty
        .iter()
        .all(|c| c.is_finite() && c.min_element() >= 0.0));
    assert!(fb.alpha.iter().all(|a| (0.0..=1.0).contains(a)));
    assert!(fb.normal.iter().all(|n| n.is_finite()));
    assert!(fb.depth.iter().all(|d| *d > 0.0));
    // The floor fills the view: some pixels lit, the spot and area light both contribute.
    assert!(fb.beauty.iter().any(|c| c.x > 0.05));
    // The constant quad shows its colour exactly (box of samples all on it).
    assert!(fb
        .beauty
        .iter()
        .any(|c| (*c - Vec3::new(0.2, 0.4, 0.8)).length() < 1e-5));
}

#[test]
fn seed_changes_the_noise_but_not_the_mean() {
    let mut w1 = lit_world();
    let a = common::render(&mut w1, settings());
    let mut w2 = lit_world();
    let b = common::render(
        &mut w2,
        RenderSettings {
            seed: 7,
            ..settings()
        },
    );
    let (fa, fb) = (a.outputs.image.unwrap(), b.outputs.image.unwrap());
    assert_ne!(fa.beauty, fb.beauty);
    let mean = |v: &[Vec3]| v.iter().map(|c| c.x as f64).sum::<f64>() / v.len() as f64;
    let (ma, mb) = (mean(&fa.beauty), mean(&fb.beauty));
    assert!((ma - mb).abs() / ma < 0.02, "{ma} vs {mb}");
}

#[test]
fn object_and_material_id_passes_label_what_each_pixel_centre_sees() {
    let frame = render_with_threads(2);
    let fb = frame.outputs.image.unwrap();
    let mut objects: Vec<u32> = fb.object_id.clone();
    objects.sort_unstable();
    objects.dedup();
    let mut materials: Vec<u32> = fb.material_id.clone();
    materials.sort_unstable();
    materials.dedup();
    // Background, three instances (floor, occluder, constant quad) and two materials.
    assert_eq!(objects, [0, 1, 2, 3], "{objects:?}");
    assert_eq!(materials, [0, 1, 2], "{materials:?}");
    for i in 0..fb.object_id.len() {
        assert_eq!(fb.object_id[i] == 0, fb.depth[i].is_infinite());
        assert_eq!(fb.object_id[i] == 0, fb.material_id[i] == 0);
    }
    // The ids reach the EXR as u32 channels.
    let bytes = encode_exr(
        &fb,
        &lit_camera(),
        &[Pass::Beauty, Pass::ObjectId, Pass::MaterialId],
    )
    .unwrap();
    let dir =
        crate::common::scratch_root().join(format!("stagelight-ids-{}.exr", std::process::id()));
    std::fs::write(&dir, &bytes).unwrap();
    let read = exr::prelude::read_all_flat_layers_from_file(&dir).unwrap();
    let names: Vec<String> = read.layer_data[0]
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    assert!(
        names.contains(&"id.object".to_string()) && names.contains(&"id.material".to_string()),
        "{names:?}"
    );
    let _ = std::fs::remove_file(&dir);
}

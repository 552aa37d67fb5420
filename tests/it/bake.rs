//! Baking against closed forms: ambient occlusion of analytic configurations, the texel
//! centre convention, dilation, inside-geometry detection, determinism and run conditions.

use crate::common;

use std::sync::Arc;

use glam::{Affine3A, Vec2, Vec3};
use hecs::{Entity, World};
use stagelight::bake::TexelImage;
use stagelight::components::{
    BakeFormat, BakeKind, BakeRequest, BakeResolution, BakeTarget, Shader, TriMesh, UvSource,
};
use stagelight::frame::{Frame, Tasks};
use stagelight::settings::RenderSettings;

/// A square `[-h, h]²` at z = 0 facing +Z with UVs spanning `[u0, u1]²`.
fn square_uv(h: f32, u0: f32, u1: f32) -> TriMesh {
    let mut m = common::square(h);
    m.uvs = Some(vec![
        Vec2::new(u0, u0),
        Vec2::new(u1, u0),
        Vec2::new(u1, u1),
        Vec2::new(u0, u1),
    ]);
    m
}

fn ao(samples: u32) -> BakeKind {
    BakeKind::AmbientOcclusion {
        samples,
        max_distance: f32::INFINITY,
        bent_normals: false,
    }
}

fn request(
    kinds: Vec<BakeKind>,
    width: u32,
    height: u32,
    texel_samples: u32,
    padding: u32,
) -> BakeRequest {
    BakeRequest {
        name: "target".into(),
        resolution: BakeResolution::Fixed { width, height },
        uvs: UvSource::Mesh,
        texel_samples,
        padding,
        mask: false,
        stitch_seams: false,
        targets: kinds
            .into_iter()
            .map(|kind| BakeTarget {
                kind,
                format: BakeFormat::Exr,
                file: None,
                denoise: None,
            })
            .collect(),
    }
}

fn spawn(world: &mut World, mesh: TriMesh, xf: Affine3A) -> Entity {
    let m = common::material(
        world,
        Shader::Lambert {
            albedo: Vec3::splat(0.5),
        },
    );
    common::instance(world, mesh, xf, m)
}

/// Runs the stages up to and including `bake_lightmaps` (writes into a scratch directory).
fn bake(world: &mut World, seed: u64) -> Frame {
    let mut frame = Frame::new(RenderSettings {
        seed,
        ..RenderSettings::default()
    });
    frame.inputs.tasks = Tasks {
        render: false,
        bake: true,
    };
    let dir = crate::common::scratch_root().join(format!(
        "stagelight-bake-test-{}-{seed}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    frame.inputs.bake_dir = dir;
    stagelight::systems::run(world, &mut frame).expect("bake");
    frame
}

/// Reads a baked EXR back (R channel per texel, row 0 at the top).
fn read_exr(path: &std::path::Path) -> (usize, usize, Vec<Vec3>) {
    use exr::prelude::*;
    let image = read_first_rgba_layer_from_file(
        path,
        |res, _| {
            (
                res.width(),
                res.height(),
                vec![Vec3::ZERO; res.width() * res.height()],
            )
        },
        |(w, _, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * *w + pos.x()] = Vec3::new(r, g, b)
        },
    )
    .unwrap();
    let (w, h, px) = image.layer_data.channel_data.pixels;
    (w, h, px)
}

fn baked(frame: &Frame, suffix: &str) -> (usize, usize, Vec<Vec3>) {
    let path = frame
        .report
        .written
        .iter()
        .find(|p| p.to_string_lossy().ends_with(suffix))
        .unwrap_or_else(|| panic!("no {suffix} in {:?}", frame.report.written));
    read_exr(path)
}

#[test]
fn unoccluded_plane_bakes_exactly_one() {
    let mut world = World::new();
    let e = spawn(&mut world, square_uv(1.0, 0.0, 1.0), Affine3A::IDENTITY);
    world
        .insert_one(e, request(vec![ao(32)], 16, 16, 4, 0))
        .unwrap();
    let frame = bake(&mut world, 1);
    let (_, _, px) = baked(&frame, "target_ao.exr");
    assert!(
        px.iter().all(|c| c.x == 1.0),
        "every texel sees the open sky"
    );
    let r = &frame.outputs.bake_reports[0];
    assert_eq!(r.covered_texels, 256);
    assert_eq!(r.invalid_texels, 0);
}

/// A floor beside an infinite wall: the wall blocks exactly the half of the cosine-weighted
/// hemisphere that faces it, so AO = 1/2 at any distance (unlimited max distance).
#[test]
fn floor_beside_an_infinite_wall_bakes_one_half_at_any_distance() {
    for distance in [0.05f32, 1.0, 20.0] {
        let mut world = World::new();
        // Wall: the plane x = 0 facing +X, 2e4 wide and tall (z ≥ 0).
        let wall_xf = Affine3A::from_translation(Vec3::new(0.0, 0.0, 1e4))
            * Affine3A::from_rotation_y(std::f32::consts::FRAC_PI_2);
        spawn(&mut world, common::square(1e4), wall_xf);
        // Floor patch 0.02 wide at distance `distance` from the wall.
        let floor = spawn(
            &mut world,
            square_uv(0.01, 0.0, 1.0),
            Affine3A::from_translation(Vec3::new(distance + 0.01, 0.0, 0.0)),
        );
        let samples = 1024;
        world
            .insert_one(floor, request(vec![ao(samples)], 2, 2, 1, 0))
            .unwrap();
        let frame = bake(&mut world, 2);
        let (_, _, px) = baked(&frame, "target_ao.exr");
        let n = px.len() as f64 * samples as f64;
        let mean = px.iter().map(|c| c.x as f64).sum::<f64>() / px.len() as f64;
        let sigma = (0.25 / n).sqrt();
        assert!(
            (mean - 0.5).abs() < 3.0 * sigma + 1e-3,
            "distance {distance}: AO {mean} (σ {sigma})"
        );
    }
}

/// A point below a sphere of radius R whose centre is at distance D along the normal: the
/// sphere covers a cone of half-angle α, sin α = R/D, whose cosine-weighted measure is
/// sin²α, so AO = 1 − (R/D)².
#[test]
fn point_facing_a_sphere_matches_one_minus_sin_squared() {
    let (r, d) = (1.0f32, 2.5f32);
    let mut world = World::new();
    // The triangulated sphere is inscribed in the true one; scale it so its faces' mean
    // radius matches R closely (segments small).
    spawn(
        &mut world,
        common::sphere(r, 256, 128),
        Affine3A::from_translation(Vec3::new(0.0, 0.0, d)),
    );
    let patch = spawn(&mut world, square_uv(1e-3, 0.0, 1.0), Affine3A::IDENTITY);
    let samples = 4096;
    world
        .insert_one(patch, request(vec![ao(samples)], 1, 1, 1, 0))
        .unwrap();
    let frame = bake(&mut world, 3);
    let (_, _, px) = baked(&frame, "target_ao.exr");
    let expected = 1.0 - (r as f64 / d as f64).powi(2);
    let sigma = (expected * (1.0 - expected) / samples as f64).sqrt();
    let got = px[0].x as f64;
    assert!(
        (got - expected).abs() < 3.0 * sigma + 2e-3,
        "AO {got}, closed form {expected} (σ {sigma})"
    );
}

/// A point below a parallel square of half-side a at height h: the square's form factor is
/// four corner rectangles, F = 4 · (1/2π)[X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))]
/// with X = Y = a/h, and AO = 1 − F.
#[test]
fn point_below_a_parallel_square_matches_the_form_factor() {
    let (a, h) = (0.8f64, 0.6f64);
    let mut world = World::new();
    // The occluder faces down (toward the point): rotate the +Z square by π about X.
    spawn(
        &mut world,
        common::square(a as f32),
        Affine3A::from_translation(Vec3::new(0.0, 0.0, h as f32))
            * Affine3A::from_rotation_x(std::f32::consts::PI),
    );
    let patch = spawn(&mut world, square_uv(1e-4, 0.0, 1.0), Affine3A::IDENTITY);
    let samples = 4096;
    world
        .insert_one(patch, request(vec![ao(samples)], 1, 1, 1, 0))
        .unwrap();
    let frame = bake(&mut world, 4);
    let (_, _, px) = baked(&frame, "target_ao.exr");
    let x = a / h;
    let corner = (x / (1.0 + x * x).sqrt() * (x / (1.0 + x * x).sqrt()).atan()) * 2.0
        / (2.0 * std::f64::consts::PI);
    let expected = 1.0 - 4.0 * corner;
    let sigma = (expected * (1.0 - expected) / samples as f64).sqrt();
    let got = px[0].x as f64;
    assert!(
        (got - expected).abs() < 3.0 * sigma,
        "AO {got}, closed form {expected} (σ {sigma})"
    );
}

#[test]
fn texel_centres_follow_the_documented_convention() {
    // A square [0,1]² (object space shifted) whose UV equals its position: texel (i, j) must
    // bake the position ((i + ½)/W, 1 − (j + ½)/H).
    let mut world = World::new();
    let e = spawn(
        &mut world,
        square_uv(0.5, 0.0, 1.0),
        Affine3A::from_translation(Vec3::new(0.5, 0.5, 0.0)),
    );
    let (w, h) = (8u32, 4u32);
    world
        .insert_one(e, request(vec![BakeKind::Positions], w, h, 1, 0))
        .unwrap();
    let frame = bake(&mut world, 5);
    let (bw, bh, px) = baked(&frame, "target_positions.exr");
    assert_eq!((bw, bh), (w as usize, h as usize));
    for j in 0..h {
        for i in 0..w {
            let p = px[(j * w + i) as usize];
            let expected = Vec3::new(
                (i as f32 + 0.5) / w as f32,
                1.0 - (j as f32 + 0.5) / h as f32,
                0.0,
            );
            assert!(
                (p - expected).length() < 1e-6,
                "texel ({i}, {j}): {p} vs {expected}"
            );
        }
    }
}

#[test]
fn dilation_fills_gutters_and_never_overwrites_covered_texels() {
    let run = |padding: u32| {
        let mut world = World::new();
        let e = spawn(&mut world, square_uv(1.0, 0.25, 0.75), Affine3A::IDENTITY);
        world
            .insert_one(e, request(vec![BakeKind::Positions], 16, 16, 4, padding))
            .unwrap();
        let frame = bake(&mut world, 6);
        let (_, _, px) = baked(&frame, "target_positions.exr");
        (px, frame.outputs.bake_reports[0].dilated_texels)
    };
    let (plain, none) = run(0);
    let (padded, filled) = run(2);
    assert_eq!(none, 0);
    // Charts cover texels 4..12 in both axes; two rings around them are 12² − 8² texels.
    assert_eq!(filled, 12 * 12 - 8 * 8);
    for j in 0..16usize {
        for i in 0..16usize {
            let idx = j * 16 + i;
            let inside = (4..12).contains(&i) && (4..12).contains(&j);
            let ring = (2..14).contains(&i) && (2..14).contains(&j);
            if inside {
                assert_eq!(padded[idx], plain[idx], "covered texel ({i}, {j}) changed");
            } else if ring {
                assert_ne!(
                    padded[idx],
                    Vec3::ZERO,
                    "gutter texel ({i}, {j}) not filled"
                );
            } else {
                assert_eq!(
                    padded[idx],
                    Vec3::ZERO,
                    "texel ({i}, {j}) beyond the padding"
                );
            }
        }
    }
}

/// A closed box resting on the floor: floor texels under it see only the box's back faces
/// and are reported invalid instead of baked black.
#[test]
fn texels_inside_geometry_are_invalid_not_black() {
    let mut world = World::new();
    let floor = spawn(&mut world, square_uv(1.0, 0.0, 1.0), Affine3A::IDENTITY);
    // A closed box [-0.5, 0.5]² × [-0.05, 0.5] sunk slightly into the floor.
    spawn(
        &mut world,
        common::box_mesh(Vec3::new(-0.5, -0.5, -0.05), Vec3::new(0.5, 0.5, 0.5)),
        Affine3A::IDENTITY,
    );
    world
        .insert_one(floor, request(vec![ao(64)], 16, 16, 4, 0))
        .unwrap();
    let frame = bake(&mut world, 7);
    let r = &frame.outputs.bake_reports[0];
    // The footprint [-0.5, 0.5]² is a quarter of the floor: exactly 8 × 8 texels.
    assert_eq!(r.invalid_texels, 64);
    let (_, _, px) = baked(&frame, "target_ao.exr");
    // Texels well outside the footprint are baked and bright-ish; none is NaN.
    assert!(px.iter().all(|c| c.is_finite()));
    assert!(px[0].x > 0.5);
}

/// 1 − F of a point on the axis below the centre of a parallel `2a × 2a` square at height
/// `c`: F is four times the form factor of a corner rectangle (A = B = a/c).
fn below_square_ao(a: f64, c: f64) -> f64 {
    let x = a / c;
    let q = (1.0 + x * x).sqrt();
    let corner = (x / q * (x / q).atan()) * 2.0 / (2.0 * std::f64::consts::PI);
    1.0 - 4.0 * corner
}

/// A 1 cm patch 0.5 below a 2 × 2 one-sided plane that faces away from it (the patch sees
/// its back face) is not inside anything: at every AO sample count every texel is valid
/// and the mean AO is 1 − F (0.169) within four binomial standard errors — the same as
/// under the plane turned to face the patch. (The AO rays used to double as the inside
/// probe from 8 rays per position: a position survived only with at most ¾ of its rays on
/// back faces, so AO was biased to ≥ 0.25 and whole texels fell invalid as the count grew.)
#[test]
fn ao_under_the_back_of_an_open_plane_is_unbiased_at_every_sample_count() {
    let exact = below_square_ao(1.0, 0.5);
    assert!((exact - 0.169).abs() < 1e-3, "{exact}");
    for facing_patch in [false, true] {
        for samples in [16, 32, 64, 128, 256] {
            let mut world = World::new();
            let patch = spawn(&mut world, square_uv(0.005, 0.0, 1.0), Affine3A::IDENTITY);
            // Facing +Z (away from the patch), or turned over to face it.
            let turn = if facing_patch {
                Affine3A::from_rotation_x(std::f32::consts::PI)
            } else {
                Affine3A::IDENTITY
            };
            spawn(
                &mut world,
                common::square(1.0),
                Affine3A::from_translation(Vec3::new(0.0, 0.0, 0.5)) * turn,
            );
            world
                .insert_one(patch, request(vec![ao(samples)], 8, 8, 4, 0))
                .unwrap();
            let frame = bake(&mut world, 46);
            let case = format!("{samples} rays, plane facing the patch: {facing_patch}");
            assert_eq!(frame.outputs.bake_reports[0].invalid_texels, 0, "{case}");
            let (_, _, px) = baked(&frame, "target_ao.exr");
            let mean = px.iter().map(|c| f64::from(c.x)).sum::<f64>() / px.len() as f64;
            let se = (exact * (1.0 - exact) / (px.len() as f64 * f64::from(samples))).sqrt();
            assert!(
                (mean - exact).abs() <= 4.0 * se,
                "{case}: mean AO {mean}, exact {exact}, standard error {se}"
            );
        }
    }
}

/// A floor 0.5 below a same-size one-sided plane facing up (away from it): no floor texel is
/// inside anything, so none is invalid.
#[test]
fn a_floor_under_the_back_of_a_same_size_plane_has_no_invalid_texels() {
    let mut world = World::new();
    let floor = spawn(&mut world, square_uv(1.0, 0.0, 1.0), Affine3A::IDENTITY);
    spawn(
        &mut world,
        common::square(1.0),
        Affine3A::from_translation(Vec3::new(0.0, 0.0, 0.5)),
    );
    world
        .insert_one(floor, request(vec![ao(64)], 16, 16, 4, 0))
        .unwrap();
    let frame = bake(&mut world, 47);
    assert_eq!(frame.outputs.bake_reports[0].invalid_texels, 0);
}

#[test]
fn bakes_are_identical_at_one_and_two_threads() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut world = World::new();
            let floor = spawn(&mut world, square_uv(1.0, 0.0, 1.0), Affine3A::IDENTITY);
            spawn(
                &mut world,
                common::sphere(0.3, 16, 8),
                Affine3A::from_translation(Vec3::new(0.0, 0.0, 0.4)),
            );
            common::light(
                &mut world,
                stagelight::components::LightShape::Point {
                    position: Vec3::new(0.5, 0.5, 2.0),
                },
                Vec3::splat(5.0),
                1,
            );
            let kinds = vec![
                ao(16),
                BakeKind::Lightmap {
                    indirect: true,
                    samples: 8,
                    max_depth: 2,
                    store: stagelight::components::LightmapStore::Irradiance,
                    scale: 1.0,
                },
            ];
            world
                .insert_one(floor, request(kinds, 24, 24, 4, 2))
                .unwrap();
            let frame = bake(&mut world, 8);
            frame
                .report
                .written
                .iter()
                .map(|p| std::fs::read(p).unwrap())
                .collect::<Vec<_>>()
        })
    };
    let a = run(1);
    let b = run(2);
    assert_eq!(a.len(), 2);
    assert!(a == b, "baked bytes differ between 1 and 2 threads");
}

#[test]
fn lightmap_of_a_point_lit_plane_matches_the_inverse_square_law() {
    let mut world = World::new();
    let e = spawn(&mut world, square_uv(1.0, 0.0, 1.0), Affine3A::IDENTITY);
    let (pos, intensity) = (Vec3::new(0.2, -0.3, 1.5), 7.0f32);
    common::light(
        &mut world,
        stagelight::components::LightShape::Point { position: pos },
        Vec3::splat(intensity),
        1,
    );
    let kind = BakeKind::Lightmap {
        indirect: false,
        samples: 1,
        max_depth: 0,
        store: stagelight::components::LightmapStore::Irradiance,
        scale: 1.0,
    };
    world
        .insert_one(e, request(vec![kind], 8, 8, 1, 0))
        .unwrap();
    let frame = bake(&mut world, 9);
    let (_, _, px) = baked(&frame, "target_lightmap.exr");
    for j in 0..8 {
        for i in 0..8 {
            // Texel centre → uv → position on the [-1, 1]² square.
            let u = (i as f32 + 0.5) / 8.0;
            let v = 1.0 - (j as f32 + 0.5) / 8.0;
            let p = Vec3::new(2.0 * u - 1.0, 2.0 * v - 1.0, 0.0);
            let d = pos - p;
            let e = intensity * d.z / d.length().powi(3);
            let got = px[j * 8 + i].x;
            assert!((got - e).abs() / e < 1e-4, "texel ({i}, {j}): {got} vs {e}");
        }
    }
}

#[test]
fn bake_stage_is_skipped_without_requests_or_outside_bake_runs() {
    let mut world = World::new();
    spawn(&mut world, square_uv(1.0, 0.0, 1.0), Affine3A::IDENTITY);
    let frame = common::render(&mut world, RenderSettings::default());
    let s = frame.report.stage("bake_lightmaps").unwrap();
    assert!(!s.ran);
    assert_eq!(s.reason, "no bake requests");

    let mut world = World::new();
    let e = spawn(&mut world, square_uv(1.0, 0.0, 1.0), Affine3A::IDENTITY);
    world
        .insert_one(e, request(vec![ao(4)], 4, 4, 1, 0))
        .unwrap();
    let frame = common::render(&mut world, RenderSettings::default());
    let s = frame.report.stage("bake_lightmaps").unwrap();
    assert!(!s.ran);
    assert!(s.reason.contains("does not bake"), "{}", s.reason);
    let _ = TexelImage::new(1, 1);
    let _ = Arc::new(());
}

/// The lightmap's indirect light gathered by the bake's own diffuse paths and by the
/// path-traced reference integrator estimate the same irradiance on an all-Lambert scene.
#[test]
fn indirect_lightmap_agrees_between_diffuse_gather_and_path_tracer() {
    let run = |integrator: stagelight::settings::Integrator, indirect: bool| {
        let mut world = World::new();
        let floor = spawn(&mut world, square_uv(1.0, 0.0, 1.0), Affine3A::IDENTITY);
        // A wall at x = −1 facing +x reflects the light back onto the floor.
        spawn(
            &mut world,
            common::box_mesh(Vec3::new(-1.2, -1.0, 0.0), Vec3::new(-1.0, 1.0, 2.0)),
            Affine3A::IDENTITY,
        );
        common::light(
            &mut world,
            stagelight::components::LightShape::Point {
                position: Vec3::new(-0.5, 0.0, 1.5),
            },
            Vec3::splat(4.0),
            1,
        );
        let kind = BakeKind::Lightmap {
            indirect,
            samples: 512,
            max_depth: 3,
            store: stagelight::components::LightmapStore::Irradiance,
            scale: 1.0,
        };
        world
            .insert_one(floor, request(vec![kind], 4, 4, 1, 0))
            .unwrap();
        let mut frame = Frame::new(RenderSettings {
            integrator,
            ..RenderSettings::default()
        });
        frame.inputs.tasks = Tasks {
            render: false,
            bake: true,
        };
        frame.inputs.bake_dir = crate::common::scratch_root().join(format!(
            "stagelight-bake-integrators-{:?}-{}",
            integrator,
            std::process::id()
        ));
        stagelight::systems::run(&mut world, &mut frame).expect("bake");
        let (_, _, px) = baked(&frame, "target_lightmap.exr");
        px.iter().map(|c| c.x as f64).sum::<f64>() / px.len() as f64
    };
    let direct = run(stagelight::settings::Integrator::Direct, false);
    let gather = run(stagelight::settings::Integrator::Direct, true) - direct;
    let path = run(stagelight::settings::Integrator::Path, true) - direct;
    // The indirect part is a sizeable fraction of the total, so the comparison means something.
    assert!(
        gather > 0.05 * direct,
        "indirect {gather} vs direct {direct}"
    );
    assert!(
        (gather - path).abs() / gather < 0.03,
        "indirect: diffuse gather {gather}, path {path}"
    );
}

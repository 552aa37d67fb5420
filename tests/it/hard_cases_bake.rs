//! Hard cases of baking (`../shared/HARDCASES.md`, group E): analytic ambient occlusion at
//! every scale (H24), no light leaking from texels inside geometry (H25), bilinear taps on
//! valid texels after dilation (H26), and exact accumulation (H27).

use crate::common;

use glam::{Affine3A, Vec2, Vec3};
use hecs::World;
use stagelight::accumulate::SampleMean;
use stagelight::bake::TexelImage;
use stagelight::components::{
    BakeFormat, BakeKind, BakeRequest, BakeResolution, BakeTarget, LightShape, LightmapStore,
    Shader, TriMesh, UvSource,
};
use stagelight::frame::{Frame, Tasks};
use stagelight::settings::RenderSettings;

/// A rectangle `[x0, x1] × [y0, y1]` at z = 0 facing +Z, UVs spanning the unit square.
fn rect(x0: f32, x1: f32, y0: f32, y1: f32) -> TriMesh {
    TriMesh {
        positions: vec![
            Vec3::new(x0, y0, 0.0),
            Vec3::new(x1, y0, 0.0),
            Vec3::new(x1, y1, 0.0),
            Vec3::new(x0, y1, 0.0),
        ],
        normals: None,
        uvs: Some(vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ]),
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    }
}

fn spawn(world: &mut World, mesh: TriMesh, xf: Affine3A) -> hecs::Entity {
    let m = common::material(
        world,
        Shader::Lambert {
            albedo: Vec3::splat(0.5),
        },
    );
    common::instance(world, mesh, xf, m)
}

fn request(kind: BakeKind, width: u32, height: u32, padding: u32, uvs: UvSource) -> BakeRequest {
    BakeRequest {
        name: "target".into(),
        resolution: BakeResolution::Fixed { width, height },
        uvs,
        texel_samples: 1,
        padding,
        mask: false,
        stitch_seams: false,
        targets: vec![BakeTarget {
            kind,
            format: BakeFormat::Exr,
            file: None,
            denoise: None,
        }],
    }
}

/// Bakes the world and reads back the first texture.
fn bake(world: &mut World, tag: &str) -> TexelImage {
    let mut frame = Frame::new(RenderSettings::default());
    frame.inputs.tasks = Tasks {
        render: false,
        bake: true,
    };
    frame.inputs.bake_dir = crate::common::scratch_root()
        .join(format!("stagelight-hard-bake-{tag}-{}", std::process::id()));
    stagelight::systems::run(world, &mut frame).expect("bake");
    use exr::prelude::*;
    let image = read_first_rgba_layer_from_file(
        &frame.report.written[0],
        |res, _| TexelImage::new(res.width() as u32, res.height() as u32),
        |img: &mut TexelImage, pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            let i = pos.y() * img.width as usize + pos.x();
            img.texels[i] = Vec3::new(r, g, b);
            img.valid[i] = true;
        },
    )
    .unwrap();
    image.layer_data.channel_data.pixels
}

fn ao(samples: u32) -> BakeKind {
    BakeKind::AmbientOcclusion {
        samples,
        max_distance: f32::INFINITY,
        bent_normals: false,
    }
}

#[test]
fn h24_open_plane_bakes_exactly_one_at_every_scale() {
    for s in [1e-3f32, 1.0, 1e3, 1e6] {
        let mut world = World::new();
        let floor = spawn(
            &mut world,
            rect(2.0 * s, 3.0 * s, -0.5 * s, 0.5 * s),
            Affine3A::IDENTITY,
        );
        world
            .insert_one(floor, request(ao(256), 8, 8, 0, UvSource::Mesh))
            .unwrap();
        let img = bake(&mut world, &format!("h24a-{s}"));
        assert!(
            img.texels.iter().all(|t| t.x == 1.0),
            "scale {s}: a ray hit the open plane itself"
        );
    }
}

/// The wall is 100·s (not 1e4·s): rays from a point 1e-5·s beside it meet it within ~1e-5·s
/// of its open bottom edge, and the sign of an f32 edge function is only resolved to about
/// 1e-7 of the triangle's size; with a 1e4·s wall (ratio 1e-9) a fifth of those rays slip
/// past the edge in any f32 intersector. The finite wall biases AO by < 0.004 at d = s.
#[test]
fn h24_floor_beside_a_wall_bakes_one_half_at_every_distance_and_scale() {
    for s in [1e-3f32, 1.0, 1e3] {
        for d in [1e-5f32, 1e-3, 1e-1, 1.0] {
            let mut world = World::new();
            // Wall x = 0 exactly (vertices written out: an f32 rotation would tilt it by
            // 4e-8 rad), facing +X, 100·s across and tall, standing on z = 0.
            let (w, hgt) = (50.0 * s, 100.0 * s);
            let wall = TriMesh {
                positions: vec![
                    Vec3::new(0.0, -w, 0.0),
                    Vec3::new(0.0, w, 0.0),
                    Vec3::new(0.0, w, hgt),
                    Vec3::new(0.0, -w, hgt),
                ],
                normals: None,
                uvs: None,
                triangles: vec![[0, 1, 2], [0, 2, 3]],
            };
            spawn(&mut world, wall, Affine3A::IDENTITY);
            let (x, half) = (d * s, 0.25 * d * s);
            let floor = spawn(
                &mut world,
                rect(x - half, x + half, -half, half),
                Affine3A::IDENTITY,
            );
            let samples = 4096;
            world
                .insert_one(floor, request(ao(samples), 1, 1, 0, UvSource::Mesh))
                .unwrap();
            let img = bake(&mut world, &format!("h24b-{s}-{d}"));
            let got = img.texels[0].x as f64;
            let se = (0.25 / samples as f64).sqrt();
            assert!(
                (got - 0.5).abs() <= 4.0 * se + 0.002,
                "scale {s}, distance {d}: AO {got}"
            );
        }
    }
}

/// A sphere of radius r resting on the floor: from a floor point at horizontal distance x
/// from the contact point, the sphere's view factor is (r/D)³ with D = √(x² + r²), so
/// AO(x) = 1 − (r/√(x² + r²))³.
#[test]
fn h24_floor_around_a_resting_sphere_matches_the_view_factor() {
    let r = 1.0f32;
    let mut world = World::new();
    spawn(
        &mut world,
        common::sphere(r, 256, 128),
        Affine3A::from_translation(Vec3::new(0.0, 0.0, r)),
    );
    // A strip of 100 texels along +x from x = 0.05 r to 3.05 r, one point per texel.
    let (x0, x1) = (0.05f32, 3.05f32);
    let floor = spawn(&mut world, rect(x0, x1, -0.005, 0.005), Affine3A::IDENTITY);
    let samples = 4096;
    world
        .insert_one(floor, request(ao(samples), 100, 1, 0, UvSource::Mesh))
        .unwrap();
    let img = bake(&mut world, "h24c");
    let mut worst = 0.0f64;
    for i in 0..100 {
        let x = (x0 + (x1 - x0) * (i as f32 + 0.5) / 100.0) as f64;
        let d = (x * x + (r as f64).powi(2)).sqrt();
        let exact = 1.0 - (r as f64 / d).powi(3);
        let se = (exact * (1.0 - exact) / samples as f64).sqrt();
        let got = img.texels[i].x as f64;
        let err = (got - exact).abs();
        assert!(err <= 4.0 * se + 0.002, "x = {x}: AO {got}, exact {exact}");
        worst = worst.max(err);
    }
    assert!(worst > 0.0);
}

/// A wall box penetrating the floor, a directional light from +x at 45°: floor texels inside
/// the wall must not leak the lit side's light into the wall's shadow on the −x side.
#[test]
fn h25_no_light_leaks_under_a_penetrating_wall() {
    let mut world = World::new();
    let floor = spawn(&mut world, rect(-2.0, 2.0, -2.0, 2.0), Affine3A::IDENTITY);
    spawn(
        &mut world,
        common::box_mesh(Vec3::new(-0.1, -1.5, -0.2), Vec3::new(0.1, 1.5, 1.0)),
        Affine3A::IDENTITY,
    );
    common::light(
        &mut world,
        LightShape::Directional {
            direction: Vec3::new(-1.0, 0.0, -1.0).normalize(),
        },
        Vec3::splat(1.0),
        1,
    );
    // 64 texels per unit over the 4 × 4 floor.
    let kind = BakeKind::Lightmap {
        indirect: false,
        samples: 1,
        max_depth: 0,
        store: LightmapStore::Irradiance,
        scale: 1.0,
    };
    let mut req = request(kind, 256, 256, 2, UvSource::Mesh);
    req.texel_samples = 4;
    world.insert_one(floor, req).unwrap();
    let img = bake(&mut world, "h25");
    let uv = |x: f32, y: f32| Vec2::new((x + 2.0) / 4.0, (y + 2.0) / 4.0);
    let texel = 4.0 / 256.0;
    let mut lit = 0.0;
    for k in 0..1000 {
        let y = -1.0 + 2.0 * (k as f32 + 0.5) / 1000.0;
        lit += img.bilinear(uv(0.5 + 0.5 * (k % 7) as f32 / 7.0, y)).x;
    }
    let lit_mean = lit / 1000.0;
    assert!(
        (lit_mean - std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-3,
        "lit side {lit_mean}"
    );
    let mut worst = 0.0f32;
    for k in 0..1000 {
        let y = -1.0 + 2.0 * (k as f32 + 0.5) / 1000.0;
        let x = -0.1 - texel * ((k % 10) as f32 + 0.5) / 10.0;
        worst = worst.max(img.bilinear(uv(x, y)).x);
    }
    assert!(
        worst <= 0.01 * lit_mean,
        "light leaked into the shadow: {worst} vs lit {lit_mean}"
    );
}

/// Generated UVs of a torus (many charts), padding 2: bilinear taps at 1,000 random points of
/// every triangle read only baked or dilated texels.
#[test]
fn h26_bilinear_taps_land_on_valid_texels_after_dilation() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/meshes/torus.obj");
    let bytes = std::fs::read(&path).unwrap();
    let mesh = TriMesh {
        normals: None,
        uvs: None,
        ..stagelight::scene::parse_obj_bytes(&bytes).unwrap()
    };
    let uvs = stagelight::bake::corner_uvs(&mesh, UvSource::Unwrap, 128, 2).unwrap();
    let mut world = World::new();
    let m = common::material(
        &mut world,
        Shader::Lambert {
            albedo: Vec3::new(0.2, 0.4, 0.6),
        },
    );
    let e = common::instance(&mut world, mesh, Affine3A::IDENTITY, m);
    world
        .insert_one(e, request(BakeKind::Albedo, 128, 128, 2, UvSource::Unwrap))
        .unwrap();
    let img = bake(&mut world, "h26");
    let mut rng = common::Rng::new(26);
    let mut bad = 0;
    for tri in &uvs {
        for _ in 0..1000 {
            let (mut a, mut b) = (rng.f64() as f32, rng.f64() as f32);
            if a + b > 1.0 {
                (a, b) = (1.0 - a, 1.0 - b);
            }
            let uv = tri[0] * (1.0 - a - b) + tri[1] * a + tri[2] * b;
            for (i, w) in img.bilinear_taps(uv) {
                if w > 0.0 && img.texels[i] == Vec3::ZERO {
                    bad += 1;
                }
            }
        }
    }
    assert_eq!(bad, 0, "bilinear taps on empty texels");
}

#[test]
fn h27_accumulators_do_not_stall() {
    let mut small = SampleMean::default();
    for _ in 0..100_000_000u64 {
        small.add(Vec3::splat(1e-3));
    }
    let sum = small.sum().x;
    // The increment is 1e-3 rounded to f32; the sum must be exactly 1e8 of them.
    let exact = 1e8 * f64::from(1e-3f32);
    assert!(
        ((sum - exact) / exact).abs() < 1e-9,
        "1e8 × 1e-3 summed to {sum}, not {exact}"
    );
    let mut ones = SampleMean::default();
    for _ in 0..(1u64 << 25) {
        ones.add(Vec3::ONE);
    }
    assert_eq!(ones.sum().x, (1u64 << 25) as f64);
}

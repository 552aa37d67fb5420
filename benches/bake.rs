//! Bake throughput: ambient occlusion on a 131,072-triangle generated terrain with a row of
//! spheres (≥ 100 k triangles), 64 and 256 rays per texel, reported as texels/s by criterion
//! and as rays/s from the bake report (printed once per configuration).
//!
//! The texture is 256² so a measurement takes seconds; texel throughput does not depend on
//! the resolution. For the full 1024² figure run
//! `stagelight bake assets/scenes/bake_ao.ron --stats` (see README).

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{Affine3A, Vec2, Vec3};
use hecs::World;
use stagelight::components::{
    BakeFormat, BakeKind, BakeRequest, BakeResolution, BakeTarget, Instance, Material, MaterialRef,
    Name, Shader, TriMesh, UvSource, WorldFromObject,
};
use stagelight::frame::{Frame, Tasks};
use stagelight::settings::RenderSettings;

/// An `n × n`-cell terrain over [-1, 1]² with smooth bumps, UVs over the unit square.
fn terrain(n: u32) -> TriMesh {
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
            let (x, y) = (2.0 * u - 1.0, 2.0 * v - 1.0);
            let z =
                0.08 * ((7.0 * x).sin() * (5.0 * y).cos()) + 0.03 * ((23.0 * x + 11.0 * y).sin());
            positions.push(Vec3::new(x, y, z));
            uvs.push(Vec2::new(u, v));
        }
    }
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh {
        positions,
        normals: None,
        uvs: Some(uvs),
        triangles,
    }
}

fn world(samples: u32) -> World {
    let mut world = World::new();
    let material = world.spawn((
        Name("grey".into()),
        Material {
            shader: Shader::Lambert {
                albedo: Vec3::splat(0.6),
            },
            two_sided: false,
            emission: Vec3::ZERO,
            graph: None,
            ..Default::default()
        },
    ));
    let mesh = Arc::new(terrain(256));
    let object = world.spawn((Name("terrain".into()), mesh.clone()));
    world.spawn((
        Name("terrain_1".into()),
        Instance { object, mesh },
        WorldFromObject(Affine3A::IDENTITY),
        MaterialRef(material),
        BakeRequest {
            name: "terrain_1".into(),
            resolution: BakeResolution::Fixed {
                width: 256,
                height: 256,
            },
            uvs: UvSource::Mesh,
            texel_samples: 4,
            padding: 2,
            mask: false,
            stitch_seams: false,
            targets: vec![BakeTarget {
                kind: BakeKind::AmbientOcclusion {
                    samples,
                    max_distance: 0.5,
                    bent_normals: false,
                },
                format: BakeFormat::Exr,
                file: None,
                denoise: None,
            }],
        },
    ));
    world
}

fn bake_once(samples: u32) -> Frame {
    let mut w = world(samples);
    let mut frame = Frame::new(RenderSettings::default());
    frame.inputs.tasks = Tasks {
        render: false,
        bake: true,
    };
    frame.inputs.bake_dir = std::env::temp_dir().join("stagelight-bench-bake");
    stagelight::systems::run(&mut w, &mut frame).expect("bake");
    frame
}

fn ao(c: &mut Criterion) {
    let mut group = c.benchmark_group("bake_lightmaps");
    group.sample_size(10);
    for samples in [64u32, 256] {
        let probe = bake_once(samples);
        let r = &probe.outputs.bake_reports[0];
        println!(
            "ao {samples} rays/texel: {} texels, {:.2} Mrays/s, {:.0} texels/s ({} threads)",
            r.covered_texels,
            r.rays_per_second / 1e6,
            r.covered_texels as f64 / r.seconds,
            probe.report.threads
        );
        group.throughput(Throughput::Elements(r.covered_texels));
        group.bench_function(format!("ao_256x256_{samples}spt_131k_tris"), |b| {
            b.iter(|| bake_once(samples))
        });
        // Thread scaling: the same bake in pools of 1 and 2 workers.
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool");
            group.bench_function(format!("ao_256x256_{samples}spt_{threads}_threads"), |b| {
                b.iter(|| pool.install(|| bake_once(samples)))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, ao);
criterion_main!(benches);

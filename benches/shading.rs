//! Shading benchmarks.
//!
//! - `shading/<family>`: shaded samples per second of each material family — a 64×64 plane
//!   under a rect light (8 shadow samples), 4 spp, direct integrator (camera ray, BSDF
//!   construction, light loop with shadow rays, delta branches). `lambert_textured` adds a
//!   shader graph: albedo = mix of two colours by 4-octave fBm of the position, plus a bump
//!   map of the same fBm (three graph evaluations per hit).
//! - `path/cornell_256_to_relmse_1e-2`: the path tracer on the Cornell box at 256×256
//!   (max_depth 8): the smallest power-of-two spp whose image reaches relMSE ≤ 1e-2 against a
//!   converged reference, then the time of a render at that spp. The reference (path tracer,
//!   `STAGELIGHT_REF_SPP` spp, default 512, another seed) is rendered once and cached under
//!   the target directory (`stagelight-ref/`). relMSE = mean over pixels and channels of
//!   (x − r)² / (r² + 10⁻²).
//! - `sampler/24_dimensions`: a path's worth of sampler dimensions (a Cornell-box path of
//!   four vertices draws about 24) for 1,024 samples of different pixels — the Sobol
//!   dimensions eight per call (`sampling/sobol8.rs`).

use std::path::PathBuf;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{Affine3A, Vec3};
use hecs::World;
use stagelight::components::{
    Camera, Emitter, Instance, LightShape, Material, MaterialRef, Name, RenderCamera, Shader,
    TriMesh, WorldFromObject,
};
use stagelight::frame::Frame;
use stagelight::sampling::Sampler;
use stagelight::scene::load_scene;
use stagelight::settings::{Integrator, RenderSettings};
use stagelight::shading::texture::noise::Fractal;
use stagelight::shading::texture::{Binding, BumpMap, MaterialGraph, NoiseKind, Op, Program};

fn families() -> Vec<(&'static str, Shader)> {
    let g = Vec3::splat;
    vec![
        ("lambert", Shader::Lambert { albedo: g(0.7) }),
        (
            "phong",
            Shader::Phong {
                ambient: Vec3::ZERO,
                diffuse: g(0.5),
                specular: g(0.4),
                spec_exp: 20.0,
            },
        ),
        (
            "cook_torrance",
            Shader::CookTorrance {
                ambient: Vec3::ZERO,
                diffuse: g(0.3),
                specular: g(0.7),
                roughness: 0.2,
                ior: Vec3::new(1.4, 1.6, 1.8),
            },
        ),
        (
            "plastic",
            Shader::Plastic {
                ka: 1.0,
                kd: 0.5,
                ks: 0.5,
                roughness: 0.1,
                specular_color: Vec3::ONE,
                color: g(0.8),
            },
        ),
        (
            "shinymetal",
            Shader::ShinyMetal {
                ka: 1.0,
                ks: 0.5,
                kr: 0.5,
                roughness: 0.1,
                color: g(0.9),
            },
        ),
        ("mirror", Shader::Mirror { color: g(0.9) }),
        (
            "dielectric",
            Shader::Dielectric {
                ior: 1.5,
                ior_out: 1.0,
                col: g(0.9),
            },
        ),
        (
            "dgs",
            Shader::Dgs {
                diffuse: g(0.3),
                glossy: g(0.3),
                specular: g(0.3),
                shiny: 20.0,
            },
        ),
    ]
}

/// Albedo = mix((0.1, 0.3, 0.7), (0.9, 0.6, 0.2), 0.5 + fbm(4·P)); bump height 0.02·fbm.
fn textured_graph() -> MaterialGraph {
    let mut program = Program::default();
    let p = program.push(Op::Position);
    let fbm = program.push(Op::Noise {
        p,
        kind: NoiseKind::Fbm,
        fractal: Fractal {
            frequency: 4.0,
            octaves: 4,
            lacunarity: 2.0,
            gain: 0.5,
            seed: 1,
        },
    });
    let half = program.push(Op::Const(Vec3::splat(0.5)));
    let t = program.push(Op::Add(half, fbm));
    let a = program.push(Op::Const(Vec3::new(0.1, 0.3, 0.7)));
    let b = program.push(Op::Const(Vec3::new(0.9, 0.6, 0.2)));
    let albedo = program.push(Op::Mix { a, b, t });
    MaterialGraph {
        program,
        bindings: vec![Binding {
            param: "albedo".into(),
            reg: albedo,
        }],
        bump: Some(BumpMap {
            height: fbm,
            scale: 0.02,
        }),
        normal_map: None,
        object_normal: None,
        emission: None,
    }
}

fn plane_world(shader: Shader, graph: Option<MaterialGraph>) -> World {
    let mut world = World::new();
    let m = world.spawn((
        Name("m".into()),
        Material {
            shader,
            two_sided: false,
            emission: Vec3::ZERO,
            graph: graph.map(std::sync::Arc::new),
            ..Default::default()
        },
    ));
    let h = 5.0;
    let mesh = std::sync::Arc::new(TriMesh {
        positions: vec![
            Vec3::new(-h, -h, 0.0),
            Vec3::new(h, -h, 0.0),
            Vec3::new(h, h, 0.0),
            Vec3::new(-h, h, 0.0),
        ],
        normals: None,
        uvs: None,
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    });
    let object = world.spawn((Name("plane".into()), mesh.clone()));
    world.spawn((
        Name("plane_1".into()),
        Instance { object, mesh },
        WorldFromObject(Affine3A::IDENTITY),
        MaterialRef(m),
    ));
    world.spawn((
        Name("panel".into()),
        Emitter {
            shape: LightShape::Rect {
                corner: Vec3::new(-1.0, -1.0, 3.0),
                edge_u: Vec3::Y * 2.0,
                edge_v: Vec3::X * 2.0,
            },
            radiant: Vec3::splat(5.0),
            shadows: true,
            shadow_factor: 0.0,
            samples: 8,
            visible: false,
            attenuation: None,
            inverse_square: true,
        },
    ));
    let eye = Vec3::new(0.0, -6.0, 4.0);
    world.spawn((
        Name("cam".into()),
        Camera {
            world_from_camera: stagelight::components::world_from_look_at(eye, Vec3::ZERO, Vec3::Z)
                .expect("camera"),
            fov_y: 40f32.to_radians(),
            width: 64,
            height: 64,
            aspect: 1.0,
            outputs: vec![],
            space_scale: 1.0,
        },
        RenderCamera,
    ));
    world
}

fn render(world: &mut World, settings: RenderSettings) -> Frame {
    let mut frame = Frame::new(settings);
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    stagelight::schedule::run_stages(&stages, world, &mut frame).expect("render");
    frame
}

fn material_families(c: &mut Criterion) {
    let mut group = c.benchmark_group("shading");
    group.sample_size(10);
    let spp = 4;
    group.throughput(Throughput::Elements(64 * 64 * spp as u64));
    let textured = (
        "lambert_textured",
        Shader::Lambert { albedo: Vec3::ONE },
        Some(textured_graph()),
    );
    let plain = families().into_iter().map(|(n, s)| (n, s, None));
    for (name, shader, graph) in plain.chain(std::iter::once(textured)) {
        let mut world = plane_world(shader, graph);
        let settings = RenderSettings {
            spp,
            ..RenderSettings::default()
        };
        group.bench_function(name, |b| b.iter(|| render(&mut world, settings.clone())));
    }
    group.finish();
}

fn cornell(spp: u32, seed: u64) -> Vec<Vec3> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/cornell_box.ron");
    let mut scene = load_scene(&path).expect("cornell box loads");
    let settings = RenderSettings {
        spp,
        seed,
        max_depth: 8,
        integrator: Integrator::Path,
        ..scene.settings.clone()
    };
    render(&mut scene.world, settings)
        .outputs
        .image
        .expect("image")
        .beauty
}

fn reference() -> Vec<Vec3> {
    let spp: u32 = std::env::var("STAGELIGHT_REF_SPP")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(512);
    let target = std::env::var("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|_| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target"));
    let file = target
        .join("stagelight-ref")
        .join(format!("cornell_path_256_d8_{spp}spp.f32"));
    if let Ok(bytes) = std::fs::read(&file) {
        if bytes.len() == 256 * 256 * 12 {
            return bytes
                .chunks_exact(12)
                .map(|c| {
                    let f = |i: usize| f32::from_le_bytes([c[i], c[i + 1], c[i + 2], c[i + 3]]);
                    Vec3::new(f(0), f(4), f(8))
                })
                .collect();
        }
    }
    eprintln!(
        "rendering the converged reference ({spp} spp) into {}",
        file.display()
    );
    let image = cornell(spp, 0xdead_beef);
    let bytes: Vec<u8> = image
        .iter()
        .flat_map(|v| v.to_array())
        .flat_map(f32::to_le_bytes)
        .collect();
    if let Some(dir) = file.parent() {
        let _ = std::fs::create_dir_all(dir);
    }
    let _ = std::fs::write(&file, bytes);
    image
}

fn rel_mse(image: &[Vec3], reference: &[Vec3]) -> f64 {
    let mut sum = 0.0f64;
    for (x, r) in image.iter().zip(reference) {
        for (a, b) in x.to_array().into_iter().zip(r.to_array()) {
            let (a, b) = (a as f64, b as f64);
            sum += (a - b) * (a - b) / (b * b + 1e-2);
        }
    }
    sum / (image.len() * 3) as f64
}

fn path_tracer_convergence(c: &mut Criterion) {
    let reference = reference();
    let mut spp = 1;
    let mut err = f64::INFINITY;
    while spp <= 4096 {
        err = rel_mse(&cornell(spp, 1), &reference);
        eprintln!("cornell path 256×256: {spp} spp → relMSE {err:.4e}");
        if err <= 1e-2 {
            break;
        }
        spp *= 2;
    }
    eprintln!("relMSE {err:.4e} ≤ 1e-2 first reached at {spp} spp");
    let mut group = c.benchmark_group("path");
    group.sample_size(10);
    group.throughput(Throughput::Elements(256 * 256 * spp as u64));
    group.bench_function("cornell_256_to_relmse_1e-2", |b| b.iter(|| cornell(spp, 1)));
    group.finish();
}

/// 24 dimensions of each of 1,024 samples, each sample of its own pixel.
fn sampler_dimensions(c: &mut Criterion) {
    let mut group = c.benchmark_group("sampler");
    group.throughput(Throughput::Elements(24 * 1024));
    group.bench_function("24_dimensions", |b| {
        b.iter(|| {
            let mut sum = 0.0f32;
            for i in 0..1024u32 {
                let mut s = Sampler::for_item(7, u64::from(i) * 31, i % 16);
                for _ in 0..24 {
                    sum += s.next_1d();
                }
            }
            std::hint::black_box(sum)
        })
    });
    group.finish();
}

criterion_group!(
    benches,
    material_families,
    path_tracer_convergence,
    sampler_dimensions
);
criterion_main!(benches);

//! Tessellation throughput: output triangles per second per technique, displacement
//! throughput, and bytes per output triangle (printed once); then thread scaling
//! (`tessellate/1t`, `tessellate/2t`: two of the cases in rayon pools of 1 and 2 workers).
//! Run the first group single-threaded so its figures are per thread:
//!
//! ```sh
//! RAYON_NUM_THREADS=1 cargo bench --bench tessellate -- 'tessellate/'
//! cargo bench --bench tessellate -- 'tessellate/[12]t'
//! ```

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec3;
use stagelight::components::{
    Approximation, CubicBasis, Displacement, DisplacementMode, LengthSpace, PatchKind, PatchMesh,
    Quadric, ScalarNode, Surface, Technique, Torus, UvAxis,
};
use stagelight::tessellation::{tessellate_surface, Options, Tessellation};

/// A 4×4-patch bicubic B-spline sheet (7×7 control points) with some relief.
fn bspline_sheet() -> Surface {
    let mut points = Vec::new();
    for j in 0..7 {
        for i in 0..7 {
            let z = ((i * 3 + j * 5) % 4) as f32 * 0.2;
            points.push(Vec3::new(i as f32, j as f32, z));
        }
    }
    Surface::Patches(PatchMesh {
        kind: PatchKind::Bicubic(CubicBasis::BSpline),
        nu: 7,
        nv: 7,
        u_wrap: false,
        v_wrap: false,
        points,
        vars: Default::default(),
    })
}

fn torus() -> Surface {
    Surface::Quadric(Quadric::Torus(Torus {
        r_major: 3.0,
        r_minor: 1.0,
        phi_min: 0.0,
        phi_max: 360.0,
        theta_max: 360.0,
    }))
}

fn approx(technique: Technique) -> Approximation {
    Approximation {
        technique,
        min_subdiv: 0,
        max_subdiv: 9,
    }
}

fn run(s: &Surface, a: &Approximation, d: Option<&Displacement>) -> Tessellation {
    let opts = Options {
        approximation: a,
        displacement: d,
        view: None,
        derivatives: false,
        max_triangles: u64::MAX,
    };
    tessellate_surface(s, &opts).expect("tessellates")
}

/// Bytes of the output mesh per triangle (positions, normals, uvs, indices).
fn bytes_per_triangle(t: &Tessellation) -> f64 {
    let m = &t.mesh;
    let v = m.positions.len() * (12 + 12 + 8);
    (v + m.triangles.len() * 12) as f64 / m.triangles.len() as f64
}

fn bench(c: &mut Criterion) {
    let sheet = bspline_sheet();
    let torus = torus();
    let noise = Displacement {
        shader: ScalarNode::Noise {
            amplitude: 0.05,
            frequency: 2.0,
            octaves: 4,
            lacunarity: 2.0,
            gain: 0.5,
            seed: 1,
        },
        bound: None,
        mode: DisplacementMode::True,
    };
    let sine = Displacement {
        shader: ScalarNode::Sine {
            amplitude: 0.01,
            factor: 50.0,
            axis: UvAxis::U,
        },
        bound: None,
        mode: DisplacementMode::True,
    };
    let cases: Vec<(&str, &Surface, Approximation, Option<&Displacement>)> = vec![
        (
            "regular_bspline_256x256",
            &sheet,
            approx(Technique::Regular { u: 256, v: 256 }),
            None,
        ),
        (
            "parametric_torus_64x64",
            &torus,
            approx(Technique::Parametric { u: 64, v: 64 }),
            None,
        ),
        (
            "spatial_torus_0.02",
            &torus,
            approx(Technique::Spatial {
                edge: 0.02,
                space: LengthSpace::Object,
            }),
            None,
        ),
        (
            "curvature_torus_1e-4",
            &torus,
            approx(Technique::Curvature {
                distance: 1e-4,
                angle: 0.0,
            }),
            None,
        ),
        (
            "displaced_noise_torus_64x64",
            &torus,
            approx(Technique::Parametric { u: 64, v: 64 }),
            Some(&noise),
        ),
        (
            "displaced_sine_torus_64x64",
            &torus,
            approx(Technique::Parametric { u: 64, v: 64 }),
            Some(&sine),
        ),
    ];
    let mut group = c.benchmark_group("tessellate");
    group.sample_size(10);
    for (name, surface, a, d) in &cases {
        let t = run(surface, a, *d);
        let tris = t.mesh.triangles.len() as u64;
        println!(
            "{name}: {tris} triangles, {:.1} bytes/triangle",
            bytes_per_triangle(&t)
        );
        group.throughput(Throughput::Elements(tris));
        group.bench_function(*name, |b| b.iter(|| run(surface, a, *d)));
    }
    group.finish();

    // Thread scaling: tessellation goes wide inside one object (edge rates, patches, welding),
    // so the same surfaces in rayon pools of 1 and 2 workers.
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        let mut group = c.benchmark_group(format!("tessellate/{threads}t"));
        group.sample_size(10);
        for (name, surface, a, d) in cases.iter().filter(|(n, ..)| SCALING.contains(n)) {
            let tris = run(surface, a, *d).mesh.triangles.len() as u64;
            group.throughput(Throughput::Elements(tris));
            group.bench_function(*name, |b| b.iter(|| pool.install(|| run(surface, a, *d))));
        }
        group.finish();
    }
}

/// The cases measured in 1- and 2-thread pools.
const SCALING: [&str; 2] = ["regular_bspline_256x256", "displaced_noise_torus_64x64"];

criterion_group!(benches, bench);
criterion_main!(benches);

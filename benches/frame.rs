//! Whole-frame benchmarks: the Cornell box at 256×256 with 16 spp through every stage but
//! output, thread scaling (1 vs 2 workers), plus the `shade` stage alone (shaded samples per
//! second, with the `Direct` integrator and with the path tracer).

use std::path::PathBuf;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use stagelight::frame::Frame;
use stagelight::scene::load_scene;

fn cornell() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/cornell_box.ron")
}

fn render_once(spp: u32) -> Frame {
    let mut scene = load_scene(&cornell()).expect("cornell box loads");
    let mut settings = scene.settings.clone();
    settings.spp = spp;
    let mut frame = Frame::new(settings);
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame).expect("render");
    frame
}

fn whole_frame(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame");
    group.sample_size(10);
    group.throughput(Throughput::Elements(256 * 256 * 16));
    group.bench_function("cornell_256x256_16spp", |b| b.iter(|| render_once(16)));
    // Thread scaling: the same frame in pools of 1 and 2 workers.
    group.throughput(Throughput::Elements(256 * 256 * 4));
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        group.bench_function(format!("cornell_256x256_4spp_{threads}_threads"), |b| {
            b.iter(|| pool.install(|| render_once(4)))
        });
    }
    group.finish();
}

fn shade_only(c: &mut Criterion) {
    let mut group = c.benchmark_group("shade");
    group.sample_size(10);
    let mut scene = load_scene(&cornell()).expect("cornell box loads");
    let mut frame = Frame::new(scene.settings.clone());
    frame.inputs.settings.spp = 4;
    let stages = stagelight::systems::STAGES;
    let shade = stages
        .iter()
        .position(|s| s.name == "shade")
        .expect("shade stage");
    // Everything before shading (geometry, BVH, photons) once.
    stagelight::schedule::run_stages(&stages[..shade], &mut scene.world, &mut frame)
        .expect("stages before shade");
    group.throughput(Throughput::Elements(256 * 256 * 4));
    group.bench_function("cornell_direct_4spp", |b| {
        b.iter(|| {
            stages[shade]
                .run_body(&mut scene.world, &frame)
                .expect("shade")
        })
    });
    // The reference path tracer on the same frame (issue 17's samples-per-second target).
    frame.inputs.settings.integrator = stagelight::settings::Integrator::Path;
    group.bench_function("cornell_path_4spp", |b| {
        b.iter(|| {
            stages[shade]
                .run_body(&mut scene.world, &frame)
                .expect("shade")
        })
    });
    group.finish();
}

criterion_group!(benches, whole_frame, shade_only);
criterion_main!(benches);

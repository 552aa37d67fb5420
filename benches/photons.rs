//! Photon-pass benchmarks (issue 16 item 8) on `assets/scenes/caustics.ron`: the global and
//! caustic passes traced wide through batch intersections against one photon at a time (the
//! same photons, bit for bit), on 1 thread, in photons emitted per second, then the batched
//! passes again through the accelerator's shortcuts past convex parts (`*_Batched_shortcuts`);
//! and the `trace_photons` stage on every thread. Alternating rounds of both (`PHOTON_BENCH_ROUNDS`,
//! default 5) print their rates and ratio first; `cargo bench --bench photons -- rounds_only`
//! prints only those (the filter matches no criterion benchmark).

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use stagelight::frame::Frame;
use stagelight::photon::{trace_map_with, Emission, MapKind, Tracing};
use stagelight::scene::load_scene;
use stagelight::scene_view::{light_set, WithEnvironment};
use stagelight::shading::ShadeContext;

const PHOTONS: u32 = 20_000;

fn caustics_scene() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/caustics.ron")
}

fn photon_pass(c: &mut Criterion) {
    let mut scene = load_scene(&caustics_scene()).expect("caustics.ron loads");
    let mut frame = Frame::new(scene.settings.clone());
    stagelight::systems::run_before("trace_photons", &mut scene.world, &mut frame)
        .expect("stages before trace_photons");
    let geometry = frame.outputs.geometry.as_ref().expect("geometry");
    let settings = &frame.inputs.settings;
    let lights = light_set(&scene.world, Some(geometry), settings, WithEnvironment::No);
    let emission = Emission::new(&lights, geometry);
    let ctx = ShadeContext::new(geometry, &lights, settings);
    let cancel = AtomicBool::new(false);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    let pass = |kind, tracing| {
        let map = (&ctx, &emission, &[][..], kind);
        one.install(|| trace_map_with(map, PHOTONS, 1, &cancel, tracing).expect("pass"))
    };
    // Alternating rounds (per photon first in even rounds, batched first in odd ones) so a
    // change of the machine's load hits both alike; each round's ratio and the median.
    let rounds: usize = std::env::var("PHOTON_BENCH_ROUNDS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(5);
    for kind in [MapKind::Global, MapKind::Caustics] {
        let time = |tracing| {
            let start = Instant::now();
            let stored = pass(kind, tracing).len();
            (start.elapsed().as_secs_f64(), stored)
        };
        let mut ratios = Vec::new();
        for round in 0..rounds {
            let order = if round % 2 == 0 {
                [Tracing::PerPhoton, Tracing::Batched]
            } else {
                [Tracing::Batched, Tracing::PerPhoton]
            };
            let mut seconds = [0.0; 2];
            let mut stored = 0;
            for tracing in order {
                let (s, n) = time(tracing);
                seconds[usize::from(tracing == Tracing::Batched)] = s;
                stored = n;
            }
            let [single, batched] = seconds;
            ratios.push(single / batched);
            println!(
                "{kind:?} round {round}: {PHOTONS} emitted, {stored} stored, 1 thread: per photon \
                 {:.0} photons/s, batched {:.0} photons/s, ratio batched/per-photon {:.3}",
                f64::from(PHOTONS) / single,
                f64::from(PHOTONS) / batched,
                single / batched
            );
        }
        ratios.sort_by(f64::total_cmp);
        if let Some(median) = ratios.get(ratios.len() / 2) {
            println!("{kind:?}: median ratio batched/per-photon over {rounds} rounds {median:.3}");
        }
    }
    let mut group = c.benchmark_group("photons");
    group.sample_size(10);
    group.throughput(Throughput::Elements(u64::from(PHOTONS)));
    for kind in [MapKind::Global, MapKind::Caustics] {
        for tracing in [Tracing::Batched, Tracing::PerPhoton] {
            group.bench_function(format!("{kind:?}_{tracing:?}_1_thread"), |b| {
                b.iter(|| pass(kind, tracing))
            });
        }
    }
    // The same batched passes once the accelerator's shortcuts past the glass ball exist
    // (`accel/shortcut.rs`; a pass of these few photons would not make them itself, and
    // uses them once made; `STAGELIGHT_SHORTCUTS=off` keeps them out of these rows too).
    println!(
        "shortcuts: {} convex part(s) of {} triangles",
        geometry.shortcuts().parts(),
        geometry.triangle_count()
    );
    for kind in [MapKind::Global, MapKind::Caustics] {
        group.bench_function(format!("{kind:?}_Batched_shortcuts_1_thread"), |b| {
            b.iter(|| pass(kind, Tracing::Batched))
        });
    }
    let trace = stagelight::systems::STAGES
        .iter()
        .find(|s| s.name == "trace_photons")
        .expect("trace_photons stage");
    group.bench_function("trace_photons_stage_all_threads", |b| {
        b.iter(|| {
            trace
                .run_body(&mut scene.world, &frame)
                .expect("trace_photons")
        })
    });
    group.finish();
}

criterion_group!(benches, photon_pass);
criterion_main!(benches);

//! Contour benchmarks (criterion group `contours`), on `assets/scenes/contours.ron`:
//!
//! - `contours/draw_1920x1080`: what contours add to a 1920×1080 render — the contour store
//!   (one probe ray per pixel, taken inside `shade`) plus the `draw_contours` stage
//!   (contrast, bisection rays, linking, styling, rasterisation).
//! - `contours/shade_16spp_480x270`: the `shade` stage without contours (direct lighting,
//!   16 spp) on a sixteenth of the pixels; × 16 it is the 1920×1080 shade the issue compares
//!   against (a 1920×1080 16-spp shade takes too long per criterion sample on the 2-core box).

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use hecs::World;
use stagelight::components::{Camera, ContourShader, RenderCamera};
use stagelight::contour::Probe;
use stagelight::frame::Frame;
use stagelight::scene::load_scene;
use stagelight::shading::CameraRays;
use stagelight::systems::{run_before, STAGES};

/// The contours scene at `w × h` with `spp`, run up to (not including) `until`.
fn prepared(w: u32, h: u32, spp: u32, until: &str, contours: bool) -> (World, Frame) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/contours.ron");
    let mut scene = load_scene(&path).expect("the contours scene loads");
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        camera.width = w;
        camera.height = h;
        camera.aspect = w as f32 / h as f32;
    }
    if !contours {
        let inked: Vec<_> = scene
            .world
            .query::<(hecs::Entity, &ContourShader)>()
            .iter()
            .map(|(e, _)| e)
            .collect();
        for e in inked {
            let _ = scene.world.remove_one::<ContourShader>(e);
        }
    }
    let mut settings = scene.settings.clone();
    settings.spp = spp;
    let mut frame = Frame::new(settings);
    run_before(until, &mut scene.world, &mut frame).expect("stages run");
    (scene.world, frame)
}

fn contours(c: &mut Criterion) {
    let mut group = c.benchmark_group("contours");
    group.sample_size(10);

    let (mut world, frame) = prepared(1920, 1080, 1, "draw_contours", true);
    let draw = STAGES.iter().find(|s| s.name == "draw_contours").unwrap();
    let fb = frame.outputs.image.as_ref().unwrap();
    let view = stagelight::scene_view::render_view(&world).unwrap();
    let rays = CameraRays::with_lenses(&view.camera, &view.lenses);
    group.throughput(Throughput::Elements(1920 * 1080));
    group.bench_function("draw_1920x1080", |b| {
        b.iter(|| {
            let probe = Probe::new(frame.outputs.geometry.as_ref(), &rays);
            let store = probe.store(fb.width, fb.height, &fb.beauty, 0);
            let work = draw.run_body(&mut world, &frame).unwrap();
            (store.samples.len(), work.items)
        })
    });

    let (mut world, frame) = prepared(480, 270, 16, "shade", false);
    let shade = STAGES.iter().find(|s| s.name == "shade").unwrap();
    group.throughput(Throughput::Elements(480 * 270));
    group.bench_function("shade_16spp_480x270", |b| {
        b.iter(|| shade.run_body(&mut world, &frame).unwrap().items)
    });
    group.finish();
}

criterion_group!(benches, contours);
criterion_main!(benches);

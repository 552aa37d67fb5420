//! `shade`: renders the render camera's frame buffers — primary rays per pixel sample, radiance
//! from the chosen integrator (direct lighting with traced mirror/refraction rays, or the
//! reference path tracer), pixel filter, and the centre-sample passes (depth, normal).
//!
//! **Reads:** the `Camera` with `RenderCamera`; `Emitter` entities; `frame.geometry` (absent
//! means an empty scene: every ray misses); `frame.photons` (the `Direct` integrator's
//! caustics and final gather; absent: none); `settings` (spp, filter, seed, face,
//! integrator, trace depths).
//! **Writes:** `frame.image`.
//! **Runs when:** the run renders and a render camera exists.
//! **After this stage:** `frame.image` holds finite beauty, alpha, depth and normal buffers of
//! the camera's resolution; each pixel depends only on (seed, pixel index, sample index).

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use glam::{Vec2, Vec3};
use hecs::{Entity, World};
use rayon::prelude::*;

use super::prelude::*;
use crate::accumulate::SampleMean;
use crate::components::{Camera, Emitter, RenderCamera};
use crate::framebuffer::FrameBuffers;
use crate::progress::Progress;
use crate::sampling::{fold_seed, Sampler};
use crate::shading::{shade_hit, CameraRays, FilterSampler, LightSet, ShadeContext};

/// Run condition: a render camera exists.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    if !frame.tasks.render {
        return Decision::skip("this run only bakes");
    }
    match world.query::<(&Camera, &RenderCamera)>().iter().next() {
        Some((camera, _)) => {
            Decision::run(format!("render camera {}×{}", camera.width, camera.height))
        }
        None => Decision::skip("no render camera"),
    }
}

/// Renders `frame.image`.
pub fn run(world: &mut World, frame: &mut Frame) -> Result<Work, StageError> {
    let camera = world
        .query::<(&Camera, &RenderCamera)>()
        .iter()
        .next()
        .map(|(c, _)| c.clone())
        .ok_or_else(|| StageError::Invalid("no render camera".into()))?;
    let mut emitters: Vec<(Entity, Emitter)> = world
        .query::<(Entity, &Emitter)>()
        .iter()
        .map(|(e, l)| (e, l.clone()))
        .collect();
    emitters.sort_by_key(|(e, _)| e.to_bits());
    let emitters: Vec<Emitter> = emitters.into_iter().map(|(_, l)| l).collect();

    let settings = frame.settings.clone();
    let geometry = frame.geometry.as_ref();
    let photons = frame.photons.as_ref();
    let lights = LightSet::new(&emitters, geometry, frame.settings.light_samples);
    let rays = CameraRays::new(&camera);
    let filter = FilterSampler::new(settings.filter);
    let seed = fold_seed(settings.seed);
    let spp = settings.spp.max(1);
    let (width, height) = (camera.width as usize, camera.height as usize);

    let mut fb = FrameBuffers::new(camera.width, camera.height);
    let cancel = frame.cancel.clone();
    let stopped = AtomicBool::new(false);
    let dropped = AtomicU64::new(0);
    let progress = Progress::start(frame.progress, "shade", "rows", height as u64);
    let ticker = progress.ticker();

    let rows: Vec<Vec<PixelResult>> = (0..height)
        .into_par_iter()
        .map(|y| {
            if cancel.load(Ordering::Relaxed) {
                stopped.store(true, Ordering::Relaxed);
                return Vec::new();
            }
            let row = (0..width)
                .map(|x| {
                    // Poll per pixel: one pixel is at most spp samples of work.
                    if cancel.load(Ordering::Relaxed) {
                        stopped.store(true, Ordering::Relaxed);
                        return PixelResult::default();
                    }
                    let pixel = (y * width + x) as u64;
                    let ctx = geometry
                        .map(|g| ShadeContext::new(g, &lights, &settings).with_photons(photons));
                    let r = shade_pixel(ctx.as_ref(), &rays, &filter, seed, pixel, x, y, spp);
                    if r.dropped > 0 {
                        dropped.fetch_add(r.dropped as u64, Ordering::Relaxed);
                    }
                    r
                })
                .collect();
            ticker.tick(1);
            row
        })
        .collect();
    drop(ticker);
    progress.finish();
    if stopped.load(Ordering::Relaxed) || cancel.load(Ordering::Relaxed) {
        return Err(StageError::Interrupted);
    }
    for (y, row) in rows.into_iter().enumerate() {
        for (x, r) in row.into_iter().enumerate() {
            let i = y * width + x;
            fb.beauty[i] = r.color;
            fb.alpha[i] = r.alpha;
            fb.depth[i] = r.depth;
            fb.normal[i] = r.normal;
            fb.object_id[i] = r.object_id;
            fb.material_id[i] = r.material_id;
        }
    }
    let n = dropped.load(Ordering::Relaxed);
    if n > 0 {
        tracing::warn!("{n} non-finite samples were dropped");
    }
    frame.image = Some(fb);
    Ok(Work {
        items: (width * height) as u64 * spp as u64,
        unit: "samples",
    })
}

/// What one pixel contributes to each pass.
#[derive(Default)]
struct PixelResult {
    color: Vec3,
    alpha: f32,
    depth: f32,
    normal: Vec3,
    dropped: u32,
    object_id: u32,
    material_id: u32,
}

#[allow(clippy::too_many_arguments)] // one pixel's full context; called from one place
fn shade_pixel(
    ctx: Option<&ShadeContext<'_>>,
    rays: &CameraRays,
    filter: &FilterSampler,
    seed: u32,
    pixel: u64,
    x: usize,
    y: usize,
    spp: u32,
) -> PixelResult {
    let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
    let mut result = PixelResult {
        color: Vec3::ZERO,
        alpha: 0.0,
        depth: f32::INFINITY,
        normal: Vec3::ZERO,
        dropped: 0,
        object_id: 0,
        material_id: 0,
    };
    let Some(ctx) = ctx else {
        return result;
    };
    // Centre-sample passes.
    let ray = rays.ray(centre.x, centre.y);
    if let Some(hit) = ctx.geometry.accel.intersect(&ray) {
        let sp = ctx.geometry.shading_point(&hit);
        result.depth = hit.t;
        result.normal = sp.normal;
        result.object_id = sp.instance + 1;
        result.material_id = sp.material + 1;
    }
    let mut sum = SampleMean::default();
    let mut covered = 0u32;
    for s in 0..spp {
        let mut sampler = Sampler::for_item(seed, pixel, s);
        let film = centre + filter.sample(sampler.next_2d());
        let ray = rays.ray(film.x, film.y);
        let Some(hit) = ctx.geometry.accel.intersect(&ray) else {
            continue;
        };
        covered += 1;
        let radiance = shade_hit(ctx, &ray, &hit, &mut sampler);
        if radiance.is_finite() {
            sum.add(radiance);
        } else {
            result.dropped += 1;
        }
    }
    result.color = sum.mean_over(spp as u64);
    result.alpha = covered as f32 / spp as f32;
    result
}

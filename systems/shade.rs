//! `shade`: renders the render camera's frame buffers — primary rays per pixel sample through
//! the camera's lens shaders, radiance from the chosen integrator (direct lighting with traced
//! mirror/refraction rays, or the reference path tracer), the camera segment through the
//! atmosphere or a material interior, pixel filter, and the centre-sample passes (depth,
//! normal).
//!
//! Samples per pixel: `spp` everywhere, or adaptive (`settings.adaptive`): `min` samples,
//! then batches that double the count until the standard error of the pixel's mean is below
//! `contrast` in every channel or `max` is reached — decided from the pixel's own samples.
//!
//! **Reads:** the `Camera` with `RenderCamera` (and its `Lenses`, `Atmosphere`); `Interior`
//! of material entities; `Emitter` entities; `frame.geometry` (absent means an empty scene:
//! every ray misses); `settings` (spp or adaptive samples, filter, seed, face, integrator,
//! trace depths).
//! **Writes:** `frame.image` (with the samples each pixel took).
//! **Runs when:** the run renders and a render camera exists.
//! **After this stage:** `frame.image` holds finite beauty, alpha, depth and normal buffers of
//! the camera's resolution; each pixel depends only on (seed, pixel index, sample index).
//! The reported work items are the camera samples actually taken.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use glam::{DVec3, Vec2, Vec3};
use hecs::{Entity, World};
use rayon::prelude::*;

use super::prelude::*;
use crate::accumulate::SampleMean;
use crate::components::{Atmosphere, Camera, Emitter, Interior, Lenses, RenderCamera};
use crate::framebuffer::FrameBuffers;
use crate::progress::Progress;
use crate::sampling::{fold_seed, Sampler};
use crate::shading::{
    shade_hit, volume, CameraRays, FilterSampler, LightSet, ShadeContext, Volumes,
};

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
    let (camera, lenses, atmosphere) = world
        .query::<(&Camera, &RenderCamera, Option<&Lenses>, Option<&Atmosphere>)>()
        .iter()
        .next()
        .map(|(c, _, l, a)| (c.clone(), l.cloned().unwrap_or_default(), a.map(|a| a.0)))
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
    let lights = LightSet::new(&emitters, geometry, frame.settings.light_samples);
    let rays = CameraRays::with_lenses(&camera, &lenses.0);
    let interiors: Vec<_> = geometry.map_or_else(Vec::new, |g| {
        g.material_entities
            .iter()
            .map(|&e| world.get::<&Interior>(e).ok().map(|i| i.0))
            .collect()
    });
    let volumes = Volumes::new(atmosphere, interiors);
    let filter = FilterSampler::new(settings.filter);
    let seed = fold_seed(settings.seed);
    let budget = SampleBudget::new(&settings);
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
                    // Poll per pixel: one pixel is at most `max` samples of work.
                    if cancel.load(Ordering::Relaxed) {
                        stopped.store(true, Ordering::Relaxed);
                        return PixelResult::default();
                    }
                    let pixel = (y * width + x) as u64;
                    let ctx = geometry.map(|g| {
                        ShadeContext::new(g, &lights, &settings).with_volumes(volumes.as_ref())
                    });
                    let r = shade_pixel(ctx.as_ref(), &rays, &filter, seed, pixel, x, y, budget);
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
    let mut taken = 0u64;
    for (y, row) in rows.into_iter().enumerate() {
        for (x, r) in row.into_iter().enumerate() {
            let i = y * width + x;
            fb.beauty[i] = r.color;
            fb.alpha[i] = r.alpha;
            fb.depth[i] = r.depth;
            fb.normal[i] = r.normal;
            fb.object_id[i] = r.object_id;
            fb.material_id[i] = r.material_id;
            fb.samples[i] = r.samples;
            taken += u64::from(r.samples);
        }
    }
    let n = dropped.load(Ordering::Relaxed);
    if n > 0 {
        tracing::warn!("{n} non-finite samples were dropped");
    }
    frame.image = Some(fb);
    Ok(Work {
        items: taken,
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
    samples: u32,
}

/// How many samples a pixel takes: `min` first, then batches doubling the count until the
/// pixel's own samples say it has converged (`contrast`) or `max` is reached.
#[derive(Debug, Clone, Copy)]
struct SampleBudget {
    min: u32,
    max: u32,
    contrast: Vec3,
}

impl SampleBudget {
    fn new(settings: &crate::settings::RenderSettings) -> Self {
        match settings.adaptive {
            Some(a) => Self {
                min: a.min.max(1),
                max: a.max.max(a.min.max(1)),
                contrast: a.contrast,
            },
            None => {
                let n = settings.spp.max(1);
                Self {
                    min: n,
                    max: n,
                    contrast: Vec3::INFINITY,
                }
            }
        }
    }
}

/// Per-channel running mean and variance of a pixel's samples (Welford, f64).
#[derive(Default)]
struct Spread {
    n: u64,
    mean: DVec3,
    m2: DVec3,
}

impl Spread {
    fn add(&mut self, x: Vec3) {
        let x = x.as_dvec3();
        self.n += 1;
        let d = x - self.mean;
        self.mean += d / self.n as f64;
        self.m2 += d * (x - self.mean);
    }

    /// Whether the standard error of the mean is at most `contrast` in every channel.
    fn converged(&self, contrast: Vec3) -> bool {
        if self.n < 2 {
            return false;
        }
        let n = self.n as f64;
        let se2 = self.m2 / ((n - 1.0) * n);
        let c = contrast.as_dvec3();
        se2.cmple(c * c).all()
    }
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
    budget: SampleBudget,
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
        samples: budget.min,
    };
    let Some(ctx) = ctx else {
        return result;
    };
    // Centre-sample passes (through the aperture centre).
    if let Some(ray) = rays.ray(centre.x, centre.y, Vec2::splat(0.5)) {
        if let Some(hit) = ctx.geometry.accel.intersect(&ray) {
            let sp = ctx.geometry.shading_point(&hit);
            result.depth = hit.t;
            result.normal = sp.normal;
            result.object_id = sp.instance + 1;
            result.material_id = sp.material + 1;
        }
    }
    let lens = rays.needs_lens_sample();
    let mut sum = SampleMean::default();
    let mut spread = Spread::default();
    let mut covered = 0u32;
    let mut taken = 0u32;
    let mut batch = budget.min;
    loop {
        for s in taken..taken + batch {
            let mut sampler = Sampler::for_item(seed, pixel, s);
            let film = centre + filter.sample(sampler.next_2d());
            let lens_u = if lens {
                sampler.next_2d()
            } else {
                Vec2::splat(0.5)
            };
            let hit = rays
                .ray(film.x, film.y, lens_u)
                .and_then(|ray| Some((ray, ctx.geometry.accel.intersect(&ray)?)));
            let radiance = match hit {
                Some((ray, hit)) => {
                    covered += 1;
                    let l = shade_hit(ctx, &ray, &hit, &mut sampler);
                    volume::segment(ctx, &ray, &hit, &mut sampler).apply(l)
                }
                None => Vec3::ZERO,
            };
            if radiance.is_finite() {
                sum.add(radiance);
                spread.add(radiance);
            } else {
                result.dropped += 1;
            }
        }
        taken += batch;
        if taken >= budget.max || spread.converged(budget.contrast) {
            break;
        }
        batch = taken.min(budget.max - taken);
    }
    result.color = sum.mean_over(taken as u64);
    result.alpha = covered as f32 / taken as f32;
    result.samples = taken;
    result
}

//! `shade`: renders the render camera's frame buffers — primary rays per pixel sample through
//! the camera's lens shaders, radiance from the chosen integrator (direct lighting with traced
//! mirror/refraction rays, or the reference path tracer), the camera segment through the
//! atmosphere or a material interior, pixel filter, and the centre-sample passes (depth,
//! normal, ids; only where something reads them, `crate::image_reads::centres_read`, and
//! not in a part of a samples split other than part 1, whose centre passes the merge takes).
//!
//! Samples per pixel: `spp` everywhere, or adaptive (`settings.adaptive`, see
//! `crate::adaptive`): pass 1 takes `min` samples in every pixel; pass 2 refines the pixels
//! whose own samples or neighbours exceed the contrast, doubling up to `max`.
//!
//! **Reads:** the `Camera` with `RenderCamera` (and its `Lenses`, `Atmosphere` or `AtmosphereFade`, and its
//! `Imager`'s background, which hides the environment from camera rays); `Interior` of
//! material entities; `Emitter` entities; the `Environment`; `outputs.geometry` (absent: a scene without
//! triangles, shaded as one whose triangles are all out of sight — camera rays meet the
//! visible lights and the environment — with no ray traced); `outputs.photons` (the `Direct` integrator's caustics and final gather;
//! absent: none); `settings` (spp or adaptive samples, filter, seed, face, integrator,
//! trace depths).
//! **Writes:** `outputs.image` (with the samples each pixel took and, when the run draws
//! contours (`crate::scene_view::contours_drawn`), the contour store: what each pixel
//! centre sees; when an output asks
//! for a component pass and the run is not a farm part, the component passes; when the
//! camera sees an environment and an output writes straight alpha, or the run is a farm part,
//! the environment's share of each pixel: `keeps_environment_share`), returned to the
//! runner.
//! **Runs when:** the run renders and a render camera exists, and the image is read; a farm
//! part must own pixels or samples (`crate::farm::part::Share`), or else it writes an empty
//! part file without shading.
//! **After this stage:** `outputs.image` holds finite beauty, alpha, depth and normal buffers of
//! the camera's resolution; each pixel depends only on (seed, pixel index, sample index).
//! The reported work items are the camera samples actually taken: with adaptive sampling a
//! tiles part also takes the first pass of the pixels around its tiles (refinement compares
//! neighbours), and counts those samples, which its part file does not keep; so the parts'
//! samples (and rays) add up to more than the single render's.

mod packets;
mod rows;

use std::sync::atomic::{AtomicBool, Ordering};

use glam::{DVec3, Vec2, Vec3};
use hecs::World;
use rayon::prelude::*;

use super::prelude::*;
use crate::accel::{Ray, RayKind};
use crate::adaptive::{pixel_value, refine_flags, PixelSamples, SampleBudget};
use crate::components::{ContourContrast, Interior};
use crate::contour::{ContourStore, Probe};
use crate::diagnostic::{samples_view, Diagnostic};
use crate::diagnostic_view;
use crate::exact_sum::ExactSum;
use crate::farm::part::Share;
use crate::farm::{Part, Split};
use crate::features::Feature;
use crate::framebuffer::{FrameBuffers, PixelSums};
use crate::geometry::SceneGeometry;
use crate::progress::Progress;
use crate::sampling::{fold_seed, Sampler};
use crate::scene_view::{light_set, render_view, scene_origin, WithEnvironment};
use crate::shading::integrator::components::{camera_sample, Component, Components};
use crate::shading::integrator::material_bsdfs::MaterialBsdfs;
use crate::shading::integrator::triangle_normals::TriangleNormals;
use crate::shading::integrator::{camera_hit, camera_hit_with, CameraHit};
use crate::shading::{CameraRays, FilterSampler, LightSet, ShadeContext, Volumes};
use rows::{RowOut, Totals};

/// Why the image is not rendered when nothing would read it.
pub const NO_OUTPUTS: &str = "the render camera has no outputs and no part file keeps its image";

/// Run condition: a render camera exists, and its image is read (an output, a part file, or
/// a caller that keeps the frame).
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    if !frame.inputs.tasks.render {
        return Decision::skip("this run only bakes");
    }
    if let Some(fb) = &frame.inputs.merged_image {
        return Decision::run(format!(
            "image {}×{} merged from parts",
            fb.width, fb.height
        ));
    }
    let Some(view) = render_view(world) else {
        return Decision::skip("no render camera");
    };
    if !crate::scene_view::image_is_read(world, &frame.inputs) {
        // Outputs that would be left unwritten read no image either.
        return match crate::scene_view::unwritten_outputs(world, &frame.inputs) {
            Some(unwritten) => {
                Decision::skip(format!("nothing reads the image: {}", unwritten.reason()))
            }
            None => Decision::skip(NO_OUTPUTS),
        };
    }
    let share = crate::scene_view::part_share(world, &frame.inputs);
    if let Some(Share::Nothing(why)) = share {
        return Decision::skip(format!("{why}; its part file is written empty"));
    }
    let off = frame.inputs.settings.disabled;
    // What `--disable lens,volume` leaves out, named only where the scene has it.
    let lenses_off = off.contains(Feature::Lens) && !view.lenses.is_empty();
    let volumes_off = off.contains(Feature::Volume)
        && (view.atmosphere.is_some()
            || view.fade.is_some()
            || world.query::<&Interior>().iter().next().is_some());
    let view = view.without(off);
    let camera = &view.camera;
    let mut reason = format!("render camera {}×{}", camera.width, camera.height);
    if let Some(a) = frame.inputs.settings.adaptive {
        reason += &format!(", adaptive {}–{} samples", a.min, a.max);
    }
    if !view.lenses.is_empty() {
        let s = if view.lenses.len() == 1 { "" } else { "s" };
        reason += &format!(", {} lens shader{s}", view.lenses.len());
    }
    if view.atmosphere.is_some() {
        reason += ", atmosphere";
    }
    if let Some(d) = frame.inputs.settings.diagnostic {
        reason += &format!(", diagnostic {}", d.name());
    }
    for (f, left_out) in [(Feature::Lens, lenses_off), (Feature::Volume, volumes_off)] {
        if left_out {
            reason += &format!(", {} shaders disabled", f.name());
        }
    }
    if !frame.outputs.has(crate::frame::Slot::Geometry) {
        reason += ", no geometry: camera rays meet only the visible lights and the environment, no ray is traced";
    }
    if let Some(why) = crate::image_reads::samples_unread(world, &frame.inputs) {
        reason += &format!(", only the pixel-centre rays: {why}");
    }
    match (share, &frame.inputs.part) {
        (Some(Share::CentresOnly(why)), _) => {
            reason += &format!(
                ", {why}; it computes only the centre-sample passes (depth, normal, ids), which the merge takes from part 1"
            );
        }
        (_, Some(run)) => reason += &format!(", {}", run.part),
        _ => {}
    }
    Decision::run(reason)
}

/// Renders the render camera's frame buffers.
pub fn run(world: &World, frame: &Frame) -> Result<Work, StageError> {
    if let Some(fb) = &frame.inputs.merged_image {
        let taken = fb.samples.iter().map(|&s| u64::from(s)).sum();
        let mut fb = fb.clone();
        fb.contour_store = contour_store(world, frame, &fb);
        // The parts took the samples in their own runs: no rate (`n/a`), as for bake parts.
        return Ok(Work::new(taken, "samples")
            .by_merged_parts()
            .with_output(StageOutput::Image(fb)));
    }
    let view = render_view(world).ok_or_else(|| StageError::Internal("no render camera".into()))?;
    let off = frame.inputs.settings.disabled;
    let view = view.without(off);
    let camera = view.camera;
    let background = view.imager.and_then(|i| i.background);
    let settings = frame.inputs.settings.clone();
    // A scene without triangles (`build_accel` skipped) is shaded as one whose triangles
    // are all out of sight: camera rays still meet the visible lights and the environment.
    // Nothing can be hit, so no ray is traced (`PixelShader::traces`).
    let empty;
    let geometry = match frame.outputs.geometry.as_ref() {
        Some(g) => g,
        None => {
            empty = SceneGeometry::empty(scene_origin(world));
            &empty
        }
    };
    let traces = frame.outputs.geometry.is_some();
    let mut lights = light_set(world, Some(geometry), &settings, WithEnvironment::Yes);
    lights.camera_sees_environment = background.is_none();
    let rays = CameraRays::with_lenses(&camera, &view.lenses);
    let interiors: Vec<_> = geometry
        .material_entities
        .iter()
        .map(|&e| world.get::<&Interior>(e).ok().map(|i| i.0))
        .map(|i| i.filter(|_| !off.contains(Feature::Volume)))
        .collect();
    let volumes = Volumes::with_fade(view.atmosphere, view.fade, interiors);
    let filter = FilterSampler::new(settings.filter);
    let seed = fold_seed(settings.seed);
    let budget = SampleBudget::new(&settings);
    // Nothing reads a sample: only the pixel-centre rays are traced.
    let centres_only = crate::image_reads::samples_unread(world, &frame.inputs).is_some();
    let (width, height) = (camera.width as usize, camera.height as usize);
    let part = frame.inputs.part.as_ref().map(|r| r.part);
    let whole = Part::whole();
    let part_or_whole = part.unwrap_or(whole);
    if part_or_whole.split == Split::Samples && budget.refines() {
        return Err(StageError::Internal(
            "adaptive sampling cannot be split by samples".into(),
        ));
    }
    let first_samples = if centres_only {
        0..0
    } else {
        part_or_whole.samples(budget.min)
    };
    let refines = budget.refines() && !centres_only;
    let environment = keeps_environment_share(world, frame, &lights) && !centres_only;

    let mut fb = FrameBuffers::new(camera.width, camera.height);
    let cancel = frame.inputs.cancel.clone();
    let stopped = AtomicBool::new(false);
    let passes = if refines { 2 } else { 1 };
    let progress = Progress::start(
        frame.inputs.progress,
        "shade",
        "rows",
        (passes * height) as u64,
    );
    let ticker = progress.ticker();
    let photons = frame.outputs.photons.as_ref();
    let normals = TriangleNormals::new(geometry);
    let bsdfs = MaterialBsdfs::new(geometry);
    let ctx = ShadeContext::new(geometry, &lights, &settings)
        .with_volumes(volumes.as_ref())
        .with_photons(photons)
        .with_normals(normals.as_ref())
        .with_bsdfs(Some(&bsdfs));
    let shade = PixelShader {
        ctx: &ctx,
        traces,
        rays: &rays,
        filter: &filter,
        seed,
        width,
        sample_offset: first_samples.start,
        cancel: &cancel,
        // A tile part owns whole pixels, so it keeps their component values exactly; a
        // samples part would need exact component sums (refused by the CLI).
        components: part.is_none_or(|p| p.split == crate::farm::Split::Tiles)
            && wants_components(&camera),
        variance: refines,
        environment,
        centres: part_or_whole.traces_centres()
            && crate::image_reads::centres_read(world, &frame.inputs),
    };
    // Pass 1: the centre-sample passes (not in a samples part other than 1) and `min`
    // samples everywhere (a tiles part: in its own pixels and, when refinement compares
    // neighbours, those next to them).
    let count = first_samples.len() as u32;
    let first_pass = |x: usize, y: usize| {
        if !part_or_whole.needs_first_pass(x, y, width, height, refines) {
            return PixelResult::empty();
        }
        shade.first_pass(x, y, count)
    };
    let owns = |x: usize, y: usize| part_or_whole.owns(x, y, width);
    let mut components = shade
        .components
        .then(|| vec![[Vec3::ZERO; 6]; width * height]);
    let mut sums = part.map(|_| PixelSums {
        sums: vec![Default::default(); width * height],
        covered: vec![0; width * height],
        dropped: vec![0; width * height],
        environment: environment.then(|| vec![Default::default(); width * height]),
    });
    fb.environment = environment.then(|| vec![Vec3::ZERO; width * height]);
    let rows = RowOut::split(&mut fb, sums.as_mut(), components.as_mut(), width, height);
    let totals = if refines {
        // Every pixel's pass-1 samples decide the refinement, so they are all kept.
        let per_pixel = |f: &(dyn Fn(usize, usize) -> Option<PixelResult> + Sync)| {
            let rows: Vec<Vec<Option<PixelResult>>> = (0..height)
                .into_par_iter()
                .map(|y| {
                    let row = (0..width)
                        .map(|x| {
                            if cancel.load(Ordering::Relaxed) {
                                stopped.store(true, Ordering::Relaxed);
                                return None;
                            }
                            f(x, y)
                        })
                        .collect();
                    ticker.tick(1);
                    row
                })
                .collect();
            rows.into_iter().flatten().collect::<Vec<_>>()
        };
        let mut pixels = per_pixel(&|x, y| Some(first_pass(x, y)));
        // A tiles part's first pass around its tiles: traced, so counted, but not kept.
        let around: u64 = (pixels.iter().enumerate())
            .filter(|(i, _)| !owns(i % width, i / width))
            .filter_map(|(_, p)| p.as_ref())
            .map(|p| u64::from(p.samples.taken))
            .sum();
        if !stopped.load(Ordering::Relaxed) {
            let pass1: Vec<PixelSamples> = pixels
                .iter()
                .map(|p| p.as_ref().map(|p| p.samples.clone()).unwrap_or_default())
                .collect();
            let flags = refine_flags(&pass1, width, height, budget.contrast);
            // Pass 2: refined pixels double their samples until converged or at `max`.
            let refined = per_pixel(&|x, y| {
                let i = y * width + x;
                let mut p = pixels[i].as_ref()?.clone();
                if !owns(x, y) {
                    return Some(PixelResult::empty());
                }
                if let Some(delta) = flags[i] {
                    shade.refine(&mut p, x, y, &budget, delta);
                }
                Some(p)
            });
            pixels = refined;
        }
        let mut rows = rows;
        let mut totals = Totals {
            taken: around,
            dropped: 0,
        };
        for (i, p) in pixels.into_iter().enumerate() {
            let Some(p) = p else { continue };
            let (x, y) = (i % width, i / width);
            totals = totals + rows[y].store(x, &p, owns(x, y));
        }
        totals
    } else {
        // Without refinement a pixel is done after pass 1: each row's worker writes its
        // pixels straight into the frame buffers.
        rows.into_par_iter()
            .enumerate()
            .map(|(y, mut row)| {
                let mut totals = Totals::default();
                for x in 0..width {
                    if cancel.load(Ordering::Relaxed) {
                        stopped.store(true, Ordering::Relaxed);
                        continue;
                    }
                    totals = totals + row.store(x, &first_pass(x, y), owns(x, y));
                }
                ticker.tick(1);
                totals
            })
            .reduce(Totals::default, |a, b| a + b)
    };
    drop(ticker);
    progress.finish();
    if stopped.load(Ordering::Relaxed) || cancel.load(Ordering::Relaxed) {
        return Err(StageError::Interrupted);
    }
    let Totals { taken, dropped } = totals;
    if dropped > 0 {
        tracing::warn!("{dropped} non-finite samples were dropped");
    }
    if settings.diagnostic == Some(Diagnostic::Samples) {
        fb.beauty = samples_view(&fb.samples, budget.max);
        fb.environment = None;
    }
    if let Some(d) = settings.diagnostic {
        let drawn = diagnostic_view::view(
            d,
            geometry,
            &rays,
            camera.world_from_camera,
            photons,
            (width, height),
        );
        if let Some(beauty) = drawn {
            fb.beauty = beauty;
            fb.environment = None;
        }
    }
    fb.sums = sums;
    fb.components = components;
    fb.contour_store = contour_store(world, frame, &fb);
    if centres_only {
        // One per pixel: the centre passes' or the diagnostic view's (none without geometry).
        let traced = if traces { (width * height) as u64 } else { 0 };
        return Ok(Work::new(traced, "centre rays").with_output(StageOutput::Image(fb)));
    }
    Ok(Work::new(taken, "samples").with_output(StageOutput::Image(fb)))
}

/// The frame buffers of a render part that computes nothing ([`Share::Nothing`]), as
/// `shade` would have returned them: no samples, nothing hit, zero exact sums, and zero
/// component passes where a tile part carries them. `write_output` writes them as the
/// part's (empty) part file, so that the set of parts stays complete for the merge.
pub fn idle_part_image(world: &World, frame: &Frame) -> Option<FrameBuffers> {
    let share = crate::scene_view::part_share(world, &frame.inputs)?;
    if !matches!(share, Share::Nothing(_)) {
        return None;
    }
    let view = render_view(world)?.without(frame.inputs.settings.disabled);
    let camera = view.camera;
    let n = camera.width as usize * camera.height as usize;
    let mut fb = FrameBuffers::new(camera.width, camera.height);
    // The environment's sums, zero, where a part with work keeps them
    // (`keeps_environment_share`: every part of a merge must carry them for it to keep them).
    let sees_environment = crate::scene_view::environment(world).is_some()
        && view.imager.and_then(|i| i.background).is_none();
    fb.sums = Some(PixelSums {
        sums: vec![Default::default(); n],
        covered: vec![0; n],
        dropped: vec![0; n],
        environment: sees_environment.then(|| vec![Default::default(); n]),
    });
    let tiles = frame
        .inputs
        .part
        .as_ref()
        .is_some_and(|r| r.part.split == Split::Tiles);
    fb.components = (tiles && wants_components(&camera)).then(|| vec![[Vec3::ZERO; 6]; n]);
    Some(fb)
}

/// The contour store of the shaded (or merged) image `fb`, when the run draws contours
/// ([`crate::scene_view::contours_drawn`]). Its samples are what the pixel centres' rays
/// see on each level, each pixel's path walked once through the levels and no further than
/// it goes ([`Probe::walk`]); they need no random numbers: a merge recomputes them exactly.
fn contour_store(world: &World, frame: &Frame, fb: &FrameBuffers) -> Option<ContourStore> {
    crate::scene_view::contours_drawn(world, &frame.inputs).ok()?;
    let view = render_view(world)?.without(frame.inputs.settings.disabled);
    let rays = CameraRays::with_lenses(&view.camera, &view.lenses);
    let ray_depth = world
        .query::<&ContourContrast>()
        .iter()
        .next()
        .map_or(0, |c| c.ray_depth);
    let probe = Probe::new(frame.outputs.geometry.as_ref(), &rays);
    Some(probe.store(fb.width, fb.height, &fb.beauty, ray_depth))
}

/// Whether the pixels keep the environment's share (the radiance of their samples that
/// missed every surface, `FrameBuffers::environment`): only where the camera can see an
/// environment (one exists and no imager `background` replaces it) and the share is read —
/// by an output that writes straight alpha, which takes it out of a partly covered pixel's
/// colour, or by a farm part, whose merge may write such an output. Other renders add
/// nothing to their sample loop.
fn keeps_environment_share(world: &World, frame: &Frame, lights: &LightSet) -> bool {
    lights.camera_sees_environment
        && lights.environment.is_some()
        && (frame.inputs.part.is_some()
            || crate::scene_view::straight_alpha_written(world, &frame.inputs))
}

/// Whether some output of `camera` asks for a component pass (emission, diffuse, …).
fn wants_components(camera: &crate::components::Camera) -> bool {
    camera
        .outputs
        .iter()
        .any(|o| o.passes.iter().any(|p| p.component().is_some()))
}

/// One pixel: its centre-sample passes and its samples so far.
#[derive(Clone)]
struct PixelResult {
    depth: f32,
    normal: Vec3,
    object_id: u32,
    material_id: u32,
    samples: PixelSamples,
    /// Sums of the finite samples' components (only when component passes are asked for).
    components: Option<Box<[DVec3; 6]>>,
    /// Exact sums of the radiance of the samples that missed every surface (only when the
    /// environment's share is kept, `keeps_environment_share`).
    environment: Option<Box<[ExactSum; 3]>>,
}

impl PixelResult {
    /// A pixel this part does not compute: no samples, nothing hit.
    fn empty() -> Self {
        Self {
            depth: f32::INFINITY,
            normal: Vec3::ZERO,
            object_id: 0,
            material_id: 0,
            samples: PixelSamples::default(),
            components: None,
            environment: None,
        }
    }

    /// The component passes' values: each component's sum over the samples taken.
    fn component_values(&self) -> [Vec3; 6] {
        let n = f64::from(self.samples.taken.max(1));
        let sums = self.components.as_deref().copied().unwrap_or_default();
        sums.map(|s| (s / n).as_vec3())
    }

    /// The environment's share of the pixel value: its missed samples' radiance summed over
    /// the samples taken, rounded as the beauty is (`pixel_value`).
    fn environment_value(&self) -> Vec3 {
        let sums = self.environment.as_deref().copied().unwrap_or_default();
        pixel_value(&sums, self.samples.taken)
    }
}

/// Everything a pixel's samples need.
struct PixelShader<'a> {
    ctx: &'a ShadeContext<'a>,
    /// Whether there are triangles to trace rays against (`build_accel` ran). Without,
    /// camera rays meet only the visible lights and the environment, and none is traced.
    traces: bool,
    rays: &'a CameraRays,
    filter: &'a FilterSampler,
    seed: u32,
    width: usize,
    /// Index of the first sample this run takes of each pixel (a samples-split part).
    sample_offset: u32,
    cancel: &'a AtomicBool,
    /// Whether to record the component passes.
    components: bool,
    /// Whether pixels keep their samples' variance (adaptive refinement reads it).
    variance: bool,
    /// Whether pixels keep the environment's share (`keeps_environment_share`).
    environment: bool,
    /// Whether to trace the centre-sample passes (not in a samples part other than 1:
    /// `Part::traces_centres`).
    centres: bool,
}

impl PixelShader<'_> {
    /// The centre-sample passes (where this run traces them) and samples `0..count` of
    /// pixel `(x, y)`.
    fn first_pass(&self, x: usize, y: usize, count: u32) -> PixelResult {
        let mut result = PixelResult::empty();
        if self.centres && self.traces {
            let ctx = self.ctx;
            // Through the aperture centre.
            let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            if let Some(ray) = self.rays.ray(centre.x, centre.y, Vec2::splat(0.5)) {
                if let Some(hit) = ctx.geometry.accel.intersect_as(&ray, RayKind::Camera) {
                    let sp = ctx.geometry.shading_point(&hit);
                    result.depth = hit.t;
                    result.normal = sp.normal;
                    result.object_id =
                        ctx.geometry.instances[sp.instance as usize].object_id(sp.instance);
                    result.material_id = sp.material + 1;
                }
            }
        }
        self.take(&mut result, x, y, count);
        result
    }

    /// Pass 2 for a refined pixel: doubling batches until converged or at `max`.
    fn refine(&self, p: &mut PixelResult, x: usize, y: usize, budget: &SampleBudget, delta: Vec3) {
        loop {
            let batch = budget.next_batch(p.samples.taken);
            if batch == 0 {
                break;
            }
            self.take(p, x, y, batch);
            if p.samples.converged_near(budget.contrast, delta) {
                break;
            }
        }
    }

    /// Takes the next `count` samples of pixel `(x, y)` (sample indices continue from the
    /// samples already taken).
    fn take(&self, result: &mut PixelResult, x: usize, y: usize, count: u32) {
        if self.components && result.components.is_none() {
            result.components = Some(Box::default());
        }
        if self.environment && result.environment.is_none() {
            result.environment = Some(Box::default());
        }
        let samples = &mut result.samples;
        let mut sums = result.components.as_deref_mut();
        let mut missed = result.environment.as_deref_mut();
        let pixel = (y * self.width + x) as u64;
        let ctx = self.ctx;
        let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        let lens = self.rays.needs_lens_sample();
        let first = self.sample_offset + samples.taken;
        // A pinhole's rays share the camera's origin: enough of them go to the tree as packets
        // (not on a small scene, whose lane kernel answers one ray faster than the gathering
        // costs: the Cornell box's path tracer took 3 % more instructions through it).
        if !lens && self.traces && ctx.geometry.accel.packs_shared_origin(count as usize) {
            self.take_in_packets(ctx, samples, sums, missed, pixel, centre, first, count);
            return;
        }
        // Each sample's sampler is made one sample ahead (`Sampler::for_item_primed`), so its
        // integer hash chains overlap the previous sample's shading.
        let mut next = Sampler::for_item_primed(self.seed, pixel, first);
        for s in first..first + count {
            // A pixel may take millions of samples (`--spp`): poll here too.
            if s % 64 == 0 && self.cancel.load(Ordering::Relaxed) {
                return;
            }
            let mut sampler = next.clone();
            if s + 1 < first + count {
                next = Sampler::for_item_primed(self.seed, pixel, s + 1);
            }
            let film = centre + self.filter.sample(sampler.next_2d());
            let lens_u = if lens {
                sampler.next_2d()
            } else {
                Vec2::splat(0.5)
            };
            let hit = self.rays.ray(film.x, film.y, lens_u).map(|ray| {
                let seen = if self.traces {
                    camera_hit(ctx, &ray)
                } else {
                    camera_hit_with(ctx, &ray, None)
                };
                (ray, seen)
            });
            let sums = sums.as_deref_mut();
            self.add_sample(ctx, hit, &mut sampler, samples, sums, missed.as_deref_mut());
        }
    }

    /// Adds one sample to the pixel's `samples`, component `sums` and, when it missed every
    /// surface, `missed` (the environment's share): what its camera ray met (`None`: no
    /// ray), shaded with `sampler` past its film and lens draws.
    #[inline(always)]
    fn add_sample(
        &self,
        ctx: &ShadeContext<'_>,
        hit: Option<(Ray, CameraHit)>,
        sampler: &mut Sampler,
        samples: &mut PixelSamples,
        sums: Option<&mut [DVec3; 6]>,
        missed: Option<&mut [ExactSum; 3]>,
    ) {
        let mut parts = Components::default();
        let recording = sums.is_some().then_some(&mut parts);
        let (l, covered) = match hit {
            Some((ray, CameraHit::Surface(hit))) => {
                (camera_sample(ctx, &ray, &hit, sampler, recording), true)
            }
            Some((_, CameraHit::Light(le))) => (le, true),
            Some((_, CameraHit::Miss(le))) => {
                if let Some(missed) = missed {
                    // As `PixelSamples` sums the beauty (non-finite values left out).
                    missed[0].add(le.x);
                    missed[1].add(le.y);
                    missed[2].add(le.z);
                }
                (le, false)
            }
            None => (Vec3::ZERO, false),
        };
        if self.variance {
            samples.add(l, covered);
        } else {
            samples.add_unmeasured(l, covered);
        }
        if let Some(sums) = sums {
            if !matches!(hit, Some((_, CameraHit::Surface(_)))) {
                parts.add(Component::Emission, l);
            }
            if l.is_finite() {
                for (sum, part) in sums.iter_mut().zip(parts.parts) {
                    *sum += part.as_dvec3();
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Tasks;
    use crate::systems::tiny_scene::{load, run_until, scene};

    #[test]
    fn the_lit_square_fills_the_centre_and_every_pixel_is_finite() {
        let (mut world, mut frame) = load(&scene("", "", "", &[]), false);
        run_until("shade", &mut world, &mut frame);
        assert_eq!(
            should_run(&world, &frame),
            Decision::run("render camera 16×12")
        );
        let work = run(&world, &frame).unwrap();
        assert_eq!(work.items, 16 * 12, "one sample per pixel");
        let Some(StageOutput::Image(fb)) = work.output else {
            panic!("shade returns the frame buffers");
        };
        assert!(fb.beauty.iter().all(|c| c.is_finite()));
        // The square (±1 at distance 3, 60° fov) covers the centre; a point light of 2 W/sr
        // 2 above it gives E = 2/4 W/m² at the centre and L = 0.5·E/π.
        let centre = fb.beauty[6 * 16 + 8];
        let expected = 0.5 * 0.5 / std::f32::consts::PI;
        assert!(
            (centre.x - expected).abs() < 0.05 * expected,
            "{centre} vs {expected}"
        );
        assert_eq!(fb.alpha[0], 0.0, "the corner sees no geometry");
    }

    #[test]
    fn skipped_in_a_bake_only_run() {
        let (world, mut frame) = load(&scene("", "", "", &[]), false);
        frame.inputs.tasks = Tasks {
            render: false,
            bake: true,
        };
        assert_eq!(
            should_run(&world, &frame),
            Decision::skip("this run only bakes")
        );
    }
}

//! Evaluates every requested kind at every covered texel of one bake request, in parallel
//! over texel rows. Each texel's random numbers derive from (seed, texel index, ray index):
//! the result does not depend on the thread count.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use glam::Vec3;
use rayon::prelude::*;

use crate::accumulate::SampleMean;
use crate::bake::ao::{
    trace_hemisphere, trace_hemispheres, HemisphereJob, HemisphereQuery, HemisphereRays,
};
use crate::bake::irradiance::{
    base_color, diffuse_albedo, direct_irradiance, indirect_irradiance_path,
    indirect_irradiance_sample,
};
use crate::bake::raster::Coverage;
use crate::bake::texture::TexelImage;
use crate::components::{BakeKind, LightmapStore, NormalSpace};
use crate::geometry::{InstanceGeometry, SceneGeometry};
use crate::progress::ProgressTicker;
use crate::sampling::{hash_combine, Sampler};
use crate::shading::texture::hit as textured;
use crate::shading::LightSet;

/// Rays of the inside-geometry probe per sample position, whatever the AO sample count: the
/// probe has its own rays (uniform in solid angle about the geometric normal), so the verdict
/// does not depend on the AO rays and the AO of a position kept is not conditioned on them.
const PROBE_RAYS: u32 = 8;
/// A sample position is inside geometry when more than this fraction of probe rays first meet
/// the back of a one-sided surface (inside a closed mesh it is all of them; beside the back of
/// a one-sided wall about half; under the back of a 2 × 2 plane 0.5 above, about 0.6 of the
/// hemisphere's solid angle).
const INSIDE_FRACTION: f32 = 0.75;

/// Inputs of one request's texel evaluation.
pub struct TexelJob<'a> {
    /// Scene geometry.
    pub geometry: &'a SceneGeometry,
    /// The baked instance.
    pub instance: &'a InstanceGeometry,
    /// Lights.
    pub lights: &'a LightSet,
    /// Coverage of the texture.
    pub coverage: &'a Coverage,
    /// Kinds to bake.
    pub kinds: &'a [BakeKind],
    /// Per-triangle corner UVs (for tangent frames).
    pub uvs: &'a [[glam::Vec2; 3]],
    /// Seed of this request.
    pub seed: u32,
    /// Render settings (the integrator decides how indirect light is gathered).
    pub settings: &'a crate::settings::RenderSettings,
    /// Only the texels `(i, j)` for which this returns true are evaluated (a farm part's
    /// share); `None` evaluates all of them.
    pub owns: Option<&'a (dyn Fn(u32, u32) -> bool + Sync)>,
}

/// Output of [`evaluate`]: one image per kind (AO with bent normals gives two, in kind order
/// then bent normals last), rays traced, invalid texels.
pub struct TexelResults {
    /// Images, aligned with the kinds; a trailing extra image holds bent normals if asked.
    pub images: Vec<TexelImage>,
    /// Rays traced: every query the evaluation made of the scene's accelerator, as the
    /// accelerator counts them (the stage's ray count is the sum over requests).
    pub rays: u64,
    /// Covered texels rejected as inside geometry.
    pub invalid: u64,
}

/// Values of one texel, one per image.
type TexelValues = Vec<Option<Vec3>>;

/// How many images a bake of `kinds` produces: one per kind, and a trailing one of bent
/// normals when an ambient-occlusion kind asks for them.
pub fn image_count(kinds: &[BakeKind]) -> usize {
    let bent = kinds.iter().any(|k| {
        matches!(
            k,
            BakeKind::AmbientOcclusion {
                bent_normals: true,
                ..
            }
        )
    });
    kinds.len() + usize::from(bent)
}

/// Evaluates every kind at every texel. Returns `None` when `cancel` was raised.
pub fn evaluate(
    job: &TexelJob<'_>,
    cancel: &AtomicBool,
    progress: &ProgressTicker,
) -> Option<TexelResults> {
    let (w, h) = (job.coverage.width, job.coverage.height);
    let n_images = image_count(job.kinds);
    let bent = n_images > job.kinds.len();
    let needs_probe = job.kinds.iter().any(|k| {
        matches!(
            k,
            BakeKind::AmbientOcclusion { .. } | BakeKind::Lightmap { .. }
        )
    });
    // Counted by the accelerator, which counts every query: exact once the rows are done.
    let rays_before = job.geometry.accel.ray_counts();
    let invalid = AtomicU64::new(0);
    let stopped = AtomicBool::new(false);
    let rows: Vec<Vec<TexelValues>> = (0..h)
        .into_par_iter()
        .map(|j| {
            if cancel.load(Ordering::Relaxed) {
                stopped.store(true, Ordering::Relaxed);
                return Vec::new();
            }
            let row = (0..w)
                .map(|i| {
                    // Poll per texel: one texel is at most its rays of work.
                    if cancel.load(Ordering::Relaxed) {
                        stopped.store(true, Ordering::Relaxed);
                        return vec![None; n_images];
                    }
                    if job.owns.is_some_and(|owns| !owns(i, j)) {
                        return vec![None; n_images];
                    }
                    let (values, bad) = texel(job, i, j, n_images, bent, needs_probe);
                    if bad {
                        invalid.fetch_add(1, Ordering::Relaxed);
                    }
                    values
                })
                .collect();
            progress.tick(1);
            row
        })
        .collect();
    if stopped.load(Ordering::Relaxed) {
        return None;
    }
    let mut images: Vec<TexelImage> = (0..n_images).map(|_| TexelImage::new(w, h)).collect();
    for (j, row) in rows.into_iter().enumerate() {
        for (i, values) in row.into_iter().enumerate() {
            let idx = j * w as usize + i;
            for (img, v) in images.iter_mut().zip(values) {
                if let Some(v) = v {
                    img.texels[idx] = v;
                    img.valid[idx] = true;
                }
            }
        }
    }
    Some(TexelResults {
        images,
        rays: job.geometry.accel.ray_counts().since(rays_before).total(),
        invalid: invalid.into_inner(),
    })
}

/// One sample position on the surface, oriented to the baked side.
struct Site {
    surface: crate::accel::SurfacePoint,
    normal: Vec3,
    ng: Vec3,
    triangle: usize,
    material: u32,
    /// The hit this site came from (for evaluating texture nodes).
    hit: crate::accel::Hit,
}

/// Evaluates texel `(i, j)`: values per image, whether it was rejected.
fn texel(
    job: &TexelJob<'_>,
    i: u32,
    j: u32,
    n_images: usize,
    bent: bool,
    needs_probe: bool,
) -> (TexelValues, bool) {
    let mut values: TexelValues = vec![None; n_images];
    let slots = job.coverage.texel(i, j);
    if slots.iter().all(Option::is_none) {
        return (values, false);
    }
    let texel_index = j as u64 * job.coverage.width as u64 + i as u64;
    let texel_seed = hash_combine(&[job.seed, texel_index as u32, (texel_index >> 32) as u32]);
    // Sample positions, minus those found inside other geometry.
    let mut sites = Vec::with_capacity(slots.len());
    for (s, slot) in slots.iter().enumerate() {
        let Some(ts) = slot else { continue };
        let hit = job.instance.hit_at(ts.triangle, ts.b1, ts.b2);
        let sp = job.geometry.shading_point(&hit);
        let site = Site {
            surface: sp.surface,
            normal: sp.normal,
            ng: sp.surface.ng,
            triangle: ts.triangle as usize,
            material: sp.material,
            hit,
        };
        if needs_probe {
            // About the geometric normal: which side of the surface the point is on.
            let probe = trace_hemisphere(
                job.geometry,
                &site.surface,
                site.ng,
                site.ng,
                f32::INFINITY,
                hash_combine(&[texel_seed, 0x9b0e, s as u32]),
                0,
                PROBE_RAYS,
                HemisphereQuery::Probe {
                    inside_fraction: INSIDE_FRACTION,
                },
            );
            if probe.inside {
                continue;
            }
        }
        sites.push(site);
    }
    if sites.is_empty() {
        return (values, true);
    }
    let n_sites = sites.len() as u32;
    for (k, kind) in job.kinds.iter().enumerate() {
        let kind_seed = hash_combine(&[texel_seed, k as u32 + 1]);
        let value = match kind {
            BakeKind::AmbientOcclusion {
                samples,
                max_distance,
                bent_normals,
            } => {
                let results = ao_rays(job, &sites, *samples, *max_distance, kind_seed);
                let open: u32 = results.iter().map(|r| r.open).sum();
                let traced: u32 = results.iter().map(|r| r.rays).sum();
                let dir_sum: Vec3 = results.iter().map(|r| r.open_dir_sum).sum();
                if *bent_normals && bent {
                    let mean_normal = sites
                        .iter()
                        .map(|s| s.normal)
                        .sum::<Vec3>()
                        .normalize_or_zero();
                    values[n_images - 1] = Some(dir_sum.try_normalize().unwrap_or(mean_normal));
                }
                Vec3::splat(open as f32 / traced.max(1) as f32)
            }
            BakeKind::Lightmap {
                indirect,
                samples,
                max_depth,
                store,
                scale,
            } => {
                let mut e = Vec3::ZERO;
                for (s, site) in sites.iter().enumerate() {
                    let mut sampler = Sampler::new(kind_seed, s as u32);
                    e += direct_irradiance(
                        job.geometry,
                        job.lights,
                        &job.geometry.materials[site.material as usize],
                        &site.surface,
                        site.normal,
                        site.ng,
                        &mut sampler,
                    );
                }
                e /= n_sites as f32;
                if *indirect && *max_depth > 0 {
                    let samples = (*samples).max(1);
                    let mut sum = SampleMean::default();
                    let path_ctx = (job.settings.integrator == crate::settings::Integrator::Path)
                        .then(|| {
                            let mut settings = job.settings.clone();
                            // The gather ray is the first bounce; the path adds the rest.
                            settings.max_depth = (*max_depth).max(1);
                            crate::shading::ShadeContext::new(job.geometry, job.lights, &settings)
                        });
                    for r in 0..samples {
                        let site = &sites[(r % n_sites) as usize];
                        let mut sampler = Sampler::new(hash_combine(&[kind_seed, 0x1d1]), r);
                        sum.add(match &path_ctx {
                            Some(ctx) => indirect_irradiance_path(
                                ctx,
                                &site.surface,
                                site.normal,
                                site.ng,
                                &mut sampler,
                            ),
                            None => indirect_irradiance_sample(
                                job.geometry,
                                job.lights,
                                &site.surface,
                                site.normal,
                                site.ng,
                                *max_depth,
                                &mut sampler,
                            ),
                        });
                    }
                    e += sum.mean_over(samples as u64);
                }
                let stored = match store {
                    LightmapStore::Irradiance => e,
                    LightmapStore::Radiance => texel_albedo(job, &sites) * e / std::f32::consts::PI,
                    LightmapStore::IrradianceOverPi => e / std::f32::consts::PI,
                };
                // Exact at the default scale of 1.
                stored * *scale
            }
            BakeKind::Normals { space } => {
                let n = sites
                    .iter()
                    .map(|s| s.normal)
                    .sum::<Vec3>()
                    .normalize_or_zero();
                match space {
                    NormalSpace::World => n,
                    NormalSpace::Tangent => tangent_space(job, &sites[0], n),
                }
            }
            // Render space back to world space, in f64, rounded once to f32.
            BakeKind::Positions => (sites
                .iter()
                .map(|s| s.surface.p.as_dvec3())
                .sum::<glam::DVec3>()
                / n_sites as f64
                + job.geometry.origin)
                .as_vec3(),
            BakeKind::Albedo => {
                // The material's texture nodes evaluated at every sample position.
                sites
                    .iter()
                    .map(|site| {
                        let material = &job.geometry.materials[site.material as usize];
                        let sp = job.geometry.shading_point(&site.hit);
                        match textured::evaluate(job.geometry, &sp, &site.hit, material) {
                            Some(t) => base_color(&t.shader),
                            None => base_color(&material.shader),
                        }
                    })
                    .sum::<Vec3>()
                    / n_sites as f32
            }
        };
        values[k] = value.is_finite().then_some(value);
    }
    (values, false)
}

/// The diffuse albedo of a texel for `Lightmap(store: Radiance)`: at each sample position,
/// of that position's material with its texture nodes evaluated; their mean, or exactly
/// their common value when every position has the same.
fn texel_albedo(job: &TexelJob<'_>, sites: &[Site]) -> Vec3 {
    let each: Vec<Vec3> = sites
        .iter()
        .map(|site| {
            let material = &job.geometry.materials[site.material as usize];
            let sp = job.geometry.shading_point(&site.hit);
            match textured::evaluate(job.geometry, &sp, &site.hit, material) {
                Some(t) => diffuse_albedo(&t.shader),
                None => diffuse_albedo(&material.shader),
            }
        })
        .collect();
    match each.first() {
        Some(&first) if each.iter().all(|&a| a == first) => first,
        _ => each.iter().sum::<Vec3>() / each.len().max(1) as f32,
    }
}

/// AO rays of every sample position: `samples` rays dealt round-robin over `sites`, traced
/// as one stream (`trace_hemispheres`).
fn ao_rays(
    job: &TexelJob<'_>,
    sites: &[Site],
    samples: u32,
    max_distance: f32,
    seed: u32,
) -> Vec<HemisphereRays> {
    let samples = samples.max(1);
    let n = sites.len() as u32;
    let mut first = 0;
    let jobs: Vec<HemisphereJob<'_>> = sites
        .iter()
        .enumerate()
        .map(|(s, site)| {
            let count = samples / n + u32::from((s as u32) < samples % n);
            let j = HemisphereJob {
                surface: &site.surface,
                normal: site.normal,
                ng_facing: site.ng,
                first,
                count,
            };
            first += count;
            j
        })
        .collect();
    trace_hemispheres(
        job.geometry,
        &jobs,
        max_distance,
        seed,
        HemisphereQuery::Occlusion,
    )
}

/// `n` in the tangent frame of the site's triangle: T = dP/du, B = dP/dv (Gram–Schmidt
/// against the geometric normal), N = geometric normal.
fn tangent_space(job: &TexelJob<'_>, site: &Site, n: Vec3) -> Vec3 {
    let prim = job.instance.first_triangle + site.triangle as u32;
    let [p0, p1, p2] = job.geometry.accel.triangle(prim);
    // The uvs in the world triangle's corner order, as its positions.
    let [t0, t1, t2] = job.instance.world_order(job.uvs[site.triangle]);
    let (e1, e2) = (p1 - p0, p2 - p0);
    let (d1, d2) = (t1 - t0, t2 - t0);
    let det = d1.x * d2.y - d2.x * d1.y;
    let ng = site.ng;
    let tangent = if det.abs() > 0.0 {
        (e1 * d2.y - e2 * d1.y) / det
    } else {
        e1
    };
    let t = (tangent - ng * ng.dot(tangent))
        .try_normalize()
        .unwrap_or_else(|| crate::bake::ao::basis(ng).0);
    let mut b = ng.cross(t);
    if det < 0.0 {
        b = -b;
    }
    Vec3::new(n.dot(t), n.dot(b), n.dot(ng))
}

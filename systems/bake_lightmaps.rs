//! `bake_lightmaps`: bakes every bake request (ambient occlusion, lightmaps, normals,
//! positions, albedo) into textures, dilates them, and writes them whole-or-nothing.
//!
//! **Reads:** `BakeRequest` + `Name` + `SourceLink` on instance entities; `Emitter` entities;
//! `frame.geometry`; `frame.bake_dir`; `settings.seed`.
//! **Writes:** texture files; `frame.bake_reports`; `frame.written`.
//! **Runs when:** the run bakes (`stagelight bake` or `render --bake`) and at least one
//! instance carries a bake request.
//! **After this stage:** every requested texture exists complete (or none was written), and
//! a report per request gives texel density, coverage, invalid texels, rays and time.
//!
//! Every request is checked (UVs, resolution, overlapping UVs) before any texel is baked.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use hecs::{Entity, World};

use super::prelude::*;
use crate::bake::texels::{evaluate, TexelJob};
use crate::bake::{bake_resolution, corner_uvs, dilate::dilate, rasterize, BakeReport, Coverage};
use crate::components::{BakeFormat, BakeKind, BakeRequest, Emitter, SourceLink};
use crate::image_io::{commit_all, PendingFile};
use crate::progress::Progress;
use crate::sampling::{fold_seed, hash_combine};
use crate::shading::LightSet;

/// Fraction of sample positions that may fall in two triangles before UVs count as
/// overlapping.
const OVERLAP_TOLERANCE: f64 = 1e-3;
/// UV page size used when generating lightmap UVs for density-sized bakes.
const UNWRAP_PAGE: u32 = 1024;

/// Run condition: bake requests exist and the run bakes.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    let n = crate::schedule::count_with::<BakeRequest>(world);
    if n == 0 {
        return Decision::skip("no bake requests");
    }
    if !frame.tasks.bake {
        return Decision::skip(format!("{n} bake request(s), but this run does not bake (use `stagelight bake` or `render --bake`)"));
    }
    Decision::run(format!("{n} bake request(s)"))
}

/// A request checked and rasterized, ready to bake.
struct Prepared {
    request: BakeRequest,
    slot: usize,
    uvs: Vec<[glam::Vec2; 3]>,
    coverage: Coverage,
    world_area: f64,
}

fn located(link: Option<&SourceLink>, name: &str, message: impl std::fmt::Display) -> String {
    match link {
        Some(l) => format!(
            "{}:{}:{}: error: bake request on instance \"{name}\": {message}",
            l.file.display(),
            l.line,
            l.column
        ),
        None => format!("error: bake request on instance \"{name}\": {message}"),
    }
}

/// Bakes every request.
pub fn run(world: &mut World, frame: &mut Frame) -> Result<Work, StageError> {
    let geometry = frame.geometry.as_ref().ok_or_else(|| {
        StageError::Invalid(
            "bake requests exist but no geometry was built (instances without triangles?)".into(),
        )
    })?;
    let mut requests: Vec<(Entity, BakeRequest, Option<SourceLink>)> = world
        .query::<(Entity, &BakeRequest, Option<&SourceLink>)>()
        .iter()
        .map(|(e, r, l)| (e, r.clone(), l.cloned()))
        .collect();
    requests.sort_by_key(|(e, ..)| e.to_bits());
    let mut emitters: Vec<(Entity, Emitter)> = world
        .query::<(Entity, &Emitter)>()
        .iter()
        .map(|(e, l)| (e, l.clone()))
        .collect();
    emitters.sort_by_key(|(e, _)| e.to_bits());
    let emitters: Vec<Emitter> = emitters.into_iter().map(|(_, l)| l).collect();
    let environment = world
        .query::<&crate::components::Environment>()
        .iter()
        .next()
        .cloned();
    let lights = LightSet::new(&emitters, Some(geometry), frame.settings.light_samples)
        .with_environment(environment.as_ref());
    let slot_of: HashMap<Entity, usize> = geometry
        .instances
        .iter()
        .enumerate()
        .map(|(i, g)| (g.entity, i))
        .collect();

    // Phase 1: check and rasterize every request before baking anything.
    let mut prepared = Vec::with_capacity(requests.len());
    let mut errors = Vec::new();
    for (entity, request, link) in &requests {
        let name = &request.name;
        let Some(&slot) = slot_of.get(entity) else {
            errors.push(located(
                link.as_ref(),
                name,
                "the instance has no triangles",
            ));
            continue;
        };
        let inst = &geometry.instances[slot];
        let page = match request.resolution {
            crate::components::BakeResolution::Fixed { width, height } => width.max(height).max(1),
            crate::components::BakeResolution::Density { max_size, .. } => {
                max_size.clamp(1, UNWRAP_PAGE)
            }
        };
        let uvs = match corner_uvs(&inst.mesh, request.uvs, page, request.padding) {
            Ok(u) => u,
            Err(e) => {
                errors.push(located(link.as_ref(), name, e));
                continue;
            }
        };
        let mut world_area = 0.0f64;
        let mut uv_area = 0.0f64;
        for (t, uv) in uvs.iter().enumerate() {
            let [a, b, c] = geometry.accel.triangle(inst.first_triangle + t as u32);
            world_area += 0.5 * (b - a).cross(c - a).length() as f64;
            uv_area += 0.5 * ((uv[1] - uv[0]).perp_dot(uv[2] - uv[0]) as f64).abs();
        }
        let (w, h) = match bake_resolution(request.resolution, world_area, uv_area) {
            Ok(r) => r,
            Err(e) => {
                errors.push(located(link.as_ref(), name, e));
                continue;
            }
        };
        let coverage = rasterize(&uvs, w, h, request.texel_samples);
        let needs_unique = request
            .targets
            .iter()
            .any(|t| !matches!(t.kind, BakeKind::Albedo));
        if needs_unique
            && coverage.overlaps as f64 > OVERLAP_TOLERANCE * coverage.inside.max(1) as f64
        {
            errors.push(located(
                link.as_ref(),
                name,
                format!(
                    "its UVs overlap ({} of {} sample positions lie in two or more triangles); {} needs unique UVs\n  help: set `uvs: Unwrap` to generate lightmap UVs",
                    coverage.overlaps,
                    coverage.inside,
                    request.targets.iter().find(|t| !matches!(t.kind, BakeKind::Albedo)).map_or("this bake", |t| t.kind.suffix())
                ),
            ));
            continue;
        }
        prepared.push(Prepared {
            request: request.clone(),
            slot,
            uvs,
            coverage,
            world_area,
        });
    }
    if !errors.is_empty() {
        return Err(StageError::Invalid(errors.join("\n")));
    }

    // Phase 2: bake.
    let seed = fold_seed(frame.settings.seed);
    let total_rows: u64 = prepared.iter().map(|p| p.coverage.height as u64).sum();
    let progress = Progress::start(frame.progress, "bake", "rows", total_rows);
    let cancel: &AtomicBool = &frame.cancel;
    let mut pending = Vec::new();
    let mut reports = Vec::new();
    let mut texels_baked = 0u64;
    for (index, p) in prepared.iter().enumerate() {
        let start = Instant::now();
        let kinds: Vec<BakeKind> = p.request.targets.iter().map(|t| t.kind.clone()).collect();
        let job = TexelJob {
            geometry,
            instance: &geometry.instances[p.slot],
            lights: &lights,
            coverage: &p.coverage,
            kinds: &kinds,
            uvs: &p.uvs,
            seed: hash_combine(&[seed, index as u32]),
            settings: &frame.settings,
        };
        let Some(mut results) = evaluate(&job, cancel, &progress.ticker()) else {
            return Err(StageError::Interrupted);
        };
        let covered = p.coverage.covered_texels();
        texels_baked += covered;
        // Texels baked from the surface (covered and not inside geometry), before dilation.
        let baked_mask = results.images.first().map(|img| img.valid.clone());
        let mut dilated = 0;
        for img in &mut results.images {
            dilated = dilate(img, p.request.padding);
        }
        let mut files = Vec::new();
        let safe_name = p.request.name.replace(['/', '\\'], "_");
        for (target, img) in p.request.targets.iter().zip(&results.images) {
            let file = target.file.clone().unwrap_or_else(|| {
                PathBuf::from(format!(
                    "{safe_name}_{}.{}",
                    target.kind.suffix(),
                    target.format.extension()
                ))
            });
            let color = matches!(target.kind, BakeKind::Lightmap { .. } | BakeKind::Albedo);
            let signed = matches!(target.kind, BakeKind::Normals { .. });
            let bytes =
                encode(img, target.format, color, signed).map_err(|message| StageError::Write {
                    path: file.clone(),
                    message,
                })?;
            files.push(frame.bake_dir.join(file));
            pending.push(PendingFile {
                path: files.last().cloned().unwrap_or_default(),
                bytes,
            });
        }
        if results.images.len() > p.request.targets.len() {
            let img = &results.images[results.images.len() - 1];
            let path = frame.bake_dir.join(format!("{safe_name}_bent_normals.exr"));
            let bytes = img.encode_exr().map_err(|message| StageError::Write {
                path: path.clone(),
                message,
            })?;
            files.push(path.clone());
            pending.push(PendingFile { path, bytes });
        }
        if p.request.mask {
            if let Some(first) = results.images.first() {
                let path = frame.bake_dir.join(format!("{safe_name}_mask.png"));
                let mut mask = first.clone();
                // The mask shows texels baked from the surface, not dilated or invalid ones.
                if let Some(baked) = &baked_mask {
                    mask.valid.clone_from(baked);
                }
                let bytes = mask
                    .encode_mask_png()
                    .map_err(|message| StageError::Write {
                        path: path.clone(),
                        message,
                    })?;
                files.push(path.clone());
                pending.push(PendingFile { path, bytes });
            }
        }
        let seconds = start.elapsed().as_secs_f64();
        reports.push(BakeReport {
            name: p.request.name.clone(),
            width: p.coverage.width,
            height: p.coverage.height,
            texels_per_unit: if p.world_area > 0.0 {
                (covered as f64 / p.world_area).sqrt()
            } else {
                0.0
            },
            covered_texels: covered,
            invalid_texels: results.invalid,
            dilated_texels: dilated,
            rays: results.rays,
            seconds,
            rays_per_second: if seconds > 0.0 {
                results.rays as f64 / seconds
            } else {
                0.0
            },
            files: files.iter().map(|f| f.display().to_string()).collect(),
        });
    }
    progress.finish();
    if frame.cancelled() {
        return Err(StageError::Interrupted);
    }
    let written = commit_all(&pending).map_err(|(path, e)| StageError::Write {
        path,
        message: e.to_string(),
    })?;
    frame.written.extend(written);
    frame.bake_reports = reports;
    Ok(Work {
        items: texels_baked,
        unit: "texels",
    })
}

/// Encodes a baked texture. Colour kinds go through sRGB in PNG; normals are mapped from
/// [−1, 1] to [0, 1] in PNG; everything is linear in EXR.
fn encode(
    img: &crate::bake::TexelImage,
    format: BakeFormat,
    color: bool,
    signed: bool,
) -> Result<Vec<u8>, String> {
    match format {
        BakeFormat::Exr => img.encode_exr(),
        BakeFormat::Png8 | BakeFormat::Png16 => {
            let mapped;
            let img = if signed {
                mapped = crate::bake::TexelImage {
                    texels: img
                        .texels
                        .iter()
                        .map(|n| *n * 0.5 + glam::Vec3::splat(0.5))
                        .collect(),
                    ..img.clone()
                };
                &mapped
            } else {
                img
            };
            img.encode_png(format == BakeFormat::Png16, color)
        }
    }
}

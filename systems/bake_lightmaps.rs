//! `bake_lightmaps`: bakes every bake request (ambient occlusion, lightmaps, normals,
//! positions, albedo) into textures, denoises those that ask for it, dilates them and
//! stitches AO and lightmaps across UV seams (`crate::bake::finish`); the runner writes them with the run's
//! other files, all or nothing.
//!
//! **Reads:** `BakeRequest` + `Name` + `SourceLink` on instance entities; `Emitter` entities;
//! `outputs.geometry`; `inputs.bake_dir`; `inputs.write_gltf`; `settings.seed`.
//! **Writes:** texture files (encoded, in `Work::pending`, committed by the runner), and
//! with `inputs.write_gltf` the baked glTF referencing them (per-vertex bakes as
//! `COLOR_0`): the copy of a glTF scene (`crate::bake::gltf_out`), else a standalone file of
//! the placed geometry (`crate::bake::gltf_export`);
//! `outputs.bake_reports`.
//! **Runs when:** the run bakes (`stagelight bake` or `render --bake`) and at least one
//! instance carries a bake request. A bake part that owns no texel writes only its empty
//! part file: where every request has a fixed size and only texture targets this is known
//! before the geometry stages (`crate::scene_view::idle_bake_part`: they skip, and the
//! stage runs without geometry, its reason saying so); otherwise the stage finds it after
//! sizing the requests and is reported skipped (`idle_part`).
//! **After this stage:** every requested texture exists complete (or none was written), and
//! a report per request gives texel density, coverage, invalid texels, rays and time.
//!
//! Every request is checked (UVs, resolution, overlapping UVs; `crate::bake::request`)
//! before any texel is baked; naming and encoding live in `crate::bake::files`. Per-vertex
//! targets (`target: Vertices`) are a request of their own whose texels are the mesh's
//! vertices (`crate::bake::vertices`), baked by the same estimators, not dilated, written
//! as PLY (`crate::bake::vertex_files`); farm parts split and merge them like textures.
//!
//! Farm parts (`crate::farm::bake_part`): a `bake --part K/N` run (`inputs.part`) bakes only
//! its texel tiles and writes them undilated as one bake part file instead of textures; a
//! merge (`inputs.merged_bake`) takes every texel from the merged parts and dilates and
//! encodes them exactly as a single bake does (and with `inputs.write_gltf`, from `merge
//! --write-gltf`, writes the same glTF copy).

use std::time::Instant;

use hecs::World;

use super::prelude::*;
use crate::bake::clipping::{clip_warning, clipped_texels};
use crate::bake::files::{encode_request, report, safe_name, target_file};
use crate::bake::glb_build::TextureSlot;
use crate::bake::gltf_textures::gltf_texture;
use crate::bake::request::prepare_bakes;
use crate::bake::request::PreparedBake;
use crate::bake::texels::TexelResults;
use crate::bake::texels::{evaluate, TexelJob};
use crate::bake::vertex_files::{encode_vertex_request, VertexValues};
use crate::components::{BakeKind, BakeRequest};
use crate::farm::bake_part::{first_tiles, tiles_of, BakePartFile, BakePartRequest, TexelOwner};
use crate::farm::idle_bake_part::owns_no_texel;
use crate::farm::PartRun;
use crate::progress::Progress;
use crate::sampling::{fold_seed, hash_combine};
use crate::scene_view::{light_set, WithEnvironment};

/// Run condition: bake requests exist and the run bakes.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    let n = crate::schedule::count_with::<BakeRequest>(world);
    if n == 0 {
        return Decision::skip("no bake requests");
    }
    if !frame.inputs.tasks.bake {
        return Decision::skip(format!("{n} bake request(s), but this run does not bake (use `stagelight bake` or `render --bake`)"));
    }
    if let Some(why) = crate::scene_view::idle_bake_part(world, &frame.inputs) {
        return Decision::run(format!("{n} bake request(s); {why}: {ONLY_EMPTY_PART}"));
    }
    Decision::run(format!("{n} bake request(s)"))
}

/// What a bake part that owns no texel does, known before the geometry stages.
const ONLY_EMPTY_PART: &str = "only its empty part file is written";

/// The empty part file of a bake part that owns no texel, where the scene alone tells
/// (`crate::scene_view::idle_bake_part`): made from the requests' fixed sizes, without
/// geometry, and the same bytes a part that found itself idle after building it writes.
fn empty_part(run: &PartRun, world: &World, frame: &Frame) -> Result<Work, StageError> {
    let requests = crate::farm::idle_bake_part::empty_requests(world)
        .ok_or_else(|| StageError::Internal("an idle bake part without fixed sizes".into()))?;
    let file = part_file(run, frame, requests)?;
    Ok(Work::new(0, "texels")
        .with_pending(vec![file])
        .with_output(StageOutput::BakeReports(Vec::new())))
}

/// Bakes every request.
pub fn run(world: &World, frame: &Frame) -> Result<Work, StageError> {
    if let Some(run) = frame.inputs.part.as_ref() {
        if crate::scene_view::idle_bake_part(world, &frame.inputs).is_some() {
            return empty_part(run, world, frame);
        }
    }
    // Phase 1: check and rasterize every request before baking anything.
    let prepared = prepare_bakes(world, frame.outputs.geometry.as_ref())?;
    for p in &prepared {
        for (message, help) in &p.warnings {
            warn_at_request(p, message, help);
        }
    }
    let geometry = frame
        .outputs
        .geometry
        .as_ref()
        .ok_or_else(|| StageError::Internal("bake requests passed without geometry".into()))?;
    let inputs = &frame.inputs;
    let lights = light_set(
        world,
        Some(geometry),
        &inputs.settings,
        WithEnvironment::Yes,
    );

    // Phase 2: bake (or take the texels merged from farm parts).
    let seed = fold_seed(inputs.settings.seed);
    let total_rows: u64 = prepared.iter().map(|p| p.coverage.height as u64).sum();
    let progress = Progress::start(inputs.progress, "bake", "rows", total_rows);
    let firsts = first_tiles(
        prepared
            .iter()
            .map(|p| (p.coverage.width, p.coverage.height)),
    );
    let idle = idle_part(frame, &prepared);
    let mut pending = Vec::new();
    let mut reports = Vec::new();
    let mut part_requests = Vec::new();
    let mut texels_baked = 0u64;
    // For `--write-gltf`: each request's (index) textures with their slots, and per-vertex
    // values.
    let mut baked_pngs: Vec<(usize, TextureSlot, Vec<u8>)> = Vec::new();
    let mut vertex_colors: Vec<(usize, VertexValues)> = Vec::new();
    for (index, p) in prepared.iter().enumerate() {
        let start = Instant::now();
        let mut results = if let Some(merged) = &inputs.merged_bake {
            merged_results(merged, index, p)?
        } else {
            let kinds: Vec<BakeKind> = p.request.targets.iter().map(|t| t.kind.clone()).collect();
            let owner = inputs.part.as_ref().map(|run| TexelOwner {
                first_tile: firsts[index],
                width: p.coverage.width,
                count: run.part.count,
                index: run.part.index,
            });
            let owns = owner.map(|o| move |i: u32, j: u32| o.owns(i, j));
            let job = TexelJob {
                geometry,
                instance: &geometry.instances[p.slot],
                lights: &lights,
                coverage: &p.coverage,
                kinds: &kinds,
                uvs: &p.uvs,
                seed: hash_combine(&[seed, index as u32]),
                settings: &inputs.settings,
                owns: owns
                    .as_ref()
                    .map(|f| f as &(dyn Fn(u32, u32) -> bool + Sync)),
            };
            let Some(results) = evaluate(&job, &inputs.cancel, &progress.ticker()) else {
                return Err(StageError::Interrupted);
            };
            results
        };
        if inputs.part.is_some() {
            // A farm part keeps its texels undilated for the merge.
            texels_baked += results
                .images
                .first()
                .map_or(0, |img| img.valid.iter().filter(|&&v| v).count() as u64);
            part_requests.push(BakePartRequest {
                name: p.request.name.clone(),
                images: results.images,
                rays: results.rays,
                invalid: results.invalid,
            });
            continue;
        }
        texels_baked += p.coverage.covered_texels();
        if p.per_vertex() {
            // Vertices: no dilation; vertices without a value take their neighbours'.
            let mesh = &geometry.instances[p.slot].mesh;
            let baked = encode_vertex_request(p, &results, mesh, &inputs.bake_dir);
            let mut r = report(
                p,
                &results,
                baked.filled,
                start.elapsed().as_secs_f64(),
                &baked.files,
            );
            r.vertices = Some(mesh.positions.len() as u64);
            if inputs.merged_bake.is_some() {
                r.rays_per_second = 0.0;
                r.merged_parts = true;
            }
            reports.push(r);
            pending.extend(baked.files.pending);
            if inputs.write_gltf.is_some() {
                vertex_colors.push((index, baked.values));
            }
            continue;
        }
        // Texels baked from the surface (covered and not inside geometry), before dilation.
        let baked_mask = results.images.first().map(|img| img.valid.clone());
        let finished = crate::bake::finish::finish(
            p,
            &geometry.instances[p.slot].mesh,
            &mut results.images,
            baked_mask.as_deref(),
        );
        let files = encode_request(p, &results, baked_mask.as_deref(), &inputs.bake_dir)?;
        warn_clipped_outputs(p, &results.images);
        if let Some(source) = &inputs.write_gltf {
            // PNG outputs byte for byte, EXR ones as a PNG of the same texels.
            let targets = p.request.targets.iter().zip(&files.pending);
            for ((target, file), img) in targets.zip(&results.images) {
                let texture = gltf_texture(target, img, &file.bytes).map_err(|message| {
                    StageError::Write {
                        path: crate::bake::gltf_out::baked_glb_path(source, &inputs.bake_dir),
                        message,
                    }
                })?;
                if let Some((slot, png)) = texture {
                    baked_pngs.push((index, slot, png));
                }
            }
        }
        let mut r = report(
            p,
            &results,
            finished.dilated,
            start.elapsed().as_secs_f64(),
            &files,
        );
        r.seams = finished.seams;
        if inputs.merged_bake.is_some() {
            // The rays are the parts' total; the merge itself traces none.
            r.rays_per_second = 0.0;
            r.merged_parts = true;
        }
        reports.push(r);
        pending.extend(files.pending);
    }
    progress.finish();
    if frame.cancelled() {
        return Err(StageError::Interrupted);
    }
    if let Some(run) = &inputs.part {
        pending.push(part_file(run, frame, part_requests)?);
    }
    if let Some(source) = &inputs.write_gltf {
        let baked = BakedOutputs {
            prepared: &prepared,
            pngs: &baked_pngs,
            vertex_colors: &vertex_colors,
        };
        let path = crate::bake::gltf_out::baked_glb_path(source, &inputs.bake_dir);
        let bytes = if crate::bake::gltf_out::is_gltf_scene(source) {
            baked_gltf(source, &baked, &path)
        } else {
            standalone_gltf(world, geometry, &baked)
        };
        let bytes = bytes.map_err(|message| StageError::Write {
            path: path.clone(),
            message,
        })?;
        pending.push(crate::image_io::PendingFile::new(path, bytes));
    }
    let work = Work::new(texels_baked, work_unit(&prepared))
        .with_pending(pending)
        .with_output(StageOutput::BakeReports(reports));
    Ok(match idle {
        Some(why) => work.reused(why),
        None => work,
    })
}

/// What the stage's items count: the texels of texture bakes and the vertices of per-vertex
/// bakes (a per-vertex bake's texels are its vertices).
fn work_unit(prepared: &[PreparedBake]) -> &'static str {
    let vertices = prepared.iter().filter(|p| p.per_vertex()).count();
    match vertices {
        0 => "texels",
        n if n == prepared.len() => "vertices",
        _ => "texels+vertices",
    }
}

/// Why a bake part (`bake --part K/N`) owns no texel, if it owns none: `K` is past the
/// number of tiles of all `prepared` requests. It traces no rays and writes an empty part
/// file; the stage is then reported skipped for this reason, which says what its time was
/// spent on. (The texture sizes of density-sized and per-vertex requests come from the
/// built geometry, so this is known only here, after the geometry stages; a part of
/// fixed-size texture requests is found idle before them: [`empty_part`].)
fn idle_part(frame: &Frame, prepared: &[PreparedBake]) -> Option<String> {
    let run = frame.inputs.part.as_ref()?;
    if frame.inputs.merged_bake.is_some() {
        return None;
    }
    let tiles = bake_tiles(prepared);
    (u64::from(run.part.index) > tiles).then(|| {
        format!(
            "{}; its part file is written empty (the time reported: sizing the requests from the geometry and writing that file)",
            owns_no_texel(run.part, tiles, prepared.len())
        )
    })
}

/// The texel tiles of all `prepared` requests, which a bake's parts share out.
pub fn bake_tiles(prepared: &[PreparedBake]) -> u64 {
    prepared
        .iter()
        .map(|p| tiles_of(p.coverage.width, p.coverage.height))
        .sum()
}

/// The texels of request `index` as merged from farm parts, checked against the request the
/// scene prepares (the merge already checked the scene's content hash).
fn merged_results(
    merged: &crate::farm::bake_part::MergedBake,
    index: usize,
    p: &PreparedBake,
) -> Result<TexelResults, StageError> {
    let request = merged
        .requests
        .get(index)
        .filter(|r| r.name == p.request.name)
        .filter(|r| {
            r.images
                .iter()
                .all(|img| (img.width, img.height) == (p.coverage.width, p.coverage.height))
        })
        .ok_or_else(|| {
            StageError::Internal(format!(
                "the merged bake parts do not hold request {} as the scene prepares it",
                p.request.name
            ))
        })?;
    Ok(TexelResults {
        images: request.images.clone(),
        rays: request.rays,
        invalid: request.invalid,
    })
}

/// The bake part file of a `bake --part K/N` run, written into the bake directory.
fn part_file(
    run: &PartRun,
    frame: &Frame,
    requests: Vec<BakePartRequest>,
) -> Result<crate::image_io::PendingFile, StageError> {
    let settings = &frame.inputs.settings;
    let file = BakePartFile {
        header: crate::farm::part_file::PartHeader {
            version: env!("CARGO_PKG_VERSION").into(),
            scene: run.scene.clone(),
            scene_hash: run.scene_hash,
            settings_hash: crate::farm::settings_hash(settings),
            recorded: crate::farm::recorded_settings::RecordedSettings::of(settings),
            seed: settings.seed,
            part: run.part,
            width: 0,
            height: 0,
        },
        requests,
    };
    let path = frame
        .inputs
        .bake_dir
        .join(crate::farm::bake_part::part_file_name(
            run.part.index,
            run.part.count,
        ));
    let bytes =
        crate::farm::bake_part_file::encode(&file).map_err(|message| StageError::Write {
            path: path.clone(),
            message,
        })?;
    Ok(crate::image_io::PendingFile::new(path, bytes))
}

/// What a bake wrote that the baked glTF file (`--write-gltf`) takes: per request (by its
/// index in `prepared`) the PNG textures with their material slots
/// (`crate::bake::gltf_textures`) and the per-vertex values.
struct BakedOutputs<'a> {
    prepared: &'a [PreparedBake],
    pngs: &'a [(usize, TextureSlot, Vec<u8>)],
    vertex_colors: &'a [(usize, VertexValues)],
}

/// The glTF copy of `source` referencing the baked PNGs (`bake --write-gltf` of a glTF
/// scene), to be written at `path`.
fn baked_gltf(
    source: &std::path::Path,
    baked: &BakedOutputs<'_>,
    path: &std::path::Path,
) -> Result<Vec<u8>, String> {
    use crate::bake::gltf_out::{baked_glb, color_source, BakedColors, BakedTexture};
    let same = |a: &std::path::Path, b: &std::path::Path| matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y);
    if same(path, source) {
        return Err("it is the glTF file being baked; bake into another directory (-o DIR)".into());
    }
    let bytes = std::fs::read(source).map_err(|e| e.to_string())?;
    let leaves =
        crate::scene::import::gltf_scene::primitive_instances(source, &bytes).map_err(|e| {
            e.iter()
                .map(|d| d.message.clone())
                .collect::<Vec<_>>()
                .join("; ")
        })?;
    let leaf = |index: usize| {
        let name = &baked.prepared[index].request.name;
        leaves
            .iter()
            .find(|(n, ..)| n == name)
            .map(|(_, node, primitive)| (*node, *primitive))
    };
    let mut textures = Vec::new();
    for (index, slot, png) in baked.pngs {
        let Some((node, primitive)) = leaf(*index) else {
            continue;
        };
        textures.push(BakedTexture {
            node,
            primitive,
            slot: *slot,
            png,
        });
    }
    let mut colors = Vec::new();
    for (index, targets) in baked.vertex_colors {
        let Some((node, primitive)) = leaf(*index) else {
            continue;
        };
        if let Some(values) = color_source(targets) {
            colors.push(BakedColors {
                node,
                primitive,
                values,
            });
        }
    }
    baked_glb(source, &textures, &colors)
}

/// The standalone glTF file of a scene that is not glTF (`bake scene.ron --write-gltf`):
/// every placed instance as a node, the baked ones with their textures or vertex colours
/// (`crate::bake::gltf_export`).
fn standalone_gltf(
    world: &World,
    geometry: &crate::geometry::SceneGeometry,
    baked: &BakedOutputs<'_>,
) -> Result<Vec<u8>, String> {
    use crate::bake::gltf_export::{standalone_glb, ExportedInstance, InstanceBake};
    use crate::bake::gltf_out::color_source;
    use crate::components::Name;
    let name_of = |entity: hecs::Entity| world.get::<&Name>(entity).ok().map(|n| n.0.clone());
    let mut instances: Vec<ExportedInstance<'_>> = geometry
        .instances
        .iter()
        .enumerate()
        .map(|(slot, inst)| ExportedInstance {
            name: name_of(inst.entity).unwrap_or_else(|| format!("instance{slot}")),
            bake: None,
        })
        .collect();
    for (index, p) in baked.prepared.iter().enumerate() {
        let exported = &mut instances[p.slot];
        exported.name = p.request.name.clone();
        exported.bake = Some(if p.per_vertex() {
            let values = baked
                .vertex_colors
                .iter()
                .find(|(i, _)| *i == index)
                .and_then(|(_, targets)| color_source(targets));
            InstanceBake::Colors(values)
        } else {
            let textures = baked
                .pngs
                .iter()
                .filter(|(i, ..)| *i == index)
                .map(|(_, slot, png)| (*slot, png.as_slice()))
                .collect();
            InstanceBake::Textures {
                uvs: &p.uvs,
                textures,
            }
        });
    }
    let material_names: Vec<String> = geometry
        .material_entities
        .iter()
        .enumerate()
        .map(|(k, &e)| name_of(e).unwrap_or_else(|| format!("material{k}")))
        .collect();
    standalone_glb(geometry, &instances, &material_names)
}

/// Warns, located at the request, about each PNG output of `p` whose values its range
/// clips (`crate::bake::clipping`).
fn warn_clipped_outputs(p: &PreparedBake, images: &[crate::bake::TexelImage]) {
    for (target, img) in p.request.targets.iter().zip(images) {
        let Some(clipped) = clipped_texels(img, target) else {
            continue;
        };
        let file = target_file(&safe_name(&p.request), target);
        let (message, help) = clip_warning(&clipped, target, &file.to_string_lossy());
        warn_at_request(p, &message, &help);
    }
}

/// Warns, located at the request when it came from a scene file:
/// `bake request on instance "NAME": MESSAGE` with the help.
fn warn_at_request(p: &PreparedBake, message: &str, help: &str) {
    let text = format!(
        "bake request on instance \"{}\": {message}\n  help: {help}",
        p.request.name
    );
    match &p.link {
        Some(l) => {
            let at = format!("{}:{}:{}", l.file.display(), l.line, l.column);
            tracing::warn!(file = %at, "{text}");
        }
        None => tracing::warn!("{text}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::systems::tiny_scene::{load, run_until, scene};

    const BAKED: &str =
        "bake: (resolution: (8, 8), outputs: [(kind: AmbientOcclusion(samples: 4))])";

    #[test]
    fn an_open_square_bakes_ao_of_one_and_reports_its_file() {
        let dir = std::env::temp_dir().join(format!("stagelight-unit-bake-{}", std::process::id()));
        let (mut world, mut frame) = load(&scene("", BAKED, "", &[]), true);
        frame.inputs.bake_dir = dir.clone();
        run_until("bake_lightmaps", &mut world, &mut frame);
        assert_eq!(
            should_run(&world, &frame),
            Decision::run("1 bake request(s)")
        );
        let work = run(&world, &frame).unwrap();
        assert_eq!(
            work.items, 64,
            "every texel of the unit-UV square is covered"
        );
        assert_eq!(work.files, vec![dir.join("square_inst_ao.exr")]);
        assert!(!work.pending[0].bytes.is_empty());
        let Some(StageOutput::BakeReports(reports)) = work.output else {
            panic!("bake_lightmaps returns its reports");
        };
        assert_eq!(reports.len(), 1);
        assert_eq!(
            (reports[0].covered_texels, reports[0].invalid_texels),
            (64, 0)
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn skipped_without_requests_or_when_the_run_does_not_bake() {
        let (world, frame) = load(&scene("", "", "", &[]), true);
        assert_eq!(
            should_run(&world, &frame),
            Decision::skip("no bake requests")
        );
        let (world, frame) = load(&scene("", BAKED, "", &[]), false);
        assert_eq!(
            should_run(&world, &frame),
            Decision::skip("1 bake request(s), but this run does not bake (use `stagelight bake` or `render --bake`)")
        );
    }
}

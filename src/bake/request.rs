//! Checking bake requests before any texel is baked: each request's instance must have
//! triangles, its UVs must exist (or be generated), its resolution must be valid, and its
//! UVs must not overlap where the kind needs unique UVs. Every problem of every request is
//! collected, located at the request in the scene file where it came from one.

use std::collections::HashMap;

use hecs::{Entity, World};

use super::density::{placed_area, uv_area, uv_placement};
use super::{bake_resolution, corner_uvs, rasterize, second_set_corner_uvs, Coverage};
use crate::components::{
    BakeKind, BakeRequest, BakeResolution, BakeTarget, Instance, SecondUvs, SourceLink, TriMesh,
    UvSource,
};
use crate::geometry::SceneGeometry;
use crate::scene::Diagnostic;
use crate::stage_error::StageError;

/// Fraction of sample positions that may fall in two triangles before UVs count as
/// overlapping.
const OVERLAP_TOLERANCE: f64 = 1e-3;
/// UV page size used when generating lightmap UVs for density-sized bakes.
const UNWRAP_PAGE: u32 = 1024;
/// The UV area of charts packed without padding on an [`UNWRAP_PAGE`] page, when sizing a
/// bake from texel density, is multiplied by this before the size is chosen: the packer
/// rounds every chart up to whole texels of that page, so a chart that fills a power of
/// two's worth of texels (a 2 × 2 quad at 32 texels/unit: 64) would otherwise round up to
/// the next (128), at twice the requested density.
const PACKING_ROUNDING: f64 = 1.02;
/// The problem of a request whose instance has nothing to bake: no triangle that is not
/// degenerate (the scene has no geometry at all, or the mesh's triangles were all dropped
/// as degenerate while other instances have some).
const NO_TRIANGLES: &str = "the instance has no triangles";
/// Share of a request's UV area that may lie outside the unit square without a warning
/// (rounding of UVs written at 0 or 1).
const OUTSIDE_TOLERANCE: f64 = 1e-6;

/// A request checked and rasterized, ready to bake.
pub struct PreparedBake {
    /// The request.
    pub request: BakeRequest,
    /// Index of its instance in `SceneGeometry::instances`.
    pub slot: usize,
    /// Per-triangle corner UVs.
    pub uvs: Vec<[glam::Vec2; 3]>,
    /// Texel coverage at the chosen resolution.
    pub coverage: Coverage,
    /// World-space area of the part of the instance that is baked: the whole instance, less
    /// the triangles' parts whose UVs lie outside the unit square (for the report's texel
    /// density).
    pub world_area: f64,
    /// Where the request stands in the scene file, when it came from one.
    pub link: Option<SourceLink>,
    /// Warnings about the request, (message, help), for the bake stage to print located at
    /// the request.
    pub warnings: Vec<(String, String)>,
}

impl PreparedBake {
    /// Whether this bake's texels are the mesh's vertices (`target: Vertices`).
    pub fn per_vertex(&self) -> bool {
        self.request
            .targets
            .first()
            .is_some_and(|t| t.format.is_per_vertex())
    }
}

/// One request's problem, located where possible.
struct Problem<'a> {
    link: Option<&'a SourceLink>,
    instance: &'a str,
    message: String,
    help: Option<String>,
}

/// Every bake request of the world, in entity order, checked and rasterized; or every
/// problem found. Without geometry (no instance had triangles) every request is refused.
pub fn prepare_bakes(
    world: &World,
    geometry: Option<&SceneGeometry>,
) -> Result<Vec<PreparedBake>, StageError> {
    let mut requests: Vec<(Entity, BakeRequest, Option<SourceLink>)> = world
        .query::<(Entity, &BakeRequest, Option<&SourceLink>)>()
        .iter()
        .map(|(e, r, l)| (e, r.clone(), l.cloned()))
        .collect();
    requests.sort_by_key(|(e, ..)| e.to_bits());
    let slot_of: HashMap<Entity, usize> = geometry
        .map(|g| g.instances.iter().enumerate().map(|(i, g)| (g.entity, i)))
        .into_iter()
        .flatten()
        .collect();
    let mut prepared = Vec::with_capacity(requests.len());
    let mut problems = Vec::new();
    for (entity, request, link) in &requests {
        let problem = |message: String, help: Option<String>| Problem {
            link: link.as_ref(),
            instance: &request.name,
            message,
            help,
        };
        let (Some(&slot), Some(geometry)) = (slot_of.get(entity), geometry) else {
            problems.push(problem(NO_TRIANGLES.into(), None));
            continue;
        };
        if !has_triangles(&geometry.instances[slot]) {
            // Not "its UVs cover no area": no UVs would help a mesh without triangles.
            problems.push(problem(NO_TRIANGLES.into(), None));
            continue;
        }
        let second = world
            .get::<&Instance>(*entity)
            .ok()
            .and_then(|i| world.get::<&SecondUvs>(i.object).ok().map(|s| s.0.clone()));
        let (textures, vertices) = split_targets(request);
        // Warnings about the kinds go with the first part of a split request only.
        let mut kind_warnings = kind_warnings(request);
        if let Some(textures) = textures {
            let unwrap = unwrap_advice(link.as_ref().map(|l| l.file.as_path()));
            match prepare(
                &textures,
                slot,
                geometry,
                second.as_deref().map(|v| v.as_slice()),
                &unwrap,
            ) {
                Ok(mut p) => {
                    p.warnings.splice(0..0, std::mem::take(&mut kind_warnings));
                    prepared.push(PreparedBake {
                        link: link.clone(),
                        ..p
                    })
                }
                Err((message, help)) => problems.push(problem(message, help)),
            }
        }
        if let Some(vertices) = vertices {
            prepared.push(PreparedBake {
                link: link.clone(),
                warnings: std::mem::take(&mut kind_warnings),
                ..prepare_vertices(vertices, slot, geometry)
            });
        }
    }
    if problems.is_empty() {
        return Ok(prepared);
    }
    if problems.iter().all(|p| p.link.is_some()) {
        return Err(StageError::Scene(
            problems
                .iter()
                .filter_map(|p| {
                    let l = p.link?;
                    Some(Diagnostic {
                        file: l.file.clone(),
                        line: l.line,
                        column: l.column,
                        message: format!(
                            "bake request on instance \"{}\": {}",
                            p.instance, p.message
                        ),
                        help: p.help.clone(),
                    })
                })
                .collect(),
        ));
    }
    let first = &problems[0];
    Err(StageError::Bake {
        instance: first.instance.to_string(),
        message: match &first.help {
            Some(h) => format!("{}\n  help: {h}", first.message),
            None => first.message.clone(),
        },
    })
}

/// The request's texture targets and its per-vertex targets as two requests (either
/// `None` when it has no such target); the per-vertex one writes no mask.
fn split_targets(request: &BakeRequest) -> (Option<BakeRequest>, Option<BakeRequest>) {
    let (vertex, texture): (Vec<_>, Vec<_>) = request
        .targets
        .iter()
        .cloned()
        .partition(|t| t.format.is_per_vertex());
    let with = |targets: Vec<BakeTarget>, mask: bool| {
        (!targets.is_empty()).then(|| BakeRequest {
            targets,
            mask,
            ..request.clone()
        })
    };
    (with(texture, request.mask), with(vertex, false))
}

/// Whether the instance has a triangle that is not degenerate where it is placed (the
/// loader drops degenerate triangles, which may leave a mesh with none).
fn has_triangles(inst: &crate::geometry::InstanceGeometry) -> bool {
    let world = |i: u32| {
        let p = inst.mesh.positions.get(i as usize).copied();
        inst.world_from_object
            .transform_point3(p.unwrap_or(glam::Vec3::NAN))
    };
    inst.mesh
        .triangles
        .iter()
        .any(|t| !crate::accel::is_degenerate(&t.map(world)))
}

/// A per-vertex request: every vertex of the instance's mesh as a texel
/// ([`super::vertices`]).
fn prepare_vertices(request: BakeRequest, slot: usize, geometry: &SceneGeometry) -> PreparedBake {
    let inst = &geometry.instances[slot];
    let coverage = super::vertices::vertex_coverage(
        &inst.mesh,
        &inst.world_from_object,
        request.texel_samples,
    );
    PreparedBake {
        uvs: super::vertices::no_uvs(&inst.mesh),
        request,
        slot,
        coverage,
        world_area: placed_area(&inst.mesh, &inst.world_from_object),
        link: None,
        warnings: Vec::new(),
    }
}

/// How to get lightmap UVs generated for a request declared in `file`: set `uvs: Unwrap`
/// in a scene that has the field; a glTF file's bakes are the reader's defaults on its
/// `TEXCOORD_1`, changed only in the RON that `stagelight convert` writes.
struct UnwrapAdvice {
    /// The sentence, starting with a verb.
    text: String,
    /// Whether the request comes from a glTF file.
    gltf: bool,
}

fn unwrap_advice(file: Option<&std::path::Path>) -> UnwrapAdvice {
    let gltf = file
        .and_then(|f| f.extension())
        .is_some_and(|e| e.eq_ignore_ascii_case("glb") || e.eq_ignore_ascii_case("gltf"));
    let text = match file {
        Some(file) if gltf => format!(
            "write the scene as RON (`stagelight convert {} -o scene.ron`) and set `uvs: Unwrap` in the instance's bake there to generate lightmap UVs (a glTF file's bakes read its TEXCOORD_1); `stagelight bake scene.ron --write-gltf` then writes the glTF with them as TEXCOORD_1",
            file.file_name().unwrap_or_default().to_string_lossy()
        ),
        _ => "set `uvs: Unwrap` to generate lightmap UVs".into(),
    };
    UnwrapAdvice { text, gltf }
}

/// Checks and rasterizes one request; the error is (message, help). `unwrap` says how to
/// have lightmap UVs generated for it ([`unwrap_advice`]).
fn prepare(
    request: &BakeRequest,
    slot: usize,
    geometry: &SceneGeometry,
    second: Option<&[glam::Vec2]>,
    unwrap: &UnwrapAdvice,
) -> Result<PreparedBake, (String, Option<String>)> {
    let inst = &geometry.instances[slot];
    let generated = generates_uvs(request.uvs, &inst.mesh);
    // In f64 from the object-space mesh: the same wherever the instance is placed.
    let world_area = placed_area(&inst.mesh, &inst.world_from_object);
    let corner_uvs_for = |page: u32, padding: u32| match (request.uvs, second) {
        (UvSource::SecondSet, Some(second)) => second_set_corner_uvs(&inst.mesh, second),
        _ => corner_uvs(&inst.mesh, request.uvs, page, padding),
    };
    let (uvs, (w, h)) = match request.resolution {
        BakeResolution::Density { .. } if generated => {
            // Measure the charts' UV area packed without padding, choose the size from it,
            // then pack for that size with the padding, which so holds in its texels.
            let measured = corner_uvs_for(UNWRAP_PAGE, 0).map_err(|e| (e.to_string(), None))?;
            let measured_area = uv_area(&measured) * PACKING_ROUNDING;
            let size = bake_resolution(request.resolution, world_area, measured_area)
                .map_err(|e| (e.to_string(), None))?;
            let uvs = corner_uvs_for(size.0.max(size.1), request.padding)
                .map_err(|e| (e.to_string(), None))?;
            (uvs, size)
        }
        _ => {
            let page = match request.resolution {
                BakeResolution::Fixed { width, height } => width.max(height).max(1),
                BakeResolution::Density { max_size, .. } => max_size.clamp(1, UNWRAP_PAGE),
            };
            let uvs = corner_uvs_for(page, request.padding).map_err(|e| (e.to_string(), None))?;
            let size = bake_resolution(request.resolution, world_area, uv_area(&uvs))
                .map_err(|e| (e.to_string(), None))?;
            (uvs, size)
        }
    };
    let advice = if generated {
        fit_advice(request, w, h)
    } else {
        unwrap.text.clone()
    };
    let uv_area = uv_area(&uvs);
    if uv_area.is_nan() || uv_area <= 0.0 {
        // All UVs at one point or on a line: nothing could be covered (issue 18, family 8).
        return Err((
            "its UVs cover no area (every triangle's UVs lie at one point or on a line)".into(),
            Some(if generated {
                advice
            } else {
                format!("give the mesh real UVs, or {advice}")
            }),
        ));
    }
    let coverage = rasterize(&uvs, w, h, request.texel_samples);
    if coverage.inside == 0 {
        // UVs wholly outside the texture: every texel would stay empty (a black map).
        return Err((
            "its UVs cover no texel of the texture (they lie outside [0, 1]², or between the sample positions)".into(),
            Some(if generated {
                advice.clone()
            } else {
                format!("bake UVs must lie in the unit square: {advice}")
            }),
        ));
    }
    let placement = uv_placement(&inst.mesh, &inst.world_from_object, &uvs);
    let mut warnings = Vec::new();
    if placement.outside_share > OUTSIDE_TOLERANCE {
        // Partly outside: the inside part bakes, the rest of the surface gets no texels.
        warnings.push((
            format!(
                "{} of its UV area lies outside the unit square [0, 1]²; that part of the surface is not baked",
                percent(placement.outside_share)
            ),
            if generated {
                advice.clone()
            } else {
                format!("bake UVs must lie in the unit square: {advice}")
            },
        ));
    }
    let unique = request
        .targets
        .iter()
        .find(|t| !matches!(t.kind, BakeKind::Albedo));
    if let Some(target) = unique {
        if coverage.overlaps as f64 > OVERLAP_TOLERANCE * coverage.inside.max(1) as f64 {
            return Err((
                format!(
                    "its UVs overlap ({} of {} sample positions lie in two or more triangles); {} needs unique UVs",
                    coverage.overlaps,
                    coverage.inside,
                    target.kind.suffix()
                ),
                Some(if unwrap.gltf && !generated {
                    format!("give TEXCOORD_1 unique lightmap UVs, or {advice}")
                } else {
                    advice.clone()
                }),
            ));
        }
    }
    Ok(PreparedBake {
        request: request.clone(),
        slot,
        uvs,
        coverage,
        world_area: placement.baked_world_area,
        link: None,
        warnings,
    })
}

/// Whether a request's UVs are generated by the unwrapper: `uvs: Unwrap`, or `Auto` on a
/// mesh without UVs.
fn generates_uvs(source: UvSource, mesh: &TriMesh) -> bool {
    match source {
        UvSource::Unwrap => true,
        UvSource::MeshOrUnwrap => mesh.uvs.is_none(),
        UvSource::Mesh | UvSource::SecondSet => false,
    }
}

/// The help when generated UVs overlap or cover no texel of the `width × height` texture:
/// the charts, packed with their padding, do not fit it (the unwrapper spreads them over
/// several pages), so it needs more texels or less padding.
fn fit_advice(request: &BakeRequest, width: u32, height: u32) -> String {
    let size = match request.resolution {
        BakeResolution::Fixed { .. } => "raise `resolution`",
        BakeResolution::Density { max_size, .. } if width.max(height) >= max_size => {
            "raise `max_size`"
        }
        BakeResolution::Density { .. } => "raise `texels_per_unit`",
    };
    format!(
        "the generated lightmap UVs do not fit a {width}×{height} texture with `padding: {}`: {size}, or lower `padding`",
        request.padding
    )
}

/// A share as a percentage for messages: one decimal, never rounded to 0 or 100.
fn percent(share: f64) -> String {
    let p = share * 100.0;
    if p < 0.1 {
        "less than 0.1%".into()
    } else if p > 99.9 {
        "more than 99.9%".into()
    } else {
        format!("{p:.1}%")
    }
}

/// Warnings about a request's kinds: a lightmap with `indirect: true` and `max_depth: 0`
/// gathers no indirect light (its bounces are `max_depth`).
fn kind_warnings(request: &BakeRequest) -> Vec<(String, String)> {
    request
        .targets
        .iter()
        .filter(|t| {
            matches!(
                t.kind,
                BakeKind::Lightmap {
                    indirect: true,
                    max_depth: 0,
                    ..
                }
            )
        })
        .map(|_| {
            (
                "`Lightmap(indirect: true, max_depth: 0)` bakes no indirect light: `max_depth` counts its bounces, and 0 allows none".into(),
                "set `max_depth: 1` or more for indirect light, or `indirect: false` for direct light only".into(),
            )
        })
        .collect()
}

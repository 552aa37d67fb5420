//! What a baked request becomes on disk: its file names (`<instance>_<kind>.<ext>` unless
//! the output names a file; `_bent_normals.exr` and `_mask.png` beside them), the encoding
//! of each texture (sRGB PNG for colour kinds, normals mapped to [0, 1] in PNG, linear EXR)
//! and the per-request report.

use std::path::{Path, PathBuf};

use super::request::PreparedBake;
use super::texels::TexelResults;
use super::{BakeReport, TexelImage};
use crate::components::{BakeFormat, BakeKind, BakeRequest, BakeTarget};
use crate::image_io::PendingFile;
use crate::stage_error::StageError;

/// The encoded files of one baked request, not yet written.
pub struct BakedFiles {
    /// The files, in request order: targets, then bent normals, then the mask.
    pub pending: Vec<PendingFile>,
}

/// Encodes the (already dilated) images of `p` for writing under `dir`. `baked` is the
/// validity of the texels baked from the surface, before dilation (the mask shows it).
pub fn encode_request(
    p: &PreparedBake,
    results: &TexelResults,
    baked: Option<&[bool]>,
    dir: &Path,
) -> Result<BakedFiles, StageError> {
    let write_error = |path: &Path| {
        let path = path.to_path_buf();
        move |message| StageError::Write { path, message }
    };
    let mut pending = Vec::new();
    let safe_name = safe_name(&p.request);
    for (target, img) in p.request.targets.iter().zip(&results.images) {
        let file = target_file(&safe_name, target);
        let color = matches!(target.kind, BakeKind::Lightmap { .. } | BakeKind::Albedo);
        let signed = matches!(target.kind, BakeKind::Normals { .. });
        let bytes = encode(img, target.format, color, signed).map_err(write_error(&file))?;
        pending.push(PendingFile::new(dir.join(file), bytes));
    }
    if results.images.len() > p.request.targets.len() {
        let img = &results.images[results.images.len() - 1];
        let path = dir.join(format!("{safe_name}_bent_normals.exr"));
        let bytes = img.encode_exr().map_err(write_error(&path))?;
        pending.push(PendingFile::new(path, bytes));
    }
    if p.request.mask {
        if let Some(first) = results.images.first() {
            let path = dir.join(format!("{safe_name}_mask.png"));
            let mut mask = first.clone();
            // The mask shows texels baked from the surface, not dilated or invalid ones.
            if let Some(baked) = baked {
                mask.valid = baked.to_vec();
            }
            let bytes = mask.encode_mask_png().map_err(write_error(&path))?;
            pending.push(PendingFile::new(path, bytes));
        }
    }
    Ok(BakedFiles { pending })
}

/// The request's name as used in file names (path separators replaced).
pub fn safe_name(request: &BakeRequest) -> String {
    request.name.replace(['/', '\\'], "_")
}

/// The file of one target, relative to the bake directory.
pub fn target_file(safe_name: &str, target: &BakeTarget) -> PathBuf {
    target.file.clone().unwrap_or_else(|| {
        PathBuf::from(format!(
            "{safe_name}_{}.{}",
            target.kind.suffix(),
            target.format.extension()
        ))
    })
}

/// For runs whose files go to a scratch directory (`bench`, `sweep`): every file a bake
/// request names, made a relative path of its plain components (`/data/rock_ao.exr` →
/// `data/rock_ao.exr`, `../x.exr` → `x.exr`), so that it lands under the run's bake
/// directory instead of where the scene would write it.
pub fn confine_to_bake_dir(world: &mut hecs::World) {
    for request in world.query_mut::<&mut BakeRequest>() {
        for file in request.targets.iter_mut().filter_map(|t| t.file.as_mut()) {
            *file = file
                .components()
                .filter(|c| matches!(c, std::path::Component::Normal(_)))
                .collect();
        }
    }
}

/// Every file a request writes under `dir`, in the order [`encode_request`] writes them
/// (targets, bent normals, mask), known before baking (output path checks).
pub fn planned_paths(request: &BakeRequest, dir: &Path) -> Vec<PathBuf> {
    let safe_name = safe_name(request);
    let mut paths: Vec<PathBuf> = request
        .targets
        .iter()
        .map(|t| dir.join(target_file(&safe_name, t)))
        .collect();
    let texture_targets = request.targets.iter().any(|t| !t.format.is_per_vertex());
    let bent = request.targets.iter().any(|t| {
        !t.format.is_per_vertex()
            && matches!(
                t.kind,
                BakeKind::AmbientOcclusion {
                    bent_normals: true,
                    ..
                }
            )
    });
    if bent {
        paths.push(dir.join(format!("{safe_name}_bent_normals.exr")));
    }
    if request.mask && texture_targets {
        paths.push(dir.join(format!("{safe_name}_mask.png")));
    }
    paths
}

/// The report of one baked request.
pub fn report(
    p: &PreparedBake,
    results: &TexelResults,
    dilated: u64,
    seconds: f64,
    files: &BakedFiles,
) -> BakeReport {
    let covered = p.coverage.covered_texels();
    BakeReport {
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
        files: files
            .pending
            .iter()
            .map(|f| f.path.display().to_string())
            .collect(),
        vertices: None,
        seams: None,
        merged_parts: false,
    }
}

/// Encodes a baked texture. Colour kinds go through sRGB in PNG; normals are mapped from
/// [−1, 1] to [0, 1] in PNG; everything is linear in EXR.
fn encode(
    img: &TexelImage,
    format: BakeFormat,
    color: bool,
    signed: bool,
) -> Result<Vec<u8>, String> {
    match format {
        BakeFormat::Exr => img.encode_exr(),
        BakeFormat::Ply => Err("per-vertex values are written by bake::vertex_files".into()),
        BakeFormat::Png8 | BakeFormat::Png16 => {
            let mapped;
            let img = if signed {
                mapped = TexelImage {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn confined_files_keep_only_their_plain_components() {
        let mut world = hecs::World::new();
        let target = |file: Option<&str>| BakeTarget {
            kind: BakeKind::Positions,
            format: BakeFormat::Exr,
            file: file.map(PathBuf::from),
            denoise: None,
        };
        let request = BakeRequest {
            name: "rock".into(),
            resolution: crate::components::BakeResolution::Fixed {
                width: 4,
                height: 4,
            },
            uvs: crate::components::UvSource::Mesh,
            texel_samples: 1,
            padding: 0,
            mask: false,
            stitch_seams: false,
            targets: vec![
                target(Some("/data/rock_ao.exr")),
                target(Some("../../x.exr")),
                target(Some("sub/./y.png")),
                target(None),
            ],
        };
        let e = world.spawn((request,));
        confine_to_bake_dir(&mut world);
        let files: Vec<Option<PathBuf>> = world
            .get::<&BakeRequest>(e)
            .unwrap()
            .targets
            .iter()
            .map(|t| t.file.clone())
            .collect();
        let p = |s: &str| Some(PathBuf::from(s));
        assert_eq!(
            files,
            [p("data/rock_ao.exr"), p("x.exr"), p("sub/y.png"), None]
        );
    }
}

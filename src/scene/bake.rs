//! Bake requests: checks each instance's `bake: (...)` entry and builds the
//! [`BakeRequest`] component for its (single) placed leaf.

use super::dag::Leaf;
use super::desc::{
    BakeDesc, BakeFormatDesc, BakeKindDesc, BakeTargetDesc, DenoiseDesc, LightmapStoreDesc,
    NormalSpaceDesc, UvsDesc,
};
use super::diagnostics::Sources;
use super::validate::{Checker, Merged};
use crate::components::{
    BakeFormat, BakeKind, BakeRequest, BakeResolution, BakeTarget, Denoise, LightmapStore,
    NormalSpace, UvSource,
};

/// One entry per merged instance: the bake request of instances that carry a valid one.
/// `has_uvs` tells, per object, whether its mesh carries texture coordinates of set 0 and
/// of set 1; `None` for a mesh that failed to load, whose UVs are not checked (its own
/// error says what is wrong; "it has no UVs" would mislead).
pub fn bake_requests(
    src: &mut Sources,
    m: &Merged<'_>,
    leaves: &[Leaf],
    has_uvs: &[Option<[bool; 2]>],
) -> Vec<Option<BakeRequest>> {
    m.instances
        .iter()
        .enumerate()
        .map(|(index, it)| {
            let desc = it.desc.bake.as_ref()?;
            let mut ck = Checker { src, file: it.file };
            let path = it.at(".bake");
            let placed: Vec<&Leaf> = leaves.iter().filter(|l| l.instance == index).collect();
            let name = &it.desc.name;
            match placed.len() {
                0 => {
                    ck.error(
                        &path,
                        format!(
                            "instance \"{name}\" has no placed object to bake: it places a group, or the root group does not reach it"
                        ),
                    );
                    return None;
                }
                1 => {}
                n => {
                    ck.error(
                        &path,
                        format!("instance \"{name}\" is placed {n} times through shared groups; a bake needs exactly one placement"),
                    );
                    return None;
                }
            }
            let has_uvs = match has_uvs.get(placed[0].object) {
                Some(Some(sets)) => *sets,
                Some(None) => [true; 2],
                None => [false; 2],
            };
            request(&mut ck, &path, name, desc, has_uvs)
        })
        .collect()
}

fn request(
    ck: &mut Checker<'_>,
    path: &str,
    name: &str,
    d: &BakeDesc,
    has_uvs: [bool; 2],
) -> Option<BakeRequest> {
    let mut ok = true;
    let resolution = match (d.resolution, d.texels_per_unit) {
        (Some((w, h)), None) => {
            if w == 0 || h == 0 || w > 16384 || h > 16384 {
                ck.error(
                    &format!("{path}.resolution"),
                    format!("bake resolution must be 1 … 16384 texels per side, found ({w}, {h})"),
                );
                ok = false;
            }
            BakeResolution::Fixed {
                width: w,
                height: h,
            }
        }
        (None, Some(density)) => {
            let p = format!("{path}.texels_per_unit");
            let finite = ck.finite(&p, "texels_per_unit", density);
            if !finite || density <= 0.0 {
                // A value past f32's range was reported by `finite` already.
                if finite {
                    ck.error(
                        &p,
                        format!("texels_per_unit must be positive, found {density}"),
                    );
                }
                ok = false;
            }
            if d.max_size == 0 || d.max_size > 16384 {
                ck.error(
                    &format!("{path}.max_size"),
                    format!("max_size must be 1 … 16384, found {}", d.max_size),
                );
                ok = false;
            }
            BakeResolution::Density {
                texels_per_unit: density as f32,
                max_size: d.max_size,
            }
        }
        (Some(_), Some(_)) => {
            ck.error(
                &format!("{path}.texels_per_unit"),
                "give either `resolution` or `texels_per_unit`, not both",
            );
            return None;
        }
        (None, None) if all_per_vertex(d) => BakeResolution::Fixed {
            width: 1,
            height: 1,
        },
        (None, None) => {
            ck.error(
                path,
                "a bake needs its size: add `resolution: (1024, 1024)` or `texels_per_unit: 64.0`",
            );
            return None;
        }
    };
    let uvs = match d.uvs {
        UvsDesc::Auto => UvSource::MeshOrUnwrap,
        UvsDesc::Mesh => {
            if !has_uvs[0] {
                ck.error(
                    &format!("{path}.uvs"),
                    format!("`uvs: Mesh`, but the mesh of \"{name}\" has no texture coordinates"),
                );
                ok = false;
            }
            UvSource::Mesh
        }
        UvsDesc::Unwrap => UvSource::Unwrap,
        UvsDesc::MeshSet(set) => match set {
            0 if has_uvs[0] => UvSource::Mesh,
            1 if has_uvs[1] => UvSource::SecondSet,
            0 | 1 => {
                ck.error(
                    &format!("{path}.uvs.MeshSet"),
                    format!("`uvs: MeshSet({set})`, but the mesh of \"{name}\" has no texture coordinates of set {set}"),
                );
                ok = false;
                UvSource::Mesh
            }
            _ => {
                ck.error(
                    &format!("{path}.uvs.MeshSet"),
                    format!("UV set {set} does not exist: meshes carry sets 0 and 1 (glTF `TEXCOORD_0`, `TEXCOORD_1`)"),
                );
                ok = false;
                UvSource::Mesh
            }
        },
    };
    if d.texel_samples == 0 || d.texel_samples > 256 {
        ck.error(
            &format!("{path}.texel_samples"),
            format!("texel_samples must be 1 … 256, found {}", d.texel_samples),
        );
        ok = false;
    }
    if d.outputs.is_empty() {
        ck.error(
            &format!("{path}.outputs"),
            "a bake needs at least one output",
        );
        ok = false;
    }
    let mut targets = Vec::with_capacity(d.outputs.len());
    let mut bent_normals_seen = false;
    for (k, o) in d.outputs.iter().enumerate() {
        let kp = format!("{path}.outputs[{k}].kind");
        let kind = match &o.kind {
            BakeKindDesc::AmbientOcclusion {
                samples,
                max_distance,
                bent_normals,
            } => {
                if *samples == 0 {
                    ck.error(
                        &format!("{kp}.AmbientOcclusion.samples"),
                        "samples must be at least 1",
                    );
                    ok = false;
                }
                let max_distance = match max_distance {
                    None => f32::INFINITY,
                    Some(x) => {
                        let p = format!("{kp}.AmbientOcclusion.max_distance");
                        if ck.finite(&p, "max_distance", *x) && *x > 0.0 {
                            *x as f32
                        } else {
                            if x.is_finite() {
                                ck.error(&p, format!("max_distance must be positive, found {x}"));
                            }
                            ok = false;
                            f32::INFINITY
                        }
                    }
                };
                BakeKind::AmbientOcclusion {
                    samples: *samples,
                    max_distance,
                    bent_normals: *bent_normals,
                }
            }
            BakeKindDesc::Lightmap {
                indirect,
                samples,
                max_depth,
                store,
                scale,
            } => {
                if *samples == 0 {
                    ck.error(
                        &format!("{kp}.Lightmap.samples"),
                        "samples must be at least 1",
                    );
                    ok = false;
                }
                let stored_scale = *scale as f32;
                if !(stored_scale.is_finite() && stored_scale > 0.0) {
                    ck.error(
                        &format!("{kp}.Lightmap.scale"),
                        format!(
                            "scale must be a positive number (it multiplies the stored value), found {scale}"
                        ),
                    );
                    ok = false;
                }
                BakeKind::Lightmap {
                    indirect: *indirect,
                    samples: *samples,
                    max_depth: *max_depth,
                    store: match store {
                        LightmapStoreDesc::Irradiance => LightmapStore::Irradiance,
                        LightmapStoreDesc::Radiance => LightmapStore::Radiance,
                        LightmapStoreDesc::IrradianceOverPi => LightmapStore::IrradianceOverPi,
                    },
                    scale: stored_scale,
                }
            }
            BakeKindDesc::Normals { space } => BakeKind::Normals {
                space: match space {
                    NormalSpaceDesc::World => NormalSpace::World,
                    NormalSpaceDesc::Tangent => NormalSpace::Tangent,
                },
            },
            BakeKindDesc::Positions => BakeKind::Positions,
            BakeKindDesc::Albedo => BakeKind::Albedo,
        };
        let format = match (o.target, o.format) {
            (BakeTargetDesc::Vertices, _) => {
                ok &= vertex_target_checks(ck, &format!("{path}.outputs[{k}]"), o, &kind);
                BakeFormat::Ply
            }
            (BakeTargetDesc::Texture, BakeFormatDesc::Exr) => BakeFormat::Exr,
            (BakeTargetDesc::Texture, BakeFormatDesc::Png8) => BakeFormat::Png8,
            (BakeTargetDesc::Texture, BakeFormatDesc::Png16) => BakeFormat::Png16,
            (BakeTargetDesc::Texture, BakeFormatDesc::Ply) => {
                ck.error(
                    &format!("{path}.outputs[{k}].format"),
                    "`format: Ply` is the format of per-vertex bakes: add `target: Vertices`, or write the texture as Exr, Png8 or Png16",
                );
                ok = false;
                BakeFormat::Exr
            }
        };
        let at = format!("{path}.outputs[{k}]");
        ok &= file_matches_format(ck, &at, o.file.as_deref(), format);
        if let BakeKind::AmbientOcclusion {
            bent_normals: true, ..
        } = kind
        {
            if format != BakeFormat::Ply && std::mem::replace(&mut bent_normals_seen, true) {
                ck.src.error(
                    ck.file,
                    &format!("{at}.kind.AmbientOcclusion.bent_normals"),
                    format!("a second ambient-occlusion output with bent normals: both would write {name}_bent_normals.exr"),
                    Some("keep `bent_normals: true` on one AmbientOcclusion output".into()),
                );
                ok = false;
            }
        }
        let denoise = match &o.denoise {
            None => None,
            Some(d) => {
                let dp = format!("{path}.outputs[{k}].denoise");
                let checked = denoise_checks(ck, &dp, d, &kind, format);
                ok &= checked.is_some();
                checked
            }
        };
        targets.push(BakeTarget {
            kind,
            format,
            file: o.file.as_ref().map(Into::into),
            denoise,
        });
    }
    ok.then(|| BakeRequest {
        name: name.to_string(),
        resolution,
        uvs,
        texel_samples: d.texel_samples,
        padding: d.padding,
        mask: d.mask,
        stitch_seams: d.stitch_seams,
        targets,
    })
}

/// A bake output's `file` ends in its format's extension (`.exr`, `.png`, `.ply`), or in
/// none: a `.png` name over EXR bytes (the default format) is refused at the name.
fn file_matches_format(
    ck: &mut Checker<'_>,
    at: &str,
    file: Option<&str>,
    format: BakeFormat,
) -> bool {
    let Some(ext) = file
        .and_then(|f| std::path::Path::new(f).extension())
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
    else {
        return true;
    };
    let (wanted, fix) = match format {
        BakeFormat::Exr => (
            "exr",
            "write `format: Png8` (or Png16) for a PNG, or name the file `.exr`",
        ),
        BakeFormat::Png8 | BakeFormat::Png16 => (
            "png",
            "name the file `.png`, or leave `format` out for an EXR",
        ),
        BakeFormat::Ply => ("ply", "name the file `.ply`"),
    };
    if ext == wanted {
        return true;
    }
    ck.src.error(
        ck.file,
        &format!("{at}.file"),
        format!(
            "file \"{}\" ends in .{ext}, but this output is written as {format:?} (.{wanted})",
            file.unwrap_or_default()
        ),
        Some(fix.into()),
    );
    false
}

/// A bake output's `denoise`: passes 1 … 8, a positive finite colour width, on an AO or
/// lightmap texture. Returns the settings when valid.
fn denoise_checks(
    ck: &mut Checker<'_>,
    path: &str,
    d: &DenoiseDesc,
    kind: &BakeKind,
    format: BakeFormat,
) -> Option<Denoise> {
    let mut ok = true;
    let mut error = |ck: &mut Checker<'_>, at: &str, message: String, help: &str| {
        ck.src.error(ck.file, at, message, Some(help.to_string()));
        ok = false;
    };
    if !matches!(
        kind,
        BakeKind::AmbientOcclusion { .. } | BakeKind::Lightmap { .. }
    ) {
        error(
            ck,
            path,
            format!(
                "`denoise` filters noisy estimates: only AmbientOcclusion and Lightmap outputs have them, not {}",
                kind.suffix()
            ),
            "remove `denoise` from this output",
        );
    }
    if format.is_per_vertex() {
        error(
            ck,
            path,
            "`denoise` filters the texels of a texture; a per-vertex output (`target: Vertices`) has none".into(),
            "remove `denoise`, or bake a texture (leave `target` out)",
        );
    }
    if d.passes == 0 || d.passes > 8 {
        error(
            ck,
            &format!("{path}.passes"),
            format!("denoise passes must be 1 … 8, found {}", d.passes),
            "3 passes (steps 1, 2 and 4 texels) is the default",
        );
    }
    if !d.sigma_color.is_finite() || d.sigma_color <= 0.0 || d.sigma_color > f64::from(f32::MAX) {
        error(
            ck,
            &format!("{path}.sigma_color"),
            format!(
                "sigma_color must be a positive finite number, found {}",
                d.sigma_color
            ),
            "4.0 (the default) keeps edges larger than four standard deviations of the noise",
        );
    }
    ok.then_some(Denoise {
        passes: d.passes,
        sigma_color: d.sigma_color as f32,
    })
}

/// Whether every output of the bake is baked per vertex (then no texture size is needed).
fn all_per_vertex(d: &BakeDesc) -> bool {
    !d.outputs.is_empty()
        && d.outputs
            .iter()
            .all(|o| o.target == BakeTargetDesc::Vertices)
}

/// What a per-vertex output may not ask for: a texture format, bent normals (a texture of
/// their own) or tangent-space normals (a texture's frame). Returns whether it is valid.
fn vertex_target_checks(
    ck: &mut Checker<'_>,
    path: &str,
    o: &super::desc::BakeOutputDesc,
    kind: &BakeKind,
) -> bool {
    let mut ok = true;
    if matches!(o.format, BakeFormatDesc::Png8 | BakeFormatDesc::Png16) {
        ck.error(
            &format!("{path}.format"),
            "`target: Vertices` writes a PLY with vertex colours; leave `format` out (or write `format: Ply`)",
        );
        ok = false;
    }
    if matches!(
        kind,
        BakeKind::AmbientOcclusion {
            bent_normals: true,
            ..
        }
    ) {
        ck.error(
            &format!("{path}.kind.AmbientOcclusion.bent_normals"),
            "bent normals are baked into a texture only; bake them in an output without `target: Vertices`",
        );
        ok = false;
    }
    if matches!(
        kind,
        BakeKind::Normals {
            space: NormalSpace::Tangent
        }
    ) {
        ck.error(
            &format!("{path}.kind.Normals.space"),
            "tangent-space normals need a texture's tangent frame; bake `space: World` per vertex",
        );
        ok = false;
    }
    ok
}

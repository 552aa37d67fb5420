//! The scene's `environment: (...)`: at most one across all files; a lat-long map is read
//! from its EXR file (relative to the declaring scene file) at load time, so a missing or bad
//! file is a located error like any other.

use std::path::Path;
use std::sync::Arc;

use glam::{DVec3, Vec3};

use super::desc::{DepthExceededDesc, EnvironmentShaderDesc, SceneDesc};
use super::diagnostics::Sources;
use super::include::io_reason;
use super::validate::Checker;
use crate::components::{
    DecodedImage, DepthExceeded, Environment, EnvironmentSource, ImageContent, LatLongMap,
};
use crate::shading::lights::environment::footprint;

/// Most texels a lat-long map may have (64 Mi: 16k × 4k maps fit).
const MAX_TEXELS: usize = 1 << 26;

/// Checks the environment of the loaded files and builds its component (errors recorded).
pub fn environment(src: &mut Sources, scenes: &[Option<SceneDesc>]) -> Option<Environment> {
    let mut found: Option<(usize, &super::desc::EnvironmentDesc)> = None;
    for (file, scene) in scenes.iter().enumerate() {
        let Some(env) = scene.as_ref().and_then(|s| s.environment.as_ref()) else {
            continue;
        };
        match found {
            Some((first, _)) => {
                let help = format!("first defined at {}", src.where_is(first, "environment"));
                src.error(
                    file,
                    "environment",
                    "environment is given twice",
                    Some(help),
                );
            }
            None => found = Some((file, env)),
        }
    }
    let (file, d) = found?;
    let mut ck = Checker { src, file };
    let intensity = ck.non_negative("environment.intensity", "intensity", d.intensity);
    if d.samples == 0 {
        ck.error("environment.samples", "samples must be at least 1, found 0");
    }
    let source = source(&mut ck, "environment", &d.shader, intensity, true);
    if d.samples == 0 {
        return None;
    }
    let source = source?;
    Some(Environment {
        source,
        samples: d.samples,
        depth_exceeded: match d.depth_exceeded {
            DepthExceededDesc::Environment => DepthExceeded::Environment,
            DepthExceededDesc::Black => DepthExceeded::Black,
        },
    })
}

/// Checks an environment's radiance source written at `at` (`environment`, or a material's
/// `….environment`) and builds it with `intensity` applied (errors recorded). A lat-long
/// map is counted against the run's memory budget from its header before it is read, with
/// its sampling tables when it is `sampled` (the scene's environment, also a light), and
/// listed once read for the run-wide estimate.
pub fn source(
    ck: &mut Checker<'_>,
    at: &str,
    shader: &EnvironmentShaderDesc,
    intensity: Option<f64>,
    sampled: bool,
) -> Option<EnvironmentSource> {
    match shader {
        EnvironmentShaderDesc::Constant { color } => {
            let c = ck.colour(&format!("{at}.shader.Constant.color"), "color", *color);
            let radiance = ck.radiant(
                &format!("{at}.intensity"),
                "color × intensity",
                c? * intensity?,
            )?;
            Some(EnvironmentSource::Constant(radiance.as_vec3()))
        }
        EnvironmentShaderDesc::LatLong {
            file: name,
            rotation,
        } => {
            let rot_ok = ck.finite(
                &format!("{at}.shader.LatLong.rotation"),
                "rotation",
                *rotation,
            );
            let path = ck.src.files[ck.file].dir().join(name);
            let file_at = format!("{at}.shader.LatLong.file");
            let content = ImageContent::EnvironmentMap { sampled };
            if let Some(size) = lat_long_size(&path) {
                let bytes = footprint::peak_bytes(size.0, size.1, sampled);
                if let Err((message, help)) = ck.src.images.admit(name, size, content, bytes) {
                    ck.src.error(ck.file, &file_at, message, Some(help));
                    return None;
                }
            }
            let map = match read_exr(&path) {
                Ok(map) => Some(map),
                Err(reason) => {
                    ck.src.error(
                        ck.file,
                        &file_at,
                        format!("cannot use EXR file \"{}\": {reason}", path.display()),
                        Some(
                            "a lat-long environment is an RGB(A) OpenEXR image; the path is \
                             relative to this scene file"
                                .into(),
                        ),
                    );
                    None
                }
            };
            let (mut map, k) = (map?, intensity? as f32);
            if !rot_ok {
                return None;
            }
            let brightest = map
                .texels
                .iter()
                .fold(0.0f32, |m, t| m.max(t.max_element()));
            ck.radiant(
                &format!("{at}.intensity"),
                "the brightest texel × intensity",
                DVec3::splat(f64::from(brightest) * f64::from(k)),
            )?;
            for t in &mut map.texels {
                *t *= k;
            }
            map.rotation = rotation.to_radians() as f32;
            let pos = ck.src.pos(ck.file, &file_at);
            let image = DecodedImage {
                width: map.width,
                height: map.height,
                bytes: footprint::peak_bytes(map.width, map.height, sampled),
                content,
            };
            ck.src.images.list(name, pos, image);
            Some(EnvironmentSource::LatLong(Arc::new(map)))
        }
    }
}

/// The size of the layer [`read_exr`] reads (the first with R, G and B), from the file's
/// headers; `None` when they cannot be read or no layer has those channels (the read then
/// says what is wrong).
fn lat_long_size(path: &Path) -> Option<(u32, u32)> {
    let meta = exr::meta::MetaData::read_from_file(path, false).ok()?;
    let header = meta.headers.iter().find(|h| {
        ["R", "G", "B"]
            .iter()
            .all(|n| h.channels.list.iter().any(|c| c.name.to_string() == *n))
    })?;
    let size = header.layer_size;
    Some((
        u32::try_from(size.width()).ok()?,
        u32::try_from(size.height()).ok()?,
    ))
}

/// Reads the first RGB(A) layer of an EXR file as a lat-long map (rotation 0); every value
/// must be finite and non-negative.
pub fn read_exr(path: &Path) -> Result<LatLongMap, String> {
    use exr::prelude::{read, ReadChannels, ReadLayers, RgbaChannels, Vec2 as ExrVec2};
    if let Err(e) = std::fs::metadata(path) {
        return Err(io_reason(&e));
    }
    use crate::image_io::exr_limits;
    exr_limits::check_file(path, exr_limits::MAX_IMAGE_SAMPLES)?;
    // `read_first_rgba_layer_from_file`'s reader, on the calling thread (see
    // `texture::image::decode_exr`).
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |size: ExrVec2<usize>, _: &RgbaChannels| {
                let n = size.width().saturating_mul(size.height());
                let texels = if n <= MAX_TEXELS {
                    vec![Vec3::ZERO; n]
                } else {
                    Vec::new()
                };
                (size.width(), texels)
            },
            |(w, texels): &mut (usize, Vec<Vec3>),
             pos: ExrVec2<usize>,
             (r, g, b, _a): (f32, f32, f32, f32)| {
                if let Some(t) = texels.get_mut(pos.y() * *w + pos.x()) {
                    *t = Vec3::new(r, g, b);
                }
            },
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_file(path)
        .map_err(|e| format!("not a readable OpenEXR RGB image ({e})"))?;
    let size = image.layer_data.size;
    let (_, texels) = image.layer_data.channel_data.pixels;
    let (w, h) = (size.width(), size.height());
    if w == 0 || h == 0 || w * h > MAX_TEXELS || texels.len() != w * h {
        return Err(format!(
            "{w}×{h} texels: a map needs between 1 and {MAX_TEXELS} texels"
        ));
    }
    if let Some(i) = texels
        .iter()
        .position(|t| !t.is_finite() || t.min_element() < 0.0)
    {
        return Err(format!(
            "texel ({}, {}) is {} (radiance must be finite and non-negative)",
            i % w,
            i / w,
            texels[i]
        ));
    }
    Ok(LatLongMap {
        width: w as u32,
        height: h as u32,
        texels,
        rotation: 0.0,
    })
}
